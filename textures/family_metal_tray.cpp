// Metal tray: polished metal (metallic 1, roughness 0.05–0.1) with fingerprints around the rim —
// the case where averaging roughness is badly wrong: a coarse texel over a print holds two lobes
// (α ≈ 0.005 clean metal and α ≈ 0.25 on the ridges of residue), not one lobe of their mean.
// A print: skin oil left on the friction ridges (period 0.42–0.52 mm) of a fingertip contact
// ellipse of about 13–16 × 17–21 mm, in a whorl; the residue scatters (roughness 0.4–0.6), tints
// the metal slightly, and stands about 1.5 µm proud (slopes of a few hundredths). Prints sit 4–9 mm
// in from the edges of the texture (the tray's rim), about one per 60 mm of rim.
#include <string>

#include "base/error.h"
#include "textures/families.h"
#include "textures/noise.h"
#include "base/math.h"

namespace svbrdf::family {

namespace {

// F0 of the metals (linear Rec.709), as the usual reference tables give it for glTF base color.
glm::vec3 metal_color(std::string_view variant) {
  if (variant == "steel") return {0.562f, 0.565f, 0.578f};
  if (variant == "silver") return {0.972f, 0.960f, 0.915f};
  if (variant == "brass") return {0.910f, 0.778f, 0.423f};
  throw Error("metal-tray: unknown variant \"" + std::string(variant) + "\"");
}

constexpr float kPolishLo = 0.05f, kPolishHi = 0.10f, kPolishMean = 0.075f;
constexpr double kPolishFeatureMm = 20.0;
constexpr double kRimPerPrintMm = 60.0;
constexpr float kInsetLo = 4.0f, kInsetHi = 9.0f;          // print center from the edge, mm
constexpr float kAcrossLo = 6.5f, kAcrossHi = 8.0f;        // contact ellipse semi-axes, mm
constexpr float kAlongLo = 8.5f, kAlongHi = 10.5f;
constexpr float kRidgeLo = 0.42f, kRidgeHi = 0.52f;        // ridge period, mm
constexpr float kResidueRoughLo = 0.45f, kResidueRoughHi = 0.55f;
constexpr float kResidueHeightMm = 0.0015f;
const glm::vec3 kResidueTint(0.95f, 0.92f, 0.86f);         // a thin oil film: slightly warm, darker

struct Print {
  glm::dvec2 center;   // mm
  glm::dvec2 along;    // unit: the finger's axis
  double across_mm, along_mm, ridge_mm;
  glm::dvec2 core;     // whorl center in the print frame, mm
  int spin;            // ±1: the whorl's spiral sense (an integer keeps the ridges continuous)
  float roughness;
  std::uint64_t seed;
};

// Residue coverage in [0, 1] of a print at offset p (mm) from its center.
float residue(const Print& f, glm::dvec2 p) {
  const glm::dvec2 across(-f.along.y, f.along.x);
  const double x = glm::dot(p, across), y = glm::dot(p, f.along);  // print frame
  const float envelope_noise = 0.1f * noise::gradient(f.seed, x / 3.0 + 100.0, y / 3.0 + 100.0, 1 << 20, 1 << 20);
  const float e = float(std::sqrt((x / f.across_mm) * (x / f.across_mm) + (y / f.along_mm) * (y / f.along_mm)));
  const float envelope = 1.0f - noise::smoothstep(0.8f, 1.0f, e + envelope_noise);
  if (envelope <= 0.0f) return 0.0f;
  // Whorl: ridges along level sets of an elongated radius around the core, turned into one
  // spiral arm, and warped by noise so they wander and split as real ridges do.
  const double cx = x - f.core.x, cy = y - f.core.y;
  const double rho = std::sqrt(cx * cx + (cy / 1.25) * (cy / 1.25));
  const double theta = std::atan2(cy, cx);
  const double warp = 0.6 * noise::gradient(f.seed ^ 0x77, x / 2.0 + 50.0, y / 2.0 + 50.0, 1 << 20, 1 << 20);
  const double phase = rho / f.ridge_mm + f.spin * theta / (2.0 * kPiD) + warp;
  const float ridge = noise::smoothstep(0.50f, 0.62f, float(0.5 + 0.5 * std::cos(2.0 * kPiD * phase)));
  // Pressure varies over the contact: parts of the print are faint or missing.
  const float pressure = noise::smoothstep(-0.35f, 0.25f, noise::gradient(f.seed ^ 0x55, x / 3.0 + 7.0, y / 3.0 + 7.0, 1 << 20, 1 << 20));
  return ridge * envelope * pressure;
}

}  // namespace

void metal_tray(const Domain& d, std::string_view variant, std::uint64_t seed, Canvas& out) {
  const glm::vec3 metal = metal_color(variant);
  out.base_color_format = PixelFormat::uint16;          // the tint is a few percent
  out.metallic_roughness_format = PixelFormat::uint16;  // roughness 0.05–0.1 would band in 8 bits
  const double side = d.side_mm();
  MaterialTexels& t = out.texels;
  std::vector<float>& h = out.height_mm;

  // Clean polished metal everywhere first.
  const int polish_cells = noise::cells_for(side, kPolishFeatureMm);
  const std::uint64_t s_polish = noise::hash(seed, 31);
  for_each_row(d.size, [&](int j) {
    for (int i = 0; i < d.size; ++i) {
      const std::size_t k = t.index(i, j);
      t.base_color[k] = metal;
      t.metallic[k] = 1.0f;
      t.roughness[k] = glm::clamp(kPolishMean + 0.025f * noise::fbm(s_polish, d.u(i), d.u(j), polish_cells, 3), kPolishLo, kPolishHi);
      h[k] = 0.0f;
    }
  });

  // Place the prints along the rim, serially (a fixed sequence per seed).
  noise::Sequence rng(seed, 32);
  const int prints = std::max(1, int(std::lround(4.0 * side / kRimPerPrintMm)));
  std::vector<Print> list;
  for (int n = 0; n < prints; ++n) {
    Print f;
    const double t_rim = rng.uniform() * 4.0 * side;
    const int edge = std::min(3, int(t_rim / side));
    const double along_edge = t_rim - edge * side;
    const double inset = std::min(double(rng.uniform(kInsetLo, kInsetHi)), 0.5 * side);
    static constexpr glm::dvec2 kInward[4] = {{0, 1}, {-1, 0}, {0, -1}, {1, 0}};  // top, right, bottom, left
    const glm::dvec2 edge_point[4] = {{along_edge, 0}, {side, along_edge}, {along_edge, side}, {0, along_edge}};
    f.center = edge_point[edge] + inset * kInward[edge];
    const double turn = (rng.uniform() - 0.5) * 0.9;  // ±25° from perpendicular to the edge
    const glm::dvec2 in = kInward[edge];
    f.along = {in.x * std::cos(turn) - in.y * std::sin(turn), in.x * std::sin(turn) + in.y * std::cos(turn)};
    f.across_mm = rng.uniform(kAcrossLo, kAcrossHi);
    f.along_mm = rng.uniform(kAlongLo, kAlongHi);
    f.ridge_mm = rng.uniform(kRidgeLo, kRidgeHi);
    f.core = {rng.uniform(-1.0f, 1.0f), rng.uniform(-0.15f, 0.15f) * f.along_mm};
    f.spin = rng.uniform() < 0.5f ? -1 : 1;
    f.roughness = rng.uniform(kResidueRoughLo, kResidueRoughHi);
    f.seed = noise::hash(seed, 33, n);
    list.push_back(f);
  }

  // Each print touches only its bounding box, on the periodic texture: a box wider than the
  // texture (a small tray) wraps onto itself, and every image of the print counts, so the texture
  // still tiles. Overlapping prints keep the heavier residue. Rows r < min(box, size) are distinct
  // texture rows, so the parallel loop never writes a texel twice at once.
  std::vector<float> coverage(t.size(), 0.0f), residue_rough(t.size(), 0.0f);
  for (const Print& f : list) {
    const double reach = 1.05 * std::max(f.across_mm, f.along_mm);
    const int box = int(std::ceil(2.0 * reach / d.mm_per_texel)) + 2;
    const int i0 = int(std::floor((f.center.x - reach) / d.mm_per_texel)), j0 = int(std::floor((f.center.y - reach) / d.mm_per_texel));
    const int span = std::min(box, d.size);
    for_each_row(span, [&](int r) {
      for (int bj = r; bj < box; bj += d.size) {
        const int j = ((j0 + bj) % d.size + d.size) % d.size;
        for (int c = 0; c < span; ++c) {
          for (int bi = c; bi < box; bi += d.size) {
            const int i = ((i0 + bi) % d.size + d.size) % d.size;
            const glm::dvec2 p((i0 + bi + 0.5) * d.mm_per_texel - f.center.x, (j0 + bj + 0.5) * d.mm_per_texel - f.center.y);
            const float cov = residue(f, p);
            const std::size_t k = t.index(i, j);
            if (cov > coverage[k]) {
              coverage[k] = cov;
              residue_rough[k] = f.roughness;
            }
          }
        }
      }
    });
  }

  for_each_row(d.size, [&](int j) {
    for (int i = 0; i < d.size; ++i) {
      const std::size_t k = t.index(i, j);
      const float c = coverage[k];
      if (c <= 0.0f) continue;
      t.roughness[k] = glm::mix(t.roughness[k], residue_rough[k], c);
      t.base_color[k] = metal * glm::mix(glm::vec3(1.0f), kResidueTint, c);
      h[k] = kResidueHeightMm * c;
    }
  });
}

}  // namespace svbrdf::family
