#include "textures/material_family.h"

#include <cmath>

#include "base/error.h"
#include "textures/families.h"
#include "textures/height_field.h"
#include "textures/material_loader.h"
#include "textures/normal_map.h"

namespace svbrdf {

namespace {

const std::vector<MaterialPreset>& presets() {
  // Scales put the smallest feature of each family at several texels: sandstone grains 0.3 mm,
  // paint bumps 2 mm, text strokes 0.22 mm (halftone dots 0.5 mm apart at 0.05 mm), fingerprint
  // ridges 0.42 mm, mica flecks 0.5 mm.
  static const std::vector<MaterialPreset> list = {
      {"sandstone", "sedimentary strata bands, grain noise, matte (roughness 0.8-1)", {"red", "ochre", "buff", "mixed"}, 0.1},
      {"painted-wall", "latex paint: near-constant albedo, bumps ~0.1 mm high ~2 mm apart, roughness ~0.7", {"white", "cream", "gray"}, 0.125},
      {"printed-paper", "white paper with black print; only albedo varies (the control case)", {"text", "halftone"}, 0.1},
      {"metal-tray", "polished metal (roughness 0.05-0.1) with fingerprints around the rim (0.4-0.6)", {"steel", "silver", "brass"}, 0.08},
      {"granite", "feldspar, quartz, hornblende and glossy mica flecks, each its own color and roughness", {"gray", "pink", "polished"}, 0.1},
  };
  return list;
}

std::string joined(const std::vector<std::string_view>& names) {
  std::string s;
  for (std::string_view n : names) s += (s.empty() ? "" : ", ") + std::string(n);
  return s;
}

// Quantizes every value to the integer code a writer of this format stores, so the image in memory
// is exactly what reading the written file gives back.
void quantize(Image& image, PixelFormat format) {
  const float max = format == PixelFormat::uint8 ? 255.0f : (format == PixelFormat::uint16 ? 65535.0f : 0.0f);
  if (max == 0.0f) return;
  for (float& v : image.pixels) v = std::nearbyint(std::clamp(v, 0.0f, 1.0f) * max) / max;
}

}  // namespace

std::span<const MaterialPreset> material_presets() { return presets(); }

const MaterialPreset& find_material_preset(std::string_view name) {
  for (const MaterialPreset& p : presets())
    if (p.name == name) return p;
  std::vector<std::string_view> names;
  for (const MaterialPreset& p : presets()) names.push_back(p.name);
  throw input_error("", "unknown material preset \"" + std::string(name) + "\" (known: " + joined(names) + ")");
}

double default_mm_per_texel(std::string_view preset, std::string_view variant) {
  const MaterialPreset& p = find_material_preset(preset);
  if (p.name == "printed-paper" && variant == "halftone") return 0.05;
  return p.mm_per_texel;
}

ProceduralMaterial generate_material(const MaterialRecipe& recipe, const ColorConfig& color, const ProgressFn& progress) {
  const MaterialPreset& preset = find_material_preset(recipe.preset);
  const std::string variant = recipe.variant.empty() ? std::string(preset.variants.front()) : recipe.variant;
  bool known = false;
  for (std::string_view v : preset.variants) known = known || v == variant;
  if (!known)
    throw input_error(std::string(preset.name), "unknown variant \"" + variant + "\" (known: " + joined(preset.variants) + ")");
  const int n = recipe.size;
  if (n < 1 || n > kMaxMaterialSize || (n & (n - 1)) != 0)
    throw input_error("", "size " + std::to_string(n) + " is not a power of two in [1, " + std::to_string(kMaxMaterialSize) + "]");
  const double mm = recipe.mm_per_texel == 0.0 ? default_mm_per_texel(preset.name, variant) : recipe.mm_per_texel;
  if (!std::isfinite(mm) || mm <= 0.0 || mm > 1000.0)
    throw input_error("", "mm per texel must be in (0, 1000], got " + std::to_string(mm));
  const auto stage = [&](std::string_view s) {
    if (progress) progress(s);
  };

  ProceduralMaterial out;
  out.preset = std::string(preset.name);
  out.variant = variant;
  out.seed = recipe.seed;
  out.mm_per_texel = mm;

  stage("pattern");
  MaterialTexels raw(n, n);
  out.height_mm.assign(raw.size(), 0.0f);
  family::Canvas canvas{raw, out.height_mm};
  const family::Domain domain{n, mm};
  if (preset.name == "sandstone") family::sandstone(domain, variant, recipe.seed, canvas);
  else if (preset.name == "painted-wall") family::painted_wall(domain, variant, recipe.seed, canvas);
  else if (preset.name == "printed-paper") family::printed_paper(domain, variant, recipe.seed, canvas);
  else if (preset.name == "metal-tray") family::metal_tray(domain, variant, recipe.seed, canvas);
  else family::granite(domain, variant, recipe.seed, canvas);
  out.base_color_format = canvas.base_color_format;
  out.metallic_roughness_format = canvas.metallic_roughness_format;
  out.normal_format = PixelFormat::uint16;  // slopes of a few hundredths need more than 8 bits

  stage("normals");
  normals_from_height(out.height_mm, n, n, mm, raw.normal);

  stage("encoding");
  store_material_images(raw, color, out);
  return out;
}

void store_material_images(const MaterialTexels& raw, const ColorConfig& color, ProceduralMaterial& out) {
  const int n = raw.width;
  out.base_color = Image(n, n, 3);
  out.metallic_roughness = Image(n, n, 3);
  out.normal = Image(n, n, 3);
  family::for_each_row(n, [&](int j) {
    for (int i = 0; i < n; ++i) {
      const std::size_t k = raw.index(i, j);
      const glm::vec3 nm = encode_normal(raw.normal[k]);
      for (int c = 0; c < 3; ++c) {
        out.base_color.at(i, j, c) = raw.base_color[k][c];
        out.normal.at(i, j, c) = nm[c];
      }
      out.metallic_roughness.at(i, j, 0) = 1.0f;
      out.metallic_roughness.at(i, j, 1) = raw.roughness[k];
      out.metallic_roughness.at(i, j, 2) = raw.metallic[k];
    }
  });
  color.linear_to_srgb_texture(out.base_color);
  quantize(out.base_color, out.base_color_format);
  quantize(out.metallic_roughness, out.metallic_roughness_format);
  quantize(out.normal, out.normal_format);

  // The level-0 parameters exactly as a reader of the stored images decodes them.
  MaterialImages stored;
  stored.base_color = &out.base_color;
  stored.metallic_roughness = &out.metallic_roughness;
  stored.normal = &out.normal;
  out.texels = decode_material_texels(stored, color);
}

}  // namespace svbrdf
