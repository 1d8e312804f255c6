// Sandstone: a sedimentary rock of cemented sand grains (~0.1–0.5 mm), laid down in strata. The
// texture shows the bedding as bands a few mm thick, gently warped, colored by the iron oxides of
// each layer; grain-scale noise in color, roughness and height; harder bands standing out by a
// fraction of a mm (differential weathering). Sandstone is matte: roughness 0.8–1. The variants
// differ in color and roughness (§27.2: "at one point red sandstone and at another ochre"); `mixed`
// puts red and ochre regions on one surface.
#include <string>

#include "base/error.h"
#include "textures/families.h"
#include "textures/noise.h"

namespace svbrdf::family {

namespace {

struct SandstoneLook {
  glm::vec3 light, dark;      // linear albedo of the light and dark strata
  float rough_lo, rough_hi;   // perceptual roughness range
};

SandstoneLook look(std::string_view variant) {
  if (variant == "red") return {srgb8(181, 101, 74), srgb8(142, 69, 52), 0.85f, 0.97f};
  if (variant == "ochre") return {srgb8(206, 154, 85), srgb8(168, 116, 60), 0.80f, 0.92f};
  if (variant == "buff") return {srgb8(220, 200, 162), srgb8(189, 167, 131), 0.88f, 1.00f};
  throw Error("sandstone: unknown variant \"" + std::string(variant) + "\"");
}

constexpr double kGrainMm = 0.3;        // sand grain size
constexpr double kBandMm = 6.0;         // bedding band thickness
constexpr double kLaminaMm = 1.2;       // fine laminae within bands
constexpr double kWarpFeatureMm = 40.0; // the bedding's waviness wavelength
constexpr double kWarpMm = 3.0;         // and amplitude
constexpr double kRegionMm = 30.0;      // `mixed`: size of red / ochre regions
constexpr float kGrainReliefMm = 0.03f; // grain-scale relief
constexpr float kBandReliefMm = 0.15f;  // hard bands stand out by this much

}  // namespace

void sandstone(const Domain& d, std::string_view variant, std::uint64_t seed, Canvas& out) {
  const bool mixed = variant == "mixed";
  const SandstoneLook a = look(mixed ? "red" : variant), b = look(mixed ? "ochre" : variant);
  const double side = d.side_mm();
  const int warp_cells = noise::cells_for(side, kWarpFeatureMm);
  const int band_cells = noise::cells_for(side, kBandMm);
  const int lamina_cells = noise::cells_for(side, kLaminaMm);
  const int grain_cells = noise::cells_for(side, kGrainMm);
  const int region_cells = noise::cells_for(side, kRegionMm);
  const std::uint64_t s_warp = noise::hash(seed, 1), s_band = noise::hash(seed, 2), s_lam = noise::hash(seed, 3),
                      s_grain = noise::hash(seed, 4), s_relief = noise::hash(seed, 5), s_region = noise::hash(seed, 6);
  MaterialTexels& t = out.texels;
  for_each_row(d.size, [&](int j) {
    for (int i = 0; i < d.size; ++i) {
      const double u = d.u(i), v = d.u(j);
      // Strata run along u; the bedding coordinate (in texture units, periodic) is v, warped.
      const double s = v + (kWarpMm / side) * noise::fbm(s_warp, u, v, warp_cells, 3);
      const float band = 0.5f + 0.6f * noise::gradient1(s_band, s * band_cells, band_cells) +
                         0.3f * noise::gradient1(s_lam, s * lamina_cells, lamina_cells);
      const float layer = glm::clamp(band, 0.0f, 1.0f);
      const float grain = noise::fbm(s_grain, u, v, grain_cells, 2);  // about [−1, 1]
      float w = 0.0f;  // weight of look b (mixed only)
      if (mixed) w = noise::smoothstep(-0.15f, 0.15f, noise::fbm(s_region, u, v, region_cells, 3));
      const glm::vec3 light = glm::mix(a.light, b.light, w), dark = glm::mix(a.dark, b.dark, w);
      const float lo = glm::mix(a.rough_lo, b.rough_lo, w), hi = glm::mix(a.rough_hi, b.rough_hi, w);
      const std::size_t k = t.index(i, j);
      t.base_color[k] = glm::clamp(glm::mix(dark, light, layer) * (1.0f + 0.10f * grain), 0.0f, 1.0f);
      // Rougher where grains stand proud; dark (cemented, finer) layers a little smoother.
      t.roughness[k] = glm::clamp(glm::mix(lo, hi, 0.5f + 0.35f * grain + 0.2f * (layer - 0.5f)), lo, hi);
      t.metallic[k] = 0.0f;
      out.height_mm[k] = kGrainReliefMm * noise::fbm(s_relief, u, v, grain_cells, 2) + kBandReliefMm * (1.0f - layer);
    }
  });
}

}  // namespace svbrdf::family
