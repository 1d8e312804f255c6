#pragma once
// A coarse texel's radial correction (bench/results/mip.md, eleventh and twelfth sessions).
//
// The reduction (lobe_reduction.h) fits each merge by moments; its errors are small per merge but
// compound over the levels, and far away, where a pixel sees a handful of coarse texels, they show as
// a highlight a percent too bright or too dark and a few percent off in shape (polished granite +1.3 %
// at 1024×). They live mostly in the radial profile of the texel's D about the geometric normal, and
// that profile averages linearly: the union's profile is the area-weighted mean of its children's.
// So from level kFirstCorrectedLevel on, the build carries the true profile P(θ) = Σ w·F0·⟨D⟩(θ)
// (⟨D⟩ the azimuthal mean, azimuthal_mean.h; F0 the mean of the lobe's three, since the correction is
// of reflected light and a metal's clean and oily texels differ in it) up the pyramid exactly — at the first corrected level from its children's lobes,
// above it as the mean of the children's true profiles — and each texel keeps the ratio
//   R(θ) = P_true(θ) / P_own(θ)
// of the true profile to its own lobes' at kNodes nodes; the specular term of each of its lobes is
// multiplied by R(θh). The lobes keep everything else: their normals (the texel's anisotropy), colors,
// V and Fresnel. R is smooth (12 nodes do what 96 did), it is 1 where the lobes are exact, and it
// corrects nothing the lobes get right. Sampling keeps to the lobes (eval carries R, so the estimate
// f/pdf stays unbiased). The MIP file stores R as 12 halves a texel (mip_file.h).
//
// Nodes: θ = 0, and 11 with u = 1 − cos θ log-spaced from u(θ_in) to u(10°), θ_in the α of the
// pyramid's sharpest level-0 lobe, within 0.03°–1° (RadialGrid); R is linear in ln u between them
// (linear in u to the first), and beyond the last it goes to 1 at 20°, linearly in ln u. The correction
// is of the highlight's core, where the compounded error showed (the far views head-on and in the
// mirror configuration). Farther out the premise fails where a texel's normals spread along one axis:
// the tile roof's isotropic lobes under-fill the plane of its slopes and over-fill the rest at the
// same θ, so its ratio at 22.5° (< 1) lowered the highlight in that plane further, from −8.3 to −9.9 %
// of the flux at 1024× under the 45° sun (bench/results/mip.md, twelfth session).
#include <array>
#include <span>

#include "mip/lobe.h"

namespace svbrdf {

inline constexpr int kFirstCorrectedLevel = 4;

struct RadialGrid {
  static constexpr int kNodes = 12;
  static constexpr double kOuterDeg = 10.0;    // the last node
  static constexpr double kFadeEndDeg = 20.0;  // R reaches 1 here
  float inner = 0.0f;    // θ of node 1, radians (a float: the MIP file's svbrdf:radial_inner)
  float log_u1 = 0.0f;   // ln u of node 1
  float inv_step = 0.0f; // 1 / (ln u step between nodes)
  float u1 = 0.0f;
  float log_u_outer = 0.0f;  // ln u of the last node
  float inv_fade = 0.0f;     // 1 / (ln u(kFadeEndDeg) − ln u(kOuterDeg))
  std::array<double, kNodes> theta{};  // the nodes' θ

  // The grid for a pyramid whose sharpest level-0 lobe has α² = alpha2_min.
  static RadialGrid for_sharpest(double alpha2_min);
  // The grid whose node 1 is at θ = inner (0 < inner < kOuterDeg).
  static RadialGrid with_inner(float inner);
};

using RadialProfile = std::array<double, RadialGrid::kNodes>;

struct RadialCorrection {
  std::array<float, RadialGrid::kNodes> ratio{};  // half floats (the MIP file's)
};
// Bytes a texel's correction takes in the MIP file.
inline constexpr int kBytesPerCorrection = RadialGrid::kNodes * 2;

// profile += Σ over lobes of weight·F0·⟨D⟩ at the grid's nodes.
void add_to_profile(const RadialGrid& grid, std::span<const Lobe> lobes, RadialProfile& profile);
// The correction that takes lobes' own profile to `truth`.
RadialCorrection correction_to(const RadialGrid& grid, const RadialProfile& truth, std::span<const Lobe> lobes);
// R at the unit half vector h (geometric tangent frame).
float correction_at(const RadialCorrection& c, const RadialGrid& grid, const glm::vec3& h);

}  // namespace svbrdf
