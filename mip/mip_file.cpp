#include "mip/mip_file.h"

#include <Imath/half.h>
#include <OpenImageIO/imageio.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <future>
#include <iterator>
#include <map>
#include <numeric>
#include <optional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/resource_limits.h"
#include "mip/mip_file_channels.h"
#include "mip/mip_file_checksum.h"
#include "mip/stored_lobe.h"
#include "mip/stored_normal.h"
#include "textures/exr_header.h"

namespace svbrdf {

namespace {

namespace fs = std::filesystem;

using namespace mip_file_channels;
using namespace mip_file_checksum;

constexpr const char* kRadialInner = "svbrdf:radial_inner";
constexpr const char* kRadialOuter = "svbrdf:radial_outer";
constexpr const char* kCacheKey = "svbrdf:cache_key";
std::string radial_channel(int node) { return "radial.R" + std::to_string(node); }
std::string where(const fs::path& p) { return p.string(); }

// A level's pixels are checked in bands of whole rows, about this many bytes each, as they are read:
// the reader keeps two (one being unpacked, the next being read), not a second copy of the level.
constexpr std::size_t kBandBytes = std::size_t(1) << 22;
int band_rows(int width, std::size_t stride) {
  return static_cast<int>(std::max<std::size_t>(1, kBandBytes / (std::size_t(std::max(width, 1)) * std::max<std::size_t>(stride, 1))));
}
// The codec: OpenEXR's zip, deflate of 16-row chunks, at zlib level 2. zlib's levels 1–3 are its
// greedy matcher, 4 (OpenEXR's default) and above its lazy one. Measured on the 4096² metal tray and
// random-family seed 4 at 1024² (bench/results/mip.md, "Build time"): level 4 takes 1.3× and 1.2× the
// CPU time of level 2 to write the file, for files 9.5 % and 4.5 % smaller; levels 1 and 3 cost about
// level 2's time for a file 1.5 % larger and 6–13 % more time for one 2 % smaller. The level is the
// writer's alone: the file says "zip", and its pixels read back the same at any level.
constexpr const char* kCompression = "zip:2";
constexpr int kZipChunkRows = 16;
// Rows a write of scanlines hands OpenEXR: whole chunks, and at least two for each thread of its pool
// where that fits in kWriteBytes. OpenEXR compresses the chunks one call completes in parallel; a call
// of a band's few rows (a 4096² material's level 1 holds 15 rows in kBandBytes) completes at most one,
// which one thread compresses while the others wait. The bound keeps a many-core machine's band from
// growing toward a level's whole pixels (16 threads: 142 MB for that level 1).
constexpr std::size_t kWriteBytes = std::size_t(1) << 26;
int write_rows(int width, std::size_t stride) {
  int threads = 1;
  OIIO::getattribute("threads", threads);
  const std::size_t chunk_bytes = std::size_t(std::max(width, 1)) * std::max<std::size_t>(stride, 1) * kZipChunkRows;
  const int fit = static_cast<int>(std::max<std::size_t>(1, kWriteBytes / chunk_bytes));
  const int chunks = std::max(band_rows(width, stride) / kZipChunkRows, std::min(2 * std::max(threads, 1), fit));
  return chunks * kZipChunkRows;
}
// Texels a packing task takes: a band of kBandBytes holds 16 to 128 thousand texels (strides of 256 to
// 32 bytes), so each band of a large level splits among at least 16 tasks.
constexpr std::size_t kPackGrain = 1024;

// The fewest bytes an OpenEXR file holding `spec`'s pixels can have, from the format (OpenEXR's
// "Technical Introduction", file layout): an 8-byte offset-table entry and an 8-byte chunk header
// for every chunk, and for the zlib-based and uncompressed codecs the pixel bytes divided by the
// codec's largest ratio (deflate's is 1032:1, RFC 1951's longest match of 258 bytes in 2 bits; run
// length's 128:2). A header that claims more pixels than its file could hold is refused before a
// level is allocated or a chunk decoded.
std::uint64_t least_exr_bytes(const OIIO::ImageSpec& spec) {
  const std::uint64_t w = std::uint64_t(std::max(spec.width, 1)), h = std::uint64_t(std::max(spec.height, 1));
  const std::string codec = spec.get_string_attribute("compression", "none");
  std::uint64_t chunks;
  if (spec.tile_width > 0 && spec.tile_height > 0) {
    chunks = ((w + spec.tile_width - 1) / spec.tile_width) * ((h + spec.tile_height - 1) / spec.tile_height);
  } else {
    const std::uint64_t lines = codec == "zip" ? 16 : codec == "none" || codec == "rle" || codec == "zips" ? 1 : 256;
    chunks = (h + lines - 1) / lines;
  }
  const std::uint64_t pixels = w * h * std::uint64_t(spec.pixel_bytes(true));
  const std::uint64_t ratio = codec == "none" ? 1 : codec == "rle" ? 64 : codec == "zip" || codec == "zips" ? 1032 : 0;
  return chunks * 16 + (ratio ? pixels / ratio : 0);
}
}  // namespace

namespace {

// The channels a level's texel holds, in the order the spec lists them: the parameters (and the
// specular layer's, coat's, sheen's, anisotropy's and transmission's means), `slots` lobes of `lobe` channels
// each, the radial correction, `coat_slots` coat lobes.
struct LevelChannels {
  bool specular = false, coat = false, sheen = false, anisotropy = false, transmission = false, radial = false;
  bool diffuse_transmission = false;
  int slots = 0, coat_slots = 0;
  std::vector<LobeChannel> lobe;
  std::size_t first_lobe() const {
    return 8 + (specular ? 4 : 0) + (coat ? 5 : 0) + (sheen ? 4 : 0) + (anisotropy ? 3 : 0) + (transmission ? 1 : 0) +
           (diffuse_transmission ? 4 : 0);
  }
  std::size_t first_radial() const { return first_lobe() + std::size_t(slots) * lobe.size(); }
  std::size_t first_coat_lobe() const { return first_radial() + (radial ? RadialGrid::kNodes : 0); }
};

// Puts `slots` lobes, the texel's and empty ones after them, into channels from `first` on.
void put_lobes(std::byte* px, const NativeLayout& layout, std::size_t first, int slots, std::span<const Lobe> lobes,
               const std::vector<LobeChannel>& channels) {
  // Empty slots: weight 0 (and a plain GGX of α² 1 about the geometric normal, so every channel holds a
  // meaningful value).
  // Packed once: most texels of a level leave most of its slots empty.
  static const LobeValues kEmpty = [] {
    Lobe l;
    l.weight = 0.0f, l.diffuse = glm::vec3(0), l.f0 = glm::vec3(0), l.alpha2 = 1.0f;
    return pack_lobe(l);
  }();
  for (int k = 0; k < slots; ++k) {
    const LobeValues v = k < static_cast<int>(lobes.size()) ? pack_lobe(lobes[static_cast<std::size_t>(k)]) : kEmpty;
    for (std::size_t c = 0; c < channels.size(); ++c) {
      const std::size_t ch = first + static_cast<std::size_t>(k) * channels.size() + c;
      if (channels[c].role == Role::normal_direction) put_uint(px, layout, ch, v.direction);
      else put_float(px, layout, ch, v[channels[c].role]);
    }
  }
}

// Rows [y0, y1) of level `level`'s pixels in `layout` (the spec's channels, by index, at the layout's
// offsets) into `out`, every byte of each texel written; texels in parallel (each is its own bytes).
void pack_rows(const ParamPyramid& param, const BrdfPyramid& brdf, int level, const NativeLayout& layout,
               const LevelChannels& ch, int y0, int y1, std::byte* out) {
  const Extent e = param.extent(level);
  const auto params = param.level(level);
  const auto specular = param.specular_level(level);
  const auto coat = param.coat_level(level);
  const auto sheen = param.sheen_level(level);
  const auto aniso = param.anisotropy_level(level);
  const auto transmission = param.transmission_level(level);
  const auto diffuse_transmission = param.diffuse_transmission_level(level);
  const std::vector<LobeChannel> coat_channels = coat_lobe_channels();
  const std::size_t first = static_cast<std::size_t>(y0) * e.width, last = static_cast<std::size_t>(y1) * e.width;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(first, last, kPackGrain), [&](const tbb::blocked_range<std::size_t>& texels) {
    for (std::size_t t = texels.begin(); t != texels.end(); ++t) {
      std::byte* px = out + (t - first) * layout.stride;
      const ParamTexel& p = params[t];
      const float values[8] = {p.base_color.r, p.base_color.g, p.base_color.b, p.metallic,
                               p.roughness,    p.normal.x,     p.normal.y,     p.normal.z};
      for (std::size_t c = 0; c < 8; ++c) put_float(px, layout, c, values[c]);
      std::size_t next = 8;
      if (ch.specular) {
        const ParamSpecular& sp = specular[t];
        for (const float v : {sp.specular, sp.color.r, sp.color.g, sp.color.b}) put_float(px, layout, next++, v);
      }
      if (ch.coat) {
        const ParamCoat& c = coat[t];
        for (const float v : {c.clearcoat, c.roughness, c.normal.x, c.normal.y, c.normal.z}) put_float(px, layout, next++, v);
      }
      if (ch.sheen) {
        const SheenLayer& c = sheen[t];
        for (const float v : {c.color.r, c.color.g, c.color.b, c.roughness}) put_float(px, layout, next++, v);
      }
      if (ch.anisotropy) {
        const AnisotropyLayer& a = aniso[t];
        for (const float v : {a.strength, a.direction.x, a.direction.y}) put_float(px, layout, next++, v);
      }
      if (ch.transmission) put_float(px, layout, next++, transmission[t]);
      if (ch.diffuse_transmission) {
        const DiffuseTransmissionLayer& d = diffuse_transmission[t];
        for (const float v : {d.share, d.color.r, d.color.g, d.color.b}) put_float(px, layout, next++, v);
      }
      if (level == 0) continue;
      const BrdfLevel& bl = brdf.level(level);
      put_lobes(px, layout, ch.first_lobe(), ch.slots, bl.texel_lobes(t), ch.lobe);
      if (ch.radial)
        for (int r = 0; r < RadialGrid::kNodes; ++r)
          put_float(px, layout, ch.first_radial() + static_cast<std::size_t>(r), bl.correction[t].ratio[static_cast<std::size_t>(r)]);
      if (ch.coat_slots > 0)
        put_lobes(px, layout, ch.first_coat_lobe(), ch.coat_slots, brdf.coat_level(level).texel_lobes(t), coat_channels);
    }
  });
}

}  // namespace

