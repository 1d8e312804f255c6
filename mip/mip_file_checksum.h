#pragma once
// Private to mip/ (mip_file.cpp): a MIP file level's svbrdf:checksum (mip_file.h) — the fingerprint of
// the header values that give its texels a meaning and of its pixels in the order of their channels'
// names, made band by band as the level is written or read.
#include <OpenImageIO/imageio.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "base/error.h"
#include "mip/mip_file_channels.h"

namespace svbrdf::mip_file_checksum {

using mip_file_channels::NativeLayout;

inline constexpr const char* kChecksum = "svbrdf:checksum";

// The fingerprint of one band of pixels in name order, appended to `bands`. Fingerprint128 is fixed
// and portable (unlike OpenImageIO's Hash128), so a file checks on any machine; it guards against
// corruption, not against an adversary (the cache key is the SHA-256 one).
void add_band(std::vector<std::uint64_t>& bands, std::span<const std::byte> name_ordered_pixels);

// A level's checksum: the header values that give its pixels their meaning, then its bands'
// fingerprints.
std::string level_checksum(const OIIO::ImageSpec& s, int max_lobes, float radial_inner, float radial_outer,
                           const std::vector<std::uint64_t>& bands);

// What a level's header holds in place of its checksum while the file is written: OpenEXR writes
// every header when the file opens, before the pixels the checksums fingerprint, so each level's
// header carries this string of the checksum's length, and put_checksums writes the checksums over
// them once the pixels are written, without moving a byte of the file.
inline const std::string kChecksumPlaceholder(32, '0');

// Writes `checksums[p]` (32 hexadecimal digits each) over part p's placeholder in the written OpenEXR
// file `file`. Throws svbrdf::Error naming `where`: internal when a part's header holds no placeholder,
// the machine's when the file cannot be written.
void put_checksums(const std::filesystem::path& file, const std::vector<std::string>& checksums, const std::string& where);

// Checks a level's pixels against its svbrdf:checksum band by band as they are read (`native`: the
// layout OpenImageIO reads them in): add() each band, then mismatch(), the error when they differ.
// The constructor throws when the checksum is absent and `required`.
class LevelCheck {
 public:
  LevelCheck(const std::filesystem::path& path, const OIIO::ImageSpec& s, const NativeLayout& native, bool required)
      : path_(path), spec_(s), native_(native), stored_(s.get_string_attribute(kChecksum, "")) {
    if (stored_.empty() && required)
      throw input_error(path.string(), "level " + std::to_string(s.get_int_attribute("svbrdf:level", -1)) + " has no " + kChecksum);
    std::vector<OIIO::TypeDesc> formats;
    for (int c = 0; c < s.nchannels; ++c) formats.push_back(s.channelformat(c));
    ordered_ = mip_file_channels::name_ordered(s.channelnames, formats);
    for (const OIIO::TypeDesc& f : formats) sizes_.push_back(f.size());
  }
  void add(std::span<const std::byte> band) {
    if (stored_.empty()) return;
    if (ordered_.offsets == native_.offsets) return add_band(bands_, band);
    // Not in name order: the band put in it first.
    scratch_.resize(band.size());
    const std::size_t texels = band.size() / native_.stride;
    // A texel at a time (its bytes stay in cache), each channel copied with its size known to the
    // compiler: a copy of a size known only at run time is a library call per texel and channel.
    for (std::size_t t = 0; t < texels; ++t) {
      std::byte* to = scratch_.data() + t * ordered_.stride;
      const std::byte* from = band.data() + t * native_.stride;
      for (std::size_t c = 0; c < sizes_.size(); ++c) {
        std::byte* d = to + ordered_.offsets[c];
        const std::byte* f = from + native_.offsets[c];
        if (sizes_[c] == 2) std::memcpy(d, f, 2);
        else if (sizes_[c] == 4) std::memcpy(d, f, 4);
        else std::memcpy(d, f, sizes_[c]);
      }
    }
    add_band(bands_, scratch_);
  }
  std::optional<Error> mismatch(int max_lobes, float radial_inner, float radial_outer) const {
    if (stored_.empty()) return std::nullopt;
    const std::string actual = level_checksum(spec_, max_lobes, radial_inner, radial_outer, bands_);
    if (actual == stored_) return std::nullopt;
    return input_error(path_.string(), "level " + std::to_string(spec_.get_int_attribute("svbrdf:level", -1)) +
                                         " does not match its " + kChecksum + " (" + stored_ + ", the texels give " + actual +
                                         "): a corrupt file");
  }

 private:
  const std::filesystem::path& path_;
  const OIIO::ImageSpec& spec_;
  const NativeLayout& native_;
  std::string stored_;
  NativeLayout ordered_;
  std::vector<std::size_t> sizes_;
  std::vector<std::byte> scratch_;
  std::vector<std::uint64_t> bands_;
};

}  // namespace svbrdf::mip_file_checksum
