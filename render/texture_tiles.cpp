#include "render/texture_tiles.h"

#include <fcntl.h>
#include <sys/stat.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <algorithm>
#include <bit>
#include <chrono>
#include <memory>

#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>

#include "base/atomic_file.h"
#include "base/error.h"
#include "render/mip_cache.h"

namespace svbrdf {

namespace fs = std::filesystem;

namespace {

OIIO::TypeDesc type_of(PixelFormat format) { return format == PixelFormat::uint8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT; }

// Makes `folder` or throws.
void create_folder(const fs::path& folder) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec)
    throw environment_error(folder.string(),
                            "cannot create the folder for the texture cache: " + ec.message());
}

// A use, for the MIP cache's eviction (least recent first).
void touch(const fs::path& path) { ::utimensat(AT_FDCWD, path.c_str(), nullptr, 0); }

// Writes `tmp` with `out`, then syncs it and renames it to `path`; a failure removes `tmp` and throws.
void finish(OIIO::ImageOutput& out, bool ok, const fs::path& tmp, const fs::path& path) {
  ok = ok && out.close();
  if (!ok) {
    const std::string why = out.geterror();
    std::error_code ec;
    fs::remove(tmp, ec);
    throw environment_error(path.string(), "cannot write the texture cache's file: " + why);
  }
  sync_file(tmp, path.string());
  move_into_place(tmp, path);
}

}  // namespace

TextureTiles::TextureTiles(fs::path folder, double megabytes) : folder_(std::move(folder)) {
  cache_ = OIIO::ImageCache::create(/*shared=*/false);
  // The cap is in 10^6 bytes (the option's MB); OpenImageIO's max_memory_MB counts 2^20 bytes.
  cache_->attribute("max_memory_MB", float(megabytes * 1e6 / 1048576.0));
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
  for (const File& f : files_)
    if (f.held) {
      std::error_code ec;
      fs::remove(f.read_path, ec);  // best effort: a link left behind is removed by a later eviction
    }
}

std::optional<TextureTiles::FoundImage> TextureTiles::inspect_image(const std::string& key, PixelFormat format,
                                                                    std::string* why) const {
  const fs::path path = path_of(key);
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return std::nullopt;
  const auto say = [&](const std::string& what) -> std::optional<FoundImage> {
    if (why) *why = what;
    return std::nullopt;
  };
  const auto in = OIIO::ImageInput::open(path.string());
  if (!in) return say("not a file OpenImageIO reads (" + OIIO::geterror() + ")");
  const OIIO::ImageSpec s = in->spec();
  if (s.width <= 0 || s.height <= 0 || s.nchannels != 4 || s.format != type_of(format) || s.channelformats.size() > 0 ||
      s.tile_width != kTileSide || s.tile_height != kTileSide || s.tile_depth > 1 || s.depth > 1 || s.x != 0 ||
      s.y != 0 || s.z != 0 || in->seek_subimage(0, 1) || in->seek_subimage(1, 0)) {
    (void)in->geterror();
    return say("it is not laid out as the texture cache writes an image");
  }
  // add() writes the tiles in order, so the last tile's bytes end the file: a file cut short cannot
  // read it. One tile of the format's bytes.
  const int x = (s.width - 1) / kTileSide * kTileSide, y = (s.height - 1) / kTileSide * kTileSide;
  std::vector<std::byte> tile(std::size_t(kTileSide) * kTileSide * 4 * type_of(format).size());
  (void)in->geterror();  // the seeks past the one level above
  if (!in->seek_subimage(0, 0) ||
      !in->read_tiles(0, 0, x, s.width, y, s.height, 0, 1, 0, 4, type_of(format), tile.data()))
    return say("its last tile does not read: the file is not whole (" + in->geterror() + ")");
  return FoundImage{s.width, s.height, std::string(s.get_string_attribute("ImageDescription"))};
}

