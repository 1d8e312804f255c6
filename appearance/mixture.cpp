#include "appearance/mixture.h"

#include <algorithm>
#include <cmath>

#include "appearance/shading.h"
#include "base/error.h"

namespace svbrdf {
namespace {

void merge_into(Impulses& out, const Impulses& in, float w) {
  for (int i = 0; i < in.count; ++i) {
    const Impulse& imp = in.items[static_cast<std::size_t>(i)];
    bool merged = false;
    for (int j = 0; j < out.count && !merged; ++j) {
      Impulse& o = out.items[static_cast<std::size_t>(j)];
      if (o.direction == imp.direction) {
        o.magnitude += w * imp.magnitude;
        merged = true;
      }
    }
    if (!merged && out.count < static_cast<int>(out.items.size())) out.add(imp.direction, w * imp.magnitude);
  }
}

}  // namespace

void Mixture::add(const Bsdf& lobe, float weight) {
  if (count_ >= kCapacity) throw Error("Mixture: more than " + std::to_string(kCapacity) + " lobes", Error::Kind::internal);
  if (!(weight >= 0) || !std::isfinite(weight))
    throw Error("Mixture: lobe weight must be finite and non-negative", Error::Kind::internal);
  lobes_[static_cast<std::size_t>(count_)] = &lobe;
  weights_[static_cast<std::size_t>(count_)] = weight;
  ++count_;
}

Rgb Mixture::eval(const glm::vec3& wi, const glm::vec3& wo) const {
  Rgb f(0);
  for (int k = 0; k < count_; ++k) f += weights_[static_cast<std::size_t>(k)] * lobes_[static_cast<std::size_t>(k)]->eval(wi, wo);
  return f;
}

Impulses Mixture::impulses_in(const glm::vec3& wo) const {
  Impulses out;
  for (int k = 0; k < count_; ++k) {
    const auto i = static_cast<std::size_t>(k);
    if (weights_[i] > 0) merge_into(out, lobes_[i]->impulses_in(wo), weights_[i]);
  }
  return out;
}

Impulses Mixture::impulses_out(const glm::vec3& wi) const {
  Impulses out;
  for (int k = 0; k < count_; ++k) {
    const auto i = static_cast<std::size_t>(k);
    if (weights_[i] > 0) merge_into(out, lobes_[i]->impulses_out(wi), weights_[i]);
  }
  return out;
}

float Mixture::selection(const glm::vec3& wo, float* q, float* p) const {
  float sum = 0;
  for (int k = 0; k < count_; ++k) {
    const auto i = static_cast<std::size_t>(k);
    p[i] = weights_[i] > 0 ? lobes_[i]->scatter_probability(wo) : 0.0f;
    q[i] = weights_[i] * p[i];
    sum += q[i];
  }
  if (sum > 1.0f) {
    for (int k = 0; k < count_; ++k) q[static_cast<std::size_t>(k)] /= sum;
    sum = 1.0f;
  }
  return sum;
}

float Mixture::scatter_probability(const glm::vec3& wo) const {
  float q[kCapacity], p[kCapacity];
  return selection(wo, q, p);
}

float Mixture::pdf_with(const glm::vec3& wi, const glm::vec3& wo, const float* q, const float* p) const {
  float pdf = 0;
  for (int k = 0; k < count_; ++k) {
    const auto i = static_cast<std::size_t>(k);
    if (q[i] > 0) pdf += q[i] / p[i] * lobes_[i]->pdf(wi, wo);
  }
  return pdf;
}

float Mixture::pdf(const glm::vec3& wi, const glm::vec3& wo) const {
  float q[kCapacity], p[kCapacity];
  selection(wo, q, p);
  return pdf_with(wi, wo, q, p);
}

BsdfSample Mixture::sample(const glm::vec3& wo, const SampleU& u) const {
  float q[kCapacity], p[kCapacity];
  selection(wo, q, p);
  float start = 0;
  for (int k = 0; k < count_; ++k) {
    const auto i = static_cast<std::size_t>(k);
    if (!(q[i] > 0) || u.x >= start + q[i]) {
      start += q[i];
      continue;
    }
    // u.x ∈ [start, start + q_k) → [0, P_k): the lobe always scatters.
    const float v = std::min((u.x - start) / q[i], 1.0f) * p[i];
    const float ux = std::min(v, std::nextafter(p[i], 0.0f));
    BsdfSample s = lobes_[i]->sample(wo, {ux, u.y, u.z});
    if (s.kind == SampleKind::absorbed) return {};
    if (s.kind == SampleKind::impulse) {
      s.pdf *= q[i] / p[i];
      s.weight *= weights_[i] * p[i] / q[i];
      return s;
    }
    return finite_sample(s.wi, pdf_with(s.wi, wo, q, p), eval(s.wi, wo));
  }
  return {};  // absorbed: u.x beyond Σ q
}

void OwningMixture::add(std::unique_ptr<Bsdf> lobe, float weight) {
  mix_.add(*lobe, weight);
  owned_.push_back(std::move(lobe));
}

}  // namespace svbrdf
