#include "textures/random_material.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "base/error.h"
#include "base/math.h"
#include "textures/families.h"
#include "textures/height_field.h"
#include "textures/noise.h"

namespace svbrdf {

namespace {

// One stream per ingredient (see the header: a new ingredient must not shift the others' draws).
enum Stream : std::uint64_t {
  kRoughnessStream = 1,
  kReliefStream = 2,
  kMetalStream = 3,
  kColorStream = 4,
  kSpecularStream = 5,  // reserved: KHR_materials_specular / ior
  kSheenStream = 6,
  kAnisotropyStream = 7,
  kTransmissionStream = 8,
};

constexpr float kMinRoughness = 0.02f, kMaxRoughness = 1.0f;
// Relative roughness variation within a population is on features of this many texels: it only has
// to keep a population from being one value.
constexpr double kRoughnessVariationFeature = 16.0;
// A mask's edge, as a share of the texels: sharp for populations and metal (a film's or a paint's
// edge), soft for the relief's extent (a hard edge would make the mask's own gradient the steepest
// slope).
constexpr float kSharpEdge = 0.02f, kSoftEdge = 0.2f;

float log_uniform(noise::Sequence& s, float lo, float hi) { return std::exp(s.uniform(std::log(lo), std::log(hi))); }

// Hue in [0, 1), saturation and value in [0, 1], as linear RGB.
glm::vec3 hsv(float h, float s, float v) {
  const float k[3] = {5.0f, 3.0f, 1.0f};
  glm::vec3 c;
  for (int i = 0; i < 3; ++i) {
    const float t = std::fmod(k[i] + 6.0f * h, 6.0f);
    c[i] = v - v * s * std::clamp(std::min(t, 4.0f - t), 0.0f, 1.0f);
  }
  return c;
}

// Lattice cells across the texture for features of `feature` texels.
int cells(int size, float feature) { return std::max(1, int(std::lround(size / double(feature)))); }

// A fractal noise field over the texture, one value per texel.
std::vector<float> field(std::uint64_t seed, int size, float feature) {
  std::vector<float> f(std::size_t(size) * size);
  const int n = cells(size, feature);
  family::for_each_row(size, [&](int j) {
    for (int i = 0; i < size; ++i) f[std::size_t(j) * size + i] = noise::fbm(seed, (i + 0.5) / size, (j + 0.5) / size, n, 3);
  });
  return f;
}

// A mask in [0, 1] over the texels ranked by their field value: 0 on the lowest 1 − share − edge/2
// of them, 1 on the highest share − edge/2, a smooth ramp over the `edge` share between. The ranks
// are the field's quantiles, so the shares are exact whatever the noise's spread.
std::vector<float> mask(std::vector<float> f, float share, float edge) {
  std::vector<float> sorted = f;
  std::sort(sorted.begin(), sorted.end());
  const auto quantile = [&](double q) { return sorted[std::size_t(std::clamp(q, 0.0, 1.0) * double(sorted.size() - 1))]; };
  const float lo = quantile(1.0 - share - 0.5 * edge), hi = quantile(1.0 - share + 0.5 * edge);
  for (float& v : f) v = hi > lo ? noise::smoothstep(lo, hi, v) : float(v >= hi);
  return f;
}

// The relief's heights in texel units, before their scale is set by the steepest tilt.
std::vector<float> relief_heights(const RandomMaterialDraw& d, int size) {
  std::vector<float> h(std::size_t(size) * size, 0.0f);
  const std::uint64_t s = noise::hash(d.seed, kReliefStream, 1);
  const glm::ivec2 a = d.corrugation_axis;
  // A corrugation's phase a·(u, v)·n is periodic over the texture for integer a and n.
  const int n_axis = std::max(1, int(std::lround(size / (d.relief_feature * std::hypot(double(a.x), double(a.y))))));
  const int n = cells(size, d.relief_feature);
  family::for_each_row(size, [&](int j) {
    for (int i = 0; i < size; ++i) {
      const double u = (i + 0.5) / size, v = (j + 0.5) / size;
      float z = 0.0f;
      switch (d.relief) {
        case Relief::flat:
          break;
        case Relief::dents: {
          // A hammered dent per cell: a smooth dimple of radius 0.45 cells (flat rim, no crease) and
          // its own depth, so the dents neither touch nor repeat.
          const noise::CellularHit c = noise::cellular(s, u, v, n);
          const float depth = 0.5f + 0.5f * noise::unit(s, c.cell_x, c.cell_y);
          const float q = std::max(0.0f, 1.0f - (c.f1 / 0.45f) * (c.f1 / 0.45f));
          z = -depth * q * q;
          break;
        }
        case Relief::bumps:
          z = noise::fbm(s, u, v, n, 3);
          break;
        case Relief::ribbed:
          z = float(std::sin(2.0 * kPiD * (a.x * u + a.y * v) * n_axis));
          break;
        case Relief::brushed: {
          // Scratches: a random profile across the brushing direction, two octaves.
          const double x = (a.x * u + a.y * v) * n_axis;
          z = noise::gradient1(s, x, n_axis) + 0.5f * noise::gradient1(noise::hash(s, 2), 2.0 * x, 2 * n_axis);
          break;
        }
      }
      h[std::size_t(j) * size + i] = z;
    }
  });
  if (d.relief_share < 1.0f) {
    const std::vector<float> m = mask(field(noise::hash(d.seed, kReliefStream, 2), size, 2.0f * d.relief_feature + 8.0f),
                                      d.relief_share, kSoftEdge);
    for (std::size_t k = 0; k < h.size(); ++k) h[k] *= m[k];
  }
  return h;
}

const char* relief_name(Relief r) {
  switch (r) {
    case Relief::flat: return "flat";
    case Relief::dents: return "dents";
    case Relief::bumps: return "bumps";
    case Relief::ribbed: return "ribbed";
    case Relief::brushed: return "brushed";
  }
  return "?";
}

}  // namespace

RandomMaterialDraw draw_random_material(std::uint64_t seed) {
  RandomMaterialDraw d;
  d.seed = seed;
  {
    // Every number of a stream is drawn whatever the branches take, so that no choice shifts the
    // draws after it (a second population's ratio, side, share and size are drawn for every seed).
    noise::Sequence s(seed, kRoughnessStream);
    d.roughness = log_uniform(s, kMinRoughness, kMaxRoughness);
    d.roughness_variation = s.uniform(0.0f, 0.15f);
    const bool two = s.uniform() < 0.5f;
    const float ratio = log_uniform(s, 2.5f, 10.0f);
    const bool up = s.uniform() < 0.5f;
    d.second_share = s.uniform(0.1f, 0.6f);
    d.second_feature = log_uniform(s, 3.0f, 24.0f);
    if (two) {
      // The other side where one side leaves the range; clamped, the two stay ≥ 2.5× apart, since
      // [0.02, 1] spans 50× and r1 is at least √50 from one of its ends.
      float r2 = up ? d.roughness * ratio : d.roughness / ratio;
      if (r2 > kMaxRoughness || r2 < kMinRoughness) r2 = up ? d.roughness / ratio : d.roughness * ratio;
      d.second_roughness = std::clamp(r2, kMinRoughness, kMaxRoughness);
    } else {
      d.second_share = 0.0f;
    }
  }
  {
    noise::Sequence s(seed, kReliefStream);
    const float kind = s.uniform();
    const bool ribbed = s.uniform() < 0.5f;
    d.relief = kind < 0.15f ? Relief::flat : kind < 0.45f ? Relief::dents : kind < 0.75f ? Relief::bumps
             : ribbed      ? Relief::ribbed
                           : Relief::brushed;
    const bool corrugated = d.relief == Relief::ribbed || d.relief == Relief::brushed;
    d.relief_feature = corrugated ? log_uniform(s, 2.0f, 16.0f) : log_uniform(s, 3.0f, 32.0f);
    d.max_tilt_deg = d.relief == Relief::flat ? 0.0f : s.uniform(5.0f, 35.0f);
    const bool partial = s.uniform() < 0.5f;
    const float share = s.uniform(0.3f, 0.9f);
    d.relief_share = partial && d.relief != Relief::flat ? share : 1.0f;
    static constexpr glm::ivec2 kAxes[4] = {{1, 0}, {0, 1}, {1, 1}, {1, -1}};
    d.corrugation_axis = kAxes[std::min(3, int(s.uniform() * 4.0f))];
  }
  {
    noise::Sequence s(seed, kMetalStream);
    const float kind = s.uniform();
    d.metal = kind < 0.35f ? MetalMix::dielectric : kind < 0.7f ? MetalMix::metal : MetalMix::both;
    d.metal_share = d.metal == MetalMix::both ? s.uniform(0.2f, 0.8f) : d.metal == MetalMix::metal ? 1.0f : 0.0f;
    d.metal_feature = log_uniform(s, 4.0f, 32.0f);
  }
  {
    noise::Sequence s(seed, kColorStream);
    const float mh = s.uniform(), ms = s.uniform(0.0f, 0.4f), mv = s.uniform(0.5f, 0.98f);
    const float dh = s.uniform(), ds = s.uniform(0.0f, 0.8f), dv = s.uniform(0.03f, 0.85f);
    d.metal_color = hsv(mh, ms, mv);
    d.dielectric_color = hsv(dh, ds, dv);
    d.color_variation = s.uniform(0.0f, 0.3f);
    d.color_feature = log_uniform(s, 2.0f, 32.0f);
  }
  {
    noise::Sequence s(seed, kSheenStream);
    const bool sheen = s.uniform() < 1.0f / 3.0f;
    const float h = s.uniform(), sat = s.uniform(0.0f, 0.6f), v = s.uniform(0.2f, 1.0f);
    const float roughness = s.uniform(0.1f, 1.0f);
    const bool textured = s.uniform() < 0.5f;
    const float share = s.uniform(0.2f, 0.8f), feature = log_uniform(s, 3.0f, 24.0f), variation = s.uniform(0.0f, 0.3f);
    if (sheen) {
      d.sheen_color = hsv(h, sat, v);
      d.sheen_roughness = roughness;
      d.sheen_textured = textured;
      if (textured) d.sheen_share = share, d.sheen_feature = feature, d.sheen_roughness_variation = variation;
    }
  }
  {
    noise::Sequence s(seed, kAnisotropyStream);
    const bool anisotropic = s.uniform() < 1.0f / 3.0f;
    const float strength = s.uniform(0.2f, 1.0f), rotation = s.uniform(0.0f, 3.14159265f);
    const bool textured = s.uniform() < 0.5f;
    const float swirl = s.uniform(0.0f, 90.0f), feature = log_uniform(s, 4.0f, 32.0f), variation = s.uniform(0.0f, 0.5f);
    if (anisotropic) {
      d.anisotropy = strength;
      d.anisotropy_rotation = rotation;
      d.anisotropy_textured = textured;
      if (textured) d.anisotropy_swirl_deg = swirl, d.anisotropy_feature = feature, d.anisotropy_variation = variation;
    }
  }
  {
    noise::Sequence s(seed, kTransmissionStream);
    const bool transmits = s.uniform() < 0.25f;
    const float factor = s.uniform(0.2f, 1.0f);
    const bool textured = s.uniform() < 0.5f;
    const float share = s.uniform(0.2f, 0.8f), feature = log_uniform(s, 3.0f, 24.0f);
    if (transmits && d.metal != MetalMix::metal) {
      d.transmission = factor;
      d.transmission_textured = textured;
      if (textured) d.transmission_share = share, d.transmission_feature = feature;
    }
  }
  // KHR_materials_specular / ior: noise::Sequence(seed, kSpecularStream) draws them here (specular
  // weight, specular colour, ior) once MaterialTexels has the fields.
  return d;
}

MaterialTexels random_material_texels(const RandomMaterialDraw& d, int size) {
  if (size < 1) throw Error("random material: size " + std::to_string(size) + " must be at least 1");
  MaterialTexels t(size, size);

  // Roughness: each population varied about its value, the second where its mask is, mixed in log.
  const std::vector<float> variation =
      field(noise::hash(d.seed, kRoughnessStream, 1), size, float(kRoughnessVariationFeature));
  std::vector<float> second;
  if (d.second_share > 0.0f)
    second = mask(field(noise::hash(d.seed, kRoughnessStream, 2), size, d.second_feature), d.second_share, kSharpEdge);
  for (std::size_t k = 0; k < t.size(); ++k) {
    float ln_r = std::log(d.roughness);
    if (!second.empty()) ln_r += second[k] * std::log(d.second_roughness / d.roughness);
    t.roughness[k] = std::clamp(std::exp(ln_r) * (1.0f + d.roughness_variation * variation[k]), kMinRoughness, kMaxRoughness);
  }

  // Relief: heights scaled so that the steepest texel tilts by exactly max_tilt_deg.
  std::vector<float> h = relief_heights(d, size);
  float steepest = 0.0f;
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) steepest = std::max(steepest, glm::length(height_slope(h, size, size, 1.0, i, j)));
  if (steepest > 0.0f) {
    const float scale = float(std::tan(d.max_tilt_deg * kPiD / 180.0)) / steepest;
    for (float& z : h) z *= scale;
    normals_from_height(h, size, size, 1.0, t.normal);
  }

