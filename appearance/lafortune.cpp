#include "appearance/lafortune.h"

#include <algorithm>
#include <cmath>

#include "appearance/sampling.h"
#include "appearance/shading.h"
#include "base/error.h"

namespace svbrdf {
namespace {

glm::vec3 lobe_axis(const LafortuneLobe& l, const glm::vec3& wo) { return l.c * wo; }

}  // namespace

Lafortune::Lafortune(const Rgb& kd, std::vector<LafortuneLobe> lobes) : kd_(kd), lobes_(std::move(lobes)) {
  if (lobes_.size() > static_cast<std::size_t>(kMaxLobes))
    throw Error("lafortune: at most " + std::to_string(kMaxLobes) + " lobes");
}

Rgb Lafortune::eval(const glm::vec3& wi, const glm::vec3& wo) const {
  if (wi.z <= 0 || wo.z <= 0) return Rgb(0);
  Rgb f = kd_ * kInvPi;
  for (const LafortuneLobe& l : lobes_) {
    const float x = glm::dot(l.c * wi, wo);  // Cx wi.x wo.x + Cy wi.y wo.y + Cz wi.z wo.z
    if (x > 0) f += l.weight * std::pow(x, l.n);
  }
  return f;
}

float Lafortune::selection(const glm::vec3& wo, float* weights) const {
  float sum = weights[0] = max_channel(kd_);
  for (std::size_t k = 0; k < lobes_.size(); ++k) {
    const LafortuneLobe& l = lobes_[k];
    const float len = glm::length(lobe_axis(l, wo));
    float w = 0.0f;
    if (len > 0) {
      const float strength = std::exp(std::min(60.0f, l.n * std::log(len)));  // |c|^n, kept finite
      w = max_channel(l.weight) * strength * kTwoPi / (l.n + 1.0f);
    }
    weights[k + 1] = w;
    sum += w;
  }
  return sum;
}

float Lafortune::scatter_probability(const glm::vec3& wo) const {
  if (wo.z <= 0) return 0.0f;
  float weights[kMaxLobes + 1];
  return std::min(1.0f, selection(wo, weights));
}

float Lafortune::lobe_pdf(const glm::vec3& wi, const glm::vec3& wo, const float* weights, float sum) const {
  float p = weights[0] * cosine_hemisphere_pdf(wi.z);
  for (std::size_t k = 0; k < lobes_.size(); ++k) {
    if (weights[k + 1] <= 0) continue;
    const glm::vec3 axis = glm::normalize(lobe_axis(lobes_[k], wo));
    p += weights[k + 1] * power_cosine_pdf(glm::dot(axis, wi), lobes_[k].n);
  }
  return p / sum;
}

BsdfSample Lafortune::sample(const glm::vec3& wo, const SampleU& u) const {
  if (wo.z <= 0) return {};
  float weights[kMaxLobes + 1];
  const float sum = selection(wo, weights);
  const float p = std::min(1.0f, sum);
  if (!(sum > 0) || u.x >= p) return {};
  float v = u.x / p * sum;
  glm::vec3 wi = sample_cosine_hemisphere({u.y, u.z});
  // The lobe whose slice of [0, sum) holds v; rounding at the far end falls on the last lobe with
  // a positive weight.
  int last = -1;
  for (std::size_t j = 0; j < lobes_.size(); ++j)
    if (weights[j + 1] > 0) last = static_cast<int>(j);
  if (v >= weights[0] && last >= 0) {
    v -= weights[0];
    std::size_t k = 0;
    while (static_cast<int>(k) < last && v >= weights[k + 1]) v -= weights[1 + k++];
    const glm::vec3 axis = glm::normalize(lobe_axis(lobes_[k], wo));
    wi = sample_power_cosine_about(axis, {u.y, u.z}, lobes_[k].n);
  }
  if (wi.z <= 0) return {};
  return finite_sample(wi, p * lobe_pdf(wi, wo, weights, sum), eval(wi, wo));
}

float Lafortune::pdf(const glm::vec3& wi, const glm::vec3& wo) const {
  if (wi.z <= 0 || wo.z <= 0) return 0.0f;
  float weights[kMaxLobes + 1];
  const float sum = selection(wo, weights);
  if (!(sum > 0)) return 0.0f;
  return std::min(1.0f, sum) * lobe_pdf(wi, wo, weights, sum);
}

}  // namespace svbrdf
