// Granite: an interlocking aggregate of crystals 1–5 mm across — feldspar (white plagioclase or
// pink orthoclase), quartz (gray, glassy), hornblende (green-black) — strewn with flecks of black
// biotite mica, the case §27.11 says a spatially varying BRDF is right for. Each mineral has its
// own base color and roughness; the mica's cleavage faces are the glossiest and, where the
// polish plucked a flake out, sit in a shallow pit (20 µm) whose floor is tilted up to 6°, so they
// glint. In glTF's metallic-roughness model a dielectric's specular reflectance is fixed (F0 =
// 0.04); the minerals' specular differs by lobe width (roughness) and, relative to their diffuse
// part, by their albedo: on dark mica the specular lobe is nearly all there is.
// Variants: gray and pink are honed (matte), polished is gray with a mirror polish.
#include <string>

#include "base/error.h"
#include "textures/families.h"
#include "textures/noise.h"

namespace svbrdf::family {

namespace {

struct Mineral {
  glm::vec3 color;
  float roughness;
};

struct GraniteLook {
  Mineral feldspar, quartz, hornblende, biotite;
  float relief_mm;  // honing scratches and grain-scale relief
};

GraniteLook look(std::string_view variant) {
  const Mineral quartz_honed{srgb8(142, 143, 147), 0.42f}, hornblende_honed{srgb8(47, 54, 48), 0.50f},
      biotite_honed{srgb8(30, 28, 26), 0.16f};
  if (variant == "gray") return {{srgb8(217, 212, 203), 0.55f}, quartz_honed, hornblende_honed, biotite_honed, 0.004f};
  if (variant == "pink") return {{srgb8(201, 138, 120), 0.55f}, quartz_honed, hornblende_honed, biotite_honed, 0.004f};
  if (variant == "polished")
    return {{srgb8(217, 212, 203), 0.16f}, {srgb8(142, 143, 147), 0.10f}, {srgb8(47, 54, 48), 0.14f},
            {srgb8(30, 28, 26), 0.06f}, 0.0008f};
  throw Error("granite: unknown variant \"" + std::string(variant) + "\"");
}

constexpr double kCrystalMm = 3.0;       // feldspar / quartz / hornblende crystals
constexpr double kFleckCellMm = 1.0;     // mica fleck grid
constexpr float kFleckChance = 0.14f;    // of a fleck cell holding a fleck
constexpr float kFleckRadiusLo = 0.22f, kFleckRadiusHi = 0.42f;  // mm
constexpr float kPitDepthMm = 0.02f, kMaxTilt = 0.105f;           // tan 6°
constexpr float kGrooveMm = 0.006f, kGrooveWidth = 0.04f;          // grain boundaries (cell units)
constexpr float kFeldspar = 0.55f, kQuartz = 0.87f;                // cumulative shares; the rest hornblende
constexpr double kReliefFeatureMm = 0.2;

}  // namespace

void granite(const Domain& d, std::string_view variant, std::uint64_t seed, Canvas& out) {
  const GraniteLook g = look(variant);
  const double side = d.side_mm();
  const int crystal_cells = noise::cells_for(side, kCrystalMm), fleck_cells = noise::cells_for(side, kFleckCellMm);
  const double fleck_cell_mm = side / fleck_cells, crystal_cell_mm = side / crystal_cells;
  const int relief_cells = noise::cells_for(side, kReliefFeatureMm);
  const std::uint64_t s_crystal = noise::hash(seed, 41), s_fleck = noise::hash(seed, 42), s_relief = noise::hash(seed, 43),
                      s_mottle = noise::hash(seed, 44), s_warp = noise::hash(seed, 45);
  const double warp = 0.25 / crystal_cells;  // a quarter crystal, in texture units
  MaterialTexels& t = out.texels;
  for_each_row(d.size, [&](int j) {
    for (int i = 0; i < d.size; ++i) {
      const double u = d.u(i), v = d.u(j);
      // Crystals: cells of a jittered grid, their straight Voronoi edges bent by a domain warp of
      // a quarter crystal so they interlock as grains in a rock do.
      const double wu = u + warp * noise::fbm(s_warp, u, v, crystal_cells, 2);
      const double wv = v + warp * noise::fbm(s_warp ^ 1, u, v, crystal_cells, 2);
      const noise::CellularHit crystal = noise::cellular(s_crystal, wu, wv, crystal_cells);
      const float pick = noise::unit(s_crystal, crystal.cell_x, crystal.cell_y, 7);
      const Mineral& m = pick < kFeldspar ? g.feldspar : (pick < kQuartz ? g.quartz : g.hornblende);
      // Each crystal a little different; a faint mottle inside it.
      const float grain_shade = 1.0f + 0.12f * (noise::unit(s_crystal, crystal.cell_x, crystal.cell_y, 8) - 0.5f);
      const float mottle = 1.0f + 0.05f * noise::fbm(s_mottle, u, v, relief_cells, 2);
      const float grain_rough = 0.06f * (noise::unit(s_crystal, crystal.cell_x, crystal.cell_y, 9) - 0.5f);
      glm::vec3 color = m.color * grain_shade * mottle;
      float roughness = m.roughness + grain_rough;
      // Grain boundaries: a hairline groove where two crystals meet (F2 − F1 small).
      const float boundary = 1.0f - noise::smoothstep(0.0f, kGrooveWidth * float(kCrystalMm / crystal_cell_mm), crystal.f2 - crystal.f1);
      float height = g.relief_mm * noise::fbm(s_relief, u, v, relief_cells, 2) - kGrooveMm * boundary;
      color *= 1.0f - 0.25f * boundary;

      // Mica flecks, over the crystals.
      const noise::CellularHit fleck = noise::cellular(s_fleck, u, v, fleck_cells);
      if (noise::unit(s_fleck, fleck.cell_x, fleck.cell_y, 1) < kFleckChance) {
        // A mica platelet: an ellipse (aspect 1.3–2.2, any orientation) with a ragged outline.
        const float radius = glm::mix(kFleckRadiusLo, kFleckRadiusHi, noise::unit(s_fleck, fleck.cell_x, fleck.cell_y, 2));
        const float aspect = glm::mix(1.3f, 2.2f, noise::unit(s_fleck, fleck.cell_x, fleck.cell_y, 8));
        const float turn = 6.2832f * noise::unit(s_fleck, fleck.cell_x, fleck.cell_y, 9);
        const glm::vec2 to_center_mm = fleck.to_nearest * float(fleck_cell_mm);
        const float px = std::cos(turn) * to_center_mm.x + std::sin(turn) * to_center_mm.y;
        const float py = -std::sin(turn) * to_center_mm.x + std::cos(turn) * to_center_mm.y;
        const float a = radius * std::sqrt(aspect), b = radius / std::sqrt(aspect);
        const float angle = std::atan2(py, px);
        const float ragged = 1.0f + 0.12f * std::sin(5.0f * angle + 6.2832f * noise::unit(s_fleck, fleck.cell_x, fleck.cell_y, 3));
        if ((px / a) * (px / a) + (py / b) * (py / b) < ragged * ragged) {
          color = g.biotite.color * (1.0f + 0.1f * (noise::unit(s_fleck, fleck.cell_x, fleck.cell_y, 4) - 0.5f));
          roughness = g.biotite.roughness + 0.02f * (noise::unit(s_fleck, fleck.cell_x, fleck.cell_y, 5) - 0.5f);
          const float tilt = kMaxTilt * noise::unit(s_fleck, fleck.cell_x, fleck.cell_y, 6);
          const float azimuth = 6.2832f * noise::unit(s_fleck, fleck.cell_x, fleck.cell_y, 7);
          // The pit floor: a plane through the fleck center, below the surface everywhere inside.
          const float rise = -tilt * (std::cos(azimuth) * to_center_mm.x - std::sin(azimuth) * to_center_mm.y);
          height = std::min(-kPitDepthMm + rise, -0.25f * kPitDepthMm);
        }
      }
      const std::size_t k = t.index(i, j);
      t.base_color[k] = glm::clamp(color, 0.0f, 1.0f);
      t.roughness[k] = glm::clamp(roughness, 0.02f, 1.0f);
      t.metallic[k] = 0.0f;
      out.height_mm[k] = height;
    }
  });
}

}  // namespace svbrdf::family
