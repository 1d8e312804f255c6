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

}  // namespace svbrdf
