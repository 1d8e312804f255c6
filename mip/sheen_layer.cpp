#include "mip/sheen_layer.h"

#include <algorithm>

#include "appearance/sheen.h"

namespace svbrdf {

SheenTerms sheen_terms(const SheenLayer& sheen, const glm::dvec3& n, const PairTerms<double>& p) {
  SheenTerms t;
  const double ci = glm::dot(n, p.wi), co = glm::dot(n, p.wo);
  if (!p.valid || !(ci > 0) || !(co > 0)) return t;
  const double alpha = sheen_alpha(sheen.roughness);
  const double lobe = sheen_distribution(glm::dot(n, p.h), alpha) * sheen_visibility(ci, co, alpha);
  t.f = glm::dvec3(sheen.color) * (lobe * ci * p.inv_wi_z);
  const double c = std::max(sheen.color.r, std::max(sheen.color.g, sheen.color.b));
  const double e = std::max(sheen_albedo(static_cast<float>(co), sheen.roughness),
                            sheen_albedo(static_cast<float>(ci), sheen.roughness));
  t.scaling = std::clamp(1.0 - c * e, 0.0, 1.0);
  return t;
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
