#include "scenes/sky.h"

#include <algorithm>
#include <cmath>

#include "base/math.h"

namespace svbrdf {

glm::dvec3 sky_radiance(const SkyModel& sky, const glm::dvec3& d) {
  glm::dvec3 L;
  if (d.y >= 0.0) {
    // Brighter toward the horizon, as scattering through a longer air path makes it.
    const double t = std::sqrt(std::min(1.0, d.y));
    L = sky.horizon + (sky.zenith - sky.horizon) * t;
  } else {
    L = sky.ground;
  }
  if (sky.disc != glm::dvec3(0.0)) {
    const double c = glm::dot(d, glm::normalize(sky.disc_direction));
    if (c >= std::cos(sky.disc_radius_deg * kPiD / 180)) L += sky.disc;
  }
  return L;
}

glm::dvec3 sky_direction(double u, double v) {
  const double theta = v * kPiD;
  const double phi = (u - 0.5) * 2 * kPiD;  // atan2(d.x, −d.z)
  const double s = std::sin(theta);
  return {s * std::sin(phi), std::cos(theta), -s * std::cos(phi)};
}

Image sky_image(const SkyModel& sky, int width, int height) {
  Image im(width, height, 3);
  constexpr int kSub = 4;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      glm::dvec3 sum(0.0);
      for (int j = 0; j < kSub; ++j)
        for (int i = 0; i < kSub; ++i)
          sum += sky_radiance(sky, sky_direction((x + (i + 0.5) / kSub) / width, (y + (j + 0.5) / kSub) / height));
      sum /= double(kSub * kSub);
      for (int c = 0; c < 3; ++c) im.at(x, y, c) = float(sum[c]);
    }
  return im;
}

}  // namespace svbrdf
