// Painted wall: latex paint as §27.11 describes it — a nearly constant, slightly varying albedo
// over a field of bumps about 0.1 mm high and about 2 mm apart (the stipple a paint roller
// leaves), seen as a normal map; roughness about 0.7, a little glossier on the bump tops where the
// film is smoothest. Bumps: one per cell of a jittered 2 mm grid, each a smooth cap
// h(r) = a·(1 − (r/R)²)² of height a ∈ [0.08, 0.12] mm and radius R ∈ [0.9, 1.3] mm, plus a
// micro-texture of a few µm.
#include <string>

#include "base/error.h"
#include "textures/families.h"
#include "textures/noise.h"

namespace svbrdf::family {

namespace {

glm::vec3 paint_color(std::string_view variant) {
  if (variant == "white") return srgb8(232, 231, 226);
  if (variant == "cream") return srgb8(233, 222, 196);
  if (variant == "gray") return srgb8(190, 191, 192);
  throw Error("painted-wall: unknown variant \"" + std::string(variant) + "\"");
}

constexpr double kBumpSpacingMm = 2.0;
constexpr float kBumpHeightLo = 0.08f, kBumpHeightHi = 0.12f;  // mm
constexpr float kBumpRadiusLo = 0.9f, kBumpRadiusHi = 1.3f;    // mm
constexpr float kBumpJitter = 0.4f;                            // of a cell, either way
constexpr double kMicroMm = 0.3;                               // micro-texture feature size
constexpr float kMicroReliefMm = 0.004f;
constexpr double kTintFeatureMm = 12.0;                        // slow albedo variation
constexpr float kRoughValley = 0.74f, kRoughTop = 0.64f;

}  // namespace

void painted_wall(const Domain& d, std::string_view variant, std::uint64_t seed, Canvas& out) {
  const glm::vec3 paint = paint_color(variant);
  out.base_color_format = PixelFormat::uint16;  // ±2 % albedo would band in 8 bits
  out.metallic_roughness_format = PixelFormat::uint16;
  const double side = d.side_mm();
  const int cells = noise::cells_for(side, kBumpSpacingMm);
  const double cell_mm = side / cells;
  const int micro_cells = noise::cells_for(side, kMicroMm);
  const int tint_cells = noise::cells_for(side, kTintFeatureMm);
  const std::uint64_t s_bump = noise::hash(seed, 11), s_micro = noise::hash(seed, 12), s_tint = noise::hash(seed, 13),
                      s_speck = noise::hash(seed, 14);
  MaterialTexels& t = out.texels;
  for_each_row(d.size, [&](int j) {
    for (int i = 0; i < d.size; ++i) {
      const double x = d.u(i) * cells, y = d.u(j) * cells;  // in cells
      const long long cx = static_cast<long long>(std::floor(x)), cy = static_cast<long long>(std::floor(y));
      // Bumps of the 3×3 neighbouring cells reach this texel (jitter 0.4 + radius 0.65 cell < 1.5).
      float bumps = 0.0f, top = 0.0f;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const long long nx = cx + dx, ny = cy + dy;
          const long long wx = ((nx % cells) + cells) % cells, wy = ((ny % cells) + cells) % cells;
          const float jx = kBumpJitter * (2.0f * noise::unit(s_bump, wx, wy, 1) - 1.0f);
          const float jy = kBumpJitter * (2.0f * noise::unit(s_bump, wx, wy, 2) - 1.0f);
          const float a = glm::mix(kBumpHeightLo, kBumpHeightHi, noise::unit(s_bump, wx, wy, 3));
          const float radius = glm::mix(kBumpRadiusLo, kBumpRadiusHi, noise::unit(s_bump, wx, wy, 4));
          const double ddx = (double(nx) + 0.5 + jx - x) * cell_mm, ddy = (double(ny) + 0.5 + jy - y) * cell_mm;
          const float q = float((ddx * ddx + ddy * ddy) / (double(radius) * radius));
          if (q < 1.0f) {
            const float cap = (1.0f - q) * (1.0f - q);
            bumps += a * cap;
            top = std::max(top, cap);
          }
        }
      const double u = d.u(i), v = d.u(j);
      const std::size_t k = t.index(i, j);
      out.height_mm[k] = bumps + kMicroReliefMm * noise::fbm(s_micro, u, v, micro_cells, 2);
      const float tint = 0.02f * noise::fbm(s_tint, u, v, tint_cells, 3) + 0.008f * noise::fbm(s_speck, u, v, micro_cells, 1);
      t.base_color[k] = glm::clamp(paint * (1.0f + tint), 0.0f, 1.0f);
      t.roughness[k] = glm::mix(kRoughValley, kRoughTop, top) + 0.01f * noise::fbm(s_speck, v, u, micro_cells, 1);
      t.metallic[k] = 0.0f;
    }
  });
}

}  // namespace svbrdf::family
