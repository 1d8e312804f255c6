#pragma once
// Out-of-core textures: images and MIP data kept as tiled files on disk and read through an
// OpenImageIO ImageCache whose memory is capped, so the texels resident at once are bounded by the cap
// whatever the scene holds (`svbrdf-render --texture-cache MB`). TextureSet (render/texture_set.h)
// writes each decoded image here once and looks its texels up through texel(); the MIP textures of
// the materials (render/mip_tiles.h) write their pyramids as record files and read them through
// record().
//
// Image files: TIFF, 4 channels (RGBA), 64 × 64 tiles, one level (the level-0 texels), 8-bit or
// 32-bit float. Record files: TIFF, one subimage a level (a level's texels have their own number of
// channels, which OpenImageIO's MIP levels do not allow), each texel a record of 32-bit words stored
// as float channels (bit-cast: the cache keeps floats as the file holds them, its other 32-bit types
// it converts), small tiles (records are up to a few hundred bytes), and a description (the TIFF
// ImageDescription) that says what the records hold. Both are named by a
// key that their writer makes from what they hold, in the MIP cache's folder (render/mip_cache.h),
// which counts them in its size and evicts them as it does its entries. A file is written to a
// temporary beside it and renamed into place (base/atomic_file.h), so concurrent renders that share
// the folder see a whole file or none; one that is there with the expected size and layout is
// reused, not written again: an image file must hold its description (render/image_file_description.h),
// which names its key, and read to its last tile; one that does not gets one warning and is written
// again. Each file is read through a hard link that this process makes beside it when it adds it
// (".KEY.heldPID.tx") and removes at the end: an eviction (this render's, after each material it
// builds, or another's) removes the file's name, not the link, so it cannot pull the file from under
// the render, whether OpenImageIO keeps it open or opens it again. A link left by a killed render is
// removed by a later eviction (render/mip_cache.h).
//
// Lookups: a per-thread table of pinned tiles (ImageCache::get_tile), direct-mapped by file, level and
// tile, so that a lookup whose tile a recent lookup of the same thread read costs a hash and a
// compare, not a call into the cache (bench/results/render.md). A thread pins at most kPinnedTiles
// tiles; the cache's own bookkeeping counts them, so they are inside the cap.
//
// The cap counts tile bytes; the process holds what its allocator keeps too. A tile evicted leaves a
// hole in the heap that libtiff's and libdeflate's buffers of each later read split, so new tiles
// grow the heap past the tiles it holds (at a 100 MB cap, 60 MiB of free chunks beside the tiles,
// bench/results/render.md); return_freed_pages() gives the holes' whole pages back to the system, so
// the resident set follows the cache within the overhead README states.
//
// A tile that cannot be read (the disk failed, a corrupt file) reads as zeros and is recorded:
// failure() says so after the render, which then fails (exit 1) rather than pass an image with holes.
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

#include <OpenImageIO/oiioversion.h>

#include "textures/image.h"

OIIO_NAMESPACE_BEGIN
class ImageCache;
namespace pvt {
class ImageCacheFile;
class ImageCachePerThreadInfo;
class ImageCacheTile;
}  // namespace pvt
OIIO_NAMESPACE_END

namespace svbrdf {

// Per channel: an 8-bit code → the value it stands for (render/texture_set.h's 8-bit form).
using CodeTable = std::array<std::array<float, 256>, 4>;

// A scene image whose texels the texture cache holds, as TextureSet::store wrote it: its 8-bit codes
// and their tables, or its floats and those of its scene-linear copy (both RGBA).
struct TiledImage {
  int width = 0, height = 0, channels = 0;  // as decoded
  bool codes = false;   // 8-bit codes: raw_file holds them, for both tables
  bool linear = false;  // a color slot shows it: linear_file / linear_table hold its scene-linear copy
  int raw_file = -1, linear_file = -1;  // TextureTiles::add's indices
  CodeTable raw_table{}, linear_table{};
};

// A level of a record file: its texels and the 32-bit words of each one's record.
struct RecordLevel {
  int width = 0, height = 0, words = 0;
  bool operator==(const RecordLevel&) const = default;
};
// What a record file holds: its levels, its tile side and the writer's description of the records.
struct RecordLayout {
  std::vector<RecordLevel> levels;
  int tile_side = 16;
  std::string description;
  bool operator==(const RecordLayout&) const = default;
};

class TextureTiles {
 public:
  static constexpr int kTileSide = 64;  // texels; a power of two (lookups shift and mask)
  static constexpr int kTileShift = 6;
  static constexpr int kPinnedTiles = 64;  // per thread; a power of two
  // The smallest cap OpenImageIO's ImageCache honours (its max_memory_MB is raised to 10 MB below).
  static constexpr double kMinMegabytes = 10.0;
  static constexpr double kDefaultMegabytes = 1024.0;

