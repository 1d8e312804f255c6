#include "mip/sheen_layer.h"

#include <algorithm>
#include <array>

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

SheenLobeTerms sheen_lobe_terms(const Lobe& l, const LobeShape<float>& s, const PairTerms<float>& p, float sides,
                                float roughness) {
  SheenLobeTerms t;
  if (!(l.sheen > 0) || !s.valid) return t;
  // The cosines to the lobe's mean normal, as its sides take them (lobe.h: clamped away from 0 where a
  // spread lobe reflects past its mean horizon; exactly n·w for one texel).
  const float ci = glm::dot(s.n, p.wi), co = glm::dot(s.n, p.wo);
  const float e = std::max(sheen_albedo(std::clamp(co, 0.0f, 1.0f), roughness), sheen_albedo(std::clamp(ci, 0.0f, 1.0f), roughness));
  t.scaling = std::clamp(1.0f - l.sheen * e, 0.0f, 1.0f);
  if (!(sides > 0)) return t;
  const double alpha = sheen_alpha(roughness);
  const double c_i = s.sigma == 0 ? ci : std::max(ci, 1e-4f), c_o = s.sigma == 0 ? co : std::max(co, 1e-4f);
  const double lobe = sheen_distribution(glm::dot(s.n, p.h), alpha) * sheen_visibility(c_i, c_o, alpha);
  t.sheen = static_cast<float>(double(l.weight) * l.sheen * lobe * sides * p.inv_wi_z);
  return t;
}

}  // namespace svbrdf