int TextureTiles::open_image(const std::string& key, int width, int height, PixelFormat format) {
  const fs::path path = path_of(key);
  touch(path);
  const int file = open_file(path, kTileSide, {Level{width, height, 4, std::size_t(format == PixelFormat::uint8 ? 4 : 16)}});
  // What the cache opened is what was inspected (another render may have replaced it since with a
  // file of the same key: then the same content).
  OIIO::ImageSpec s;
  if (!cache_->get_imagespec(files_.back().handle, nullptr, s, 0, 0) || s.width != width || s.height != height ||
      s.nchannels != 4 || s.format != type_of(format) || s.tile_width != kTileSide)
    throw environment_error(path.string(), "the texture cache's file changed under it");
  return file;
}

void TextureTiles::refuse(const std::string& key, const std::string& why) {
  if (std::find(refused_.begin(), refused_.end(), key) != refused_.end()) return;
  refused_.push_back(key);
  warnings_.push_back("the texture cache's file " + path_of(key).string() + ": " + why + "; it is written again");
}

int TextureTiles::add(const std::string& key, int width, int height, PixelFormat format, const void* rgba,
                      const std::string& description) {
  const fs::path path = path_of(key);
  std::string why;
  const std::optional<FoundImage> there = inspect_image(key, format, &why);
  if (there && (there->width != width || there->height != height || there->description != description))
    why = "it does not hold the image its key names";
  if (!why.empty()) refuse(key, why);
  if (!there || !why.empty()) {
    create_folder(folder_);
    const fs::path tmp = temp_path_for(path);
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) throw environment_error(path.string(), "OpenImageIO writes no TIFF: " + OIIO::geterror());
    OIIO::ImageSpec spec(width, height, 4, type_of(format));
    spec.tile_width = spec.tile_height = kTileSide;
    spec.attribute("compression", "zip");
    spec.attribute("ImageDescription", description);
    finish(*out, out->open(tmp.string(), spec) && out->write_image(type_of(format), rgba), tmp, path);
  }
  return open_image(key, width, height, format);
}

int TextureTiles::open_file(const fs::path& path, int tile_side, std::vector<Level> levels) {
  File f;
  // Read through a hard link of this process's own (".KEY.heldPID.tx"): an eviction of the folder,
  // this render's or another's, removes the file's name, not the link, so the texels stay readable
  // whether OpenImageIO keeps the file open or opens it again, and read_all can open it. The link is
  // removed when this ends (a killed render's by a later eviction, render/mip_cache.h). Where the
  // folder takes no hard links the file is read by its name.
  const fs::path held = process_path_for(path, kHeldTag);
  std::error_code ec;
  fs::remove(held, ec);  // this process's link of an earlier opening of the same file
  ec.clear();
  fs::create_hard_link(path, held, ec);
  f.held = !ec;
  f.path = path;
  f.read_path = f.held ? held : path;
  f.tile_shift = std::countr_zero(unsigned(tile_side));
  f.levels = std::move(levels);
  std::size_t tile_bytes = 0;
  for (const Level& l : f.levels)
    tile_bytes = std::max(tile_bytes, l.texel_bytes * std::size_t(tile_side) * std::size_t(tile_side));
  if (zero_tile_.size() < tile_bytes) zero_tile_.assign(tile_bytes, std::byte{0});
  // Opened now and kept open (see the header): one more file than are added is always allowed.
  cache_->attribute("max_open_files", std::max(100, int(files_.size()) + 16));
  f.handle = cache_->get_image_handle(OIIO::ustring(f.read_path.string()));
  OIIO::ImageSpec spec;
  if (!f.handle || !cache_->get_imagespec(f.handle, nullptr, spec, 0, 0))
    throw environment_error(path.string(), "the texture cache cannot open its file: " + cache_->geterror());
  files_.push_back(std::move(f));
  return int(files_.size()) - 1;
}

