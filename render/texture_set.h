#pragma once
// The scene's textures ready for lookups at shading time, through the textures module: color images
// (base color, emissive, specular color) converted sRGB → scene-linear once by its OpenColorIO
// config, data images kept raw; lookups by its sampler (textures/sampler.h) with the glTF sampler's
// wrap modes and the slot's KHR_texture_transform. The `level0` texture filter is the nearest texel
// at the exact uv. Allocation-free and thread-safe after construction.
//
// The fast path: most glTF textures are 8-bit PNG or JPEG, whose decoded floats take 256 values per
// channel. Such an image is also kept as 8-bit codes (4 bytes a texel instead of 16) with a table per
// channel from code to the float the image holds — and to the float its linearized copy holds,
// checked texel by texel while the table is made, so lookups return exactly what textures/sampler.h's
// nearest lookup of the float images returns, from a quarter of the memory traffic: both read their
// texel through the sampler's nearest_texel_index. Wrap repeat on a power-of-two side is a mask.
//
// Out of core (`--texture-cache`, render/texture_tiles.h): store() writes each image as the loader
// decodes it — the same 8-bit codes and tables, or the same floats (RGBA) of the image and of its
// linearized copy — to the texture cache's files and drops its pixels; lookups then read the texel
// of the same index from the cache's tiles, so they return the same values bit for bit. The files are
// named by the encoded bytes and their descriptions hold the size, channels and code tables
// (render/image_file_description.h), so a later load finds them (find()) and decodes nothing: what the
// render reads of the image (lookups, the whole image for a MIP build: image()) comes from the files.
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "gltf/scene.h"
#include "textures/color.h"
#include "textures/sampler.h"
#include "render/texture_tiles.h"

namespace svbrdf {

class TextureSet {
 public:
  // `tiles`: where store() put the images whose pixels the scene no longer holds (null: none did).
  TextureSet(const Scene& scene, const ColorConfig& color = ColorConfig::builtin(), const TextureTiles* tiles = nullptr);
  ~TextureSet();

  // Writes image `index` of a scene being loaded (LoadOptions::take_image) to `tiles`: its 8-bit form
  // or its floats, and with `color` those of its copy linearized by `config`; then frees its pixels.
  // Throws svbrdf::Error (environment) when the files cannot be written.
  static void store(std::size_t index, ImageDesc& image, bool color, const ColorConfig& config, TextureTiles& tiles);
  // Before image `index` is decoded (LoadOptions::find_image): when `tiles` holds its files whole for
  // its encoded bytes (image.encoded_digest), as store() wrote them for `color` and `config`, takes
  // them instead of a decode: its size and channels, and its code tables, from the files. Then true,
  // and the image keeps its size and channels and no pixels, as store() leaves it. A file there that
  // is not whole or not described as store() describes it is refused with one warning (store() writes
  // it again after the decode). Throws svbrdf::Error (environment) when a file found cannot be opened.
  static bool find(std::size_t index, ImageDesc& image, bool color, const ColorConfig& config, TextureTiles& tiles);

  // The slot's texture at `uv` (the primitive's TEXCOORD_n, before the slot's transform); RGBA with
  // gray expanded and a missing alpha read as 1. `color` selects the linearized copy.
  glm::vec4 lookup(const TextureRef& ref, glm::vec2 uv, bool color) const {
    const Prepared& p = textures_[static_cast<std::size_t>(ref.texture)];
    const glm::vec2 t = ref.transform.apply(uv);
    if (const Packed* k = p.packed) {
      const int i = nearest_texel_index(t.x, k->width, p.sampler.wrap_s, p.mask_s);
      const int j = nearest_texel_index(t.y, k->height, p.sampler.wrap_t, p.mask_t);
      const std::uint8_t* c = &k->codes[4 * (static_cast<std::size_t>(j) * k->width + i)];
      const Table& tab = color && p.linear ? k->linear : k->raw;
      return {tab[0][c[0]], tab[1][c[1]], tab[2][c[2]], tab[3][c[3]]};
    }
    if (const TiledImage* k = p.tiled) {
      const int i = nearest_texel_index(t.x, k->width, p.sampler.wrap_s, p.mask_s);
      const int j = nearest_texel_index(t.y, k->height, p.sampler.wrap_t, p.mask_t);
      const bool linear = color && k->linear;
      if (k->codes) {
        const auto* c = reinterpret_cast<const std::uint8_t*>(tiles_->texel(k->raw_file, i, j));
        const Table& tab = linear ? k->linear_table : k->raw_table;
        return {tab[0][c[0]], tab[1][c[1]], tab[2][c[2]], tab[3][c[3]]};
      }
      const auto* v = reinterpret_cast<const float*>(tiles_->texel(linear ? k->linear_file : k->raw_file, i, j));
      return {v[0], v[1], v[2], v[3]};
    }
    const Image& image = color && p.linear ? *p.linear : *p.raw;
    return sample(image, p.sampler, t);
  }

