#include "mip/lobe_mixture_bsdf.h"

#include <algorithm>
#include <cmath>

#include "appearance/microfacet_distribution.h"
#include "appearance/sampling.h"

namespace svbrdf {

namespace {
float mean3(const glm::vec3& c) { return (c.x + c.y + c.z) * (1.0f / 3.0f); }
}  // namespace

void LobeMixtureBsdf::assign(std::span<const Lobe> lobes) {
  count_ = 0;
  for (const Lobe& l : lobes) {
    if (count_ == kMaxLobes) break;
    Slot& k = slots_[static_cast<std::size_t>(count_)].s;
    k.lobe = l;
    k.shape = lobe_shape<float>(l);
    if (!k.shape.valid) continue;
    // Albedo estimates for the choice: the diffuse term 0.96·ρ, the specular F0 plus Fresnel's rise.
    const float scale = l.weight * k.shape.len;
    k.diffuse_albedo = scale * 0.96f * mean3(l.diffuse);
    k.spec_albedo = scale * (mean3(l.f0) + 0.1f * (1.0f - mean3(l.f0)));
    ++count_;
  }
}

Rgb LobeMixtureBsdf::eval(const glm::vec3& wi, const glm::vec3& wo) const {
  const PairTerms<float> p = pair_terms<float>(wi, wo);
  if (!p.valid) return Rgb(0);
  Rgb f(0);
  for (int k = 0; k < count_; ++k) f += lobe_eval(slot(k).lobe, slot(k).shape, p);
  return f;
}

LobeMixtureBsdf::Choice LobeMixtureBsdf::choice(const glm::vec3& wo) const {
  Choice c;
  float total = 0;
  for (int k = 0; k < count_; ++k) {
    const std::size_t i = static_cast<std::size_t>(k);
    // The specular sampler needs wo above the lobe's own horizon.
    const bool spec_ok = glm::dot(slot(k).shape.n, wo) > 1e-4f;
    const float d = slot(k).diffuse_albedo, s = spec_ok ? slot(k).spec_albedo : 0.0f;
    c.lobe[i] = d + s;
    c.diffuse[i] = d + s > 0 ? d / (d + s) : 1.0f;
    total += d + s;
  }
  const float scale = total > 0 ? (1.0f - kDefensive) / total : 0.0f;
  for (int k = 0; k < count_; ++k) c.lobe[static_cast<std::size_t>(k)] *= scale;
  return c;
}

float LobeMixtureBsdf::pdf_with(const Choice& c, const glm::vec3& wi, const glm::vec3& wo) const {
  if (!(wi.z > 0) || !(wo.z > 0)) return 0.0f;
  float pdf = 0;
  float defensive = kDefensive;
  float used = 0;
  for (int k = 0; k < count_; ++k) used += c.lobe[static_cast<std::size_t>(k)];
  if (used == 0) defensive = 1.0f;  // no lobe to sample: all defensive
  pdf += defensive * cosine_hemisphere_pdf(wi.z);
  for (int k = 0; k < count_; ++k) {
    const std::size_t i = static_cast<std::size_t>(k);
    if (!(c.lobe[i] > 0)) continue;
    const glm::vec3 n = slot(k).shape.n;
    float p = c.diffuse[i] * cosine_hemisphere_pdf(glm::dot(n, wi));
    if (c.diffuse[i] < 1.0f) {
      const Frame fr = Frame::from_normal(n);
      const glm::vec3 wo_l = fr.to_local(wo), wi_l = fr.to_local(wi);
      const glm::vec3 hsum = wi_l + wo_l;
      const float len = glm::length(hsum);
      if (len > 0) {
        const glm::vec3 h = hsum / len;
        const float oh = glm::dot(wo_l, h);
        if (oh > 0) {
          const LobeShape<float>& sh = slot(k).shape;
          float vis = ggx_visible_pdf(std::sqrt(sh.alpha2), wo_l, h);
          if (sh.lmean > 0) vis = 0.5f * (vis + ggx_visible_pdf(std::sqrt(sh.alpha2_hi), wo_l, h));
          p += (1.0f - c.diffuse[i]) * vis / (4.0f * oh);
        }
      }
    }
    pdf += c.lobe[i] * p;
  }
  return pdf;
}

float LobeMixtureBsdf::pdf(const glm::vec3& wi, const glm::vec3& wo) const { return pdf_with(choice(wo), wi, wo); }

BsdfSample LobeMixtureBsdf::sample(const glm::vec3& wo, const SampleU& u) const {
  BsdfSample s;
  if (!(wo.z > 0)) return s;
  const Choice c = choice(wo);
  float ux = u.x;
  glm::vec3 wi(0, 0, 1);
  int picked = -1;
  float acc = 0;
  for (int k = 0; k < count_; ++k) {
    const float q = c.lobe[static_cast<std::size_t>(k)];
    if (q > 0 && ux < acc + q) {
      picked = k;
      ux = (ux - acc) / q;
      break;
    }
    acc += q;
  }
  const glm::vec2 uv(u.y, u.z);
  if (picked < 0) {
    wi = sample_cosine_hemisphere(uv);
  } else {
    const std::size_t i = static_cast<std::size_t>(picked);
    const Frame fr = Frame::from_normal(slot(picked).shape.n);
    if (ux < c.diffuse[i]) {
      wi = fr.to_world(sample_cosine_hemisphere(uv));
    } else {
      const glm::vec3 wo_l = fr.to_local(wo);
      // A roughness mixture (lobe.h) is sampled half from each end of its α² range.
      const LobeShape<float>& sh = slot(picked).shape;
      const bool upper = sh.lmean > 0 && (ux - c.diffuse[i]) >= 0.5f * (1.0f - c.diffuse[i]);
      const glm::vec3 h = sample_ggx_visible(std::sqrt(upper ? sh.alpha2_hi : sh.alpha2), wo_l, uv);
      wi = fr.to_world(2.0f * glm::dot(wo_l, h) * h - wo_l);
    }
  }
  s.wi = wi;
  s.pdf = pdf_with(c, wi, wo);
  if (!(wi.z > 0) || !(s.pdf > 0)) {
    s.kind = SampleKind::absorbed;
    s.weight = Rgb(0);
    return s;
  }
  s.kind = SampleKind::finite;
  s.weight = eval(wi, wo) * (wi.z / s.pdf);
  return s;
}

}  // namespace svbrdf
