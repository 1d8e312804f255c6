#include "render/texture_set.h"

#include <algorithm>
#include <bit>
#include <mutex>
#include <span>

#include "base/sha256.h"
#include "render/image_file_description.h"
#include "render/mip_cache_key.h"

#include <OpenImageIO/oiioversion.h>

#include <tbb/parallel_for.h>

namespace svbrdf {

namespace {

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

TextureSet::TextureSet(const Scene& scene, const ColorConfig& color, const TextureTiles* tiles) : tiles_(tiles) {
  // The images store() wrote out of core: their pixels are gone, the cache's files hold them.
  std::vector<const TiledImage*> tiled(scene.images.size(), nullptr);
  if (tiles)
    for (std::size_t i = 0; i < scene.images.size(); ++i) tiled[i] = tiles->image(i);
  std::vector<char> needs_linear(scene.images.size(), 0);
  for (std::size_t t = 0; t < scene.textures.size(); ++t) {
    const int image = scene.textures[t].image;
    if (image < 0) continue;
    for (const MaterialDesc& m : scene.materials)
      if (m.shows_as_color(int(t))) needs_linear[std::size_t(image)] = 1;
  }
  linear_images_.resize(scene.images.size());
  for (std::size_t i = 0; i < scene.images.size(); ++i) {
    if (!needs_linear[i] || tiled[i]) continue;
    linear_images_[i] = scene.images[i].pixels;
    color.srgb_texture_to_linear(linear_images_[i]);
  }
  packed_images_.resize(scene.images.size());
  tbb::parallel_for(std::size_t(0), scene.images.size(), [&](std::size_t i) {
    if (!tiled[i]) packed_images_[i] = pack(scene.images[i].pixels, needs_linear[i] ? &linear_images_[i] : nullptr);
  });
  read_back_.resize(scene.images.size());
  for (std::size_t i = 0; i < scene.images.size(); ++i)
    if (tiled[i]) read_back_[i] = std::make_unique<ReadBack>();
  textures_.resize(scene.textures.size());
  for (std::size_t t = 0; t < scene.textures.size(); ++t) {
    const TextureDesc& d = scene.textures[t];
    if (d.image < 0) continue;
    const auto image = static_cast<std::size_t>(d.image);
    Prepared& p = textures_[t];
    p.raw = &scene.images[image].pixels;
    if (needs_linear[image] && !tiled[image]) p.linear = &linear_images_[image];
    p.packed = packed_images_[image].get();
    p.tiled = tiled[image];
    p.image = image;
    p.sampler = d.sampler;
    p.sampler.filter = FilterMode::nearest;  // level0: the nearest texel at the exact uv
    p.mask_s = repeat_mask(p.sampler.wrap_s, p.raw->width);
    p.mask_t = repeat_mask(p.sampler.wrap_t, p.raw->height);
  }
}

TextureSet::~TextureSet() = default;

namespace {

// The name of a texture cache file: what the texels are (the image's content and which form) and
// what made them of the content: the decoder, this code (the MIP code's identity covers textures/ and
// this file) and, for a linearized copy, the color config. The content fixes the size: a render that
// has only the encoded bytes finds the file (find()).
std::string tile_key(const Sha256Digest& content, const std::string& form) {
  return to_hex(sha256(std::string("svbrdf texture tiles 2|") + mip_code_identity() + "|OpenImageIO " +
                       OIIO_VERSION_STRING + "|" + to_hex(content) + "|" + form));
}
// The forms: the 8-bit codes (with the linear table of `config` when a color slot shows the image),
// the image's floats, and its linearized copy's floats.
std::string codes_form(bool color, const ColorConfig& config) { return color ? "codes|linear|" + config.identity() : "codes"; }
std::string linear_form(const ColorConfig& config) { return "linear|" + config.identity(); }

// The image's texels as RGBA floats (texel()'s expansion: what a nearest lookup returns).
std::vector<float> rgba_floats(const Image& image) {
  std::vector<float> out(4 * std::size_t(image.width) * std::size_t(image.height));
  tbb::parallel_for(0, image.height, [&](int j) {
    for (int i = 0; i < image.width; ++i) {
      const glm::vec4 v = texel(image, i, j);
      float* o = &out[4 * (std::size_t(j) * std::size_t(image.width) + std::size_t(i))];
      o[0] = v.r, o[1] = v.g, o[2] = v.b, o[3] = v.a;
    }
  });
  return out;
}

// The description of the image file of `key` when one is there, whole, holding `format` and
// described as the key's form says (`codes`, with a linear table when `linear`). One there that is not
// is refused (a warning) and left for store() to write again.
std::optional<ImageFileDescription> found_file(TextureTiles& tiles, const std::string& key, PixelFormat format, bool codes,
                                               bool linear) {
  std::string why;
  const std::optional<TextureTiles::FoundImage> file = tiles.inspect_image(key, format, &why);
  std::optional<ImageFileDescription> d;
  if (file) {
    d = parse_image_file_description(file->description, key, &why);
    if (d && (d->width != file->width || d->height != file->height || d->codes != codes || d->linear != linear)) {
      why = "its description does not describe its texels";
      d.reset();
    }
  }
  if (!why.empty()) tiles.refuse(key, why);
  return d;
}

}  // namespace

void TextureSet::store(std::size_t index, ImageDesc& desc, bool color, const ColorConfig& config, TextureTiles& tiles) {
  Image& raw = desc.pixels;
  if (raw.width <= 0 || raw.height <= 0 || raw.channels < 1) return;
  // An image made in memory has no encoded bytes: its shape and floats are its content.
  if (!desc.encoded_digest) desc.encoded_digest = image_content(desc);
  const Sha256Digest& content = *desc.encoded_digest;
  TiledImage t;
  t.width = raw.width, t.height = raw.height, t.channels = raw.channels;
  t.linear = color;
  ImageFileDescription d;
  d.width = raw.width, d.height = raw.height, d.channels = raw.channels;
  Image linear;
  if (color) {
    linear = raw;
    config.srgb_texture_to_linear(linear);
  }
  if (const std::unique_ptr<Packed> k = pack(raw, color ? &linear : nullptr)) {
    t.codes = true;
    t.raw_table = k->raw, t.linear_table = k->linear;
    d.key = tile_key(content, codes_form(color, config));
    d.codes = true, d.linear = color;
    d.raw_table = k->raw, d.linear_table = k->linear;
    t.raw_file = t.linear_file = tiles.add(d.key, raw.width, raw.height, PixelFormat::uint8, k->codes.data(), describe(d));
  } else {
    d.key = tile_key(content, "raw");
    t.raw_file = tiles.add(d.key, raw.width, raw.height, PixelFormat::float32, rgba_floats(raw).data(), describe(d));
    if (color) {
      d.key = tile_key(content, linear_form(config));
      t.linear_file = tiles.add(d.key, raw.width, raw.height, PixelFormat::float32, rgba_floats(linear).data(), describe(d));
    }
  }
  tiles.set_image(index, t);
  tiles.count_image(false);
  std::vector<float>().swap(raw.pixels);  // the size and channels stay: TextureSet::size, the MIP key
}

bool TextureSet::find(std::size_t index, ImageDesc& desc, bool color, const ColorConfig& config, TextureTiles& tiles) {
  if (!desc.encoded_digest) return false;
  const Sha256Digest& content = *desc.encoded_digest;
  TiledImage t;
  t.linear = color;
  const std::string codes = tile_key(content, codes_form(color, config));
  if (const std::optional<ImageFileDescription> d = found_file(tiles, codes, PixelFormat::uint8, true, color)) {
    t.width = d->width, t.height = d->height, t.channels = d->channels;
    t.codes = true;
    t.raw_table = d->raw_table, t.linear_table = d->linear_table;
    t.raw_file = t.linear_file = tiles.open_image(codes, t.width, t.height, PixelFormat::uint8);
  } else {
    // No 8-bit file: the image's values are not 256 codes a channel (store() wrote its floats), or
    // it has not been written.
    const std::string raw_key = tile_key(content, "raw"), linear_key = tile_key(content, linear_form(config));
    const std::optional<ImageFileDescription> raw = found_file(tiles, raw_key, PixelFormat::float32, false, false);
    if (!raw) return false;
    if (color) {
      const std::optional<ImageFileDescription> linear = found_file(tiles, linear_key, PixelFormat::float32, false, false);
      if (!linear) return false;
      if (linear->width != raw->width || linear->height != raw->height || linear->channels != raw->channels) {
        tiles.refuse(linear_key, "its image's size is not that of the image's own file");
        return false;
      }
    }
    t.width = raw->width, t.height = raw->height, t.channels = raw->channels;
    t.raw_file = tiles.open_image(raw_key, t.width, t.height, PixelFormat::float32);
    if (color) t.linear_file = tiles.open_image(linear_key, t.width, t.height, PixelFormat::float32);
  }
  tiles.set_image(index, t);
  tiles.count_image(true);
  // The size and channels a decode would have given, and no pixels (as store() leaves them).
  desc.pixels = Image();
  desc.pixels.width = t.width, desc.pixels.height = t.height, desc.pixels.channels = t.channels;
  return true;
}

struct TextureSet::ReadBack {
  std::mutex mutex;
  bool done[2] = {false, false};
  Image image[2];  // raw, linear
};

void TextureSet::release(const TextureRef& ref) const {
  const Prepared& p = textures_[static_cast<std::size_t>(ref.texture)];
  if (!p.tiled) return;
  ReadBack& r = *read_back_[p.image];
  const std::lock_guard<std::mutex> lock(r.mutex);
  for (int k = 0; k < 2; ++k) {
    r.done[k] = false;
    r.image[k] = Image();
  }
}

const Image& TextureSet::read_back(const Prepared& p, bool color) const {
  const TiledImage& t = *p.tiled;
  const bool linear = color && t.linear;
  ReadBack& r = *read_back_[p.image];
  Image& out = r.image[linear];
  const std::lock_guard<std::mutex> lock(r.mutex);
  if (r.done[linear]) return out;
  {
    const std::vector<std::byte> bytes = tiles_->read_all(linear && !t.codes ? t.linear_file : t.raw_file);
    // The decoded image's channels from texel()'s RGBA: gray is R, gray+alpha is (R, A).
    const int channels = std::min(t.channels, 4);
    const int from[4][4] = {{0}, {0, 3}, {0, 1, 2}, {0, 1, 2, 3}};
    out = Image(t.width, t.height, channels);
    const Table& table = linear ? t.linear_table : t.raw_table;
    for (std::size_t k = 0; k < std::size_t(t.width) * std::size_t(t.height); ++k)
      for (int c = 0; c < channels; ++c) {
        const int s = from[channels - 1][c];
        out.pixels[k * std::size_t(channels) + std::size_t(c)] =
            t.codes ? table[std::size_t(s)][std::to_integer<std::size_t>(bytes[4 * k + std::size_t(s)])]
                    : reinterpret_cast<const float*>(bytes.data())[4 * k + std::size_t(s)];
      }
  }
  r.done[linear] = true;
  return out;
}

}  // namespace svbrdf