void write_mip_file(const fs::path& path, const MipData& mip, const std::string& cache_key) {
  write_mip_file(path, mip.param, mip.brdf, cache_key);
}

void write_mip_file(const fs::path& path, const ParamPyramid& param, const BrdfPyramid& brdf, const std::string& cache_key) {
  const int levels = param.levels();
  if (levels == 0) throw Error(where(path) + ": nothing to write (an empty material)", Error::Kind::internal);
  bool corrected = false;
  for (int level = 1; level < levels; ++level) corrected |= !brdf.level(level).correction.empty();
  const float radial_inner = corrected ? brdf.radial_grid().inner : 0.0f;
  const float radial_outer = corrected ? brdf.radial_grid().outer_deg : 0.0f;
  // A coated material's file carries the coat in both pyramids (mip_file.h).
  if (levels > 1 && param.has_coat() != brdf.has_coat())
    throw Error(where(path) + ": the parameter and BRDF pyramids disagree about the clear coat", Error::Kind::internal);
  if (levels > 1 && param.has_sheen() != brdf.has_sheen())
    throw Error(where(path) + ": the parameter and BRDF pyramids disagree about the sheen", Error::Kind::internal);
  std::vector<LevelChannels> channels(static_cast<std::size_t>(levels));
  for (int level = 0; level < levels; ++level) {
    LevelChannels& c = channels[static_cast<std::size_t>(level)];
    c.specular = !param.specular_level(0).empty();
    c.coat = param.has_coat();
    c.sheen = param.has_sheen();
    c.anisotropy = param.has_anisotropy();
    c.transmission = param.has_transmission();
    c.diffuse_transmission = param.has_diffuse_transmission();
    if (level == 0) continue;
    const BrdfLevel& bl = brdf.level(level);
    c.slots = bl.slots;
    c.radial = !bl.correction.empty();
    c.lobe = lobe_channels({.specular = bl.specular_layer(), .tint = brdf.tintable() && bl.tint_layer(), .coat = c.coat,
                            .sheen = c.sheen, .stretch = bl.stretch_layer(), .transmission = bl.transmission_layer(),
                            .transmission90 = bl.transmission90_layer(),
                            .transmission_stretch = bl.transmission_stretch_layer(),
                            .diffuse_transmission = bl.diffuse_transmission_layer(),
                            .diffuse_transmission90 = bl.diffuse_transmission90_layer()});
    c.coat_slots = c.coat ? brdf.coat_level(level).slots : 0;
  }
  // Each level is packed once, a band of rows at a time, into one buffer (a level's whole pixels would
  // be hundreds of megabytes of fresh pages), fingerprinted for its checksum and written.
  std::unique_ptr<std::byte[]> band_bytes;
  std::size_t band_capacity = 0;
  const auto band_buffer = [&](std::size_t bytes) {
    if (bytes > band_capacity) band_bytes = std::make_unique_for_overwrite<std::byte[]>(band_capacity = bytes);
    return std::span<std::byte>(band_bytes.get(), bytes);
  };
  std::vector<OIIO::ImageSpec> specs(static_cast<std::size_t>(levels));
  std::vector<NativeLayout> layouts(static_cast<std::size_t>(levels));
  for (int level = 0; level < levels; ++level) {
    const Extent e = param.extent(level);
    const LevelChannels& ch = channels[static_cast<std::size_t>(level)];
    OIIO::ImageSpec& s = specs[static_cast<std::size_t>(level)];
    NativeLayout& layout = layouts[static_cast<std::size_t>(level)];
    s = OIIO::ImageSpec(e.width, e.height, 0, OIIO::TypeDesc::FLOAT);
    // OpenEXR parts share their display window: every level's is level 0's.
    s.full_x = 0, s.full_y = 0, s.full_width = param.extent(0).width, s.full_height = param.extent(0).height;
    s.channelnames.clear();
    s.channelformats.clear();
    const auto add = [&](std::string name, OIIO::TypeDesc f) {
      s.channelnames.push_back(std::move(name));
      s.channelformats.push_back(f);
      layout.add(f);
    };
    for (const char* c : kParamChannels) add(c, OIIO::TypeDesc::FLOAT);
    if (ch.specular)
      for (const char* c : kParamSpecularChannels) add(c, OIIO::TypeDesc::FLOAT);
    if (ch.coat)
      for (const char* c : kParamCoatChannels) add(c, OIIO::TypeDesc::FLOAT);
    if (ch.sheen)
      for (const char* c : kParamSheenChannels) add(c, OIIO::TypeDesc::FLOAT);
    if (ch.anisotropy)
      for (const char* c : kParamAnisotropyChannels) add(c, OIIO::TypeDesc::FLOAT);
    if (ch.transmission)
      for (const char* c : kParamTransmissionChannels) add(c, OIIO::TypeDesc::FLOAT);
    if (ch.diffuse_transmission)
      for (const char* c : kParamDiffuseTransmissionChannels) add(c, OIIO::TypeDesc::FLOAT);
    for (int k = 0; k < ch.slots; ++k)
      for (const LobeChannel& c : ch.lobe) add("lobe" + std::to_string(k) + "." + c.suffix, c.format);
    if (ch.radial)
      for (int r = 0; r < RadialGrid::kNodes; ++r) add(radial_channel(r), OIIO::TypeDesc::HALF);
    for (int k = 0; k < ch.coat_slots; ++k)
      for (const LobeChannel& c : kCoatLobeChannels) add("coat" + std::to_string(k) + "." + c.suffix, c.format);
    s.nchannels = static_cast<int>(s.channelnames.size());
    s.attribute("name", "level" + std::to_string(level));
    s.attribute("compression", kCompression);
    s.attribute("svbrdf:mip_version", kMipFileVersion);
    s.attribute("svbrdf:level", level);
    s.attribute("svbrdf:max_lobes", brdf.max_lobes());
    s.attribute("svbrdf:slots", ch.slots);
    if (ch.coat && level > 0) s.attribute(kCoatSlots, ch.coat_slots);
    if (param.ior() != 1.5f) s.attribute(kIor, param.ior());
    if (brdf.tintable()) s.attribute(kTint, 1);
    if (corrected) {
      s.attribute(kRadialInner, radial_inner);
      s.attribute(kRadialOuter, radial_outer);
    }
    if (level == 0 && !cache_key.empty()) s.attribute(kCacheKey, cache_key);
    // The pixels are packed in the order of the channels' names, the order OpenEXR stores them in and
    // the checksum takes them in, and the spec lists the channels in that order, so the bands written
    // are the bands fingerprinted. The checksum, known once the level is written, replaces a
    // placeholder in the written file (put_checksums).
    layout = name_ordered(s.channelnames, s.channelformats);
    std::vector<std::size_t> by_name(s.channelnames.size());
    std::iota(by_name.begin(), by_name.end(), std::size_t(0));
    std::sort(by_name.begin(), by_name.end(), [&](std::size_t a, std::size_t b) { return s.channelnames[a] < s.channelnames[b]; });
    std::vector<std::string> names;
    std::vector<OIIO::TypeDesc> formats;
    for (const std::size_t c : by_name) names.push_back(s.channelnames[c]), formats.push_back(s.channelformats[c]);
    s.channelnames = std::move(names);
    s.channelformats = std::move(formats);
    s.attribute(kChecksum, kChecksumPlaceholder);
  }
  // OpenImageIO 2.4's multi-part OpenEXR writer ignores an "oiio:ioproxy" (it writes a file of the
  // given name in the working folder), so the file is written to a temporary by OpenEXR, which throws
  // on a failed write, and renamed after an fsync; a failure there is the machine's (exit 1).
  std::vector<std::string> checksums(static_cast<std::size_t>(levels));
  write_atomically(path, [&](const fs::path& tmp) {
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(tmp.string());
    if (!out) throw environment_error(where(path), "cannot write OpenEXR: " + OIIO::geterror());
    if (!out->open(tmp.string(), levels, specs.data()))
      throw environment_error(where(path), "cannot write: " + out->geterror());
    for (int level = 0; level < levels; ++level) {
      const OIIO::ImageSpec& s = specs[static_cast<std::size_t>(level)];
      if (level > 0 && !out->open(tmp.string(), s, OIIO::ImageOutput::AppendSubimage))
        throw environment_error(where(path), "cannot write level " + std::to_string(level) + ": " + out->geterror());
      const NativeLayout& layout = layouts[static_cast<std::size_t>(level)];
      // Whole checksum bands (the reader's, band_rows) a write, as many as make write_rows' rows.
      const int band = band_rows(s.width, layout.stride);
      const int rows = (write_rows(s.width, layout.stride) + band - 1) / band * band;
      std::vector<std::uint64_t> bands;
      for (int y = 0; y < s.height; y += rows) {
        const int end = std::min(s.height, y + rows);
        const std::size_t row_bytes = std::size_t(s.width) * layout.stride;
        const std::span<std::byte> pixels = band_buffer(static_cast<std::size_t>(end - y) * row_bytes);
        pack_rows(param, brdf, level, layout, channels[static_cast<std::size_t>(level)], y, end, pixels.data());
        std::vector<std::vector<std::uint64_t>> prints(static_cast<std::size_t>((end - y + band - 1) / band));
        tbb::parallel_for(std::size_t(0), prints.size(), [&](std::size_t b) {
          const std::size_t first = b * std::size_t(band) * row_bytes;
          add_band(prints[b], pixels.subspan(first, std::min(pixels.size() - first, std::size_t(band) * row_bytes)));
        });
        for (const std::vector<std::uint64_t>& p : prints) bands.insert(bands.end(), p.begin(), p.end());
        if (!out->write_scanlines(y, end, 0, OIIO::TypeUnknown, pixels.data()))
          throw environment_error(where(path), "cannot write level " + std::to_string(level) + ": " + out->geterror());
      }
      checksums[static_cast<std::size_t>(level)] = level_checksum(s, brdf.max_lobes(), radial_inner, radial_outer, bands);
    }
    if (!out->close()) throw environment_error(where(path), "cannot finish writing: " + out->geterror());
    put_checksums(tmp, checksums, where(path));
  });
}

