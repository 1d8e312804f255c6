#pragma once
// The model configurations the appearance tests run over: every model of brdf-models.md, built
// through the registry from "k=v" parameters as a user would give them.
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "appearance/bsdf.h"

namespace svbrdf::testing {

struct ModelCase {
  std::string name;
  std::vector<std::string> params;
  std::vector<std::string> impulses = {};
  std::string label() const;
  std::unique_ptr<Bsdf> build() const;
};

// A unit direction at polar angle θ (degrees) and azimuth φ (degrees).
glm::vec3 direction_deg(double theta, double phi);

// Finite-part models with their samplers, a spread of parameters each.
const std::vector<ModelCase>& sampler_cases();

// A MERL table tabulated from the gltf model once per test run (written to a temporary file and
// read back, so the measured model goes through its reader); returns the path.
const std::string& gltf_merl_path();

}  // namespace svbrdf::testing
