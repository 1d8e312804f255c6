#pragma once
// The directional albedo ρ(wo) = ∫ f(wi, wo) |wi.z| dwi of a model's finite part (CGPP §27.4),
// estimated with the model's own sampler as Σ f·|cos|/pdf over stratified samples (eval and pdf
// are called, not the sample's weight, so what is integrated is eval itself), and the impulse
// total Σ magnitudes of impulses_in(wo).
#include <cstdint>

#include "appearance/bsdf.h"

namespace svbrdf {

// strata² quasi-random samples (albedo.cpp says how); deterministic for a seed.
Rgb directional_albedo(const Bsdf& bsdf, const glm::vec3& wo, int strata = 256, std::uint64_t seed = 1);
Rgb impulse_total(const Bsdf& bsdf, const glm::vec3& wo);

}  // namespace svbrdf
