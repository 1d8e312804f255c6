#include "mip/sheen_layer.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/glm.hpp>

#include "appearance/sheen.h"
#include "mip/direction_grid.h"

namespace svbrdf {

namespace {

// What sheen_terms needs of one direction w: its cosine to n, and where it faces n its Λ and E.
struct SheenSide {
  double c = 0, lambda = 0;
  float albedo = 0;
};

SheenSide sheen_side(const SheenLayer& sheen, double alpha, const glm::dvec3& n, const glm::dvec3& w) {
  SheenSide s;
  s.c = glm::dot(n, w);
  if (!(s.c > 0)) return s;
  s.lambda = sheen_lambda(s.c, alpha);
  s.albedo = sheen_albedo(static_cast<float>(s.c), sheen.roughness);
  return s;
}

SheenTerms terms_of(const SheenLayer& sheen, double alpha, const glm::dvec3& n, const PairTerms<double>& p,
                    const SheenSide& i, const SheenSide& o) {
  SheenTerms t;
  if (!p.valid || !(i.c > 0) || !(o.c > 0)) return t;
  const double lobe = sheen_distribution(glm::dot(n, p.h), alpha) * sheen_visibility_of(i.lambda, o.lambda, i.c, o.c);
  t.f = glm::dvec3(sheen.color) * (lobe * i.c * p.inv_wi_z);
  const double c = std::max(sheen.color.r, std::max(sheen.color.g, sheen.color.b));
  t.scaling = std::clamp(1.0 - c * std::max(o.albedo, i.albedo), 0.0, 1.0);
  return t;
}

}  // namespace

SheenTerms sheen_terms(const SheenLayer& sheen, const glm::dvec3& n, const PairTerms<double>& p) {
  const double alpha = sheen_alpha(sheen.roughness);
  return terms_of(sheen, alpha, n, p, sheen_side(sheen, alpha, n, p.wi), sheen_side(sheen, alpha, n, p.wo));
}

void apply_sheen(const SheenLayer& sheen, const glm::dvec3& n, std::span<glm::dvec3> f) {
  const DirectionGrid& g = DirectionGrid::get();
  const double alpha = sheen_alpha(sheen.roughness);
  std::array<SheenSide, DirectionGrid::kDirections> side;
  for (int d = 0; d < DirectionGrid::kDirections; ++d) side[std::size_t(d)] = sheen_side(sheen, alpha, n, g.direction(d));
  for (int q = 0; q < DirectionGrid::kPairs; ++q) {
    const SheenTerms s = terms_of(sheen, alpha, n, g.pair_d(q), side[std::size_t(DirectionGrid::wi_index(q))],
                                  side[std::size_t(DirectionGrid::wo_index(q))]);
    glm::dvec3& v = f[static_cast<std::size_t>(q)];
    v = s.scaling * v + s.f;
  }
}

std::vector<SheenLayer> sheen_level0(const MaterialTexels& m) {
  std::vector<SheenLayer> out(m.size());
  for (std::size_t k = 0; k < m.size(); ++k) out[k] = m.sheen_layer(k);
  return out;
}

namespace {

// A 7-point rule for the standard bivariate normal, exact for polynomials of total degree ≤ 5 (as the
// 3 × 3 Gauss–Hermite product is, with two points fewer): the centre with weight 1/2 and six points
// on the circle of radius 2 at 60° steps, 1/12 each. Its moments: Σw·x² = 6·(1/12)·4·½ = 1,
// Σw·x⁴ = ½·16·⅜ = 3, Σw·x²y² = ½·16·⅛ = 1, the odd ones 0 by symmetry.
constexpr int kSpreadNodes = 7;
constexpr double kSpreadX[kSpreadNodes] = {0.0, 2.0, 1.0, -1.0, -2.0, -1.0, 1.0};
constexpr double kSpreadY[kSpreadNodes] = {0.0, 0.0, 1.7320508075688772, 1.7320508075688772, 0.0, -1.7320508075688772, -1.7320508075688772};
constexpr double kSpreadWeight[kSpreadNodes] = {0.5, 1.0 / 12, 1.0 / 12, 1.0 / 12, 1.0 / 12, 1.0 / 12, 1.0 / 12};

// The sheen term of a lobe whose texels' normals spread about n̂ (σ > 0): the mean over those normals
// of each texel's D(n·h)·V(n·wi, n·wo)·max(0, n·wi)·[n·wo > 0], per unit weight and share, before
// 1/wi.z. With the normals' slopes about n̂ the isotropic Gaussian of per-axis variance σ² that the
// lobe's horizons assume (lobe.h), the mean is a 2-D Gaussian integral over the slopes, taken by the
// rule above. Why not the term at n̂ times the lobe's two sides, as a texel without spread takes it:
// the Charlie V holds 1/(4·n·wi·n·wo), which toward grazing changes by an order of magnitude over
// normals tens of degrees apart, and D(n·h) with it; the texels tilted toward a grazing pair reflect
// it with larger cosines, those tilted away not at all (docs/mip-algorithm.md §1, "The sheen").
double spread_sheen(const LobeShape<float>& s, const PairTerms<float>& p, double alpha) {
  // The nodes' normals are m = (n̂ + σx·t + σy·b)/√(1 + σ²(x² + y²)) for a tangent frame (t, b) of n̂
  // (any: the spread is isotropic), so each cosine m·w is a sum of w's three cosines to n̂, t, b.
  const glm::vec3 n = s.n;
  const glm::vec3 t = glm::normalize(std::abs(n.z) < 0.9f ? glm::cross(n, glm::vec3(0, 0, 1)) : glm::cross(n, glm::vec3(1, 0, 0)));
  const glm::vec3 b = glm::cross(n, t);
  const glm::vec3 wi_nb(glm::dot(n, p.wi), glm::dot(t, p.wi), glm::dot(b, p.wi));
  const glm::vec3 wo_nb(glm::dot(n, p.wo), glm::dot(t, p.wo), glm::dot(b, p.wo));
  const glm::vec3 h_nb(glm::dot(n, p.h), glm::dot(t, p.h), glm::dot(b, p.h));
  const float sigma = s.sigma, inv_ring = 1.0f / std::sqrt(1.0f + 4.0f * sigma * sigma);
  const SheenLambda lambda(alpha);
  // sheen_distribution's (2 + 1/α)·sin²θh^(1/(2α))/(2π), in float.
  const float d_scale = float((2.0 + 1.0 / alpha) / (2.0 * kPiD)), d_power = float(0.5 / alpha);
  float sum = 0;
  for (int q = 0; q < kSpreadNodes; ++q) {
    const glm::vec3 m_nb(1.0f, sigma * float(kSpreadX[q]), sigma * float(kSpreadY[q]));
    const float inv = q == 0 ? 1.0f : inv_ring;
    const float ci = glm::dot(m_nb, wi_nb) * inv, co = glm::dot(m_nb, wo_nb) * inv;
    if (!(ci > 0) || !(co > 0)) continue;
    const float ch = glm::dot(m_nb, h_nb) * inv;
    const float d = d_scale * std::pow(std::max(0.0f, 1.0f - ch * ch), d_power);
    // D·V·cos θi with V = 1/((1 + Λi + Λo)·4·cos θi·cos θo) (sheen_visibility).
    sum += float(kSpreadWeight[q]) * d / ((1.0f + lambda(ci) + lambda(co)) * 4.0f * co);
  }
  return sum;
}

}  // namespace

SheenLobeTerms sheen_lobe_terms(const Lobe& l, const LobeShape<float>& s, const PairTerms<float>& p, float sides,
                                float roughness) {
  SheenLobeTerms t;
  if (!(l.sheen > 0) || !s.valid) return t;
  // The scaling at the lobe's mean normal, as its sides take the cosines (lobe.h: clamped away from 0
  // where a spread lobe reflects past its mean horizon; exactly n·w for one texel). E is smooth in the
  // cosine, and the scaling multiplies the base lobe's own term, whose spread its sides carry.
  const float ci = glm::dot(s.n, p.wi), co = glm::dot(s.n, p.wo);
  const float e = std::max(sheen_albedo(std::clamp(co, 0.0f, 1.0f), roughness), sheen_albedo(std::clamp(ci, 0.0f, 1.0f), roughness));
  t.scaling = std::clamp(1.0f - l.sheen * e, 0.0f, 1.0f);
  if (!(sides > 0)) return t;
  const double alpha = sheen_alpha(roughness);
  // One texel's normal, or texels sharing one: the texel's own term, its sides being max(0, n·wi) and
  // [n·wo > 0]. Spread normals: their mean term, which holds its own sides.
  double lobe, side_factor = sides;
  if (s.sigma > 0) {
    lobe = spread_sheen(s, p, alpha);
    side_factor = 1.0;
  } else {
    lobe = sheen_distribution(glm::dot(s.n, p.h), alpha) * sheen_visibility(ci, co, alpha);
  }
  t.sheen = static_cast<float>(double(l.weight) * l.sheen * lobe * side_factor * p.inv_wi_z);
  return t;
}

}  // namespace svbrdf
