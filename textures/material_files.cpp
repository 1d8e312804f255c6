// load_material_texels: a material's files → MaterialTexels. Files of 8- or 16-bit codes (PNG, JPEG)
// are decoded band by band straight into the texels, each code through a table of what
// decode_material_texels makes of the float read_image reads for it (the sRGB decode's own output for
// that float, code_tables.h): the same texels bit for bit, without each image's floats in memory (a
// 4096² RGBA image is 256 MB of them) or a second pass over them. Any other set (float or tiled files,
// a failed check) is read whole and goes through decode_material_texels.
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <exception>
#include <optional>
#include <span>
#include <vector>

#include "base/error.h"
#include "base/huge_pages.h"
#include "textures/code_tables.h"
#include "textures/material_loader.h"
#include "textures/normal_map.h"

namespace svbrdf {

namespace {

// The files in reading order: a failure reported is the first in this order, as reading them one
// after another would meet it.
enum Slot { kBaseColor, kMetallicRoughness, kNormal, kSlots };

struct Opened {
  std::array<const std::optional<std::filesystem::path>*, kSlots> paths{};
  std::array<std::optional<ImageFile>, kSlots> files;
  std::array<std::exception_ptr, kSlots> failed;

  void rethrow_first() const {
    for (const std::exception_ptr& e : failed)
      if (e) std::rethrow_exception(e);
  }
};

// Runs body(k) for every slot with a file, in parallel (a PNG's inflate runs on one thread), keeping
// each slot's failure.
template <class Body>
void for_files(Opened& o, const Body& body) {
  const auto one = [&](int k) {
    if (!*o.paths[std::size_t(k)] || o.failed[std::size_t(k)]) return;
    try {
      body(k);
    } catch (...) {
      o.failed[std::size_t(k)] = std::current_exception();
    }
  };
  tbb::parallel_invoke([&] { one(kBaseColor); }, [&] { one(kMetallicRoughness); }, [&] { one(kNormal); });
}

// The images read whole, then decode_material_texels, which makes every check and gives every error.
MaterialTexels decode_whole(Opened& o, const MaterialFiles& files, const ColorConfig& color) {
  std::array<std::optional<Image>, kSlots> images;
  for_files(o, [&](int k) { images[std::size_t(k)] = o.files[std::size_t(k)]->read(); });
  o.rethrow_first();
  MaterialImages in;
  if (files.base_color) {
    const PixelFormat stored = o.files[kBaseColor]->stored_format();
    in.base_color_is_linear = stored == PixelFormat::half || stored == PixelFormat::float32;
    in.base_color = &*images[kBaseColor];
    in.base_color_name = files.base_color->string();
  }
  if (files.metallic_roughness) {
    in.metallic_roughness = &*images[kMetallicRoughness];
    in.metallic_roughness_name = files.metallic_roughness->string();
  }
  if (files.normal) {
    in.normal = &*images[kNormal];
    in.normal_name = files.normal->string();
  }
  in.base_color_factor = files.base_color_factor;
  in.metallic_factor = files.metallic_factor;
  in.roughness_factor = files.roughness_factor;
  in.normal_scale = files.normal_scale;
  return decode_material_texels(in, color);
}

// Whether the set decodes from its codes: every file opened and stores codes, and every check of
// decode_material_texels passes (where one fails, decode_whole gives its error, after any earlier
// file's own). The files' size is returned in `width`, `height`.
bool decodes_from_codes(const Opened& o, const MaterialFiles& files, int& width, int& height) {
  const auto unit = [](float v) { return std::isfinite(v) && v >= 0.0f && v <= 1.0f; };
  for (int c = 0; c < 3; ++c)
    if (!std::isfinite(files.base_color_factor[c]) || files.base_color_factor[c] < 0.0f) return false;
  if (!unit(files.metallic_factor) || !unit(files.roughness_factor) || !std::isfinite(files.normal_scale)) return false;
  width = height = 0;
  for (int k = 0; k < kSlots; ++k) {
    if (!*o.paths[std::size_t(k)]) continue;
    const std::optional<ImageFile>& f = o.files[std::size_t(k)];
    if (!f || f->code_bits() == 0) return false;
    if (width == 0) width = f->width(), height = f->height();
    if (f->width() != width || f->height() != height) return false;
    if (k == kNormal && f->channels() < 3) return false;
    try {
      check_image_size(o.paths[std::size_t(k)]->value().string(), width, height);
    } catch (const Error&) {
      return false;
    }
  }
  return width > 0;
}

// Calls body(first, codes, n) for bands of rows from the top: n texels from texel `first` on, their
// codes interleaved as the file stores them.
template <class Code, class Body>
void for_bands(ImageFile& file, const Body& body) {
  // About a quarter of a MB of codes a band: in cache while the band is decoded into the texels.
  constexpr std::size_t kBandBytes = std::size_t(1) << 18;
  const std::size_t row = std::size_t(file.width()) * std::size_t(file.channels());
  const int rows = int(std::clamp<std::size_t>(kBandBytes / (row * sizeof(Code)), 1, std::size_t(file.height())));
  std::vector<Code> band(row * std::size_t(rows));
  for (int y0 = 0; y0 < file.height(); y0 += rows) {
    const int y1 = std::min(file.height(), y0 + rows);
    file.read_codes(y0, y1, band.data());
    body(std::size_t(y0) * std::size_t(file.width()), band.data(), std::size_t(y1 - y0) * std::size_t(file.width()));
  }
}

// One file's codes → its slot of the texels, as decode_material_texels decodes the floats the codes
// read as (texel(): a gray image's value in R, G and B).
template <class Code>
void decode_slot(int slot, ImageFile& file, const MaterialFiles& files, const ColorConfig& color, MaterialTexels& out) {
  constexpr int kBits = sizeof(Code) == 1 ? 8 : 16;
  const std::vector<float>& value = code_values(kBits);
  const std::size_t nc = std::size_t(file.channels());
  const std::size_t g = nc >= 3 ? 1 : 0, b = nc >= 3 ? 2 : 0;
  if (slot == kBaseColor) {
    const glm::vec3 factor(files.base_color_factor);
    const CodeTables* tables = color.srgb_texture_to_linear_codes();
    for_bands<Code>(file, [&](std::size_t first, const Code* codes, std::size_t n) {
      glm::vec3* texels = out.base_color.data() + first;
      if (tables) {
        const CodeTables::Table& t = tables->codes(kBits);
        const float *r_out = t.out[0].data(), *g_out = t.out[1].data(), *b_out = t.out[2].data();
        for (std::size_t p = 0; p < n; ++p) {
          const Code* c = codes + p * nc;
          texels[p] = glm::vec3(r_out[c[0]], g_out[c[g]], b_out[c[b]]) * factor;
        }
        return;
      }
      // A transform with channel crosstalk: the floats through it, as decode_material_texels sends them.
      for (std::size_t p = 0; p < n; ++p) {
        const Code* c = codes + p * nc;
        texels[p] = glm::vec3(value[c[0]], value[c[g]], value[c[b]]);
      }
      color.srgb_texture_to_linear(std::span(texels, n));
      for (std::size_t p = 0; p < n; ++p) texels[p] *= factor;
    });
  } else if (slot == kMetallicRoughness) {
    const float metallic = files.metallic_factor, roughness = files.roughness_factor;
    for_bands<Code>(file, [&](std::size_t first, const Code* codes, std::size_t n) {
      for (std::size_t p = 0; p < n; ++p) {
        const Code* c = codes + p * nc;
        out.metallic[first + p] = std::clamp(value[c[b]], 0.0f, 1.0f) * metallic;
        out.roughness[first + p] = std::clamp(value[c[g]], 0.0f, 1.0f) * roughness;
      }
    });
  } else {
    const float scale = files.normal_scale;
    for_bands<Code>(file, [&](std::size_t first, const Code* codes, std::size_t n) {
      for (std::size_t p = 0; p < n; ++p) {
        const Code* c = codes + p * nc;
        out.normal[first + p] = decode_normal(glm::vec3(value[c[0]], value[c[1]], value[c[2]]), scale);
      }
    });
  }
}

}  // namespace

MaterialTexels load_material_texels(const MaterialFiles& files, const ColorConfig& color) {
  Opened o;
  o.paths = {&files.base_color, &files.metallic_roughness, &files.normal};
  for_files(o, [&](int k) { o.files[std::size_t(k)].emplace(o.paths[std::size_t(k)]->value()); });
  int width = 0, height = 0;
  if (!decodes_from_codes(o, files, width, height)) return decode_whole(o, files, color);

  // Each slot's texels are made (first touched) by the task that decodes into them, so both
  // threads share that work too.
  MaterialTexels out;
  out.width = width;
  out.height = height;
  const std::size_t n = out.size();
  const auto slot = [&](int k) {
    if (k == kBaseColor) assign_huge(out.base_color, n, glm::vec3(files.base_color_factor));
    if (k == kMetallicRoughness) assign_huge(out.metallic, n, files.metallic_factor), assign_huge(out.roughness, n, files.roughness_factor);
    if (k == kNormal) assign_huge(out.normal, n, glm::vec3(0, 0, 1));
    if (!*o.paths[std::size_t(k)]) return;
    try {
      ImageFile& file = *o.files[std::size_t(k)];
      if (file.code_bits() == 8) decode_slot<std::uint8_t>(k, file, files, color, out);
      else decode_slot<std::uint16_t>(k, file, files, color, out);
    } catch (...) {
      o.failed[std::size_t(k)] = std::current_exception();
    }
    o.files[std::size_t(k)].reset();  // its bytes and decoder, no longer needed
  };
  tbb::parallel_invoke([&] { slot(kBaseColor); }, [&] { slot(kMetallicRoughness); }, [&] { slot(kNormal); });
  o.rethrow_first();
  return out;
}

}  // namespace svbrdf
