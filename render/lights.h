#pragma once
// The lights the integrator samples: KHR_lights_punctual lights (plus --sun) and the environment.
// Units are radiometric: a directional light delivers `intensity` W/m² to a surface
// facing it; a point or spot light has radiant intensity `intensity` W/sr, falling off with the
// inverse square and glTF's range window; the environment's value is radiance.
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "render/alias_table.h"
#include "gltf/scene.h"
#include "textures/image.h"

namespace svbrdf {

// What a punctual light delivers at a point: the direction toward it, the distance (infinite for a
// directional light) and the irradiance on a surface facing it.
struct LightArrival {
  glm::vec3 wi{0.0f};
  float distance = 0.0f;
  Rgb irradiance{0.0f};
};

LightArrival arrive(const LightDesc& light, const glm::vec3& p);

// The environment at infinity: a uniform radiance or an equirectangular image. The image's mapping:
// direction d (glTF world, +Y up) ↦ u = 1/2 + atan2(d.x, −d.z)/(2π), v = acos(d.y)/π, so the image's
// centre is seen looking along −Z (glTF's default view) and its top row is straight up.
class Environment {
 public:
  static Environment uniform(const Rgb& radiance);
  // Throws svbrdf::Error for an unreadable image.
  static Environment from_image(Image image, const std::string& where);

  bool black() const { return black_; }
  // The radiance from direction `dir` and, when `pdf` is given, sample()'s density of it (one
  // mapping of the direction to the image for both).
  Rgb radiance(const glm::vec3& dir, float* pdf = nullptr) const;
  // A direction drawn with density pdf (solid angle) roughly proportional to radiance·sinθ, and
  // when asked for its radiance (the pixel drawn: no mapping back). Three uniforms: the pixel takes
  // u.x and u.y (an alias table), the point in it u.y's rest and u.z.
  glm::vec3 sample(glm::vec3 u, float& pdf, Rgb* radiance = nullptr) const;
  float pdf(const glm::vec3& dir) const;

 private:
  Rgb uniform_{0.0f};
  bool black_ = true;
  // The pixel (i, j) that direction d falls in, and sin θ of d.
  struct Pixel {
    std::size_t i = 0, j = 0;
    float sin_theta = 0.0f;
  };
  Pixel pixel_of(const glm::vec3& d) const;
  // sample()'s density at a direction of pixel p with the given sin θ.
  float pixel_pdf(std::size_t i, std::size_t j, float sin_theta) const;
  const float* texel(std::size_t i, std::size_t j) const { return &image_.pixels[(j * std::size_t(image_.width) + i) * 3]; }

  Image image_;  // RGB, empty for a uniform environment
  // The piecewise-constant distribution over pixels: each pixel's luminance·sinθ (pixel_func_, sum
  // total_), drawn from in constant time by an alias table (a row-then-column CDF took two bisections,
  // 15 dependent loads for a 256 × 128 sky; bench/results/render.md).
  std::vector<float> pixel_func_;
  float total_ = 0.0f;
  AliasTable pixels_;
};

// "--sun elevation,azimuth[,irradiance]" in degrees: a directional light coming from `elevation`
// above the horizon (+Y up) and `azimuth` measured from +Z (glTF's front, where a default camera
// stands) toward +X, so azimuth 0 lights what faces the viewer.
LightDesc sun_light(float elevation_deg, float azimuth_deg, float irradiance);

}  // namespace svbrdf
