#pragma once
// Internal to the textures library: what the family units (family_*.cpp) share. Users include
// textures/material_family.h.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdint>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "textures/image.h"
#include "textures/material_texels.h"

namespace svbrdf::family {

// The texture's physical layout: size × size texels of mm_per_texel each.
struct Domain {
  int size = 0;
  double mm_per_texel = 0.0;

  double side_mm() const { return size * mm_per_texel; }
  // Texture coordinate of texel i's center, and of a sub-texel sample (i + s, s ∈ [0, 1)).
  double u(int i) const { return (i + 0.5) / size; }
  double u(int i, double s) const { return (i + s) / size; }
};

// What a family fills: parameters in linear units, heights in mm, and the bit depth each stored
// image needs (16 bits where a smooth or small-range signal would band in 8).
struct Canvas {
  MaterialTexels& texels;
  std::vector<float>& height_mm;
  PixelFormat base_color_format = PixelFormat::uint8;
  PixelFormat metallic_roughness_format = PixelFormat::uint8;
};

void sandstone(const Domain& d, std::string_view variant, std::uint64_t seed, Canvas& out);
void painted_wall(const Domain& d, std::string_view variant, std::uint64_t seed, Canvas& out);
void printed_paper(const Domain& d, std::string_view variant, std::uint64_t seed, Canvas& out);
void metal_tray(const Domain& d, std::string_view variant, std::uint64_t seed, Canvas& out);
void granite(const Domain& d, std::string_view variant, std::uint64_t seed, Canvas& out);

// Authoring helper: a color written as 8-bit sRGB (how palettes are usually quoted) in linear
// Rec.709, by the IEC 61966-2-1 decode. Only for constants; image data goes through OCIO.
inline glm::vec3 srgb8(int r, int g, int b) {
  const auto decode = [](int c) {
    const double v = c / 255.0;
    return float(v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
  };
  return {decode(r), decode(g), decode(b)};
}

// Runs body(j) for every row j, in parallel over bands of rows.
template <class Body>
void for_each_row(int rows, const Body& body) {
  tbb::parallel_for(tbb::blocked_range<int>(0, rows, 8), [&](const tbb::blocked_range<int>& r) {
    for (int j = r.begin(); j != r.end(); ++j) body(j);
  });
}

}  // namespace svbrdf::family
