#pragma once
// A coarse texel's radial correction (docs/mip-algorithm.md, §5; its measurements in
// bench/results/mip.md, "The radial correction").
//
// The reduction (lobe_reduction.h) fits each merge by moments; its errors are small per merge but
// compound over the levels, and far away, where a pixel sees a handful of coarse texels, they show as
// a highlight a percent too bright or too dark and a few percent off in shape (polished granite +1.3 %
// at 1024×). They live mostly in the radial profile of the texel's D about the geometric normal, and
// that profile averages linearly: the union's profile is the area-weighted mean of its children's.
// So from level kFirstCorrectedLevel on, the build carries the true profile P(θ) = Σ w·F0·⟨D⟩(θ)
// (⟨D⟩ the azimuthal mean, azimuthal_mean.h; F0 the mean of the lobe's three, since the correction is
// of reflected light and a metal's clean and oily texels differ in it) up the pyramid exactly — at the
// first corrected level from its children's lobes, above it as the mean of the children's true
// profiles — and each texel keeps the ratio
//   R(θ) = P_true(θ) / P_own(θ)
// of the true profile to its own lobes' at kNodes nodes; the specular term of each of its lobes is
// multiplied by R(θh). The lobes keep everything else: their normals (the texel's anisotropy), colors,
// V and Fresnel. R is smooth (12 nodes do what 96 did), it is 1 where the lobes are exact, and it
// corrects nothing the lobes get right. Sampling keeps to the lobes (eval carries R, so the estimate
// f/pdf stays unbiased). The MIP file stores R as 12 halves a texel (mip_file.h).
//
// Nodes: θ = 0, and 11 with u = 1 − cos θ log-spaced from u(θ_in) to u(30°), θ_in the α of the
// pyramid's sharpest level-0 lobe, within 0.03°–1° (RadialGrid); R is linear in ln u between them
// (linear in u to the first), and beyond the last it goes to 1 at 60°, linearly in ln u.
//
// Beyond 10° a texel's correction is gated. There the premise — that the lobes' error is radial — fails
// where a texel's normals spread along one axis: the tile roof's isotropic lobes under-fill the plane of
// its slopes and over-fill the rest at the same θ, and a radial ratio below 1 at 22.5° lowered its
// highlight in that plane further (−8.3 → −9.9 % of the flux at 1024× under the 45° sun). The build
// carries the truth's first and second azimuthal harmonics up the pyramid with its profile (they
// average linearly too; azimuthal_fourier_d has them in closed form) and compares them, relative to the profile, with the lobes' own: where the two azimuthal shapes
// differ, by 2 Σₙ |tₙ − oₙ| ≥ 15 % (the ratio's first-order variation over φ), no radial correction is
// right for every azimuth and the node keeps R = 1; below 5 % all of R; linearly between (correction_gate).
// The gate only closes outward. On the roof it closes at the first gated node, which keeps the roof
// where the 10° grid had it; the polished tray's glow at 22.5° (−1.6 % of the flux at level 5 against the
// exact mean, −0.4 % of it from the levels below 4) keeps most of its correction.
//
// Before its ratio, a texel's lobes are re-centred (recentring_tilt). The truth's first azimuthal
// harmonics at the nodes within kGateFromDeg say where its highlight's centre is, and a few lobes of a
// near-mirror miss it: merging sharp lobes a fraction of a degree apart puts the merged peak at the
// mean of their normals, and which lobes merge is decided where the cost cannot see such distances.
// On the polished tray (α ≈ 0.005) the whole-texture highlight at level 7 was 1–1.6 % too bright on
// one side and too dark on the other at 0.1–0.3° (a shift of about 1.5e-5 rad), 76 % of its error
// over the ±2.5° a far mirror view sees (bench/results/mip.md, "The stored normal"). A tilt δ of all
// the texel's lobes, fitted to those harmonics, moves that centre back; the ratio is then taken
// against the tilted lobes. It costs no bytes (the normals hold it), but it needs the normals' code
// to resolve steps of 1e-6 rad near the pole (stored_normal.h).
#include <array>
#include <span>

#include "mip/lobe.h"