  // Files in `folder` (created when missing), at most `megabytes` (10^6 bytes) of tiles in memory.
  TextureTiles(std::filesystem::path folder, double megabytes);
  ~TextureTiles();
  TextureTiles(const TextureTiles&) = delete;
  TextureTiles& operator=(const TextureTiles&) = delete;

  const std::filesystem::path& folder() const { return folder_; }

  // The image file of `key` (64 hexadecimal digits) holding `rgba` (width · height · 4 values, rows
  // from the top, uint8 or float32 as `format` says) with `description` (its ImageDescription: render/
  // image_file_description.h), written unless a whole one with that description is there (one that is
  // not is refused: refuse()); its index for texel(). Throws svbrdf::Error (environment) when it can
  // be neither found nor written.
  int add(const std::string& key, int width, int height, PixelFormat format, const void* rgba,
          const std::string& description);
  // An image file there: its size and its description.
  struct FoundImage {
    int width = 0, height = 0;
    std::string description;
  };
  // The image file of `key` when one is there laid out as add() writes one of `format` (RGBA, 64²
  // tiles, one level) and whole: its last tile, the last bytes add() wrote, reads, so a file cut short
  // is refused at once rather than failing the render at its first lookup there. nullopt when there is
  // none, or, with `why` set, when the one there is refused. Reads one tile, decodes no image.
  std::optional<FoundImage> inspect_image(const std::string& key, PixelFormat format, std::string* why) const;
  // Opens the image file of `key` that inspect_image found, for texel(); its index. Throws
  // svbrdf::Error (environment) when it cannot be opened as inspected.
  int open_image(const std::string& key, int width, int height, PixelFormat format);

  // A file of `key` that is there but not to be trusted (`why`): one warning a file, whoever refuses
  // it first (a render that finds it, then the writer that replaces it). The warnings, in order.
  void refuse(const std::string& key, const std::string& why);
  const std::vector<std::string>& warnings() const { return warnings_; }

  // The scene images decoded and written here, and those whose files were found here (not decoded).
  struct ImageCounts {
    int decoded = 0, found = 0;
  };
  void count_image(bool found) { ++(found ? image_counts_.found : image_counts_.decoded); }
  ImageCounts image_counts() const { return image_counts_; }

  // The record file of `key` as `path_of` names it: the layout that file holds (nullopt: none, or
  // not one this class wrote: `why` says what is wrong with one that is there).
  std::optional<RecordLayout> inspect_records(const std::string& key, std::string* why = nullptr) const;
  // Writes the record file of `key` (temporary, sync, rename) with `layout`, each level's rows from
  // `fill` (level, first row, end row, out: (end − first) · width · words words, rows from the top),
  // then opens it; open_records opens the one there, which must hold `layout` (inspect_records). The
  // file's index for record(). Throw svbrdf::Error (environment) when it cannot be written or opened.
  using FillRows = std::function<void(int level, int row_begin, int row_end, std::uint32_t* out)>;
  int write_records(const std::string& key, const RecordLayout& layout, const FillRows& fill);
  int open_records(const std::string& key, const RecordLayout& layout);
  std::filesystem::path path_of(const std::string& key) const { return folder_ / (key + ".tx"); }

  // The first byte of texel (i, j) of file `file` (inside the image): 4 bytes or 4 floats.
  // Thread-safe; the pointer holds until this thread's next texel() or record() call.
  const std::byte* texel(int file, int i, int j) const { return fetch(file, 0, i, j); }
  // The record of texel (i, j) of level `level` of record file `file` (inside the level): its words.
  // Thread-safe; the pointer holds until this thread's next texel() or record() call.
  const std::uint32_t* record(int file, int level, int i, int j) const {
    return reinterpret_cast<const std::uint32_t*>(fetch(file, level, i, j));
  }

