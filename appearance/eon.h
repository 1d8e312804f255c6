#pragma once
// The energy-preserving Oren–Nayar diffuse BRDF of KHR_materials_diffuse_roughness (Portsmouth,
// Kutz & Hill 2024, "EON: A practical energy-preserving rough diffuse BRDF"), roughness σ in [0, 1].
#include "appearance/bsdf.h"

namespace svbrdf {

// EON's directional albedo of its single-scattering (FON) part, the fitted form of the paper's
// Listing 1 (error < 0.1 %), and the full EON BRDF (local frame, both directions above).
float eon_fon_albedo(float mu, float r);
Rgb eon_eval(const Rgb& rho, float r, const glm::vec3& wi, const glm::vec3& wo);

}  // namespace svbrdf
