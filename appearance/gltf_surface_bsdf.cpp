#include "appearance/gltf_surface_bsdf.h"

#include <algorithm>
#include <cmath>

#include "appearance/eon.h"
#include "appearance/frame.h"
#include "appearance/gltf.h"
#include "appearance/microfacet_distribution.h"
#include "appearance/sampling.h"
#include "appearance/sheen.h"
#include "appearance/thin_film.h"

namespace svbrdf {

namespace {

// KHR_materials_clearcoat fixes the coat's ior at 1.5: F0 = ((1.5 − 1)/(1.5 + 1))² = 0.04.
constexpr float kCoatF0 = 0.04f;

}  // namespace

float clearcoat_blend(float clearcoat, float cos_view) {
  if (!(clearcoat > 0.0f)) return 0.0f;
  return clearcoat * (kCoatF0 + (1.0f - kCoatF0) * schlick_weight(std::min(std::abs(cos_view), 1.0f)));
}

SurfaceBsdf::SurfaceBsdf(const ShadingParams& p) : p_(p) {
  alpha_ = gltf_alpha(std::clamp(p.roughness, 0.0f, 1.0f));
  const float q = (p.ior - 1.0f) / (p.ior + 1.0f);
  f0_ = glm::min(Rgb(q * q) * p.specular_color, Rgb(1.0f));
  p_.metallic = std::clamp(p.metallic, 0.0f, 1.0f);
  p_.transmission = std::clamp(p.transmission, 0.0f, 1.0f);
  p_.specular = std::clamp(p.specular, 0.0f, 1.0f);
  p_.anisotropy = std::clamp(p.anisotropy, 0.0f, 1.0f);
  p_.clearcoat = std::clamp(p.clearcoat, 0.0f, 1.0f);
  p_.diffuse_transmission = std::clamp(p.diffuse_transmission, 0.0f, 1.0f);
  // KHR_materials_anisotropy: the direction of increased roughness gets mix(α, 1, strength²).
  anisotropic_ = p_.anisotropy > 0.0f;
  const float s2 = p_.anisotropy * p_.anisotropy;
  alpha_aniso_ = glm::vec2(alpha_ + (1.0f - alpha_) * s2, alpha_);
  const float dl = glm::length(p.anisotropy_direction);
  p_.anisotropy_direction = dl > 0.0f && std::isfinite(dl) ? p.anisotropy_direction / dl : glm::vec2(1.0f, 0.0f);
  coat_alpha_ = gltf_alpha(std::clamp(p.clearcoat_roughness, 0.0f, 1.0f));
  const float nl = glm::length(p.clearcoat_normal);
  p_.clearcoat_normal = nl > 0.0f && std::isfinite(nl) ? p.clearcoat_normal / nl : glm::vec3(0.0f, 0.0f, 1.0f);
  const Frame cf = Frame::from_normal(p_.clearcoat_normal);
  coat_t_ = cf.s, coat_b_ = cf.t;
  transmission_weight_ = (1.0f - p_.metallic) * p_.transmission * max_channel(p_.base_color);
  thin_transmission_ = p_.thin_walled && transmission_weight_ > 0.0f;
}

glm::vec3 SurfaceBsdf::to_anisotropy(const glm::vec3& w) const {
  const glm::vec2 d = p_.anisotropy_direction;
  return {d.x * w.x + d.y * w.y, -d.y * w.x + d.x * w.y, w.z};
}

glm::vec3 SurfaceBsdf::from_anisotropy(const glm::vec3& w) const {
  const glm::vec2 d = p_.anisotropy_direction;
  return {d.x * w.x - d.y * w.y, d.y * w.x + d.x * w.y, w.z};
}

float SurfaceBsdf::coat_blend(const glm::vec3& wo) const {
  return clearcoat_blend(p_.clearcoat, glm::dot(wo, p_.clearcoat_normal));
}

Rgb SurfaceBsdf::diffuse_f(const glm::vec3& wi, const glm::vec3& wo) const {
  if (p_.diffuse_roughness > 0.0f) return eon_eval(p_.base_color, std::min(p_.diffuse_roughness, 1.0f), wi, wo);
  return p_.base_color * kInvPi;
}

float SurfaceBsdf::specular_vd(const glm::vec3& wi, const glm::vec3& wo, const glm::vec3& h) const {
  if (!anisotropic_) return smith_ggx_visibility(alpha_ * alpha_, wi.z, wo.z) * ggx_d(alpha_, h);
  return ggx_visibility(alpha_aniso_, to_anisotropy(wi), to_anisotropy(wo)) * ggx_d(alpha_aniso_, to_anisotropy(h));
}

float SurfaceBsdf::specular_pdf(const glm::vec3& wi, const glm::vec3& wo) const {
  // Visible-normal density D_wo(h) = G1(wo)·max(0, wo·h)·D(h)/wo.z, over the reflection Jacobian 4·(wo·h).
  const glm::vec3 h = glm::normalize(wi + wo);
  if (!anisotropic_) return (1.0f / (1.0f + ggx_lambda(alpha_, wo))) * ggx_d(alpha_, h) / (4.0f * wo.z);
  return ggx_d(alpha_aniso_, to_anisotropy(h)) / ((1.0f + ggx_lambda(alpha_aniso_, to_anisotropy(wo))) * 4.0f * wo.z);
}

glm::vec3 SurfaceBsdf::sample_specular_normal(const glm::vec3& wo, const glm::vec2& u) const {
  if (!anisotropic_) return sample_ggx_visible(alpha_, wo, u);
  return from_anisotropy(sample_ggx_visible(alpha_aniso_, to_anisotropy(wo), u));
}

float SurfaceBsdf::coat_vd(const glm::vec3& wi, const glm::vec3& wo) const {
  const glm::vec3& n = p_.clearcoat_normal;
  const float ci = glm::dot(wi, n), co = glm::dot(wo, n);
  if (ci <= 0.0f || co <= 0.0f) return 0.0f;
  const glm::vec3 h = wi + wo;
  const glm::vec3 hc(glm::dot(h, coat_t_), glm::dot(h, coat_b_), glm::dot(h, n));
  return smith_ggx_visibility(coat_alpha_ * coat_alpha_, ci, co) * ggx_d(coat_alpha_, hc);
}

float SurfaceBsdf::coat_pdf(const glm::vec3& wi, const glm::vec3& wo) const {
  const glm::vec3& n = p_.clearcoat_normal;
  const float ci = glm::dot(wi, n), co = glm::dot(wo, n);
  if (ci <= 0.0f || co <= 0.0f) return 0.0f;
  const glm::vec3 h = wi + wo;
  const glm::vec3 hc(glm::dot(h, coat_t_), glm::dot(h, coat_b_), glm::dot(h, n));
  const glm::vec3 woc(glm::dot(wo, coat_t_), glm::dot(wo, coat_b_), co);
  return ggx_d(coat_alpha_, hc) / ((1.0f + ggx_lambda(coat_alpha_, woc)) * 4.0f * co);
}

Rgb SurfaceBsdf::dielectric_fresnel(float c, float w) const {
  if (!p_.thin_walled && p_.eta < 1.0f) {
    // Leaving the denser medium: Schlick's approximation holds at the angle on the rarer side.
    const float sin2_t = std::max(0.0f, 1.0f - c * c) / (p_.eta * p_.eta);
    if (sin2_t >= 1.0f) return Rgb(1.0f);  // total internal reflection
    c = std::sqrt(1.0f - sin2_t);
    w = schlick_weight(c);
  }
  const Rgb schlick = f0_ + (Rgb(1.0f) - f0_) * w;
  if (!(p_.iridescence > 0.0f)) return schlick;
  const Rgb film = iridescence_fresnel(c, p_.iridescence_thickness, p_.iridescence_ior, f0_);
  return glm::mix(schlick, film, p_.iridescence);
}

Rgb SurfaceBsdf::metal_fresnel(float c, float w) const {
  const Rgb schlick = p_.base_color + (Rgb(1.0f) - p_.base_color) * w;
  if (!(p_.iridescence > 0.0f)) return schlick;
  const Rgb film = iridescence_fresnel(c, p_.iridescence_thickness, p_.iridescence_ior, p_.base_color);
  return glm::mix(schlick, film, p_.iridescence);
}

Rgb SurfaceBsdf::base_f(const glm::vec3& wi, const glm::vec3& wo) const {
  const glm::vec3 h = glm::normalize(wi + wo);
  const float s = specular_vd(wi, wo, h);
  const float c = std::abs(glm::dot(wo, h));
  const float w = schlick_weight(c);
  Rgb base = (1.0f - p_.transmission) * diffuse_f(wi, wo);
  if (p_.diffuse_transmission > 0.0f) base *= 1.0f - p_.diffuse_transmission;
  const Rgb material = gltf_layers(metal_fresnel(c, w), p_.metallic, base, dielectric_fresnel(c, w), p_.specular, s);
  if (!has_sheen()) return material;
  return sheen_brdf(wi, wo, p_.sheen_color, p_.sheen_roughness) +
         material * sheen_albedo_scaling(wi, wo, p_.sheen_color, p_.sheen_roughness);
}

Rgb SurfaceBsdf::diffuse_transmission_f(const glm::vec3& wi, const glm::vec3& wo) const {
  const float c = std::min(wo.z, 1.0f);
  const Rgb fr = dielectric_fresnel(c, schlick_weight(c));
  Rgb f = (1.0f - coat_blend(wo)) * (1.0f - p_.metallic) * (1.0f - p_.transmission) * p_.diffuse_transmission *
          (1.0f - p_.specular * max_channel(fr)) * p_.diffuse_transmission_color * kInvPi;
  if (has_sheen()) f *= sheen_albedo_scaling(glm::vec3(wi.x, wi.y, -wi.z), wo, p_.sheen_color, p_.sheen_roughness);
  return f;
}

Rgb SurfaceBsdf::specular_transmission_f(const glm::vec3& wi, const glm::vec3& wo) const {
  const glm::vec3 wm = mirrored(wi);
  const glm::vec3 h = glm::normalize(wm + wo);
  const float c = std::min(std::abs(glm::dot(wo, h)), 1.0f);
  const Rgb fr = dielectric_fresnel(c, schlick_weight(c));
  Rgb f = ((1.0f - coat_blend(wo)) * (1.0f - p_.metallic) * p_.transmission * (1.0f - p_.specular * max_channel(fr)) *
           specular_vd(wm, wo, h)) *
          p_.base_color;
  if (has_sheen()) f *= sheen_albedo_scaling(wm, wo, p_.sheen_color, p_.sheen_roughness);
  return f;
}

Rgb SurfaceBsdf::eval(const glm::vec3& wi, const glm::vec3& wo) const {
  // The whole BSDF, coat included, vanishes below the shading horizon but for the transmissions:
  // the integrator's cosine is the shading normal's, and a coat normal tilted off it would
  // otherwise reflect with a negative one.
  if (wo.z <= 0.0f) return Rgb(0.0f);
  if (wi.z < 0.0f) {
    Rgb f(0.0f);
    if (diffuse_transmits()) f += diffuse_transmission_f(wi, wo);
    if (thin_transmission_) f += specular_transmission_f(wi, wo);
    return f;
  }
  if (wi.z <= 0.0f) return Rgb(0.0f);
  if (p_.clearcoat <= 0.0f) return base_f(wi, wo);
  const float blend = coat_blend(wo);
  return blend * coat_vd(wi, wo) + (1.0f - blend) * base_f(wi, wo);
}

Rgb SurfaceBsdf::transmission_magnitude(const glm::vec3& w) const {
  const float c = std::min(std::abs(w.z), 1.0f);
  const Rgb fr = dielectric_fresnel(c, schlick_weight(c));
  Rgb m = (1.0f - coat_blend(w)) * (1.0f - p_.metallic) * p_.transmission * (1.0f - p_.specular * max_channel(fr)) *
          p_.base_color;
  // The sheen's albedo scaling at (w, −w), whose cosines are equal: 1 − max(sheenColor)·E(|w.z|).
  if (has_sheen()) m *= std::clamp(1.0f - max_channel(p_.sheen_color) * sheen_albedo(c, p_.sheen_roughness), 0.0f, 1.0f);
  return m;
}

bool SurfaceBsdf::transmitted(const glm::vec3& w, glm::vec3& wt, Rgb& magnitude) const {
  if (!has_impulse()) return false;
  if (!refract_through(w, p_.eta, wt)) return false;
  magnitude = transmission_magnitude(w) / (p_.eta * p_.eta);
  return max_channel(magnitude) > 0.0f;
}

Impulses SurfaceBsdf::impulses_in(const glm::vec3& wo) const {
  Impulses im;
  glm::vec3 wt;
  Rgb m;
  if (wo.z > 0.0f && transmitted(wo, wt, m)) im.add(wt, m);
  return im;
}

Impulses SurfaceBsdf::impulses_out(const glm::vec3& wi) const {
  // Light from this side crosses as a view from it would (impulses_in); light from the far side
  // (wi.z < 0) leaves toward this side along the reverse of that path, with its magnitude.
  if (wi.z > 0.0f) return impulses_in(wi);
  Impulses im;
  if (!has_impulse() || wi.z == 0.0f) return im;
  glm::vec3 wo;
  if (!refract_through(wi, 1.0f / p_.eta, wo)) return im;
  glm::vec3 wt;
  Rgb m;
  if (transmitted(wo, wt, m)) im.add(wo, m);
  return im;
}

SurfaceBsdf::LobeChoice SurfaceBsdf::choose(const glm::vec3& wo) const {
  // Probabilities proportional to each lobe's approximate weight at wo (Fresnel at n·wo; the
  // sheen's and the coat's own albedo-like weights over what they cover).
  LobeChoice c;
  if (wo.z > 0.0f) {
    c.coat = coat_blend(wo);
    float under = 1.0f - c.coat;
    if (has_sheen()) {
      const float e = max_channel(p_.sheen_color) * sheen_albedo(std::min(wo.z, 1.0f), p_.sheen_roughness);
      c.sheen = under * std::clamp(e, 0.0f, 1.0f);
      under *= std::clamp(1.0f - e, 0.0f, 1.0f);
    }
    const float cos_o = std::min(wo.z, 1.0f);
    const float fr = max_channel(dielectric_fresnel(cos_o, schlick_weight(cos_o)));
    const float spec_d = p_.specular * fr;
    const float rest = under * (1.0f - p_.metallic) * (1.0f - spec_d) * max_channel(p_.base_color);
    // The metal's share by its Fresnel reflectance, not 1: a dark metal under a coat would otherwise
    // draw its own lobe where the coat's reflection dominates.
    const float metal = max_channel(p_.base_color + (Rgb(1.0f) - p_.base_color) * schlick_weight(cos_o));
    c.specular = under * (p_.metallic * metal + (1.0f - p_.metallic) * spec_d);
    c.diffuse = rest * (1.0f - p_.transmission);
    c.transmission = rest * p_.transmission;
    if (diffuse_transmits()) {
      c.diffuse *= 1.0f - p_.diffuse_transmission;
      c.diffuse_transmission = under * (1.0f - p_.metallic) * (1.0f - spec_d) * (1.0f - p_.transmission) *
                               p_.diffuse_transmission * max_channel(p_.diffuse_transmission_color);
    }
  }
  const float sum = c.coat + c.specular + c.sheen + c.diffuse + c.diffuse_transmission + c.transmission;
  if (!(sum > 0.0f)) return LobeChoice{};
  c.coat /= sum, c.specular /= sum, c.sheen /= sum, c.diffuse /= sum, c.diffuse_transmission /= sum;
  c.transmission /= sum;
  return c;
}

float SurfaceBsdf::pdf(const glm::vec3& wi, const glm::vec3& wo) const {
  if (wo.z <= 0.0f) return 0.0f;
  if (wi.z < 0.0f) {
    if (!transmits_finitely()) return 0.0f;
    const LobeChoice c = choose(wo);
    float p = c.diffuse_transmission * -wi.z * kInvPi;
    if (thin_transmission_ && c.transmission > 0.0f) p += c.transmission * specular_pdf(mirrored(wi), wo);
    return p;
  }
  if (wi.z == 0.0f) return 0.0f;
  const LobeChoice c = choose(wo);
  float p = c.diffuse * wi.z * kInvPi;
  if (c.specular > 0.0f) p += c.specular * specular_pdf(wi, wo);
  if (c.coat > 0.0f) p += c.coat * coat_pdf(wi, wo);
  if (c.sheen > 0.0f) p += c.sheen * sheen_pdf(wi, wo);
  return p;
}

BsdfSample SurfaceBsdf::sample(const glm::vec3& wo, const SampleU& u) const {
  BsdfSample out;
  const LobeChoice c = choose(wo);
  const glm::vec2 uv(u.y, u.z);
  glm::vec3 wi;
  bool transmitting = false;
  if (u.x < c.transmission && thin_transmission_) {
    // The reflection's visible normals, the reflected direction mirrored through the surface plane
    // (specular_transmission_f's H_T is then the sampled normal).
    wi = mirrored(reflect_about(wo, sample_specular_normal(wo, uv)));
    transmitting = true;
  } else if (u.x < c.transmission) {
    Rgb m;
    if (!transmitted(wo, out.wi, m)) return out;
    out.pdf = c.transmission;
    out.weight = m / c.transmission;
    out.kind = SampleKind::impulse;
    return out;
  } else if (u.x < c.transmission + c.coat) {
    const glm::vec3& n = p_.clearcoat_normal;
    const glm::vec3 woc(glm::dot(wo, coat_t_), glm::dot(wo, coat_b_), glm::dot(wo, n));
    const glm::vec3 hc = sample_ggx_visible(coat_alpha_, woc, uv);
    wi = reflect_about(wo, hc.x * coat_t_ + hc.y * coat_b_ + hc.z * n);
  } else if (u.x < c.transmission + c.coat + c.specular) {
    wi = reflect_about(wo, sample_specular_normal(wo, uv));
  } else if (u.x < c.transmission + c.coat + c.specular + c.sheen) {
    wi = sample_sheen(uv);
  } else if (u.x < c.transmission + c.coat + c.specular + c.sheen + c.diffuse) {
    wi = sample_cosine_hemisphere(uv);
  } else if (c.diffuse_transmission > 0.0f) {
    wi = sample_cosine_hemisphere(uv);
    wi.z = -wi.z;
    transmitting = true;
  } else {
    return out;
  }
  // A reflection below the horizon is absorbed (pdf counts only the transmission there).
  if (transmitting ? !(wi.z < 0.0f) : !(wi.z > 0.0f)) return out;
  const float p = pdf(wi, wo);
  if (!(p > 0.0f)) return out;
  out.wi = wi;
  out.pdf = p;
  out.weight = eval(wi, wo) * (std::abs(wi.z) / p);
  out.kind = SampleKind::finite;
  return out;
}

}  // namespace svbrdf
