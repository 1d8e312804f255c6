#pragma once
// Private to mip/: the reduction's arithmetic of stretched lobes (lobe.h, "Stretched shapes").
//
// A lobe's microfacet slopes, in the geometric tangent frame's x–y plane, spread as α²·S about its
// normal's slope, S = R·diag(r, 1/r)·Rᵀ symmetric with det S = 1 (R the rotation to its stretch_dir).
// A union's spread is the k-weighted mean of its members' α²·S plus the spread of their normals'
// slopes about the merged normal; LEAN mapping composes them so (Olano & Baker 2010, "LEAN Mapping":
// the second moments of the slopes add), with the GGX α² taken as twice a Gaussian's per-axis
// variance (a Beckmann lobe of α² has slope variance α²/2 per axis, Walter et al. 2007 eq. 25), so a
// normal's slope offset τ adds 2·ττᵀ in α²'s units. The merged lobe's stretch is that sum scaled to
// det 1; its α² stays what the isotropic fit of the union's moments gives (lobe_fit.h), with the
// moments taken in the merged stretch's own frame (the slopes multiplied by S_m^(−1/2), which keeps
// every density normalized, det S_m = 1):
//   - a member's tail coefficient A (far out, D ≈ A/(π·t²·cos⁴θ) along each azimuth, averaged over
//     the azimuth) becomes A·tr(S_m⁻¹·S_k)/2: an anisotropic GGX of slope matrix M has the azimuthal
//     mean of 1/(uᵀM⁻¹u)² equal to tr(M)·√det M/2, so its mean tail is tr(M)/2; its peak P (π·D at
//     its own normal, 1/√det M) is unchanged;
//   - a member's tilt to the merged normal is τᵀ·S_m⁻¹·τ in place of |τ|²,
// and the member's D at the merged normal is its shape at τᵀ·S_k⁻¹·τ (its own stretch). For a union
// of lobes sharing one stretch and one normal, S_m is that stretch and every moment is the isotropic
// one: the merge is exact as before.
#include <cmath>

#include <glm/glm.hpp>

#include "mip/lobe.h"

namespace svbrdf::reduction {

// A symmetric 2×2 matrix [[xx, xy], [xy, yy]].
struct Sym2 {
  double xx = 1, xy = 0, yy = 1;
  double det() const { return xx * yy - xy * xy; }
  double trace() const { return xx + yy; }
  // vᵀ·M·v
  double quad(const glm::dvec2& v) const { return xx * v.x * v.x + 2 * xy * v.x * v.y + yy * v.y * v.y; }
  // The inverse of a det-1 matrix.
  Sym2 inverse_det1() const { return {yy, -xy, xx}; }
};

// tr(A·B) of two symmetric matrices.
inline double trace_of_product(const Sym2& a, const Sym2& b) { return a.xx * b.xx + 2 * a.xy * b.xy + a.yy * b.yy; }

// The stretch S of ratio `ratio` along `dir` (the identity for ratio ≤ 1).
inline Sym2 stretch_matrix(float ratio, const glm::vec2& dir) {
  if (!(ratio > 1.0f)) return {};
  const double r = ratio, c = dir.x, s = dir.y, inv_r = 1.0 / r;
  const double n2 = c * c + s * s;  // dir is unit; divided out all the same
  return {(r * c * c + inv_r * s * s) / n2, (r - inv_r) * c * s / n2, (r * s * s + inv_r * c * c) / n2};
}
// A lobe's stretch S.
inline Sym2 stretch_matrix(const Lobe& l) { return stretch_matrix(l.stretch, l.stretch_dir); }
// A lobe's transmission stretch (lobe.h "Transmission").
inline Sym2 transmission_stretch_matrix(const Lobe& l) {
  return stretch_matrix(l.transmission_stretch, l.transmission_stretch_dir);
}

// The stretch's logarithm as a vector, ln r·(cos 2φ, sin 2φ) with φ the stretch direction's angle: the
// matrix ln S is [[x, y], [y, −x]], so the distance between two of these is the stretches' log distance
// (rough_distance).
inline glm::dvec2 stretch_log(const Lobe& l) {
  if (!(l.stretch > 1.0f)) return glm::dvec2(0.0);
  const double c = l.stretch_dir.x, s = l.stretch_dir.y, n2 = c * c + s * s;
  return std::log(double(l.stretch)) * glm::dvec2((c * c - s * s) / n2, 2 * c * s / n2);
}

// Sets a stretch (ratio, dir) to a positive-definite matrix scaled to det 1: the ratio the larger
// eigenvalue, the direction its eigenvector. Stretches below 1 + 1e-6 are none.
inline void set_stretch(float& ratio, glm::vec2& dir, const Sym2& m) {
  const double d = m.det();
  ratio = 1.0f;
  dir = glm::vec2(1.0f, 0.0f);
  if (!(d > 0) || !(m.trace() > 0)) return;
  const double inv = 1.0 / std::sqrt(d);
  const double half_diff = 0.5 * (m.xx - m.yy) * inv, off = m.xy * inv;
  const double rad = std::sqrt(half_diff * half_diff + off * off);
  const double r = 0.5 * m.trace() * inv + rad;
  if (!(r > 1.0 + 1e-6)) return;
  const double phi = 0.5 * std::atan2(off, half_diff);
  ratio = static_cast<float>(r);
  dir = glm::vec2(static_cast<float>(std::cos(phi)), static_cast<float>(std::sin(phi)));
}
inline void set_stretch(Lobe& l, const Sym2& m) { set_stretch(l.stretch, l.stretch_dir, m); }

// A unit normal's slope in the geometric tangent frame, (x, y)/z (z > 0 for every normal a texel has).
inline glm::dvec2 normal_slope(const glm::dvec3& n) {
  const double z = std::max(n.z, 1e-6);
  return glm::dvec2(n.x / z, n.y / z);
}

}  // namespace svbrdf::reduction
