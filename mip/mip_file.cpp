#include "mip/mip_file.h"

#include <Imath/half.h>
#include <OpenImageIO/hash.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <map>
#include <numeric>
#include <optional>
#include <memory>
#include <string>
#include <vector>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/resource_limits.h"
#include "mip/mip_file_channels.h"
#include "mip/stored_lobe.h"
#include "mip/stored_normal.h"
#include "textures/exr_header.h"

namespace svbrdf {

namespace {

namespace fs = std::filesystem;

using namespace mip_file_channels;

constexpr const char* kRadialInner = "svbrdf:radial_inner";
constexpr const char* kRadialOuter = "svbrdf:radial_outer";
constexpr const char* kChecksum = "svbrdf:checksum";
constexpr const char* kCacheKey = "svbrdf:cache_key";
std::string radial_channel(int node) { return "radial.R" + std::to_string(node); }
std::string where(const fs::path& p) { return p.string(); }

// A pixel's channels as the file stores them (OpenEXR's per-channel formats): byte offsets into a
// native pixel, and typed access.
struct NativeLayout {
  std::vector<OIIO::TypeDesc> formats;
  std::vector<std::size_t> offsets;
  std::size_t stride = 0;
  void add(OIIO::TypeDesc f) {
    formats.push_back(f);
    offsets.push_back(stride);
    stride += f.size();
  }
};

void put_float(std::byte* px, const NativeLayout& layout, std::size_t c, float v) {
  std::byte* at = px + layout.offsets[c];
  if (layout.formats[c] == OIIO::TypeDesc::HALF) {
    const std::uint16_t bits = Imath::half(v).bits();  // exact: every half channel holds half values
    std::memcpy(at, &bits, 2);
  } else {
    std::memcpy(at, &v, 4);
  }
}
void put_uint(std::byte* px, const NativeLayout& layout, std::size_t c, std::uint32_t v) {
  std::memcpy(px + layout.offsets[c], &v, 4);
}

// A channel's value as a float, whatever its stored format; false for a format no MIP file has.
bool get_float(const std::byte* at, OIIO::TypeDesc f, float& v) {
  if (f == OIIO::TypeDesc::FLOAT) {
    std::memcpy(&v, at, 4);
  } else if (f == OIIO::TypeDesc::HALF) {
    Imath::half h;
    std::uint16_t bits;
    std::memcpy(&bits, at, 2);
    h.setBits(bits);
    v = h;
  } else if (f == OIIO::TypeDesc::UINT) {
    std::uint32_t u;
    std::memcpy(&u, at, 4);
    v = static_cast<float>(u);
  } else {
    return false;
  }
  return true;
}

// The layout of a pixel whose channels (`formats`, by channel index) lie in the order of their names:
// OpenEXR stores them so and reads them back so, whatever order they were written in, which makes it
// the one order in which a writer and a reader see the same bytes.
NativeLayout name_ordered(const std::vector<std::string>& names, const std::vector<OIIO::TypeDesc>& formats) {
  std::vector<std::size_t> by_name(names.size());
  std::iota(by_name.begin(), by_name.end(), std::size_t(0));
  std::sort(by_name.begin(), by_name.end(), [&](std::size_t a, std::size_t b) { return names[a] < names[b]; });
  NativeLayout l;
  l.formats = formats;
  l.offsets.assign(names.size(), 0);
  for (const std::size_t c : by_name) {
    l.offsets[c] = l.stride;
    l.stride += formats[c].size();
  }
  return l;
}

// A level's pixels are checked in bands of whole rows, about this many bytes each, as they are read:
// the reader keeps one band, not a second copy of the level.
constexpr std::size_t kBandBytes = std::size_t(1) << 22;
int band_rows(int width, std::size_t stride) {
  return static_cast<int>(std::max<std::size_t>(1, kBandBytes / (std::size_t(std::max(width, 1)) * std::max<std::size_t>(stride, 1))));
}

// The fingerprint of one band of pixels in name order. Fingerprint128 is fixed and portable (unlike
// OpenImageIO's Hash128), so a file checks on any machine; it guards against corruption, not against
// an adversary (the cache key is the SHA-256 one).
void add_band(std::vector<std::uint64_t>& bands, std::span<const std::byte> name_ordered_pixels) {
  const auto f = OIIO::farmhash::Fingerprint128(reinterpret_cast<const char*>(name_ordered_pixels.data()),
                                                name_ordered_pixels.size());
  bands.push_back(OIIO::farmhash::Uint128Low64(f));
  bands.push_back(OIIO::farmhash::Uint128High64(f));
}

// A level's checksum (mip_file.h, svbrdf:checksum): the header values that give its pixels their
// meaning, then its bands' fingerprints.
std::string level_checksum(const OIIO::ImageSpec& s, int max_lobes, float radial_inner, float radial_outer,
                           const std::vector<std::uint64_t>& bands) {
  std::string header = "level " + std::to_string(s.get_int_attribute("svbrdf:level", -1)) + " " +
                       std::to_string(s.width) + "x" + std::to_string(s.height) + " version " +
                       std::to_string(s.get_int_attribute("svbrdf:mip_version", 0)) + " slots " +
                       std::to_string(s.get_int_attribute("svbrdf:slots", -1)) + " max_lobes " +
                       std::to_string(max_lobes);
  std::uint32_t bits[2];
  std::memcpy(&bits[0], &radial_inner, 4);
  std::memcpy(&bits[1], &radial_outer, 4);
  header += " radial " + std::to_string(bits[0]) + " " + std::to_string(bits[1]);
  const float ior = s.get_float_attribute(kIor, 1.5f);
  std::memcpy(&bits[0], &ior, 4);
  header += " ior " + std::to_string(bits[0]);
  header += " tint " + std::to_string(s.get_int_attribute(kTint, 0));
  // Channels in name order, as the pixels: OpenImageIO lists a file's channels in an order of its own.
  std::vector<std::string> channels;
  for (int c = 0; c < s.nchannels; ++c)
    channels.push_back(s.channelnames[static_cast<std::size_t>(c)] + ":" + std::string(s.channelformat(c).c_str()));
  std::sort(channels.begin(), channels.end());
  for (const std::string& c : channels) header += " " + c;
  for (const std::uint64_t b : bands) header += " " + std::to_string(b);
  const auto all = OIIO::farmhash::Fingerprint128(header.data(), header.size());
  char hex[33];
  std::snprintf(hex, sizeof hex, "%016llx%016llx", static_cast<unsigned long long>(OIIO::farmhash::Uint128High64(all)),
                static_cast<unsigned long long>(OIIO::farmhash::Uint128Low64(all)));
  return hex;
}

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

// Level `level`'s pixels in `layout` (the spec's channels, by index, at the layout's offsets).
std::vector<std::byte> pack_level(const ParamPyramid& param, const BrdfPyramid& brdf, int level, const NativeLayout& layout,
                                  const std::vector<LobeChannel>& lobe_ch) {
  const std::size_t lobe_nch = lobe_ch.size();
  const bool param_specular = !param.specular_level(0).empty();
  const std::size_t first_lobe = param_specular ? 12 : 8;  // the first lobe channel
  const Extent e = param.extent(level);
  const std::size_t texels = static_cast<std::size_t>(e.width) * e.height;
  std::vector<std::byte> buf(texels * layout.stride);
  const auto params = param.level(level);
  const auto specular = param.specular_level(level);
  for (std::size_t t = 0; t < texels; ++t) {
    std::byte* px = buf.data() + t * layout.stride;
    const ParamTexel& p = params[t];
    const float values[8] = {p.base_color.r, p.base_color.g, p.base_color.b, p.metallic,
                             p.roughness,    p.normal.x,     p.normal.y,     p.normal.z};
    for (std::size_t c = 0; c < 8; ++c) put_float(px, layout, c, values[c]);
    if (param_specular) {
      const ParamSpecular& sp = specular[t];
      const float spec[4] = {sp.specular, sp.color.r, sp.color.g, sp.color.b};
      for (std::size_t c = 0; c < 4; ++c) put_float(px, layout, 8 + c, spec[c]);
    }
    if (level == 0) continue;
    // Empty slots: weight 0 (and a plain GGX of α² 1 about the geometric normal, so every channel
    // holds a meaningful value).
    static const Lobe kEmpty = [] {
      Lobe l;
      l.weight = 0.0f, l.diffuse = glm::vec3(0), l.f0 = glm::vec3(0), l.alpha2 = 1.0f;
      return l;
    }();
    const BrdfLevel& bl = brdf.level(level);
    const std::span<const Lobe> lobes = bl.texel_lobes(t);
    for (int k = 0; k < bl.slots; ++k) {
      const LobeValues v = pack_lobe(k < static_cast<int>(lobes.size()) ? lobes[static_cast<std::size_t>(k)] : kEmpty);
      for (std::size_t c = 0; c < lobe_nch; ++c) {
        const std::size_t ch = first_lobe + static_cast<std::size_t>(k) * lobe_nch + c;
        const LobeChannel& lc = lobe_ch[c];
        if (lc.role == Role::normal_direction) put_uint(px, layout, ch, v.direction);
        else put_float(px, layout, ch, v[lc.role]);
      }
    }
    if (!bl.correction.empty())
      for (int r = 0; r < RadialGrid::kNodes; ++r)
        put_float(px, layout, first_lobe + static_cast<std::size_t>(bl.slots) * lobe_nch + static_cast<std::size_t>(r),
                  bl.correction[t].ratio[static_cast<std::size_t>(r)]);
  }
  return buf;
}

// Checks a level's pixels against its svbrdf:checksum band by band as they are read (`native`: the
// layout OpenImageIO reads them in): add() each band, then mismatch(), the error when they differ.
// The constructor throws when the checksum is absent and `required`.
class LevelCheck {
 public:
  LevelCheck(const fs::path& path, const OIIO::ImageSpec& s, const NativeLayout& native, bool required)
      : path_(path), spec_(s), native_(native), stored_(s.get_string_attribute(kChecksum, "")) {
    if (stored_.empty() && required)
      throw input_error(where(path), "level " + std::to_string(s.get_int_attribute("svbrdf:level", -1)) + " has no " + kChecksum);
    std::vector<OIIO::TypeDesc> formats;
    for (int c = 0; c < s.nchannels; ++c) formats.push_back(s.channelformat(c));
    ordered_ = name_ordered(s.channelnames, formats);
    for (const OIIO::TypeDesc& f : formats) sizes_.push_back(f.size());
  }
  void add(std::span<const std::byte> band) {
    if (stored_.empty()) return;
    if (ordered_.offsets == native_.offsets) return add_band(bands_, band);
    // Not in name order: the band put in it first.
    scratch_.resize(band.size());
    const std::size_t texels = band.size() / native_.stride;
    for (std::size_t c = 0; c < sizes_.size(); ++c)
      for (std::size_t t = 0; t < texels; ++t)
        std::memcpy(&scratch_[t * ordered_.stride + ordered_.offsets[c]], &band[t * native_.stride + native_.offsets[c]], sizes_[c]);
    add_band(bands_, scratch_);
  }
  std::optional<Error> mismatch(int max_lobes, float radial_inner, float radial_outer) const {
    if (stored_.empty()) return std::nullopt;
    const std::string actual = level_checksum(spec_, max_lobes, radial_inner, radial_outer, bands_);
    if (actual == stored_) return std::nullopt;
    return input_error(where(path_), "level " + std::to_string(spec_.get_int_attribute("svbrdf:level", -1)) +
                                         " does not match its " + kChecksum + " (" + stored_ + ", the texels give " + actual +
                                         "): a corrupt file");
  }