MipData read_mip_file(const fs::path& path, const std::string& cache_key) {
  check_exr_file_header(path, where(path));  // no allocation at a size only the file states
  // OpenEXR's reader only: ImageInput::open tries every other format's reader on a file OpenEXR's
  // refuses (LibRaw's alone clears tens of megabytes to say no), and a MIP file is OpenEXR.
  std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::create("openexr");
  if (OIIO::ImageSpec opened; in && !in->open(path.string(), opened)) {
    const std::string why = in->geterror();
    in.reset();
    (void)OIIO::geterror();
    throw input_error(where(path), "cannot read the MIP file: " + (fs::exists(path) ? why : "no such file"));
  }
  if (!in) {
    std::string why = OIIO::geterror();
    if (!fs::exists(path)) why = "no such file";
    throw input_error(where(path), "cannot read the MIP file: " + why);
  }
  const OIIO::ImageSpec& first = in->spec();
  const int version = first.get_int_attribute("svbrdf:mip_version", 0);
  if (version == 0) throw input_error(where(path), "not an svbrdf MIP file (no svbrdf:mip_version attribute)");
  // Another version's channels mean other things (mip_file.h): refused, with the way to a current file.
  if (version != kMipFileVersion)
    throw input_error(where(path), "MIP file version " + std::to_string(version) + "; this build reads version " +
                                       std::to_string(kMipFileVersion) + " only — rebuild it with `svbrdf-bake mip ... --out " +
                                       where(path) + "`");
  // A cache entry names its key before anything else is read: another key's entry is never used.
  if (!cache_key.empty()) {
    const std::string stored = first.get_string_attribute(kCacheKey, "");
    if (stored != cache_key)
      throw input_error(where(path), stored.empty() ? "has no " + std::string(kCacheKey) + " (not a MIP cache entry)"
                                                    : "holds the cache entry of key " + stored + ", not of " + cache_key);
  }
  const Extent level0{first.width, first.height};
  if (level0.width <= 0 || level0.height <= 0) throw input_error(where(path), "level 0 has no texels");
  const int levels = level_count(level0);
  const int max_lobes = first.get_int_attribute("svbrdf:max_lobes", 1);
  const float radial_inner = first.get_float_attribute(kRadialInner, 0.0f);
  const float ior = first.get_float_attribute(kIor, 1.5f);
  const int tint = first.get_int_attribute(kTint, 0);
  if (tint != 0 && tint != 1) throw input_error(where(path), std::string(kTint) + " is " + std::to_string(tint) + ", not 0 or 1");
  if (!(std::isfinite(ior) && ior >= 0.0f && ior <= 1e4f))
    throw input_error(where(path), std::string(kIor) + " is " + std::to_string(ior) + ", not an index of refraction");
  if (first.find_attribute(kRadialInner) && !(radial_inner > 0.0f && radial_inner < 0.5f))
    throw input_error(where(path), std::string(kRadialInner) + " is " + std::to_string(radial_inner) +
                                       ", not an angle in (0, 0.5) radians");
  const float radial_outer = first.get_float_attribute(kRadialOuter, 0.0f);
  if (radial_inner > 0.0f && !(radial_outer > radial_inner * 57.2957795f && radial_outer <= 45.0f))
    throw input_error(where(path), std::string(kRadialOuter) + " is " + std::to_string(radial_outer) +
                                       ", not an angle in degrees between " + kRadialInner + " and 45");
  // Every level's header before any pixel: the texels and the bytes they need are checked against
  // --max-texels, the memory budget and the file's own size first, so a corrupt header that claims
  // 8192² texels costs nothing.
  check_image_size(std::uint64_t(level0.width), std::uint64_t(level0.height), 1, where(path) + ": level 0");
  {
    std::uint64_t need = 0, least = 0;
    for (int level = 0; level < levels; ++level) {
      if (!in->seek_subimage(level, 0)) break;  // reported as a missing level below
      const OIIO::ImageSpec& s = in->spec();
      const Extent e = level_extent(level0, level);
      if (s.width != e.width || s.height != e.height) break;  // reported below, with the sizes
      // The encoded texels, then the parameters and lobes they unpack into: about twice as much again.
      need += std::uint64_t(e.width) * std::uint64_t(e.height) * (3 * std::uint64_t(s.pixel_bytes(true)));
      least += least_exr_bytes(s);
    }
    check_allocation(need, 1, where(path), "bytes of MIP levels");
    std::error_code ec;
    const std::uint64_t size = fs::file_size(path, ec);
    if (!ec && size < least)
      throw input_error(where(path), "is " + std::to_string(size) + " bytes, fewer than the " + std::to_string(least) +
                                         " its headers' " + std::to_string(level0.width) + "x" +
                                         std::to_string(level0.height) + " levels need: a truncated or corrupt file");
  }
  MipData mip;
  std::optional<Error> corrupt;  // the first level that fails its checksum
  std::vector<std::vector<ParamTexel>> param_levels;
  std::vector<std::vector<ParamSpecular>> specular_levels;
  std::vector<std::vector<ParamCoat>> coat_levels;
  std::vector<std::vector<SheenLayer>> sheen_levels;
  std::vector<std::vector<AnisotropyLayer>> anisotropy_levels;
  std::vector<std::vector<float>> transmission_levels;
  std::vector<std::vector<DiffuseTransmissionLayer>> diffuse_transmission_levels;
  std::vector<BrdfLevel> coarse, coarse_coat;
  for (int level = 0; level < levels; ++level) {
    const std::string at_level = "level " + std::to_string(level);
    if (!in->seek_subimage(level, 0))
      throw input_error(where(path), at_level + " is missing (a " + std::to_string(level0.width) + "x" +
                                         std::to_string(level0.height) + " level 0 needs " + std::to_string(levels) + ")");
    const OIIO::ImageSpec s = in->spec();
    const Extent e = level_extent(level0, level);
    if (s.width != e.width || s.height != e.height)
      throw input_error(where(path), at_level + " is " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                                         ", expected " + std::to_string(e.width) + "x" + std::to_string(e.height));
    if (s.get_int_attribute("svbrdf:mip_version", 0) != version || s.get_int_attribute("svbrdf:level", -1) != level)
      throw input_error(where(path), "subimage " + std::to_string(level) + " is not level " + std::to_string(level) + " of this file");
    const int slots = level == 0 ? 0 : s.get_int_attribute("svbrdf:slots", -1);
    if (level > 0 && (slots < 1 || slots > kMaxLobes))
      throw input_error(where(path), at_level + " has " + std::to_string(slots) + " lobe slots");
    // Channels by name: OpenEXR stores them sorted, whatever order they were written in. Read natively
    // (each channel in its own format): a normal's 32-bit code does not survive a float.
    NativeLayout layout;
    std::map<std::string, int> index;
    for (int c = 0; c < s.nchannels; ++c) {
      index[s.channelnames[static_cast<std::size_t>(c)]] = c;
      layout.add(s.channelformat(c));
    }
    std::vector<std::size_t> order;  // byte offsets of the channels read, in the order unpacked
    std::vector<OIIO::TypeDesc> formats;
    auto need = [&](const std::string& name) {
      const auto it = index.find(name);
      if (it == index.end()) throw input_error(where(path), at_level + " has no channel " + name);
      const OIIO::TypeDesc f = layout.formats[static_cast<std::size_t>(it->second)];
      if (f != OIIO::TypeDesc::FLOAT && f != OIIO::TypeDesc::HALF && f != OIIO::TypeDesc::UINT)
        throw input_error(where(path), at_level + " channel " + name + " is " + std::string(f.c_str()) +
                                           ", not a float, half or uint channel");
      order.push_back(layout.offsets[static_cast<std::size_t>(it->second)]);
      formats.push_back(f);
    };
    for (const char* c : kParamChannels) need(c);
    // A layer's means (the specular layer's, the coat's, the sheen's, the anisotropy's, the
    // transmission's, the diffuse transmission's): in every level or in none, as level 0 has them or
    // not; its lobes' channels are per level (below).
    const auto means = [&](std::span<const char* const> channels, bool in_level0) {
      const bool here = index.count(channels[0]) > 0;
      if (level > 0 && here != in_level0)
        throw input_error(where(path), at_level + (here ? " has" : " has no") + " channel " + channels[0] +
                                           (here ? " but level 0 has none" : " but level 0 has"));
      if (here)
        for (const char* c : channels) need(c);
      return here;
    };
    const bool param_specular = means(kParamSpecularChannels, !specular_levels.empty());
    const bool coat = means(kParamCoatChannels, !coat_levels.empty());
    const bool sheen = means(kParamSheenChannels, !sheen_levels.empty());
    const bool anisotropy = means(kParamAnisotropyChannels, !anisotropy_levels.empty());
    const bool transmission = means(kParamTransmissionChannels, !transmission_levels.empty());
    const bool diffuse_transmission =
        means(kParamDiffuseTransmissionChannels, !diffuse_transmission_levels.empty());
    const int coat_slots = level > 0 && coat ? s.get_int_attribute(kCoatSlots, -1) : 0;
    if (coat_slots < 0 || coat_slots > kMaxLobes)
      throw input_error(where(path), at_level + " has " + std::to_string(coat_slots) + " coat lobe slots (" + kCoatSlots + ")");
    const std::size_t first_lobe = order.size();
    // The tint layer's: only in a tintable file (a lobe of any other has no f0_tint).
    const bool tint_channels = slots > 0 && index.count("lobe0.F0tint.R") > 0;
    if (tint_channels && s.get_int_attribute(kTint, 0) != 1)
      throw input_error(where(path), at_level + " has channel lobe0.F0tint.R but the file is not " + kTint + " 1");
    const auto lobe_layer = [&](const char* channel) { return slots > 0 && index.count(channel) > 0; };
    const std::vector<LobeChannel> lobe_ch = lobe_channels(
        {.specular = lobe_layer("lobe0.F90"), .tint = tint_channels, .coat = coat, .sheen = sheen,
         .stretch = lobe_layer("lobe0.stretch"), .transmission = lobe_layer("lobe0.transmission.R"),
         .transmission90 = lobe_layer("lobe0.transmission90.R"),
         .transmission_stretch = lobe_layer("lobe0.transmission.stretch"),
         .diffuse_transmission = lobe_layer("lobe0.diffuseTransmission.R"),
         .diffuse_transmission90 = lobe_layer("lobe0.diffuseTransmission90.R")});
    const std::vector<LobeChannel> coat_ch = coat_lobe_channels();
    const auto need_lobes = [&](const char* prefix, int n, const std::vector<LobeChannel>& channels) {
      for (int k = 0; k < n; ++k)
        for (const LobeChannel& c : channels) {
          const std::string name = prefix + std::to_string(k) + "." + c.suffix;
          need(name);
          if (c.role == Role::normal_direction && formats.back() != OIIO::TypeDesc::UINT)
            throw input_error(where(path), at_level + " channel " + name + " is " + std::string(formats.back().c_str()) +
                                               ", not the 32-bit unsigned integer of an octahedral code");
        }
    };
    need_lobes("lobe", slots, lobe_ch);
    const bool radial = level > 0 && index.count(radial_channel(0)) > 0;
    if (radial) {
      if (!(radial_inner > 0.0f))
        throw input_error(where(path), at_level + " has radial corrections but the file has no " + kRadialInner);
      for (int r = 0; r < RadialGrid::kNodes; ++r) need(radial_channel(r));
    }
    const std::size_t first_coat_lobe = order.size();
    need_lobes("coat", coat_slots, coat_ch);
    const std::size_t texels = static_cast<std::size_t>(e.width) * e.height;
    LevelCheck check(path, s, layout, !cache_key.empty());
    const int rows = band_rows(e.width, layout.stride);
    const std::size_t row_bytes = std::size_t(e.width) * layout.stride;
    // Two bands: OpenEXR inflates the next (on its own threads) while this thread unpacks one.
    std::array<std::vector<std::byte>, 2> bands;
    for (std::vector<std::byte>& b : bands) b.resize(std::size_t(std::min(rows, e.height)) * row_bytes);
    const auto read_band = [&](int first_row, std::vector<std::byte>& into) {
      if (!in->read_scanlines(level, 0, first_row, std::min(e.height, first_row + rows), 0, 0, s.nchannels,
                              OIIO::TypeUnknown, into.data()))
        throw input_error(where(path), "cannot read " + at_level + ": " + in->geterror());
    };
    std::vector<ParamTexel> params(texels);
    BrdfLevel bl, cl;  // the base lobes, the coat lobes
    if (level > 0) {
      bl.reset(e, texels);
      bl.slots = slots;
      // Room for every slot: address space only until written, and no copy as the lobes grow.
      bl.lobes.reserve(texels * std::size_t(slots));
      if (radial) bl.correction.resize(texels);
      cl.reset(e, texels);
      cl.slots = coat_slots;
      cl.lobes.reserve(texels * std::size_t(coat_slots));
    }
    std::vector<ParamSpecular> specular(param_specular ? texels : 0);
    std::vector<ParamCoat> coat_means(coat ? texels : 0);
    std::vector<SheenLayer> sheen_means(sheen ? texels : 0);
    std::vector<AnisotropyLayer> anisotropy_means(anisotropy ? texels : 0);
    std::vector<float> transmission_means(transmission ? texels : 0);
    std::vector<DiffuseTransmissionLayer> diffuse_transmission_means(diffuse_transmission ? texels : 0);
    // Declared after the bands it writes: leaving early waits for the read in flight before they go.
    std::future<void> ahead = std::async(std::launch::async, read_band, 0, std::ref(bands[0]));
    for (int first_row = 0, band = 0; first_row < e.height; first_row += rows, ++band) {
      ahead.get();
      const int end = std::min(e.height, first_row + rows);
      if (end < e.height) ahead = std::async(std::launch::async, read_band, end, std::ref(bands[(band + 1) % 2]));
      const std::vector<std::byte>& buf = bands[band % 2];
      check.add(std::span(buf).first(std::size_t(end - first_row) * row_bytes));
      for (std::size_t t = std::size_t(first_row) * e.width; t < std::size_t(end) * e.width; ++t) {
        const std::byte* px = buf.data() + (t - std::size_t(first_row) * e.width) * layout.stride;
        const auto value = [&](std::size_t c) {
          float v = 0.0f;
          get_float(px + order[c], formats[c], v);
          return v;
        };
        ParamTexel& p = params[t];
        p.base_color = {value(0), value(1), value(2)};
        p.metallic = value(3);
        p.roughness = value(4);
        p.normal = {value(5), value(6), value(7)};
        std::size_t next = 8;
        if (param_specular) specular[t] = {value(8), {value(9), value(10), value(11)}}, next = 12;
        if (coat) coat_means[t] = {value(next), value(next + 1), {value(next + 2), value(next + 3), value(next + 4)}}, next += 5;
        if (sheen) sheen_means[t] = {{value(next), value(next + 1), value(next + 2)}, value(next + 3)}, next += 4;
        if (anisotropy) anisotropy_means[t] = {value(next), {value(next + 1), value(next + 2)}}, next += 3;
        if (transmission) transmission_means[t] = value(next), next += 1;
        if (diffuse_transmission)
          diffuse_transmission_means[t] = {value(next), {value(next + 1), value(next + 2), value(next + 3)}};
        if (level == 0) continue;
        // Texel t's lobes into `into`, from `n` slots of `channels` from `first` on.
        const auto read_lobes = [&](BrdfLevel& into, std::size_t first, int n, const std::vector<LobeChannel>& channels,
                                    bool coat_lobes) {
          into.first[t] = static_cast<std::uint32_t>(into.lobes.size());
          // Lobes are packed from slot 0: the first empty slot (weight 0) ends the texel's.
          for (int k = 0; k < n; ++k) {
            LobeValues v;
            v[Role::f90] = 1.0f;  // the plain layer's, where the level has no specular channels
            for (std::size_t c = 0; c < channels.size(); ++c) {
              const std::size_t ch = first + static_cast<std::size_t>(k) * channels.size() + c;
              const Role role = channels[c].role;
              if (role == Role::normal_direction) std::memcpy(&v.direction, px + order[ch], 4);
              else v[role] = value(ch);
            }
            Lobe l = unpack_lobe(v);
            if (!(l.weight > 0)) break;
            if (coat_lobes) set_coat_colours(l);
            into.lobes.push_back(l);
            into.counts[t] = static_cast<std::uint8_t>(k + 1);
          }
          // A texel's lone lobe goes to its own slot (brdf_pyramid.h).
          if (into.counts[t] == 1) into.single[t] = into.lobes.back(), into.lobes.pop_back();
        };
        read_lobes(bl, first_lobe, slots, lobe_ch, false);
        read_lobes(cl, first_coat_lobe, coat_slots, coat_ch, true);
        if (radial)
          for (int r = 0; r < RadialGrid::kNodes; ++r)
            bl.correction[t].ratio[static_cast<std::size_t>(r)] = value(first_lobe + static_cast<std::size_t>(slots) * lobe_ch.size() + r);
      }
    }
    // Said after the whole file is read: a more telling refusal of a later level (a missing grid)
    // comes first.
    if (!corrupt) corrupt = check.mismatch(max_lobes, radial_inner, radial_outer);
    if (level > 0) {
      coarse.push_back(std::move(bl));
      if (coat) coarse_coat.push_back(std::move(cl));
    }
    param_levels.push_back(std::move(params));
    if (param_specular) specular_levels.push_back(std::move(specular));
    if (coat) coat_levels.push_back(std::move(coat_means));
    if (sheen) sheen_levels.push_back(std::move(sheen_means));
    if (anisotropy) anisotropy_levels.push_back(std::move(anisotropy_means));
    if (transmission) transmission_levels.push_back(std::move(transmission_means));
    if (diffuse_transmission) diffuse_transmission_levels.push_back(std::move(diffuse_transmission_means));
  }
  if (in->seek_subimage(levels, 0))
    throw input_error(where(path), "has more subimages than the " + std::to_string(levels) + " levels of its level 0");
  if (corrupt) throw *corrupt;
  // The BRDF pyramid reads the sheen means the parameter pyramid stores (brdf_pyramid.h).
  std::vector<std::vector<SheenLayer>> brdf_sheen = sheen_levels;
  mip.param = ParamPyramid::from_levels(level0, std::move(param_levels), std::move(specular_levels), ior,
                                        std::move(coat_levels), std::move(sheen_levels), std::move(anisotropy_levels),
                                        std::move(transmission_levels), std::move(diffuse_transmission_levels));
  // Level 0's texels are the parameter pyramid's (the same floats).
  mip.level0 = mip.param.level0_texels();
  mip.brdf = BrdfPyramid::from_levels(mip.level0, max_lobes, std::move(coarse),
                                      radial_inner > 0.0f ? RadialGrid::with_inner(radial_inner, radial_outer) : RadialGrid{},
                                      tint == 1, std::move(coarse_coat), std::move(brdf_sheen));
  return mip;
}

}  // namespace svbrdf
