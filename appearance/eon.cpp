#include "appearance/eon.h"

#include <algorithm>

#include "base/math.h"

namespace svbrdf {

float eon_fon_albedo(float mu, float r) {
  constexpr float c1 = 0.5f - 2.0f / (3.0f * kPi);
  const float mc = 1.0f - mu;
  const float g_over_pi = mc * (0.0571085289f + mc * (0.491881867f + mc * (-0.332181442f + mc * 0.0714429953f)));
  return (1.0f + r * g_over_pi) / (1.0f + c1 * r);
}

Rgb eon_eval(const Rgb& rho, float r, const glm::vec3& wi, const glm::vec3& wo) {
  constexpr float c1 = 0.5f - 2.0f / (3.0f * kPi);
  constexpr float c2 = 2.0f / 3.0f - 28.0f / (15.0f * kPi);
  const float mi = wi.z, mo = wo.z;
  const float s = glm::dot(wi, wo) - mi * mo;
  const float s_over_t = s > 0.0f ? s / std::max(mi, mo) : s;
  const float af = 1.0f / (1.0f + c1 * r);
  const Rgb f_ss = rho * kInvPi * (af * (1.0f + r * s_over_t));
  const float avg = af * (1.0f + c2 * r);
  const Rgb rho_ms = rho * rho * avg / (Rgb(1.0f) - rho * (1.0f - avg));
  const float e_o = eon_fon_albedo(mo, r), e_i = eon_fon_albedo(mi, r);
  const float eps = 1e-7f;
  const Rgb f_ms = rho_ms * kInvPi *
                   (std::max(eps, 1.0f - e_o) * std::max(eps, 1.0f - e_i) / std::max(eps, 1.0f - avg));
  return f_ss + f_ms;
}

}  // namespace svbrdf
