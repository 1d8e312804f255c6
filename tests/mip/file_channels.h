#pragma once
// Test helpers for the layers' storage tests: the channels of a level of a MIP file (mip/mip_file.h), and
// a texel's value before and after the file's round trip.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "mip/lobe_mixture_bsdf.h"
#include "mip/mip_data.h"

namespace svbrdf::testing_files {

// The channels of subimage `level` of a MIP file: names and byte sizes.
struct Channels {
  std::vector<std::string> names;
  std::vector<int> bytes;
  bool has(const std::string& name) const { return std::find(names.begin(), names.end(), name) != names.end(); }
  // Bytes of the channels whose name starts with `prefix` and contains `part`.
  int bytes_of(const std::string& prefix, const std::string& part = "") const {
    int n = 0;
    for (std::size_t c = 0; c < names.size(); ++c)
      if (names[c].rfind(prefix, 0) == 0 && names[c].find(part) != std::string::npos) n += bytes[c];
    return n;
  }
};
inline Channels channels_of(const std::filesystem::path& path, int level) {
  auto in = OIIO::ImageInput::open(path.string());
  EXPECT_TRUE(in && in->seek_subimage(level, 0));
  Channels c;
  const OIIO::ImageSpec& s = in->spec();
  for (int k = 0; k < s.nchannels; ++k) {
    c.names.push_back(s.channelnames[std::size_t(k)]);
    c.bytes.push_back(int(s.channelformat(k).size()));
  }
  return c;
}

// The first texel of level `l` of `a` with a lobe for which `has` holds (the last texel where none
// has) evaluates, as the renderer's mixture under its coat, bit for bit as the same texel of `b` for
// the pair (wi, wo), to a value whose green is above 0.
template <class Has>
void expect_same_texel_value(const MipData& a, const MipData& b, int l, const glm::vec3& wi, const glm::vec3& wo,
                             const Has& has) {
  const Extent e = a.extent(l);
  int at = 0;
  while (at + 1 < e.width * e.height) {
    const std::span<const Lobe> lobes = a.brdf.texel(l, at % e.width, at / e.width);
    if (std::any_of(lobes.begin(), lobes.end(), has)) break;
    ++at;
  }
  Lobe sa, sb, ca, cb;
  const int i = at % e.width, j = at / e.width;
  const LobeMixtureBsdf ma(brdf_texel(a, l, i, j, sa), brdf_coat(a, l, i, j, ca).lobes),
      mb(brdf_texel(b, l, i, j, sb), brdf_coat(b, l, i, j, cb).lobes);
  const Rgb ea = ma.eval(wi, wo), eb = mb.eval(wi, wo);
  EXPECT_EQ(std::memcmp(&ea, &eb, sizeof ea), 0);
  EXPECT_GT(ea.g, 0.0f);
}

}  // namespace svbrdf::testing_files
