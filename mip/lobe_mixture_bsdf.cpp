#include "mip/lobe_mixture_bsdf.h"

#include <algorithm>
#include <cmath>

#include "appearance/microfacet_distribution.h"
#include "appearance/sampling.h"
#include "appearance/sheen.h"
#include "mip/coat_layer.h"
#include "mip/diffuse_transmission.h"
#include "mip/sheen_layer.h"

namespace svbrdf {

namespace {
float mean3(const glm::vec3& c) { return (c.x + c.y + c.z) * (1.0f / 3.0f); }

// The density of the specular sampler of a lobe (GGX visible normals about n, Heitz 2018) for the
// reflected direction, from the cosines alone: D_wo(h)/(4·(wo·h)) = G1(wo)·D(h)/(4·(n·wo)) with
// G1 = 2/(1 + √(1 + α²·tan²θo)) and D = α²/(π·(|n×h|² + (n·h)²·α²)²) (Walter et al. 2007, eqs. 33, 34;
// Heitz 2014, eq. 2). |n×h|² rather than 1 − (n·h)² keeps the peak of sharp lobes exact. For a stretched
// lobe (lobe.h) the same with its stretched |n×h|² (shape_sin2) and tan²θo (stretched_tangent2 / co²):
// the anisotropic GGX of α_t = α·√r, α_b = α/√r (Heitz 2014, eqs. 85–86), whose visible normals the
// sampler draws with those two α.
float ggx_reflection_pdf(float alpha2, float co, float ch, float sin2h, float t2o) {
  const float g1 = 2.0f / (1.0f + std::sqrt(1.0f + alpha2 * t2o));
  const float q = sin2h + ch * ch * alpha2;
  return g1 * alpha2 * kInvPi / (q * q * 4.0f * co);
}

}  // namespace

bool LobeMixtureBsdf::fill_slot(int at, const Lobe& l) {
  Slot& k = slots_[static_cast<std::size_t>(at)].s;
  k.lobe = l;
  k.shape = lobe_shape<float>(l);
  if (!k.shape.valid) return false;
  // Albedo estimates for the choice: the diffuse term 0.96·ρ (and ρ90 at grazing angles), the
  // specular F0 plus Fresnel's rise toward F90 (a coat lobe's: 0.04 and 1, no diffuse).
  const float scale = l.weight * k.shape.len;
  k.diffuse_albedo = scale * (0.96f * mean3(l.diffuse) + 0.05f * mean3(l.diffuse90));
  k.spec_albedo = scale * (mean3(l.f0) + 0.1f * (l.f90 - mean3(l.f0)));
  k.trans_albedo = scale * (mean3(l.transmission) + 0.1f * (mean3(l.transmission90) - mean3(l.transmission)));
  k.dtrans_albedo = scale * (mean3(l.diffuse_transmission) +
                             0.1f * (mean3(l.diffuse_transmission90) - mean3(l.diffuse_transmission)));
  return true;
}

void LobeMixtureBsdf::assign(std::span<const Lobe> lobes, std::span<const Lobe> coat) {
  correction_ = nullptr;
  own_correction_ = false;
  sheen_on_ = false;
  count_ = 0;
  coat_count_ = 0;
  transmits_ = false;
  for (const Lobe& l : lobes)
    if (count_ < kMaxLobes && fill_slot(count_, l)) {
      transmits_ = transmits_ || transmits(l) || diffuse_transmits(l);
      ++count_;
    }
  for (const Lobe& l : coat)
    if (coat_count_ < kMaxLobes && l.weight > 0 && fill_slot(count_ + coat_count_, l)) ++coat_count_;
}

void LobeMixtureBsdf::set_sheen(const SheenLayer& sheen) {
  sheen_on_ = false;
  float shares = 0;
  for (int k = 0; k < count_; ++k) shares += slot(k).lobe.weight * slot(k).lobe.sheen;
  if (!(shares > 0) || !(std::max(sheen.color.r, std::max(sheen.color.g, sheen.color.b)) > 0)) return;
  sheen_on_ = true;
  sheen_roughness_ = sheen.roughness;
  sheen_scale_ = sheen.color / shares;
  sheen_albedo_ = mean3(sheen.color);
}

Rgb LobeMixtureBsdf::transmission_eval(const glm::vec3& wi, const glm::vec3& wo) const {
  // Each base lobe's transmission (lobe.h) and diffuse transmission (diffuse_transmission.h) under its
  // sheen's scaling at the mirrored pair, less what the coat reflects of them: coated_eval's layering
  // with no coat term below the surface. The radial correction is the reflection's and takes no part.
  // Both have the mirrored pair's sides, so either's `sides` is the sheen's.
  Rgb f(0), coated(0);
  for (int k = 0; k < count_; ++k) {
    const Slot& sk = slot(k);
    const bool specular = transmits(sk.lobe), diffuse = diffuse_transmits(sk.lobe);
    if (!specular && !diffuse) continue;
    float sides = 0;
    Rgb fk(0);
    if (specular) fk = lobe_transmission_eval(sk.lobe, sk.shape, wi, wo, 1.0f, &sides);
    if (diffuse) fk += lobe_diffuse_transmission_eval(sk.lobe, sk.shape, wi, wo, &sides);
    if (sheen_on_ && sides > 0) {
      const PairTerms<float> m = transmission_pair(sk.shape, wi, wo);
      fk *= sheen_lobe_terms(sk.lobe, sk.shape, m, sides, sheen_roughness_).scaling;
    }
    f += fk;
    coated += sk.lobe.coat * fk;
  }
  if (coat_count_ == 0) return f;
  CoatFresnel<float> fresnel;
  for (int k = count_; k < count_ + coat_count_; ++k) fresnel.add(slot(k).lobe, slot(k).shape, wo);
  return f - fresnel.value() * coated;
}

Rgb LobeMixtureBsdf::eval(const glm::vec3& wi, const glm::vec3& wo) const {
  if (transmits_ && wi.z < 0 && wo.z > 0) return transmission_eval(wi, wo);
  const PairTerms<float> p = pair_terms<float>(wi, wo);
  if (!p.valid) return Rgb(0);
  Rgb f(0);
  const RadialCorrection* correction = own_correction_ ? &correction_copy_ : correction_;
  const float scale = correction ? correction_at(*correction, *grid_, p.h) : 1.0f;
  if (coat_count_ == 0 && !sheen_on_) {
    for (int k = 0; k < count_; ++k) f += lobe_eval(slot(k).lobe, slot(k).shape, p, scale);
    return f;
  }
  // The layered f_eff of coat_layer.h, as coated_eval writes it: the base lobes (the radial correction
  // is theirs), each under its sheen where there is one (sheen_layer.h), less what the coat reflects of
  // them, plus the coat lobes under the base's cosine factor. Each lobe's horizons and each coat lobe's
  // Schlick weight are evaluated once, for all their uses.
  Rgb coated(0);
  CoatCosine<float> cosine;
  for (int k = 0; k < count_; ++k) {
    float sides;
    Rgb fk = lobe_eval(slot(k).lobe, slot(k).shape, p, scale, &sides);
    if (sheen_on_) {
      const SheenLobeTerms t = sheen_lobe_terms(slot(k).lobe, slot(k).shape, p, sides, sheen_roughness_);
      fk = t.scaling * fk + t.sheen * sheen_scale_;
    }
    f += fk;
    coated += slot(k).lobe.coat * fk;
    cosine.add_sides(slot(k).lobe, slot(k).shape, sides);
  }
  if (coat_count_ == 0) return f;
  CoatFresnel<float> fresnel;
  Rgb coat(0);
  const float k_cos = cosine.value(p);
  for (int k = count_; k < count_ + coat_count_; ++k) {
    const float w = fresnel.add(slot(k).lobe, slot(k).shape, p.wo);
    if (k_cos > 0) coat += coat_lobe_eval(slot(k).lobe, slot(k).shape, p, w);
  }
  return f - fresnel.value() * coated + k_cos * coat;
}

LobeMixtureBsdf::Choice LobeMixtureBsdf::choice(const glm::vec3& wo) const {
  Choice c;
  float total = 0, transmitted = 0;
  const int n = count_ + coat_count_;
  for (int k = 0; k < n; ++k) {
    const std::size_t i = static_cast<std::size_t>(k);
    // The specular sampler needs wo above the lobe's own horizon.
    const bool spec_ok = glm::dot(slot(k).shape.n, wo) > 1e-4f;
    const float d = slot(k).diffuse_albedo, s = spec_ok ? slot(k).spec_albedo : 0.0f;
    const float t = spec_ok && k < count_ && transmits_ ? slot(k).trans_albedo : 0.0f;
    // The diffuse transmission's cosine sampler needs no view above the lobe's horizon (as the diffuse's).
    const float dt = k < count_ && transmits_ ? slot(k).dtrans_albedo : 0.0f;
    const float all = d + s + t + dt;
    c.lobe[i] = all;
    c.diffuse[i] = all > 0 ? d / all : 1.0f;
    c.transmit[i] = t > 0 ? t / all : 0.0f;  // no division per lobe and hit where nothing transmits
    c.dtrans[i] = dt > 0 ? dt / all : 0.0f;
    total += all;
    transmitted += t + dt;
  }
  if (sheen_on_ && wo.z > 0) {
    c.sheen = sheen_albedo_ * sheen_albedo(wo.z, sheen_roughness_);
    total += c.sheen;
  }
  const float scale = total > 0 ? (1.0f - kDefensive) / total : 0.0f;
  for (int k = 0; k < n; ++k) c.lobe[static_cast<std::size_t>(k)] *= scale;
  c.sheen *= scale;
  // The defensive share below the surface: the transmission's share of the albedo estimates.
  c.below = total > 0 ? transmitted / total : 0.0f;
  return c;
}

float LobeMixtureBsdf::transmission_pdf(const Choice& c, const glm::vec3& wi, const glm::vec3& wo) const {
  float pdf = kDefensive * c.below * cosine_hemisphere_pdf(-wi.z);
  // Each lobe's transmission is its specular sampler's direction mirrored through the lobe's plane, an
  // isometry: the density of wi is the reflection's at the mirrored wi'.
  for (int k = 0; k < count_; ++k) {
    const std::size_t i = static_cast<std::size_t>(k);
    if (!(c.lobe[i] > 0) || !(c.transmit[i] > 0)) continue;  // (the diffuse transmission's below)
    const LobeShape<float> ts = transmission_shape(slot(k).lobe, slot(k).shape);
    const PairTerms<float> m = transmission_pair(ts, wi, wo);
    if (m.valid && glm::dot(wo, m.h) > 0) pdf += c.lobe[i] * c.transmit[i] * specular_pdf(ts, wo, m.h);
  }
  // Each lobe's diffuse transmission: its diffuse sampler mirrored through its plane, cosine about −n̂.
  for (int k = 0; k < count_; ++k) {
    const std::size_t i = static_cast<std::size_t>(k);
    if (c.dtrans[i] > 0) pdf += c.lobe[i] * c.dtrans[i] * cosine_hemisphere_pdf(-glm::dot(slot(k).shape.n, wi));
  }
  return pdf;
}

float LobeMixtureBsdf::specular_pdf(const LobeShape<float>& sh, const glm::vec3& wo, const glm::vec3& h) {
  const float co = glm::dot(sh.n, wo), ch = glm::dot(sh.n, h);
  if (!(co > 0) || !(ch > 0)) return 0.0f;
  const float sin2h = shape_sin2(sh, glm::cross(sh.n, h));
  const float t2o = (sh.stretched ? stretched_tangent2(sh, wo) : std::max(0.0f, 1.0f - co * co)) / (co * co);
  const float p = ggx_reflection_pdf(sh.alpha2, co, ch, sin2h, t2o);
  // A roughness mixture is sampled half from each end of its range (sample below).
  return sh.alpha2_hi > 0 ? 0.5f * (p + ggx_reflection_pdf(sh.alpha2_hi, co, ch, sin2h, t2o)) : p;
}

float LobeMixtureBsdf::pdf_with(const Choice& c, const glm::vec3& wi, const glm::vec3& wo) const {
  if (transmits_ && wi.z < 0 && wo.z > 0) return transmission_pdf(c, wi, wo);
  if (!(wi.z > 0) || !(wo.z > 0)) return 0.0f;
  float pdf = 0;
  float defensive = kDefensive;
  float used = 0;
  for (int k = 0; k < count_ + coat_count_; ++k) used += c.lobe[static_cast<std::size_t>(k)];
  used += c.sheen;
  if (used == 0) defensive = 1.0f;  // no lobe to sample: all defensive
  pdf += defensive * (1.0f - c.below) * cosine_hemisphere_pdf(wi.z);
  pdf += c.sheen * sheen_pdf(wi, wo);
  // The half vector is every lobe's; each lobe's density needs only its cosines (no frame per lobe).
  const glm::vec3 hsum = wi + wo;
  const float hlen2 = glm::dot(hsum, hsum);
  const glm::vec3 h = hlen2 > 0 ? hsum * (1.0f / std::sqrt(hlen2)) : hsum;
  const bool h_ok = hlen2 > 0 && glm::dot(wo, h) > 0;
  for (int k = 0; k < count_ + coat_count_; ++k) {
    const std::size_t i = static_cast<std::size_t>(k);
    if (!(c.lobe[i] > 0)) continue;
    const LobeShape<float>& sh = slot(k).shape;
    float p = c.diffuse[i] * cosine_hemisphere_pdf(glm::dot(sh.n, wi));
    if (c.diffuse[i] + c.dtrans[i] + c.transmit[i] < 1.0f && h_ok)
      p += (1.0f - c.diffuse[i] - c.dtrans[i] - c.transmit[i]) * specular_pdf(sh, wo, h);
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
  for (int k = 0; k < count_ + coat_count_; ++k) {
    const float q = c.lobe[static_cast<std::size_t>(k)];
    if (q > 0 && ux < acc + q) {
      picked = k;
      ux = (ux - acc) / q;
      break;
    }
    acc += q;
  }
  const bool sheen = picked < 0 && c.sheen > 0 && ux < acc + c.sheen;
  const glm::vec2 uv(u.y, u.z);
  bool below = false;  // a transmission's sample: wi on the far side
  if (sheen) {
    wi = sample_sheen(uv);
  } else if (picked < 0) {
    // The defensive share, below the surface in proportion to the transmission's estimate.
    const float rest = ux - acc - c.sheen, defensive = 1.0f - acc - c.sheen;
    below = defensive > 0 && rest < c.below * defensive;
    wi = sample_cosine_hemisphere(uv);
    if (below) wi.z = -wi.z;
  } else {
    const std::size_t i = static_cast<std::size_t>(picked);
    const LobeShape<float>& sh = slot(picked).shape;
    // A stretched lobe's frame has its stretch direction for x (lobe.h); any frame about n otherwise.
    const auto frame_of = [](const LobeShape<float>& s) {
      return s.stretched ? Frame{s.st, s.sb, s.n} : Frame::from_normal(s.n);
    };
    if (ux < c.diffuse[i]) {
      wi = frame_of(sh).to_world(sample_cosine_hemisphere(uv));
    } else if (ux < c.diffuse[i] + c.dtrans[i]) {
      // The diffuse transmission: the diffuse part's direction mirrored through the lobe's plane.
      glm::vec3 r = sample_cosine_hemisphere(uv);
      r.z = -r.z;
      wi = frame_of(sh).to_world(r);
      below = true;
    } else {
      // The specular part's and the transmission's share of the lobe's choice after its diffuse part:
      // each draws the same visible normals, the transmission mirrors the reflected direction through
      // the lobe's plane (lobe.h). A roughness mixture or a transmission's band (lobe.h) is sampled half
      // from each end of its α² range.
      const float spec = 1.0f - c.diffuse[i] - c.dtrans[i] - c.transmit[i];
      float v = ux - c.diffuse[i] - c.dtrans[i];
      below = c.transmit[i] > 0 && v >= spec;
      if (below) v -= spec;
      // The transmission's shape has its own stretch (lobe.h "Transmission"), so its own frame.
      const LobeShape<float> ts = below ? transmission_shape(slot(picked).lobe, sh) : sh;
      const Frame fr = frame_of(ts);
      const glm::vec3 wo_l = fr.to_local(wo);
      const bool upper = ts.alpha2_hi > 0 && v >= 0.5f * (below ? c.transmit[i] : spec);
      const float alpha = std::sqrt(upper ? ts.alpha2_hi : ts.alpha2);
      const glm::vec2 axes = ts.stretched ? glm::vec2(alpha * std::sqrt(ts.r), alpha * std::sqrt(ts.inv_r)) : glm::vec2(alpha);
      const glm::vec3 h = sample_ggx_visible(axes, wo_l, uv);
      glm::vec3 r = 2.0f * glm::dot(wo_l, h) * h - wo_l;
      if (below) r.z = -r.z;
      wi = fr.to_world(r);
    }
  }
  s.wi = wi;
  s.pdf = pdf_with(c, wi, wo);
  if (!(below ? wi.z < 0 : wi.z > 0) || !(s.pdf > 0)) {
    s.kind = SampleKind::absorbed;
    s.weight = Rgb(0);
    return s;
  }
  s.kind = SampleKind::finite;
  s.weight = eval(wi, wo) * (std::abs(wi.z) / s.pdf);
  return s;
}

}  // namespace svbrdf
