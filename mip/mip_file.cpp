#include "mip/mip_file.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "base/atomic_file.h"
#include "base/error.h"

namespace svbrdf {

namespace {

namespace fs = std::filesystem;

const char* const kParamChannels[8] = {"param.R",         "param.G",   "param.B",   "param.metallic",
                                       "param.roughness", "param.N.X", "param.N.Y", "param.N.Z"};
// Version 4: 32 bytes a lobe (kBytesPerLobe): α (not α²) as a half, which frees the two bytes of the
// skirt. Version 3 had α² as a float and no skirt (c = 1).
constexpr int kLobeChannels = 13;
const char* const kLobeSuffix[kLobeChannels] = {"weight", "diffuse.R", "diffuse.G", "diffuse.B", "F0.R",  "F0.G", "F0.B",
                                                "N.X",    "N.Y",       "N.Z",       "alpha",     "shape", "skirt"};
bool lobe_channel_is_half(int c) { return c <= 6 || c >= 10; }
// Versions 1 and 2 have the first 10 and then α² as a float (weight as a float too); version 2 then the
// shape as two channels, version 1 nothing (plain GGX lobes).
constexpr int kCommonLobeChannels = 10;
const char* const kShapeSuffixV2[2] = {"alpha2_hi", "ggx"};
// Version 4: all; version 3: all but the skirt; version 2: the common ones, α² and the two shape
// channels; version 1: the common ones and α².
int lobe_channels(int version) {
  return version >= 4 ? kLobeChannels : version == 3 ? kLobeChannels - 1 : kCommonLobeChannels + (version == 2 ? 3 : 1);
}
std::string lobe_suffix(int version, int c) {
  if (c < kCommonLobeChannels) return kLobeSuffix[c];
  if (c == kCommonLobeChannels) return version >= 4 ? "alpha" : "alpha2";
  return version >= 3 ? kLobeSuffix[c] : kShapeSuffixV2[c - kCommonLobeChannels - 1];
}

std::string where(const fs::path& p) { return p.string(); }

void pack_param(const ParamTexel& t, float* out) {
  out[0] = t.base_color.r, out[1] = t.base_color.g, out[2] = t.base_color.b;
  out[3] = t.metallic, out[4] = t.roughness;
  out[5] = t.normal.x, out[6] = t.normal.y, out[7] = t.normal.z;
}
ParamTexel unpack_param(const float* in) {
  ParamTexel t;
  t.base_color = {in[0], in[1], in[2]};
  t.metallic = in[3];
  t.roughness = in[4];
  t.normal = {in[5], in[6], in[7]};
  return t;
}
void pack_lobe(const Lobe& l, float* out) {
  out[0] = l.weight;
  out[1] = l.diffuse.r, out[2] = l.diffuse.g, out[3] = l.diffuse.b;
  out[4] = l.f0.r, out[5] = l.f0.g, out[6] = l.f0.b;
  out[7] = l.normal.x, out[8] = l.normal.y, out[9] = l.normal.z;
  out[10] = std::sqrt(l.alpha2);  // exact: a stored α² is the square of a half (round_to_stored)
  out[11] = lobe_shape_code(l);
  out[12] = lobe_skirt_code(l);
}
Lobe unpack_lobe(int version, const float* in) {
  Lobe l;
  l.weight = in[0];
  l.diffuse = {in[1], in[2], in[3]};
  l.f0 = {in[4], in[5], in[6]};
  l.normal = {in[7], in[8], in[9]};
  l.alpha2 = version >= 4 ? in[10] * in[10] : in[10];
  if (version >= 3) {
    set_lobe_shape_code(l, in[11]);
    // Version 4 had no atoms: its mixtures are bands of share 1 and its skirt channel holds 1 for them.
    if (version >= 5) set_lobe_skirt_code(l, in[12]);
    else if (version == 4 && l.alpha2_hi == 0.0f) l.skirt = in[12];
  } else if (version == 2) {
    l.alpha2_hi = in[11];
    l.ggx = in[12];
  }
  return l;
}

}  // namespace

void write_mip_file(const fs::path& path, const MipData& mip) {
  const int levels = mip.levels();
  if (levels == 0) throw Error(where(path) + ": nothing to write (an empty material)", Error::Kind::internal);
  write_atomically(path, [&](const fs::path& tmp) {
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(tmp.string());
    if (!out) throw input_error(where(path), "cannot write OpenEXR: " + OIIO::geterror());
    std::vector<OIIO::ImageSpec> specs(static_cast<std::size_t>(levels));
    for (int level = 0; level < levels; ++level) {
      const Extent e = mip.extent(level);
      const int slots = level == 0 ? 0 : mip.brdf.level(level).slots;
      OIIO::ImageSpec& s = specs[static_cast<std::size_t>(level)];
      s = OIIO::ImageSpec(e.width, e.height, 8 + slots * kLobeChannels, OIIO::TypeDesc::FLOAT);
      // OpenEXR parts share their display window: every level's is level 0's.
      s.full_x = 0, s.full_y = 0, s.full_width = mip.extent(0).width, s.full_height = mip.extent(0).height;
      s.channelnames.clear();
      s.channelformats.clear();
      for (const char* c : kParamChannels) s.channelnames.emplace_back(c), s.channelformats.push_back(OIIO::TypeDesc::FLOAT);
      for (int k = 0; k < slots; ++k)
        for (int c = 0; c < kLobeChannels; ++c) {
          s.channelnames.push_back("lobe" + std::to_string(k) + "." + kLobeSuffix[c]);
          s.channelformats.push_back(lobe_channel_is_half(c) ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
        }
      s.attribute("name", "level" + std::to_string(level));
      s.attribute("compression", "zip");
      s.attribute("svbrdf:mip_version", kMipFileVersion);
      s.attribute("svbrdf:level", level);
      s.attribute("svbrdf:max_lobes", mip.brdf.max_lobes());
      s.attribute("svbrdf:slots", slots);
    }
    if (!out->open(tmp.string(), levels, specs.data()))
      throw input_error(where(path), "cannot write: " + out->geterror());
    for (int level = 0; level < levels; ++level) {
      const OIIO::ImageSpec& s = specs[static_cast<std::size_t>(level)];
      if (level > 0 && !out->open(tmp.string(), s, OIIO::ImageOutput::AppendSubimage))
        throw input_error(where(path), "cannot write level " + std::to_string(level) + ": " + out->geterror());
      const Extent e = mip.extent(level);
      const std::size_t texels = static_cast<std::size_t>(e.width) * e.height;
      const int nch = s.nchannels;
      std::vector<float> buf(texels * static_cast<std::size_t>(nch));
      const auto params = mip.param.level(level);
      for (std::size_t t = 0; t < texels; ++t) {
        float* px = buf.data() + t * static_cast<std::size_t>(nch);
        pack_param(params[t], px);
        if (level > 0) {
          // Empty slots: weight 0 (and a plain GGX of α² 1 about the geometric normal, so every
          // channel holds a meaningful value).
          static const Lobe kEmpty{0.0f, glm::vec3(0), glm::vec3(0), glm::vec3(0, 0, 1), 1.0f};
          const BrdfLevel& bl = mip.brdf.level(level);
          const std::span<const Lobe> lobes = bl.texel_lobes(t);
          for (int k = 0; k < bl.slots; ++k)
            pack_lobe(k < static_cast<int>(lobes.size()) ? lobes[static_cast<std::size_t>(k)] : kEmpty, px + 8 + k * kLobeChannels);
        }
      }
      if (!out->write_image(OIIO::TypeDesc::FLOAT, buf.data()))
        throw input_error(where(path), "cannot write level " + std::to_string(level) + ": " + out->geterror());
    }
    if (!out->close()) throw input_error(where(path), "cannot finish writing: " + out->geterror());
  });
}

MipData read_mip_file(const fs::path& path) {
  std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path.string());
  if (!in) {
    std::string why = OIIO::geterror();
    if (!fs::exists(path)) why = "no such file";
    throw input_error(where(path), "cannot read the MIP file: " + why);
  }
  const OIIO::ImageSpec& first = in->spec();
  const int version = first.get_int_attribute("svbrdf:mip_version", 0);
  if (version == 0) throw input_error(where(path), "not an svbrdf MIP file (no svbrdf:mip_version attribute)");
  if (version > kMipFileVersion)
    throw input_error(where(path), "MIP file version " + std::to_string(version) +
                                       " is newer than this program reads (version " + std::to_string(kMipFileVersion) +
                                       "); rebuild it with svbrdf-bake mip or update svbrdf");
  const Extent level0{first.width, first.height};
  if (level0.width <= 0 || level0.height <= 0) throw input_error(where(path), "level 0 has no texels");
  const int levels = level_count(level0);
  const int max_lobes = first.get_int_attribute("svbrdf:max_lobes", 1);
  MipData mip;
  std::vector<std::vector<ParamTexel>> param_levels;
  std::vector<BrdfLevel> coarse;
  for (int level = 0; level < levels; ++level) {
    if (!in->seek_subimage(level, 0))
      throw input_error(where(path), "level " + std::to_string(level) + " is missing (a " + std::to_string(level0.width) +
                                         "x" + std::to_string(level0.height) + " level 0 needs " + std::to_string(levels) + ")");
    const OIIO::ImageSpec s = in->spec();
    const Extent e = level_extent(level0, level);
    if (s.width != e.width || s.height != e.height)
      throw input_error(where(path), "level " + std::to_string(level) + " is " + std::to_string(s.width) + "x" +
                                         std::to_string(s.height) + ", expected " + std::to_string(e.width) + "x" +
                                         std::to_string(e.height));
    if (s.get_int_attribute("svbrdf:mip_version", 0) != version || s.get_int_attribute("svbrdf:level", -1) != level)
      throw input_error(where(path), "subimage " + std::to_string(level) + " is not level " + std::to_string(level) + " of this file");
    const int slots = level == 0 ? 0 : s.get_int_attribute("svbrdf:slots", -1);
    if (level > 0 && (slots < 1 || slots > kMaxLobes))
      throw input_error(where(path), "level " + std::to_string(level) + " has " + std::to_string(slots) + " lobe slots");
    // Channels by name: OpenEXR stores them sorted, whatever order they were written in.
    std::map<std::string, int> index;
    for (int c = 0; c < s.nchannels; ++c) index[s.channelnames[static_cast<std::size_t>(c)]] = c;
    std::vector<int> order;
    auto need = [&](const std::string& name) {
      const auto it = index.find(name);
      if (it == index.end()) throw input_error(where(path), "level " + std::to_string(level) + " has no channel " + name);
      order.push_back(it->second);
    };
    for (const char* c : kParamChannels) need(c);
    const int lobe_nch = lobe_channels(version);
    for (int k = 0; k < slots; ++k)
      for (int c = 0; c < lobe_nch; ++c) need("lobe" + std::to_string(k) + "." + lobe_suffix(version, c));
    const std::size_t texels = static_cast<std::size_t>(e.width) * e.height;
    const int nch = s.nchannels;
    std::vector<float> buf(texels * static_cast<std::size_t>(nch));
    if (!in->read_image(level, 0, 0, nch, OIIO::TypeDesc::FLOAT, buf.data()))
      throw input_error(where(path), "cannot read level " + std::to_string(level) + ": " + in->geterror());
    std::vector<float> px(order.size());
    std::vector<ParamTexel> params(texels);
    BrdfLevel bl;
    if (level > 0) {
      bl.reset(e, texels);
      bl.slots = slots;
    }
    for (std::size_t t = 0; t < texels; ++t) {
      for (std::size_t c = 0; c < order.size(); ++c) px[c] = buf[t * static_cast<std::size_t>(nch) + static_cast<std::size_t>(order[c])];
      params[t] = unpack_param(px.data());
      if (level > 0) bl.first[t] = static_cast<std::uint32_t>(bl.lobes.size());
      // Lobes are packed from slot 0: the first empty slot (weight 0) ends the texel's.
      for (int k = 0; k < slots; ++k) {
        const Lobe l = unpack_lobe(version, px.data() + 8 + k * lobe_nch);
        if (!(l.weight > 0)) break;
        bl.lobes.push_back(l);
        bl.counts[t] = static_cast<std::uint8_t>(k + 1);
      }
      // A texel's lone lobe goes to its own slot (brdf_pyramid.h).
      if (level > 0 && bl.counts[t] == 1) bl.single[t] = bl.lobes.back(), bl.lobes.pop_back();
    }
    if (level == 0) {
      MaterialTexels& m = mip.level0;
      m = MaterialTexels(e.width, e.height);
      for (std::size_t t = 0; t < texels; ++t) {
        m.base_color[t] = params[t].base_color;
        m.metallic[t] = params[t].metallic;
        m.roughness[t] = params[t].roughness;
        m.normal[t] = params[t].normal;
      }
    } else {
      coarse.push_back(std::move(bl));
    }
    param_levels.push_back(std::move(params));
  }
  if (in->seek_subimage(levels, 0))
    throw input_error(where(path), "has more subimages than the " + std::to_string(levels) + " levels of its level 0");
  mip.param = ParamPyramid::from_levels(level0, std::move(param_levels));
  mip.brdf = BrdfPyramid::from_levels(mip.level0, max_lobes, std::move(coarse));
  return mip;
}

}  // namespace svbrdf
