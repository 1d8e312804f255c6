#include "render/texture_set.h"

#include <algorithm>
#include <bit>

#include <tbb/parallel_for.h>

namespace svbrdf {

namespace {

bool color_slot_uses(const MaterialDesc& m, int texture) {
  return m.base_color_texture.texture == texture || m.emissive_texture.texture == texture ||
         m.specular_color_texture.texture == texture;
}

int repeat_mask(WrapMode mode, int n) {
  return mode == WrapMode::repeat && std::has_single_bit(static_cast<unsigned>(n)) ? n - 1 : -1;
}

}  // namespace

// The 8-bit form of an image and its linearized copy, or null when some channel takes a value that
// is not one of 256 codes, or one code stands for two different values (then lookups read floats).
// Bands of rows in parallel, each with its own tables, merged in band order with the same checks: the
// first texel in scan order that shows a code gives its values, as a single pass would.
std::unique_ptr<TextureSet::Packed> TextureSet::pack(const Image& raw, const Image* linear) {
  if (raw.width <= 0 || raw.height <= 0 || raw.channels < 1) return nullptr;
  auto k = std::make_unique<Packed>();
  k->width = raw.width, k->height = raw.height;
  k->codes.resize(4 * static_cast<std::size_t>(raw.width) * raw.height);
  struct Band {
    Table raw{}, linear{};
    std::array<std::array<bool, 256>, 4> seen{};
    bool ok = true;
  };
  const int band_rows = kPackBandRows;
  std::vector<Band> bands(static_cast<std::size_t>((raw.height + band_rows - 1) / band_rows));
  tbb::parallel_for(std::size_t(0), bands.size(), [&](std::size_t b) {
    Band& band = bands[b];
    const int first = static_cast<int>(b) * band_rows, last = std::min(raw.height, first + band_rows);
    for (int j = first; j < last; ++j)
      for (int i = 0; i < raw.width; ++i) {
        const glm::vec4 v = texel(raw, i, j);
        const glm::vec4 l = linear ? texel(*linear, i, j) : v;
        std::uint8_t* out = &k->codes[4 * (static_cast<std::size_t>(j) * raw.width + i)];
        for (std::size_t c = 0; c < 4; ++c) {
          const float x = v[int(c)] * 255.0f;
          if (!(x > -0.5f && x < 255.5f)) {
            band.ok = false;
            return;
          }
          const auto code = static_cast<std::size_t>(x + 0.5f);  // rounds: x + 0.5 > 0
          if (std::fabs(x - static_cast<float>(code)) > 1e-3f) {
            band.ok = false;
            return;
          }
          out[c] = static_cast<std::uint8_t>(code);
          float &rv = band.raw[c][code], &lv = band.linear[c][code];
          if (!band.seen[c][code]) {
            rv = v[int(c)], lv = l[int(c)];
            band.seen[c][code] = true;
          } else if (rv != v[int(c)] || lv != l[int(c)]) {
            band.ok = false;  // one code, two values: not an 8-bit image after all
            return;
          }
        }
      }
  });
  std::array<std::array<bool, 256>, 4> seen{};
  for (const Band& band : bands) {
    if (!band.ok) return nullptr;
    for (std::size_t c = 0; c < 4; ++c)
      for (std::size_t code = 0; code < 256; ++code) {
        if (!band.seen[c][code]) continue;
        if (!seen[c][code]) {
          k->raw[c][code] = band.raw[c][code], k->linear[c][code] = band.linear[c][code];
          seen[c][code] = true;
        } else if (k->raw[c][code] != band.raw[c][code] || k->linear[c][code] != band.linear[c][code]) {
          return nullptr;
        }
      }
  }
  return k;
}

TextureSet::TextureSet(const Scene& scene, const ColorConfig& color) {
  std::vector<char> needs_linear(scene.images.size(), 0);
  for (std::size_t t = 0; t < scene.textures.size(); ++t) {
    const int image = scene.textures[t].image;
    if (image < 0) continue;
    for (const MaterialDesc& m : scene.materials)
      if (color_slot_uses(m, int(t))) needs_linear[std::size_t(image)] = 1;
  }
  linear_images_.resize(scene.images.size());
  for (std::size_t i = 0; i < scene.images.size(); ++i) {
    if (!needs_linear[i]) continue;
    linear_images_[i] = scene.images[i].pixels;
    color.srgb_texture_to_linear(linear_images_[i]);
  }
  packed_images_.resize(scene.images.size());
  tbb::parallel_for(std::size_t(0), scene.images.size(), [&](std::size_t i) {
    packed_images_[i] = pack(scene.images[i].pixels, needs_linear[i] ? &linear_images_[i] : nullptr);
  });
  textures_.resize(scene.textures.size());
  for (std::size_t t = 0; t < scene.textures.size(); ++t) {
    const TextureDesc& d = scene.textures[t];
    if (d.image < 0) continue;
    const auto image = static_cast<std::size_t>(d.image);
    Prepared& p = textures_[t];
    p.raw = &scene.images[image].pixels;
    if (needs_linear[image]) p.linear = &linear_images_[image];
    p.packed = packed_images_[image].get();
    p.sampler = d.sampler;
    p.sampler.filter = FilterMode::nearest;  // level0: the nearest texel at the exact uv
    p.mask_s = repeat_mask(p.sampler.wrap_s, p.raw->width);
    p.mask_t = repeat_mask(p.sampler.wrap_t, p.raw->height);
  }
}

}  // namespace svbrdf