  // Metal, and colour: the metal's and the dielectric's own colour, each varied in brightness.
  std::vector<float> metal;
  if (d.metal == MetalMix::both)
    metal = mask(field(noise::hash(d.seed, kMetalStream, 1), size, d.metal_feature), d.metal_share, kSharpEdge);
  const std::vector<float> shade = field(noise::hash(d.seed, kColorStream, 1), size, d.color_feature);
  for (std::size_t k = 0; k < t.size(); ++k) {
    const float m = d.metal == MetalMix::both ? metal[k] : d.metal == MetalMix::metal ? 1.0f : 0.0f;
    const float f = 1.0f + d.color_variation * shade[k];
    t.metallic[k] = m;
    t.base_color[k] = glm::clamp(f * glm::mix(d.dielectric_color, d.metal_color, m), glm::vec3(0.0f), glm::vec3(1.0f));
  }

  // Sheen: its factors, and for a textured one its patches and its roughness's variation per texel.
  if (d.sheen_color != glm::vec3(0.0f)) {
    t.sheen_color_factor = d.sheen_color;
    t.sheen_roughness_factor = d.sheen_roughness;
    if (d.sheen_textured) {
      const std::vector<float> cover =
          mask(field(noise::hash(d.seed, kSheenStream, 1), size, d.sheen_feature), d.sheen_share, kSharpEdge);
      const std::vector<float> vary = field(noise::hash(d.seed, kSheenStream, 2), size, float(kRoughnessVariationFeature));
      t.sheen_color.resize(t.size());
      t.sheen_roughness.resize(t.size());
      for (std::size_t k = 0; k < t.size(); ++k) {
        t.sheen_color[k] = cover[k] * d.sheen_color;
        t.sheen_roughness[k] = std::clamp(d.sheen_roughness * (1.0f + d.sheen_roughness_variation * vary[k]), 0.0f, 1.0f);
      }
    }
  }
  // Anisotropy: its factors, and for a textured one its direction turned and its strength varied per
  // texel by smooth fields.
  if (d.anisotropy > 0.0f) {
    t.anisotropy_factor = d.anisotropy;
    t.anisotropy_direction_factor = glm::vec2(std::cos(d.anisotropy_rotation), std::sin(d.anisotropy_rotation));
    if (d.anisotropy_textured) {
      const std::vector<float> turn = field(noise::hash(d.seed, kAnisotropyStream, 1), size, d.anisotropy_feature);
      const std::vector<float> vary = field(noise::hash(d.seed, kAnisotropyStream, 2), size, float(kRoughnessVariationFeature));
      t.anisotropy.resize(t.size());
      t.anisotropy_direction.resize(t.size());
      for (std::size_t k = 0; k < t.size(); ++k) {
        const float phi = d.anisotropy_rotation + glm::radians(d.anisotropy_swirl_deg) * turn[k];
        t.anisotropy[k] = std::clamp(d.anisotropy * (1.0f + d.anisotropy_variation * vary[k]), 0.0f, 1.0f);
        t.anisotropy_direction[k] = glm::vec2(std::cos(phi), std::sin(phi));
      }
    }
  }
  // Transmission: its factor, and for a textured one its patches (the texel's value is factor × the
  // texture's, as MaterialTexels holds it).
  if (d.transmission > 0.0f) {
    t.transmission_factor = d.transmission;
    if (d.transmission_textured) {
      const std::vector<float> cover =
          mask(field(noise::hash(d.seed, kTransmissionStream, 1), size, d.transmission_feature), d.transmission_share, kSharpEdge);
      t.transmission.resize(t.size());
      for (std::size_t k = 0; k < t.size(); ++k) t.transmission[k] = cover[k] * d.transmission;
    }
  }
  return t;
}