 private:
  const fs::path& path_;
  const OIIO::ImageSpec& spec_;
  const NativeLayout& native_;
  std::string stored_;
  NativeLayout ordered_;
  std::vector<std::size_t> sizes_;
  std::vector<std::byte> scratch_;
  std::vector<std::uint64_t> bands_;
};

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
  const bool param_specular = !param.specular_level(0).empty();
  std::vector<std::vector<LobeChannel>> channels(static_cast<std::size_t>(levels));
  for (int level = 1; level < levels; ++level)
    channels[static_cast<std::size_t>(level)] =
        lobe_channels(brdf.level(level).specular_layer(), brdf.tintable() && brdf.level(level).tint_layer());
  std::vector<OIIO::ImageSpec> specs(static_cast<std::size_t>(levels));
  std::vector<NativeLayout> layouts(static_cast<std::size_t>(levels));
  for (int level = 0; level < levels; ++level) {
    const Extent e = param.extent(level);
    const int slots = level == 0 ? 0 : brdf.level(level).slots;
    const bool radial = level > 0 && !brdf.level(level).correction.empty();
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
    if (param_specular)
      for (const char* c : kParamSpecularChannels) add(c, OIIO::TypeDesc::FLOAT);
    for (int k = 0; k < slots; ++k)
      for (const LobeChannel& c : channels[static_cast<std::size_t>(level)])
        add("lobe" + std::to_string(k) + "." + c.suffix, c.format);
    if (radial)
      for (int r = 0; r < RadialGrid::kNodes; ++r) add(radial_channel(r), OIIO::TypeDesc::HALF);
    s.nchannels = static_cast<int>(s.channelnames.size());
    s.attribute("name", "level" + std::to_string(level));
    s.attribute("compression", "zip");
    s.attribute("svbrdf:mip_version", kMipFileVersion);
    s.attribute("svbrdf:level", level);
    s.attribute("svbrdf:max_lobes", brdf.max_lobes());
    s.attribute("svbrdf:slots", slots);
    if (param.ior() != 1.5f) s.attribute(kIor, param.ior());
    if (brdf.tintable()) s.attribute(kTint, 1);
    if (corrected) {
      s.attribute(kRadialInner, radial_inner);
      s.attribute(kRadialOuter, radial_outer);
    }
    if (level == 0 && !cache_key.empty()) s.attribute(kCacheKey, cache_key);
    // Every header is written when the file opens, so the checksums come first: the level packed once
    // in name order for them, and again as written below.
    const NativeLayout ordered_layout = name_ordered(s.channelnames, s.channelformats);
    const std::vector<std::byte> ordered = pack_level(param, brdf, level, ordered_layout, channels[static_cast<std::size_t>(level)]);
    const std::size_t band_bytes = std::size_t(band_rows(e.width, ordered_layout.stride)) * e.width * ordered_layout.stride;
    std::vector<std::uint64_t> bands;
    for (std::size_t at = 0; at < ordered.size(); at += band_bytes)
      add_band(bands, std::span(ordered).subspan(at, std::min(band_bytes, ordered.size() - at)));
    s.attribute(kChecksum, level_checksum(s, brdf.max_lobes(), radial_inner, radial_outer, bands));
  }
  // OpenImageIO 2.4's multi-part OpenEXR writer ignores an "oiio:ioproxy" (it writes a file of the
  // given name in the working folder), so the file is written to a temporary by OpenEXR, which throws
  // on a failed write, and renamed after an fsync; a failure there is the machine's (exit 1).
  write_atomically(path, [&](const fs::path& tmp) {
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(tmp.string());
    if (!out) throw environment_error(where(path), "cannot write OpenEXR: " + OIIO::geterror());
    if (!out->open(tmp.string(), levels, specs.data()))
      throw environment_error(where(path), "cannot write: " + out->geterror());
    for (int level = 0; level < levels; ++level) {
      const OIIO::ImageSpec& s = specs[static_cast<std::size_t>(level)];
      if (level > 0 && !out->open(tmp.string(), s, OIIO::ImageOutput::AppendSubimage))
        throw environment_error(where(path), "cannot write level " + std::to_string(level) + ": " + out->geterror());
      const std::vector<std::byte> buf =
          pack_level(param, brdf, level, layouts[static_cast<std::size_t>(level)], channels[static_cast<std::size_t>(level)]);
      if (!out->write_image(OIIO::TypeUnknown, buf.data()))
        throw environment_error(where(path), "cannot write level " + std::to_string(level) + ": " + out->geterror());
    }
    if (!out->close()) throw environment_error(where(path), "cannot finish writing: " + out->geterror());
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
  std::vector<BrdfLevel> coarse;
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
    // The specular layer's channels: in every level or in none (param), per level (lobes).
    const bool param_specular = index.count(kParamSpecularChannels[0]) > 0;
    if (level > 0 && param_specular != !specular_levels.empty())
      throw input_error(where(path), at_level + (param_specular ? " has" : " has no") + " channel " +
                                         kParamSpecularChannels[0] + (param_specular ? " but level 0 has none" : " but level 0 has"));
    if (param_specular)
      for (const char* c : kParamSpecularChannels) need(c);
    const std::size_t first_lobe = order.size();
    // The tint layer's: only in a tintable file (a lobe of any other has no f0_tint).
    const bool tint_channels = slots > 0 && index.count("lobe0.F0tint.R") > 0;
    if (tint_channels && s.get_int_attribute(kTint, 0) != 1)
      throw input_error(where(path), at_level + " has channel lobe0.F0tint.R but the file is not " + kTint + " 1");
    const std::vector<LobeChannel> lobe_ch = lobe_channels(slots > 0 && index.count("lobe0.F90") > 0, tint_channels);
    for (int k = 0; k < slots; ++k)
      for (const LobeChannel& c : lobe_ch) {
        const std::string name = "lobe" + std::to_string(k) + "." + c.suffix;
        need(name);
        if (c.role == Role::normal_direction && formats.back() != OIIO::TypeDesc::UINT)
          throw input_error(where(path), at_level + " channel " + name + " is " + std::string(formats.back().c_str()) +
                                             ", not the 32-bit unsigned integer of an octahedral code");
      }
    const bool radial = level > 0 && index.count(radial_channel(0)) > 0;
    if (radial) {
      if (!(radial_inner > 0.0f))
        throw input_error(where(path), at_level + " has radial corrections but the file has no " + kRadialInner);
      for (int r = 0; r < RadialGrid::kNodes; ++r) need(radial_channel(r));
    }
    const std::size_t texels = static_cast<std::size_t>(e.width) * e.height;
    LevelCheck check(path, s, layout, !cache_key.empty());
    const int rows = band_rows(e.width, layout.stride);
    std::vector<std::byte> buf(std::size_t(std::min(rows, e.height)) * e.width * layout.stride);
    std::vector<ParamTexel> params(texels);
    BrdfLevel bl;
    if (level > 0) {
      bl.reset(e, texels);
      bl.slots = slots;
      // Room for every slot: address space only until written, and no copy as the lobes grow.
      bl.lobes.reserve(texels * std::size_t(slots));
      if (radial) bl.correction.resize(texels);
    }
    const std::size_t lobe_nch = lobe_ch.size();
    std::vector<ParamSpecular> specular(param_specular ? texels : 0);
    for (std::size_t t = 0; t < texels; ++t) {
      const std::size_t row = t / std::size_t(e.width);
      if (t % (std::size_t(rows) * e.width) == 0) {  // the next band
        const int end = std::min(e.height, int(row) + rows);
        if (!in->read_scanlines(level, 0, int(row), end, 0, 0, s.nchannels, OIIO::TypeUnknown, buf.data()))
          throw input_error(where(path), "cannot read " + at_level + ": " + in->geterror());
        check.add(std::span(buf).first(std::size_t(end - int(row)) * e.width * layout.stride));
      }
      const std::byte* px = buf.data() + (t - (row - row % std::size_t(rows)) * e.width) * layout.stride;
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
      if (param_specular) specular[t] = {value(8), {value(9), value(10), value(11)}};
      if (level == 0) continue;
      bl.first[t] = static_cast<std::uint32_t>(bl.lobes.size());
      // Lobes are packed from slot 0: the first empty slot (weight 0) ends the texel's.
      for (int k = 0; k < slots; ++k) {
        LobeValues v;
        v[Role::f90] = 1.0f;  // the plain layer's, where the level has no specular channels
        for (std::size_t c = 0; c < lobe_nch; ++c) {
          const std::size_t ch = first_lobe + static_cast<std::size_t>(k) * lobe_nch + c;
          const Role role = lobe_ch[c].role;
          if (role == Role::normal_direction) std::memcpy(&v.direction, px + order[ch], 4);
          else v[role] = value(ch);
        }
        const Lobe l = unpack_lobe(v);
        if (!(l.weight > 0)) break;
        bl.lobes.push_back(l);
        bl.counts[t] = static_cast<std::uint8_t>(k + 1);
      }
      // A texel's lone lobe goes to its own slot (brdf_pyramid.h).
      if (bl.counts[t] == 1) bl.single[t] = bl.lobes.back(), bl.lobes.pop_back();
      if (radial)
        for (int r = 0; r < RadialGrid::kNodes; ++r)
          bl.correction[t].ratio[static_cast<std::size_t>(r)] = value(first_lobe + static_cast<std::size_t>(slots) * lobe_nch + r);
    }
    // Said after the whole file is read: a more telling refusal of a later level (a missing grid)
    // comes first.
    if (!corrupt) corrupt = check.mismatch(max_lobes, radial_inner, radial_outer);
    if (level == 0) {
      MaterialTexels& m = mip.level0;
      m = MaterialTexels(e.width, e.height);
      for (std::size_t t = 0; t < texels; ++t) {
        m.base_color[t] = params[t].base_color;
        m.metallic[t] = params[t].metallic;
        m.roughness[t] = params[t].roughness;
        m.normal[t] = params[t].normal;
      }
      m.ior = ior;
      if (param_specular) {
        m.specular.resize(texels);
        m.specular_color.resize(texels);
        for (std::size_t t = 0; t < texels; ++t) m.specular[t] = specular[t].specular, m.specular_color[t] = specular[t].color;
      }
    } else {
      coarse.push_back(std::move(bl));
    }
    param_levels.push_back(std::move(params));
    if (param_specular) specular_levels.push_back(std::move(specular));
  }
  if (in->seek_subimage(levels, 0))
    throw input_error(where(path), "has more subimages than the " + std::to_string(levels) + " levels of its level 0");
  if (corrupt) throw *corrupt;
  mip.param = ParamPyramid::from_levels(level0, std::move(param_levels), std::move(specular_levels), ior);
  mip.brdf = BrdfPyramid::from_levels(mip.level0, max_lobes, std::move(coarse),
                                      radial_inner > 0.0f ? RadialGrid::with_inner(radial_inner, radial_outer) : RadialGrid{},
                                      tint == 1);
  return mip;
}

}  // namespace svbrdf