namespace svbrdf {

inline constexpr int kFirstCorrectedLevel = 4;

struct RadialGrid {
  static constexpr int kNodes = 12;
  static constexpr double kOuterDeg = 30.0;       // the last node
  static constexpr double kFadePerOuter = 2.0;    // R reaches 1 at this multiple of the last node's θ
  static constexpr double kGateFromDeg = 10.0;    // nodes beyond this are gated by the ratio's azimuthal spread
  float inner = 0.0f;    // θ of node 1, radians (a float: the MIP file's svbrdf:radial_inner)
  float outer_deg = 0.0f;  // θ of the last node, degrees (the MIP file's svbrdf:radial_outer)
  float log_u1 = 0.0f;   // ln u of node 1
  float inv_step = 0.0f; // 1 / (ln u step between nodes)
  float u1 = 0.0f;
  float log_u_outer = 0.0f;  // ln u of the last node
  float inv_fade = 0.0f;     // 1 / (ln u(kFadeEndDeg) − ln u(kOuterDeg))
  std::array<double, kNodes> theta{};  // the nodes' θ

  // The grid for a pyramid whose sharpest level-0 lobe has α² = alpha2_min.
  static RadialGrid for_sharpest(double alpha2_min);
  // The grid whose node 1 is at θ = inner (0 < inner < outer_deg) and whose last node at outer_deg.
  static RadialGrid with_inner(float inner, float outer_deg = static_cast<float>(kOuterDeg));
};

using RadialProfile = std::array<double, RadialGrid::kNodes>;
// At each node, the first and second azimuthal Fourier coefficients of the same sum about the geometric
// normal: ⟨·cos φ⟩, ⟨·sin φ⟩, ⟨·cos 2φ⟩, ⟨·sin 2φ⟩ (φ the azimuth of h in the tangent frame). Like the
// profile they average linearly, so the truth's carry up the pyramid exactly too. Node 0 (θ = 0) holds
// zeros.
using AzimuthalHarmonics = std::array<std::array<double, 4>, RadialGrid::kNodes>;

struct RadialCorrection {
  std::array<float, RadialGrid::kNodes> ratio{};  // half floats (the MIP file's)
};
// Bytes a texel's correction takes in the MIP file.
inline constexpr int kBytesPerCorrection = RadialGrid::kNodes * 2;

// profile += Σ over lobes of weight·F0·⟨D⟩ at the grid's nodes, and, when given, harmonics += the same
// sum's azimuthal harmonics.
void add_to_profile(const RadialGrid& grid, std::span<const Lobe> lobes, RadialProfile& profile,
                    AzimuthalHarmonics* harmonics = nullptr);
// The correction that takes lobes' own profile to `truth`; beyond kGateFromDeg, only as far as the true
// and the lobes' azimuthal shapes agree (correction_gate).
RadialCorrection correction_to(const RadialGrid& grid, const RadialProfile& truth, const AzimuthalHarmonics& truth_harmonics,
                               std::span<const Lobe> lobes);
// The share of a node's radial correction that applies, from the relative azimuthal harmonics of the
// truth (t) and the lobes (o): 1 while the ratio truth/own is nearly flat over the azimuth, 0 where it
// varies by kGateOff or more (2 Σₙ |tₙ − oₙ|, the first-order amplitude of its variation).
double correction_gate(const std::array<double, 4>& t, const std::array<double, 4>& o);
// The tilt δ (x, y, radians) of all of a texel's lobes that brings their first azimuthal harmonics to
// the truth's at the nodes within kGateFromDeg (the re-centring above): shifting a profile P(θ) by δ
// changes ⟨D cos φ⟩ by −½P'(θ)δx and ⟨D sin φ⟩ by −½P'(θ)δy to first order, and δ is their least-squares
// fit with each node weighted by its ring's area θ·Δθ. P' is the lobes' own, by forward differences
// of 1 % in θ. |δ| is held to a tenth of the grid's inner node (the linearization's range) and to
// 2.5e-4 rad, where the tilt changes a lobe's cosine factor at θi = 75° by 0.1 % (radial_correction.cpp).
// Zero where the lobes reflect nothing there.
glm::dvec2 recentring_tilt(const RadialGrid& grid, const AzimuthalHarmonics& truth_harmonics, std::span<const Lobe> lobes);
// R at the unit half vector h (geometric tangent frame).
float correction_at(const RadialCorrection& c, const RadialGrid& grid, const glm::vec3& h);

}  // namespace svbrdf
