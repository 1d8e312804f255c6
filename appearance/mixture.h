#pragma once
// A mixture of lobes f = Σ_k w_k f_k with one-sample selection (CGPP §27.14; Veach 1997 §9.2.4
// one-sample model with the mixture density). Lobe k is picked with probability
//   q_k = w_k P_k(wo)            when Σ_j w_j P_j(wo) ≤ 1 (every lobe keeps its absolute energy split),
//   q_k = w_k P_k / Σ_j w_j P_j  otherwise,
// where P_k = lobe k's scatter_probability. The picked lobe gets u.x remapped into [0, P_k), so it
// always scatters, then:
//   finite sample: pdf = Σ_j (q_j / P_j) pdf_j(wi, wo), weight = f·|wi.z| / pdf with the whole f;
//   impulse:       probability q_k / P_k times the lobe's, weight w_k P_k / q_k times the lobe's.
// This realizes the §27.14 example: mirror impulse 0.4 + Lambert albedo 0.2 → 40 % impulse,
// 20 % finite, 40 % absorbed.
//
// No heap allocation: a Mixture refers to at most kCapacity lobes it does not own (the renderer or
// the MIP lookup keeps them, e.g. in a std::array on the stack). OwningMixture keeps its lobes.
#include <array>
#include <memory>
#include <vector>

#include "appearance/bsdf.h"

namespace svbrdf {

class Mixture final : public Bsdf {
 public:
  static constexpr int kCapacity = 16;

  // Adds w·lobe. The lobe must outlive the mixture. Throws svbrdf::Error (internal) when full or
  // when w is negative or not finite.
  void add(const Bsdf& lobe, float weight = 1.0f);
  void clear() { count_ = 0; }
  int size() const { return count_; }
  const Bsdf& lobe(int k) const { return *lobes_[static_cast<std::size_t>(k)]; }
  float weight(int k) const { return weights_[static_cast<std::size_t>(k)]; }

  Rgb eval(const glm::vec3& wi, const glm::vec3& wo) const override;
  // The union of the lobes' impulses scaled by w_k; impulses along the same direction merge. A
  // mixture holds at most two distinct impulse directions (Impulses' capacity: a dielectric's
  // reflection and refraction); further distinct ones are dropped — the registry refuses to build
  // such a combination.
  Impulses impulses_in(const glm::vec3& wo) const override;
  Impulses impulses_out(const glm::vec3& wi) const override;
  BsdfSample sample(const glm::vec3& wo, const SampleU& u) const override;
  float pdf(const glm::vec3& wi, const glm::vec3& wo) const override;
  float scatter_probability(const glm::vec3& wo) const override;

 private:
  // Fills q (selection probabilities) and p (the lobes' scatter probabilities); returns Σ q.
  float selection(const glm::vec3& wo, float* q, float* p) const;
  float pdf_with(const glm::vec3& wi, const glm::vec3& wo, const float* q, const float* p) const;
  std::array<const Bsdf*, kCapacity> lobes_{};
  std::array<float, kCapacity> weights_{};
  int count_ = 0;
};

// A mixture that owns its lobes (what the model registry builds for `--impulse`).
class OwningMixture final : public Bsdf {
 public:
  void add(std::unique_ptr<Bsdf> lobe, float weight = 1.0f);
  const Mixture& mixture() const { return mix_; }

  Rgb eval(const glm::vec3& wi, const glm::vec3& wo) const override { return mix_.eval(wi, wo); }
  Impulses impulses_in(const glm::vec3& wo) const override { return mix_.impulses_in(wo); }
  Impulses impulses_out(const glm::vec3& wi) const override { return mix_.impulses_out(wi); }
  BsdfSample sample(const glm::vec3& wo, const SampleU& u) const override { return mix_.sample(wo, u); }
  float pdf(const glm::vec3& wi, const glm::vec3& wo) const override { return mix_.pdf(wi, wo); }
  float scatter_probability(const glm::vec3& wo) const override { return mix_.scatter_probability(wo); }

 private:
  std::vector<std::unique_ptr<Bsdf>> owned_;
  Mixture mix_;
};

}  // namespace svbrdf
