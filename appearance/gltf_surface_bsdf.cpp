#include "appearance/gltf_surface_bsdf.h"

#include <algorithm>
#include <cmath>

#include "appearance/gltf.h"
#include "appearance/microfacet_distribution.h"
#include "appearance/sampling.h"

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

SurfaceBsdf::SurfaceBsdf(const ShadingParams& p) : p_(p) {
  alpha_ = gltf_alpha(std::clamp(p.roughness, 0.0f, 1.0f));
  const float q = (p.ior - 1.0f) / (p.ior + 1.0f);
  f0_ = glm::min(Rgb(q * q) * p.specular_color, Rgb(1.0f));
  p_.metallic = std::clamp(p.metallic, 0.0f, 1.0f);
  p_.transmission = std::clamp(p.transmission, 0.0f, 1.0f);
  p_.specular = std::clamp(p.specular, 0.0f, 1.0f);
  transmission_weight_ = (1.0f - p_.metallic) * p_.transmission * max_channel(p_.base_color);
}

Rgb SurfaceBsdf::diffuse_f(const glm::vec3& wi, const glm::vec3& wo) const {
  if (p_.diffuse_roughness > 0.0f) return eon_eval(p_.base_color, std::min(p_.diffuse_roughness, 1.0f), wi, wo);
  return p_.base_color * kInvPi;
}

Rgb SurfaceBsdf::eval(const glm::vec3& wi, const glm::vec3& wo) const {
  if (wi.z <= 0.0f || wo.z <= 0.0f) return Rgb(0.0f);
  const glm::vec3 h = glm::normalize(wi + wo);
  const float a2 = alpha_ * alpha_;
  const float s = smith_ggx_visibility(a2, wi.z, wo.z) * ggx_d(alpha_, h);
  const float w = schlick_weight(std::abs(glm::dot(wo, h)));
  const Rgb fr = f0_ + (Rgb(1.0f) - f0_) * w;
  const Rgb base = (1.0f - p_.transmission) * diffuse_f(wi, wo);
  return gltf_layers(p_.base_color, p_.metallic, base, fr, p_.specular, s, w);
}

Rgb SurfaceBsdf::transmission_magnitude(float cos_o) const {
  const Rgb fr = f0_ + (Rgb(1.0f) - f0_) * schlick_weight(std::abs(cos_o));
  return (1.0f - p_.metallic) * p_.transmission * (1.0f - p_.specular * max_channel(fr)) * p_.base_color;
}

Impulses SurfaceBsdf::impulses_in(const glm::vec3& wo) const {
  Impulses im;
  if (transmission_weight_ > 0.0f) im.add(-wo, transmission_magnitude(wo.z));
  return im;
}

Impulses SurfaceBsdf::impulses_out(const glm::vec3& wi) const {
  Impulses im;
  if (transmission_weight_ > 0.0f) im.add(-wi, transmission_magnitude(wi.z));
  return im;
}

SurfaceBsdf::LobeChoice SurfaceBsdf::choose(const glm::vec3& wo) const {
  // Probabilities proportional to each lobe's approximate weight at wo (Fresnel at n·wo).
  const float fr = max_channel(f0_ + (Rgb(1.0f) - f0_) * schlick_weight(std::clamp(wo.z, 0.0f, 1.0f)));
  const float spec_d = p_.specular * fr;
  const float rest = (1.0f - p_.metallic) * (1.0f - spec_d) * max_channel(p_.base_color);
  LobeChoice c;
  c.specular = p_.metallic + (1.0f - p_.metallic) * spec_d;
  c.diffuse = rest * (1.0f - p_.transmission);
  c.transmission = rest * p_.transmission;
  const float sum = c.specular + c.diffuse + c.transmission;
  if (!(sum > 0.0f)) return LobeChoice{};
  c.specular /= sum, c.diffuse /= sum, c.transmission /= sum;
  return c;
}

float SurfaceBsdf::pdf(const glm::vec3& wi, const glm::vec3& wo) const {
  if (wi.z <= 0.0f || wo.z <= 0.0f) return 0.0f;
  const LobeChoice c = choose(wo);
  float p = c.diffuse * wi.z * kInvPi;
  if (c.specular > 0.0f) {
    const glm::vec3 h = glm::normalize(wi + wo);
    // Visible-normal density D_wo(h) = G1(wo)·max(0, wo·h)·D(h)/wo.z, over the reflection Jacobian 4·(wo·h).
    p += c.specular * (1.0f / (1.0f + ggx_lambda(alpha_, wo))) * ggx_d(alpha_, h) / (4.0f * wo.z);
  }
  return p;
}

BsdfSample SurfaceBsdf::sample(const glm::vec3& wo, const SampleU& u) const {
  BsdfSample out;
  if (wo.z <= 0.0f) return out;
  const LobeChoice c = choose(wo);
  const glm::vec2 uv(u.y, u.z);
  glm::vec3 wi;
  if (u.x < c.transmission) {
    out.wi = -wo;
    out.pdf = c.transmission;
    out.weight = transmission_magnitude(wo.z) / c.transmission;
    out.kind = SampleKind::impulse;
    return out;
  } else if (u.x < c.transmission + c.specular) {
    const glm::vec3 h = sample_ggx_visible(alpha_, wo, uv);
    wi = 2.0f * glm::dot(wo, h) * h - wo;
  } else if (c.diffuse > 0.0f) {
    wi = sample_cosine_hemisphere(uv);
  } else {
    return out;
  }
  if (wi.z <= 0.0f) return out;  // below the horizon: absorbed
  const float p = pdf(wi, wo);
  if (!(p > 0.0f)) return out;
  out.wi = wi;
  out.pdf = p;
  out.weight = eval(wi, wo) * (wi.z / p);
  out.kind = SampleKind::finite;
  return out;
}

}  // namespace svbrdf
