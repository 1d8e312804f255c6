#pragma once
// A simple sky for the renderer's environment: a gradient from the horizon to the zenith over a
// uniform ground, with an optional soft disc (a sun seen through haze, for scenes lit by the sky
// alone). Written as an equirectangular image in svbrdf-render's mapping (render/lights.h):
// direction d (+Y up) ↦ u = 1/2 + atan2(d.x, −d.z)/(2π), v = acos(d.y)/π. Radiance, linear Rec.709.
#include <glm/glm.hpp>

#include "textures/image.h"

namespace svbrdf {

struct SkyModel {
  glm::dvec3 zenith{0.10, 0.18, 0.40};
  glm::dvec3 horizon{0.40, 0.45, 0.50};
  glm::dvec3 ground{0.05, 0.045, 0.04};
  // A disc of uniform radiance `disc` around `disc_direction` (toward it), `disc_radius_deg` wide;
  // none when the radiance is zero.
  glm::dvec3 disc{0.0};
  glm::dvec3 disc_direction{0.0, 1.0, 0.0};
  double disc_radius_deg = 10.0;
};

// Radiance arriving from direction d (unit, toward the sky).
glm::dvec3 sky_radiance(const SkyModel& sky, const glm::dvec3& d);
// The direction at equirectangular coordinates (u, v) ∈ [0, 1]² and back (the renderer's mapping).
glm::dvec3 sky_direction(double u, double v);
// width × height RGB, each pixel the mean of 4×4 directions in it (so the disc's edge is smooth).
Image sky_image(const SkyModel& sky, int width, int height);

}  // namespace svbrdf