std::string RandomMaterialDraw::summary() const {
  char buf[512];
  std::string s;
  std::snprintf(buf, sizeof buf, "seed %llu: roughness %.3f ±%.0f%%", static_cast<unsigned long long>(seed), roughness,
                100.0 * roughness_variation);
  s += buf;
  if (second_share > 0.0f) {
    std::snprintf(buf, sizeof buf, " + %.3f on %.0f%% (%.0f-texel blotches)", second_roughness, 100.0 * second_share,
                  second_feature);
    s += buf;
  }
  if (relief == Relief::flat) {
    s += "; flat";
  } else {
    std::snprintf(buf, sizeof buf, "; %s %.0f texels, to %.1f°", relief_name(relief), relief_feature, max_tilt_deg);
    s += buf;
    if (relief == Relief::ribbed || relief == Relief::brushed) {
      std::snprintf(buf, sizeof buf, " along (%d,%d)", corrugation_axis.x, corrugation_axis.y);
      s += buf;
    }
    if (relief_share < 1.0f) {
      std::snprintf(buf, sizeof buf, " on %.0f%%", 100.0 * relief_share);
      s += buf;
    }
  }
  switch (metal) {
    case MetalMix::dielectric:
      std::snprintf(buf, sizeof buf, "; dielectric (%.2f,%.2f,%.2f)", dielectric_color.r, dielectric_color.g, dielectric_color.b);
      break;
    case MetalMix::metal:
      std::snprintf(buf, sizeof buf, "; metal (%.2f,%.2f,%.2f)", metal_color.r, metal_color.g, metal_color.b);
      break;
    case MetalMix::both:
      std::snprintf(buf, sizeof buf, "; metal (%.2f,%.2f,%.2f) on %.0f%% (%.0f-texel patches), dielectric (%.2f,%.2f,%.2f)",
                    metal_color.r, metal_color.g, metal_color.b, 100.0 * metal_share, metal_feature, dielectric_color.r,
                    dielectric_color.g, dielectric_color.b);
      break;
  }
  s += buf;
  std::snprintf(buf, sizeof buf, "; colour ±%.0f%% on %.0f texels", 100.0 * color_variation, color_feature);
  s += buf;
  if (sheen_color != glm::vec3(0.0f)) {
    std::snprintf(buf, sizeof buf, "; sheen (%.2f,%.2f,%.2f) r %.2f", sheen_color.r, sheen_color.g, sheen_color.b,
                  sheen_roughness);
    s += buf;
    if (sheen_textured) {
      std::snprintf(buf, sizeof buf, " on %.0f%% (%.0f-texel patches) ±%.0f%%", 100.0 * sheen_share, sheen_feature,
                    100.0 * sheen_roughness_variation);
      s += buf;
    }
  }
  if (anisotropy > 0.0f) {
    std::snprintf(buf, sizeof buf, "; anisotropy %.2f at %.0f°", anisotropy, glm::degrees(anisotropy_rotation));
    s += buf;
    if (anisotropy_textured) {
      std::snprintf(buf, sizeof buf, " turned ±%.0f° on %.0f texels, strength ±%.0f%%", anisotropy_swirl_deg,
                    anisotropy_feature, 100.0 * anisotropy_variation);
      s += buf;
    }
  }
  if (transmission > 0.0f) {
    std::snprintf(buf, sizeof buf, "; transmission %.2f", transmission);
    s += buf;
    if (transmission_textured) {
      std::snprintf(buf, sizeof buf, " on %.0f%% (%.0f-texel patches)", 100.0 * transmission_share, transmission_feature);
      s += buf;
    }
  }
  return s;
}

}  // namespace svbrdf