  // Asks the memory system for the texel lookup(ref, uv, ·) reads (on the 8-bit path; a float image
  // is left alone), for a caller with other work to do before the lookup.
  void prefetch(const TextureRef& ref, glm::vec2 uv) const {
    const Prepared& p = textures_[static_cast<std::size_t>(ref.texture)];
    if (const Packed* k = p.packed) {
      const glm::vec2 t = ref.transform.apply(uv);
      const int i = nearest_texel_index(t.x, k->width, p.sampler.wrap_s, p.mask_s);
      const int j = nearest_texel_index(t.y, k->height, p.sampler.wrap_t, p.mask_t);
      __builtin_prefetch(&k->codes[4 * (static_cast<std::size_t>(j) * k->width + i)]);
    }
  }

  // The image a slot reads: the linearized copy when `color` and one exists, else as stored. Out of
  // core, read back from the texture cache's files on first use and kept until release() (the MIP
  // builds read every texel; a level0 render never asks).
  const Image& image(const TextureRef& ref, bool color) const {
    const Prepared& p = textures_[static_cast<std::size_t>(ref.texture)];
    if (p.tiled) return read_back(p, color);
    return color && p.linear ? *p.linear : *p.raw;
  }
  // Out of core: frees what image() read back of the slot's image (both forms); a later image() reads it
  // back again. No reference image() gave for it may be in use. In memory: nothing.
  void release(const TextureRef& ref) const;
  // Whether image(ref, true) is a linearized copy (color slots have one).
  bool linearized(const TextureRef& ref) const {
    const Prepared& p = textures_[static_cast<std::size_t>(ref.texture)];
    return p.linear != nullptr || (p.tiled && p.tiled->linear);
  }
  // The texture's sampler (its wrap modes; the filter is nearest).
  const Sampler& sampler(const TextureRef& ref) const { return textures_[static_cast<std::size_t>(ref.texture)].sampler; }
  // Whether lookups of the slot's texture take the 8-bit path.
  bool packed(const TextureRef& ref) const { return textures_[static_cast<std::size_t>(ref.texture)].packed != nullptr; }

  // Rows of an image that the 8-bit form is made of at a time, in parallel (each band with its own
  // tables, merged in order): enough texels a band to repay a task, bands enough for every core.
  static constexpr int kPackBandRows = 32;

  // The decoded image's channels (without reading an out-of-core image back).
  int channels(const TextureRef& ref) const { return textures_[static_cast<std::size_t>(ref.texture)].raw->channels; }

  // Texture size in texels (for footprints and the MIP-level AOV).
  glm::ivec2 size(const TextureRef& ref) const {
    const Image& im = *textures_[static_cast<std::size_t>(ref.texture)].raw;
    return {im.width, im.height};
  }

 private:
  using Table = CodeTable;  // per channel: code → value
  struct Packed {
    int width = 0, height = 0;
    std::vector<std::uint8_t> codes;  // RGBA per texel, rows from the top
    Table raw{}, linear{};            // the image's values and its linearized copy's
  };
  struct Prepared {
    const Image* raw = nullptr;
    const Image* linear = nullptr;  // null unless a color slot uses the image
    const Packed* packed = nullptr;  // the 8-bit path, when the image allows it
    const TiledImage* tiled = nullptr;  // out of core: the texture cache holds the texels
    std::size_t image = 0;           // Scene::images index
    Sampler sampler;                // nearest, with the texture's wrap modes
    int mask_s = -1, mask_t = -1;   // width − 1, height − 1 where the wrap is repeat on a power of two
  };
  static std::unique_ptr<Packed> pack(const Image& raw, const Image* linear);
  // An out-of-core image read back whole (image()).
  struct ReadBack;
  const Image& read_back(const Prepared& p, bool color) const;

  const TextureTiles* tiles_ = nullptr;
  std::vector<std::unique_ptr<ReadBack>> read_back_;  // per scene image, out of core

  std::vector<Image> linear_images_;  // per scene image; empty when no color slot uses it
  std::vector<std::unique_ptr<Packed>> packed_images_;  // per scene image; null when not 8-bit
  std::vector<Prepared> textures_;     // per scene texture
};

}  // namespace svbrdf
