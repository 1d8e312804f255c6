#include "render/lights.h"

#include <algorithm>
#include <cmath>

#include "base/error.h"

namespace svbrdf {

namespace {
constexpr float kPiF = 3.14159265358979323846f;

std::size_t upper_index(const float* cdf, std::size_t n, float u) {
  // The k with cdf[k] ≤ u < cdf[k+1], k ∈ [0, n).
  const float* it = std::upper_bound(cdf, cdf + n + 1, u);
  const std::size_t k = std::size_t(std::max<std::ptrdiff_t>(it - cdf - 1, 0));
  return std::min(k, n - 1);
}
}  // namespace

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
  e.col_cdf_.resize(std::size_t(h) * (w + 1));
  e.row_func_.resize(std::size_t(h));
  e.row_cdf_.resize(std::size_t(h) + 1);
  for (int j = 0; j < h; ++j) {
    const float sin_theta = std::sin(kPiF * (j + 0.5f) / float(h));
    float* cdf = &e.col_cdf_[std::size_t(j) * (w + 1)];
    cdf[0] = 0.0f;
    for (int i = 0; i < w; ++i) {
      const float* px = &e.image_.pixels[(std::size_t(j) * w + i) * 3];
      // Luminance (Rec.709) times the sphere's area element; a small floor keeps every direction
      // sampleable so MIS stays unbiased where the image is black.
      const float f = (0.2126f * px[0] + 0.7152f * px[1] + 0.0722f * px[2]) * sin_theta + 1e-8f;
      e.pixel_func_[std::size_t(j) * w + i] = f;
      cdf[i + 1] = cdf[i] + f;
    }
    e.row_func_[std::size_t(j)] = cdf[w];
    for (int i = 1; i <= w; ++i) cdf[i] /= cdf[w];
    e.row_cdf_[std::size_t(j) + 1] = e.row_cdf_[std::size_t(j)] + e.row_func_[std::size_t(j)];
  }
  e.total_ = e.row_cdf_[std::size_t(h)];
  for (auto& c : e.row_cdf_) c /= e.total_;
  return e;
}

Rgb Environment::radiance(const glm::vec3& d) const {
  if (image_.pixels.empty()) return uniform_;
  const float u = 0.5f + std::atan2(d.x, -d.z) / (2.0f * kPiF);
  const float v = std::atan2(std::sqrt(d.x * d.x + d.z * d.z), d.y) / kPiF;
  const int i = std::clamp(int(u * float(image_.width)), 0, image_.width - 1);
  const int j = std::clamp(int(v * float(image_.height)), 0, image_.height - 1);
  const float* px = &image_.pixels[(std::size_t(j) * image_.width + i) * 3];
  return {px[0], px[1], px[2]};
}

glm::vec3 Environment::sample(glm::vec2 u, float& pdf) const {
  if (image_.pixels.empty()) {
    // Uniform on the sphere.
    const float z = 1.0f - 2.0f * u.x, r = std::sqrt(std::max(0.0f, 1.0f - z * z)), phi = 2.0f * kPiF * u.y;
    pdf = 1.0f / (4.0f * kPiF);
    return {r * std::cos(phi), z, r * std::sin(phi)};
  }
  const int w = image_.width, h = image_.height;
  const std::size_t j = upper_index(row_cdf_.data(), std::size_t(h), u.y);
  const float row_width = row_cdf_[j + 1] - row_cdf_[j];
  const float dv = row_width > 0.0f ? (u.y - row_cdf_[j]) / row_width : 0.5f;
  const float* cdf = &col_cdf_[j * (w + 1)];
  const std::size_t i = upper_index(cdf, std::size_t(w), u.x);
  const float col_width = cdf[i + 1] - cdf[i];
  const float du = col_width > 0.0f ? (u.x - cdf[i]) / col_width : 0.5f;
  const float uu = (float(i) + std::clamp(du, 0.0f, 1.0f)) / float(w);
  const float vv = (float(j) + std::clamp(dv, 0.0f, 1.0f)) / float(h);
  const float theta = vv * kPiF, phi = (uu - 0.5f) * 2.0f * kPiF;
  const float st = std::sin(theta);
  const glm::vec3 d(st * std::sin(phi), std::cos(theta), -st * std::cos(phi));
  pdf = this->pdf(d);
  return d;
}

float Environment::pdf(const glm::vec3& d) const {
  if (image_.pixels.empty()) return 1.0f / (4.0f * kPiF);
  const int w = image_.width, h = image_.height;
  // θ from atan2 and sinθ from the horizontal length: accurate near the poles, where acos(d.y)
  // and 1 − d.y² lose every digit.
  const float sin_theta = std::sqrt(d.x * d.x + d.z * d.z);
  const float u = 0.5f + std::atan2(d.x, -d.z) / (2.0f * kPiF);
  const float v = std::atan2(sin_theta, d.y) / kPiF;
  const int i = std::clamp(int(u * float(w)), 0, w - 1);
  const int j = std::clamp(int(v * float(h)), 0, h - 1);
  if (sin_theta <= 0.0f) return 0.0f;
  // Density in (u, v) is f·w·h / total; the map (u, v) → direction has Jacobian 2π²·sinθ.
  const float p_uv = pixel_func_[std::size_t(j) * w + i] * float(w) * float(h) / total_;
  return p_uv / (2.0f * kPiF * kPiF * sin_theta);
}

}  // namespace svbrdf
