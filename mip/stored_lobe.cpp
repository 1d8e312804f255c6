#include "mip/stored_lobe.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include <glm/gtc/packing.hpp>

#include "mip/coat_layer.h"
#include "mip/stored_normal.h"

namespace svbrdf {

namespace {
// x rounded to the nearest half float (ties to even), as a float. In half's normal range by the bits:
// drop 13 of the 23 mantissa bits with rounding (this runs for every stored number of every lobe);
// elsewhere (zero, subnormal halves, overflow, NaN) through glm's conversion.
float to_half(float x) {
  const float a = std::abs(x);
  if (!(a >= 6.103515625e-05f && a < 65504.0f)) return glm::unpackHalf1x16(glm::packHalf1x16(x));
  std::uint32_t b;
  std::memcpy(&b, &x, sizeof b);
  b += 0x0fffu + ((b >> 13) & 1u);
  b &= ~0x1fffu;
  float r;
  std::memcpy(&r, &b, sizeof r);
  return r;
}
bool is_mixture(const Lobe& lobe) { return lobe.alpha2_hi > lobe.alpha2 * 1.001f; }
}  // namespace

float lobe_shape_code(const Lobe& lobe) {
  if (is_mixture(lobe)) {
    const float span = static_cast<float>(std::log(double(lobe.alpha2_hi) / double(lobe.alpha2)));
    return to_half(lobe.skirt == 0.0f ? -(1.0f + span) : span);
  }
  return to_half(-std::clamp(lobe.ggx, 0.0f, 1.0f));
}

void set_lobe_shape_code(Lobe& lobe, float code) {
  if (code > 0 || code < -1) {
    // In double, so that writing the lobe again gives back the same half (the float rounding of
    // alpha2_hi moves the logarithm by 6e-8, far below a half's spacing at the smallest code, 1e-3).
    const bool two_point = code < -1;
    const double span = two_point ? -double(code) - 1.0 : double(code);
    lobe.alpha2_hi = static_cast<float>(double(lobe.alpha2) * std::exp(span));
    lobe.ggx = 1.0f;
    lobe.skirt = two_point ? 0.0f : 1.0f;
  } else {
    lobe.alpha2_hi = 0.0f;
    lobe.ggx = std::min(1.0f, -code);
    lobe.skirt = 1.0f;
  }
}

float lobe_skirt_code(const Lobe& lobe) {
  if (is_mixture(lobe)) {
    const float beta = std::clamp(lobe.ggx, 1e-3f, 1.0f);
    return to_half(beta <= 0.5f ? beta : beta - 1.0f);  // β − 1 is exact in a float
  }
  return lobe.ggx < 1.0f ? std::max(1.0f, to_half(lobe.skirt)) : 1.0f;
}

void set_lobe_skirt_code(Lobe& lobe, float code) {
  // β ≥ 1e-3 as set_shape makes it (the atom's weight in V is (1 − β)/β); 1 + a half in (−½, 0] is exact.
  if (lobe.alpha2_hi > 0.0f)
    lobe.ggx = std::clamp(code > 0.0f ? code : 1.0f + code, 1e-3f, 1.0f);
  else
    lobe.skirt = code;
}

float stretch_code(float stretch) {
  const double ln_r = stretch > 1.0f ? std::log(double(stretch)) : 0.0;
  return ln_r < kLeastStoredLnStretch ? 0.0f : to_half(static_cast<float>(ln_r));
}

namespace {
constexpr double kStretchDirectionStep = 3.14159265358979323846 / double(1u << kStretchDirectionBits);
}

std::uint32_t stretch_direction_code(const glm::vec2& direction) {
  // The direction is axial (φ and φ + π stretch alike): φ in [0, π).
  double phi = std::atan2(double(direction.y), double(direction.x));
  if (phi < 0) phi += 3.14159265358979323846;
  const auto k = static_cast<std::uint64_t>(std::llround(phi / kStretchDirectionStep));
  return static_cast<std::uint32_t>(k % (std::uint64_t(1) << kStretchDirectionBits));
}

void set_stretch_code(float& stretch, glm::vec2& direction, float code, std::uint32_t direction_code) {
  if (!(code > 0.0f)) {
    stretch = 1.0f;
    direction = glm::vec2(1.0f, 0.0f);
    return;
  }
  const double phi = double(direction_code) * kStretchDirectionStep;
  // At most e^16 (no lobe a texel makes comes near it: r ≤ 1/α_min = 1000), so that a corrupt code
  // gives a finite stretch.
  stretch = static_cast<float>(std::exp(std::min(double(code), 16.0)));
  direction = glm::vec2(static_cast<float>(std::cos(phi)), static_cast<float>(std::sin(phi)));
}

void round_to_stored(Lobe& lobe) {
  lobe.weight = to_half(lobe.weight);
  // α as a half (α ≥ 1e-3 is in its normal range): at most 2^-11 (4.9e-4) relative on α, and α·α is
  // exact in a float.
  const float alpha = to_half(std::sqrt(lobe.alpha2));
  lobe.alpha2 = alpha * alpha;
  for (int c = 0; c < 3; ++c) {
    lobe.diffuse[c] = to_half(lobe.diffuse[c]);
    lobe.f0[c] = to_half(lobe.f0[c]);
    lobe.f0_tint[c] = to_half(lobe.f0_tint[c]);
    lobe.diffuse90[c] = to_half(lobe.diffuse90[c]);
  }
  lobe.f90 = to_half(lobe.f90);
  lobe.coat = to_half(lobe.coat);
  lobe.sheen = to_half(lobe.sheen);
  for (int c = 0; c < 3; ++c) {
    lobe.transmission[c] = to_half(lobe.transmission[c]);
    lobe.transmission90[c] = to_half(lobe.transmission90[c]);
    lobe.diffuse_transmission[c] = to_half(lobe.diffuse_transmission[c]);
    lobe.diffuse_transmission90[c] = to_half(lobe.diffuse_transmission90[c]);
  }
  // As α: α_T ≥ 1e-3, and its square is exact in a float; a band's upper end the same way, a band
  // narrower than a half's step a GGX.
  const auto round_alpha2 = [](float& a2) {
    if (!(a2 > 0.0f)) return;
    const float a = to_half(std::sqrt(a2));
    a2 = a * a;
  };
  round_alpha2(lobe.transmission_alpha2);
  round_alpha2(lobe.transmission_alpha2_hi);
  if (!(lobe.transmission_alpha2_hi > lobe.transmission_alpha2)) lobe.transmission_alpha2_hi = 0.0f;
  lobe.normal = round_normal(lobe.normal);
  set_lobe_stretch_code(lobe, lobe_stretch_code(lobe), lobe_stretch_direction_code(lobe));
  set_lobe_transmission_stretch_code(lobe, lobe_transmission_stretch_code(lobe), lobe_transmission_stretch_direction_code(lobe));
  const float skirt_code = lobe_skirt_code(lobe);
  set_lobe_shape_code(lobe, lobe_shape_code(lobe));
  set_lobe_skirt_code(lobe, skirt_code);
}

void round_coat_lobe_to_stored(Lobe& lobe) {
  round_to_stored(lobe);
  set_coat_colours(lobe);
}

void set_coat_colours(Lobe& lobe) {
  lobe.diffuse = glm::vec3(0.0f);
  lobe.diffuse90 = glm::vec3(0.0f);
  lobe.f0 = glm::vec3(kCoatF0);
  lobe.f0_tint = glm::vec3(0.0f);
  lobe.f90 = 1.0f;
  lobe.coat = 0.0f;
  lobe.sheen = 0.0f;
}

}  // namespace svbrdf
