#include "render/texture_tiles.h"

#include <fcntl.h>
#include <sys/stat.h>

#include <algorithm>
#include <memory>

#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>

#include "base/atomic_file.h"
#include "base/error.h"

namespace svbrdf {

namespace fs = std::filesystem;

namespace {

OIIO::TypeDesc type_of(PixelFormat format) { return format == PixelFormat::uint8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT; }

// What a tile that cannot be read reads as: zeros, as many bytes as a float tile.
alignas(64) const std::byte kZeroTile[TextureTiles::kTileSide * TextureTiles::kTileSide * 16] = {};

}  // namespace

TextureTiles::TextureTiles(fs::path folder, double megabytes) : folder_(std::move(folder)) {
  cache_ = OIIO::ImageCache::create(/*shared=*/false);
  cache_->attribute("max_memory_MB", float(megabytes));
  // Tiles as the files store them (8-bit stays 8-bit), no tiling made up for untiled files, and no
  // sharing of tiles between files found equal: each file is ours and tiled.
  cache_->attribute("forcefloat", 0);
  cache_->attribute("autotile", 0);
  cache_->attribute("deduplicate", 0);
}

TextureTiles::~TextureTiles() {
  for (Pins& pins : pins_)
    for (Pin& pin : pins.slots)
      if (pin.tile) cache_->release_tile(pin.tile);
  pins_.clear();
  OIIO::ImageCache::destroy(cache_);
}

// Whether the file at `path` is one this class wrote for an image of this size and format.
bool TextureTiles::usable(const fs::path& path, int width, int height, PixelFormat format) const {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return false;
  const auto in = OIIO::ImageInput::open(path.string());
  if (!in) {
    (void)OIIO::geterror();  // a bad file is written again; its error is not ours to keep
    return false;
  }
  const OIIO::ImageSpec& s = in->spec();
  return s.width == width && s.height == height && s.nchannels == 4 && s.format == type_of(format) &&
         s.tile_width == kTileSide && s.tile_height == kTileSide && s.tile_depth <= 1 && s.x == 0 && s.y == 0 &&
         !in->seek_subimage(0, 1) && !in->seek_subimage(1, 0);
}

int TextureTiles::add(const std::string& key, int width, int height, PixelFormat format, const void* rgba) {
  const fs::path path = folder_ / (key + ".tx");
  if (!usable(path, width, height, format)) {
    std::error_code ec;
    fs::create_directories(folder_, ec);
    if (ec) throw environment_error(folder_.string(), "cannot create the folder for the texture cache: " + ec.message());
    const fs::path tmp = temp_path_for(path);
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) throw environment_error(path.string(), "OpenImageIO writes no TIFF: " + OIIO::geterror());
    OIIO::ImageSpec spec(width, height, 4, type_of(format));
    spec.tile_width = spec.tile_height = kTileSide;
    spec.attribute("compression", "zip");
    const bool ok = out->open(tmp.string(), spec) && out->write_image(type_of(format), rgba) && out->close();
    if (!ok) {
      const std::string why = out->geterror();
      fs::remove(tmp, ec);
      throw environment_error(path.string(), "cannot write the texture cache's file: " + why);
    }
    sync_file(tmp, path.string());
    move_into_place(tmp, path);
  } else {
    ::utimensat(AT_FDCWD, path.c_str(), nullptr, 0);  // a use, for the MIP cache's eviction (least recent first)
  }
  File f;
  f.path = path;
  f.width = width, f.height = height;
  f.texel_bytes = format == PixelFormat::uint8 ? 4 : 16;
  // Opened now and kept open (see the header): one more file than are added is always allowed.
  cache_->attribute("max_open_files", std::max(100, int(files_.size()) + 16));
  f.handle = cache_->get_image_handle(OIIO::ustring(path.string()));
  OIIO::ImageSpec spec;
  if (!f.handle || !cache_->get_imagespec(f.handle, nullptr, spec, 0, 0))
    throw environment_error(path.string(), "the texture cache cannot open its file: " + cache_->geterror());
  files_.push_back(std::move(f));
  return int(files_.size()) - 1;
}

void TextureTiles::refill(Pins& pins, Pin& pin, int file, std::uint64_t key) const {
  if (!pins.info) pins.info = cache_->get_perthread_info();
  if (pin.tile) cache_->release_tile(pin.tile);
  pin = Pin{};
  const File& f = files_[std::size_t(file)];
  const int x = int(key & 0x1FFFFF) << kTileShift, y = int((key >> 21) & 0x1FFFFF) << kTileShift;
  OIIO::ImageCache::Tile* tile = cache_->get_tile(f.handle, pins.info, 0, 0, x, y, 0);
  OIIO::TypeDesc format;
  const void* pixels = tile ? cache_->tile_pixels(tile, format) : nullptr;
  if (!pixels || 4 * format.size() != f.texel_bytes) {
    if (tile) cache_->release_tile(tile);
    const std::lock_guard<std::mutex> lock(mutex_);
    if (failure_.empty())
      failure_ = f.path.string() + ": the texture cache cannot read the tile at (" + std::to_string(x) + ", " +
                 std::to_string(y) + "): " + cache_->geterror() + " (removing the file makes the next render write it again)";
    failed_.store(true, std::memory_order_relaxed);
    pin.pixels = kZeroTile;  // key left unset: the next lookup of this tile tries again
    return;
  }
  pin.key = key, pin.tile = tile, pin.pixels = static_cast<const std::byte*>(pixels);
}

std::vector<std::byte> TextureTiles::read_all(int file) const {
  const File& f = files_[std::size_t(file)];
  std::vector<std::byte> out(f.texel_bytes * std::size_t(f.width) * std::size_t(f.height));
  const auto in = OIIO::ImageInput::open(f.path.string());
  if (!in || !in->read_image(0, 0, 0, 4, f.texel_bytes == 4 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT, out.data()))
    throw environment_error(f.path.string(), "the texture cache cannot read its file: " +
                                                 (in ? in->geterror() : OIIO::geterror()));
  return out;
}

std::string TextureTiles::failure() const {
  if (!failed_.load(std::memory_order_relaxed)) return {};
  const std::lock_guard<std::mutex> lock(mutex_);
  return failure_;
}

}  // namespace svbrdf