std::optional<RecordLayout> TextureTiles::inspect_records(const std::string& key, std::string* why) const {
  const fs::path path = path_of(key);
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return std::nullopt;
  const auto say = [&](const std::string& what) -> std::optional<RecordLayout> {
    if (why) *why = path.string() + ": " + what;
    return std::nullopt;
  };
  const auto in = OIIO::ImageInput::open(path.string());
  if (!in) return say("not a file OpenImageIO reads (" + OIIO::geterror() + ")");
  RecordLayout layout;
  for (int level = 0; in->seek_subimage(level, 0); ++level) {
    const OIIO::ImageSpec s = in->spec();
    if (level == 0) {
      layout.tile_side = s.tile_width;
      layout.description = s.get_string_attribute("ImageDescription");
    }
    if (s.format != OIIO::TypeDesc::FLOAT || s.channelformats.size() > 0 ||
        s.tile_width != layout.tile_side || s.tile_height != layout.tile_side || s.tile_depth > 1 ||
        s.x != 0 || s.y != 0 || s.z != 0 || s.depth > 1 || s.width <= 0 || s.height <= 0 ||
        s.nchannels <= 0 || in->seek_subimage(level, 1))
      return say("level " + std::to_string(level) + " is not laid out as the texture cache writes it");
    layout.levels.push_back({s.width, s.height, s.nchannels});
  }
  (void)in->geterror();
  if (layout.levels.empty()) return say("holds no level");
  if (!std::has_single_bit(unsigned(layout.tile_side)) || layout.tile_side < 8 ||
      layout.tile_side > kTileSide)
    return say("its tiles are not as the texture cache writes them");
  return layout;
}

int TextureTiles::write_records(const std::string& key, const RecordLayout& layout, const FillRows& fill) {
  const fs::path path = path_of(key);
  create_folder(folder_);
  const fs::path tmp = temp_path_for(path);
  auto out = OIIO::ImageOutput::create(path.string());
  if (!out) throw environment_error(path.string(), "OpenImageIO writes no TIFF: " + OIIO::geterror());
  std::vector<OIIO::ImageSpec> specs;
  for (const RecordLevel& l : layout.levels) {
    OIIO::ImageSpec& s = specs.emplace_back(l.width, l.height, l.words, OIIO::TypeDesc::FLOAT);
    s.tile_width = s.tile_height = layout.tile_side;
    s.attribute("compression", "zip");
    s.attribute("ImageDescription", layout.description);
  }
  bool ok = out->open(tmp.string(), int(specs.size()), specs.data());
  std::vector<std::uint32_t> band, tile;
  for (std::size_t level = 0; ok && level < specs.size(); ++level) {
    const RecordLevel& l = layout.levels[level];
    if (level > 0) ok = out->open(tmp.string(), specs[level], OIIO::ImageOutput::AppendSubimage);
    // A row of tiles at a time: the level is never whole in memory. Each tile is written whole, the
    // part past the level's edge zeros (what OpenImageIO pads a partial tile with is not defined, and
    // the file must be the same for the same records).
    const std::size_t side = std::size_t(layout.tile_side), words = std::size_t(l.words);
    band.resize(side * std::size_t(l.width) * words);
    tile.resize(side * side * words);
    for (int y = 0; ok && y < l.height; y += layout.tile_side) {
      const int rows = std::min(l.height - y, layout.tile_side);
      fill(int(level), y, y + rows, band.data());
      for (int x = 0; ok && x < l.width; x += layout.tile_side) {
        const std::size_t columns = std::size_t(std::min(l.width - x, layout.tile_side));
        std::fill(tile.begin(), tile.end(), 0u);
        for (std::size_t r = 0; r < std::size_t(rows); ++r)
          std::copy_n(band.begin() + std::ptrdiff_t((r * std::size_t(l.width) + std::size_t(x)) * words),
                      columns * words, tile.begin() + std::ptrdiff_t(r * side * words));
        ok = out->write_tile(x, y, 0, OIIO::TypeDesc::FLOAT, tile.data());
      }
    }
  }
  finish(*out, ok, tmp, path);
  return open_records(key, layout);
}

