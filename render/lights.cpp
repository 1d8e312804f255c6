#include "render/lights.h"

#include <algorithm>
#include <cmath>

#include "base/error.h"
#include "base/fast_atan2.h"
#include "base/math.h"

namespace svbrdf {

LightArrival arrive(const LightDesc& l, const glm::vec3& p) {
  LightArrival a;
  if (l.type == LightDesc::Type::directional) {
    a.wi = -l.direction;
    a.distance = std::numeric_limits<float>::infinity();
    a.irradiance = l.color * l.intensity;
    return a;
  }
  const glm::vec3 d = l.position - p;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.0f)) return a;
  a.distance = std::sqrt(dist2);
  a.wi = d / a.distance;
  float falloff = 1.0f / dist2;
  if (l.range > 0.0f) {
    // KHR_lights_punctual's recommended window: max(min(1 − (d/range)^4, 1), 0) / d².
    const float r = a.distance / l.range;
    falloff *= std::clamp(1.0f - r * r * r * r, 0.0f, 1.0f);
  }
  if (l.type == LightDesc::Type::spot) {
    // The extension's smooth cone: saturate(cd·scale + offset)², cd the cosine to the spot axis.
    const float cos_outer = std::cos(l.outer_cone), cos_inner = std::cos(l.inner_cone);
    const float scale = 1.0f / std::max(0.001f, cos_inner - cos_outer);
    const float t = std::clamp(glm::dot(l.direction, -a.wi) * scale - cos_outer * scale, 0.0f, 1.0f);
    falloff *= t * t;
  }
  a.irradiance = l.color * (l.intensity * falloff);
  return a;
}

LightDesc sun_light(float elevation_deg, float azimuth_deg, float irradiance) {
  LightDesc l;
  l.name = "sun";
  l.type = LightDesc::Type::directional;
  l.intensity = irradiance;
  const float el = glm::radians(elevation_deg), az = glm::radians(azimuth_deg);
  const glm::vec3 toward_sun(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
  l.direction = -toward_sun;
  return l;
}

Environment Environment::uniform(const Rgb& radiance) {
  Environment e;
  e.uniform_ = radiance;
  e.black_ = radiance == Rgb(0.0f);
  return e;
}

Environment Environment::from_image(Image im, const std::string& where) {
  if (im.width < 1 || im.height < 1) throw input_error(where, "environment image is empty");
  Environment e;
  e.black_ = false;
  // Keep RGB (gray expanded).
  Image rgb(im.width, im.height, 3);
  for (std::size_t p = 0; p < std::size_t(im.width) * im.height; ++p)
    for (int c = 0; c < 3; ++c) {
      const float v = im.pixels[p * im.channels + std::size_t(im.channels >= 3 ? c : 0)];
      if (!std::isfinite(v) || v < 0.0f)
        throw input_error(where, "environment pixel " + std::to_string(p) + " is negative or not finite");
      rgb.pixels[p * 3 + c] = v;
    }
  e.image_ = std::move(rgb);
  const int w = e.image_.width, h = e.image_.height;
  e.pixel_func_.resize(std::size_t(w) * h);
  double total = 0.0;
  for (int j = 0; j < h; ++j) {
    const float sin_theta = std::sin(kPi * (j + 0.5f) / float(h));
    for (int i = 0; i < w; ++i) {
      const float* px = &e.image_.pixels[(std::size_t(j) * w + i) * 3];
      // Luminance (Rec.709) times the sphere's area element; a small floor keeps every direction
      // sampleable so MIS stays unbiased where the image is black.
      const float f = (0.2126f * px[0] + 0.7152f * px[1] + 0.0722f * px[2]) * sin_theta + 1e-8f;
      e.pixel_func_[std::size_t(j) * w + i] = f;
      total += f;
    }
  }
  e.total_ = float(total);
  e.pixels_ = AliasTable(e.pixel_func_);
  return e;
}

Environment::Pixel Environment::pixel_of(const glm::vec3& d) const {
  // θ from atan2 and sinθ from the horizontal length: accurate near the poles, where acos(d.y)
  // and 1 − d.y² lose every digit.
  Pixel p;
  p.sin_theta = std::sqrt(d.x * d.x + d.z * d.z);
  const float u = 0.5f + fast_atan2(d.x, -d.z) * (0.5f / kPi);
  const float v = fast_atan2(p.sin_theta, d.y) * (1.0f / kPi);
  p.i = std::size_t(std::clamp(int(u * float(image_.width)), 0, image_.width - 1));
  p.j = std::size_t(std::clamp(int(v * float(image_.height)), 0, image_.height - 1));
  return p;
}

float Environment::pixel_pdf(std::size_t i, std::size_t j, float sin_theta) const {
  if (!(sin_theta > 0.0f)) return 0.0f;
  // Density in (u, v) is f·w·h / total; the map (u, v) → direction has Jacobian 2π²·sinθ.
  const float w = float(image_.width), h = float(image_.height);
  const float p_uv = pixel_func_[j * std::size_t(image_.width) + i] * w * h / total_;
  return p_uv / (2.0f * kPi * kPi * sin_theta);
}

Rgb Environment::radiance(const glm::vec3& d, float* pdf) const {
  if (image_.pixels.empty()) {
    if (pdf) *pdf = 1.0f / (4.0f * kPi);
    return uniform_;
  }
  const Pixel p = pixel_of(d);
  if (pdf) *pdf = pixel_pdf(p.i, p.j, p.sin_theta);
  const float* px = texel(p.i, p.j);
  return {px[0], px[1], px[2]};
}

glm::vec3 Environment::sample(glm::vec3 u, float& pdf, Rgb* radiance) const {
  if (image_.pixels.empty()) {
    // Uniform on the sphere.
    const float z = 1.0f - 2.0f * u.x, r = std::sqrt(std::max(0.0f, 1.0f - z * z)), phi = 2.0f * kPi * u.y;
    pdf = 1.0f / (4.0f * kPi);
    if (radiance) *radiance = uniform_;
    return {r * std::cos(phi), z, r * std::sin(phi)};
  }
  // A pixel in proportion to its share (pixel_func_), then a uniform point in it (u.y's rest, u.z).
  const int w = image_.width, h = image_.height;
  float du = 0.0f;
  const std::size_t k = pixels_.sample(u.x, u.y, du);
  const std::size_t i = k % std::size_t(w), j = k / std::size_t(w);
  const float uu = (float(i) + du) / float(w);
  const float vv = (float(j) + u.z) / float(h);
  const float theta = vv * kPi, phi = (uu - 0.5f) * 2.0f * kPi;
  const float st = std::sin(theta);
  const glm::vec3 d(st * std::sin(phi), std::cos(theta), -st * std::cos(phi));
  // The pixel drawn gives the density and the radiance: d is not mapped back to the image.
  pdf = pixel_pdf(i, j, st);
  if (radiance) {
    const float* px = texel(i, j);
    *radiance = {px[0], px[1], px[2]};
  }
  return d;
}

float Environment::pdf(const glm::vec3& d) const {
  if (image_.pixels.empty()) return 1.0f / (4.0f * kPi);
  const Pixel p = pixel_of(d);
  return pixel_pdf(p.i, p.j, p.sin_theta);
}

}  // namespace svbrdf