  // The whole level-0 image of `file`, as stored (for the MIP builds, which read every texel).
  std::vector<std::byte> read_all(int file) const;

  // The scene's images as stored here, by Scene::images index (null: not stored here).
  void set_image(std::size_t index, const TiledImage& image) {
    if (images_.size() <= index) images_.resize(index + 1);
    images_[index] = std::make_unique<TiledImage>(image);
  }
  const TiledImage* image(std::size_t index) const { return index < images_.size() ? images_[index].get() : nullptr; }

  // The files added, and their texels' bytes in memory were all of them resident (the scene's
  // texture memory at the cache's formats: what a cap is a fraction of).
  int file_count() const { return int(files_.size()); }
  std::uint64_t texel_bytes() const {
    std::uint64_t n = 0;
    for (const File& f : files_)
      for (const Level& l : f.levels) n += l.texel_bytes * std::uint64_t(l.width) * std::uint64_t(l.height);
    return n;
  }

  // What went wrong reading tiles, or empty: the first file that failed.
  std::string failure() const;

 private:
  static constexpr int kPinBits = 6;
  static_assert(1 << kPinBits == kPinnedTiles);
  // A pin's key: file, level and tile, 17 + 5 + 21 + 21 bits.
  static constexpr int kLevelShift = 42, kFileShift = 47;
  struct Level {
    int width = 0, height = 0;
    int channels = 0;             // an image's 4; a record's words
    std::size_t texel_bytes = 0;  // an image's 4 (uint8) or 16 (float); a record's 4 a word
  };
  struct File {
    std::filesystem::path path;       // its name in the folder (what messages name)
    std::filesystem::path read_path;  // what it is read by: this process's link of it, or its name (open_file)
    bool held = false;
    OIIO::pvt::ImageCacheFile* handle = nullptr;
    int tile_shift = kTileShift;
    std::vector<Level> levels;  // an image's one
  };
  const std::byte* fetch(int file, int level, int i, int j) const {
    const File& f = files_[std::size_t(file)];
    const int shift = f.tile_shift, mask = (1 << shift) - 1;
    const std::uint64_t key = (std::uint64_t(file) << kFileShift) | (std::uint64_t(level) << kLevelShift) |
                              (std::uint64_t(j >> shift) << 21) | std::uint64_t(i >> shift);
    Pins& pins = pins_.local();
    Pin& pin = pins.slots[(key * 0x9E3779B97F4A7C15ull) >> (64 - kPinBits)];
    if (pin.key != key) refill(pins, pin, file, key);
    return pin.pixels +
           f.levels[std::size_t(level)].texel_bytes * std::size_t(((j & mask) << shift) + (i & mask));
  }
  int open_file(const std::filesystem::path& path, int tile_side, std::vector<Level> levels);
  struct Pin {
    std::uint64_t key = ~std::uint64_t(0);
    OIIO::pvt::ImageCacheTile* tile = nullptr;
    const std::byte* pixels = nullptr;
  };
  struct Pins {
    OIIO::pvt::ImageCachePerThreadInfo* info = nullptr;
    std::array<Pin, kPinnedTiles> slots{};
  };
  void refill(Pins& pins, Pin& pin, int file, std::uint64_t key) const;
  // Hands the pages of freed tiles back to the system, at most once a kReturnInterval (see the .cpp).
  void return_freed_pages() const;

  std::filesystem::path folder_;
  OIIO::ImageCache* cache_ = nullptr;
  std::vector<File> files_;  // complete before the first lookup
  std::vector<std::byte> zero_tile_;  // what a tile that cannot be read reads as: the largest tile's bytes
  std::vector<std::unique_ptr<TiledImage>> images_;
  std::vector<std::string> warnings_;
  std::vector<std::string> refused_;  // the keys refuse() warned of
  ImageCounts image_counts_;
  mutable tbb::enumerable_thread_specific<Pins, tbb::cache_aligned_allocator<Pins>, tbb::ets_key_per_instance> pins_;
  mutable std::mutex mutex_;  // guards failure_
  mutable std::string failure_;
  mutable std::atomic<bool> failed_{false};
  mutable std::atomic<std::int64_t> last_return_ns_{0};  // steady clock, when pages were last handed back
};

}  // namespace svbrdf