int TextureTiles::open_records(const std::string& key, const RecordLayout& layout) {
  const fs::path path = path_of(key);
  touch(path);
  std::vector<Level> levels;
  for (const RecordLevel& l : layout.levels)
    levels.push_back({l.width, l.height, l.words, 4 * std::size_t(l.words)});
  const int file = open_file(path, layout.tile_side, std::move(levels));
  // What the cache opened is what was inspected or written (another render may have replaced it
  // since with a file of the same key: then the same content).
  for (std::size_t level = 0; level < layout.levels.size(); ++level) {
    OIIO::ImageSpec s;
    const RecordLevel& l = layout.levels[level];
    if (!cache_->get_imagespec(files_.back().handle, nullptr, s, int(level), 0) || s.width != l.width ||
        s.height != l.height || s.nchannels != l.words || s.tile_width != layout.tile_side)
      throw environment_error(path.string(), "the texture cache's file changed under it");
  }
  return file;
}

void TextureTiles::refill(Pins& pins, Pin& pin, int file, std::uint64_t key) const {
  if (!pins.info) pins.info = cache_->get_perthread_info();
  if (pin.tile) cache_->release_tile(pin.tile);
  pin = Pin{};
  const File& f = files_[std::size_t(file)];
  const int level = int((key >> kLevelShift) & 31);
  const int x = int(key & 0x1FFFFF) << f.tile_shift, y = int((key >> 21) & 0x1FFFFF) << f.tile_shift;
  OIIO::ImageCache::Tile* tile = cache_->get_tile(f.handle, pins.info, level, 0, x, y, 0);
  return_freed_pages();
  OIIO::TypeDesc format;
  const void* pixels = tile ? cache_->tile_pixels(tile, format) : nullptr;
  // The tile's bytes per texel: the cache's channels are the file's (checked when it was opened).
  const std::size_t texel_bytes = f.levels[std::size_t(level)].texel_bytes;
  if (!pixels || format.size() * std::size_t(f.levels[std::size_t(level)].channels) != texel_bytes) {
    if (tile) cache_->release_tile(tile);
    const std::lock_guard<std::mutex> lock(mutex_);
    if (failure_.empty())
      failure_ = f.path.string() + ": the texture cache cannot read the tile at (" + std::to_string(x) + ", " +
                 std::to_string(y) + "): " + cache_->geterror() + " (removing the file makes the next render write it again)";
    failed_.store(true, std::memory_order_relaxed);
    pin.pixels = zero_tile_.data();  // key left unset: the next lookup of this tile tries again
    return;
  }
  pin.key = key, pin.tile = tile, pin.pixels = static_cast<const std::byte*>(pixels);
}

// glibc's malloc_trim(0) releases every whole free page of every arena, not only the top of the heap
// (malloc_trim(3): glibc 2.8 and later), which the cache's eviction leaves behind. It walks the free
// lists under each arena's lock: run at most every kReturnInterval, and only while tiles are read (a
// miss is what frees and allocates), it costs about 1 % of a render's CPU, 6 % where a full cache
// churns (bench/results/render.md). Elsewhere the allocator keeps the pages.
void TextureTiles::return_freed_pages() const {
#ifdef __GLIBC__
  constexpr std::int64_t kReturnInterval = 100'000'000;  // ns
  const std::int64_t now = std::chrono::duration_cast<std::chrono::nanoseconds>(
                               std::chrono::steady_clock::now().time_since_epoch())
                               .count();
  std::int64_t last = last_return_ns_.load(std::memory_order_relaxed);
  if (now - last < kReturnInterval ||
      !last_return_ns_.compare_exchange_strong(last, now, std::memory_order_relaxed))
    return;  // not yet, or another thread does it now
  ::malloc_trim(0);
#endif
}

std::vector<std::byte> TextureTiles::read_all(int file) const {
  const File& f = files_[std::size_t(file)];
  const Level& l = f.levels[0];
  std::vector<std::byte> out(l.texel_bytes * std::size_t(l.width) * std::size_t(l.height));
  const auto in = OIIO::ImageInput::open(f.read_path.string());
  if (!in || !in->read_image(0, 0, 0, 4, l.texel_bytes == 4 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT,
                             out.data()))
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
