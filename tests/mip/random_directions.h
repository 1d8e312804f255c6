#pragma once
// Random directions above the geometric surface for the MIP tests' evaluations.
#include <glm/glm.hpp>

#include "appearance/rng.h"

namespace svbrdf::testing_directions {

// A unit direction drawn from the upper unit half ball (rejection), at least min_z above the horizon.
inline glm::dvec3 random_above(Rng& rng, double min_z = 0.05) {
  for (;;) {
    const glm::dvec3 v(2 * rng.next_double() - 1, 2 * rng.next_double() - 1, rng.next_double());
    const double l = glm::length(v);
    if (l > 0.1 && l <= 1.0 && v.z / l > min_z) return v / l;
  }
}

}  // namespace svbrdf::testing_directions
