// The MIP file: a bit-identical round trip, OpenImageIO's tools list it, a newer version and foreign
// files are refused with a clear message, files of older versions still read.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>

#include <glm/geometric.hpp>

#include "base/error.h"
#include "base/resource_limits.h"
#include "mip/mip_file.h"
#include "mip/stored_normal.h"
#include "textures/material_family.h"
#include "tests/mip/synthetic_materials.h"
#include "tests/common/temp_dir.h"

namespace svbrdf {
namespace {

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  // (memcmp of empty vectors' null data is undefined: level 0 of the BRDF pyramid holds no lobes.)
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

MaterialTexels mixed_material(int w, int h) {
  MaterialTexels m = synthetic::painted_wall(std::max(w, h));
  MaterialTexels out(w, h);
  const MaterialTexels tray = synthetic::tray(std::max(w, h));
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const bool metal = (i / 3 + j / 2) % 2 == 0;
      const MaterialTexels& src = metal ? tray : m;
      out.base_color[out.index(i, j)] = src.base_color[src.index(i, j)];
      out.metallic[out.index(i, j)] = src.metallic[src.index(i, j)];
      out.roughness[out.index(i, j)] = src.roughness[src.index(i, j)];
      out.normal[out.index(i, j)] = m.normal[m.index(i, j)];
    }
  return out;
}

TEST(MipFile, RoundTripIsBitIdentical) {
  testing::TempDir dir;
  int skirts = 0;  // spread cores whose skirt is not 1: the polished granite has them
  int atoms = 0;   // roughness mixtures with an atom (version 5): the tray's texels in the mixed material
  std::size_t corrected = 0;  // texels with a radial correction (version 6)
  for (auto [w, h] : {std::pair{16, 16}, std::pair{12, 5}, std::pair{64, 0}}) {
    BrdfBuildOptions o;
    o.reduction.max_lobes = 3;
    const MipData a =
        build_mip(h > 0 ? mixed_material(w, h) : generate_material(MaterialRecipe{"granite", "polished", w, 25}).texels, o);
    for (int l = 1; l < a.levels(); ++l)
      for (const Lobe& lobe : a.brdf.level(l).all_lobes()) {
        skirts += lobe.alpha2_hi == 0.0f && lobe.skirt != 1.0f;
        atoms += lobe.alpha2_hi > 0.0f && lobe.ggx < 1.0f;
      }
    std::string name = "m";  // appended, not concatenated: GCC 12 -O3 warns falsely otherwise (PR 105651)
    name += std::to_string(w);
    name += ".exr";
    const auto path = dir / name;
    write_mip_file(path, a);
    const MipData b = read_mip_file(path);
    ASSERT_EQ(b.levels(), a.levels());
    EXPECT_TRUE(same_bits(a.level0.base_color, b.level0.base_color));
    EXPECT_TRUE(same_bits(a.level0.metallic, b.level0.metallic));
    EXPECT_TRUE(same_bits(a.level0.roughness, b.level0.roughness));
    EXPECT_TRUE(same_bits(a.level0.normal, b.level0.normal));
    EXPECT_EQ(b.brdf.max_lobes(), 3);
    for (int l = 0; l < a.levels(); ++l) {
      const auto pa = a.param.level(l), pb = b.param.level(l);
      ASSERT_EQ(pa.size(), pb.size());
      EXPECT_EQ(std::memcmp(pa.data(), pb.data(), pa.size_bytes()), 0) << "param level " << l;
      const BrdfLevel &la = a.brdf.level(l), &lb = b.brdf.level(l);
      EXPECT_EQ(la.slots, lb.slots);
      EXPECT_TRUE(same_bits(la.counts, lb.counts)) << "level " << l;
      EXPECT_TRUE(same_bits(la.first, lb.first)) << "level " << l;
      EXPECT_TRUE(same_bits(la.lobes, lb.lobes)) << "level " << l;
      EXPECT_TRUE(same_bits(la.single, lb.single)) << "level " << l;
      ASSERT_EQ(la.correction.size(), lb.correction.size()) << "level " << l;
      corrected += la.correction.size();
      for (std::size_t t = 0; t < la.correction.size(); ++t)
        EXPECT_EQ(std::memcmp(la.correction[t].ratio.data(), lb.correction[t].ratio.data(), sizeof(la.correction[t].ratio)), 0)
            << "level " << l << " texel " << t;
    }
    EXPECT_EQ(a.brdf.radial_grid().inner, b.brdf.radial_grid().inner);
    EXPECT_EQ(std::memcmp(&a.brdf.radial_grid(), &b.brdf.radial_grid(), sizeof(RadialGrid)), 0);
  }
  EXPECT_GT(skirts, 0);
  EXPECT_GT(atoms, 0);
  EXPECT_GT(corrected, 0u) << "the levels from kFirstCorrectedLevel on should carry radial corrections";
}

TEST(MipFile, OpenImageIOToolsListIt) {
  testing::TempDir dir;
  const auto path = dir / "tray.exr";
  write_mip_file(path, build_mip(synthetic::tray(8)));
  const std::string cmd = "oiiotool --info -v '" + path.string() + "' 2>&1";
  FILE* p = ::popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  char buf[4096];
  while (std::fgets(buf, sizeof buf, p)) out += buf;
  const int rc = ::pclose(p);
  if (out.find("not found") != std::string::npos) GTEST_SKIP() << "oiiotool is not installed";
  EXPECT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("4 subimages"), std::string::npos) << out;
  EXPECT_NE(out.find("param.roughness"), std::string::npos) << out;
  EXPECT_NE(out.find("svbrdf:mip_version: " + std::to_string(kMipFileVersion)), std::string::npos) << out;
}

void write_exr_with_version(const std::filesystem::path& path, int version) {
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(out);
  OIIO::ImageSpec spec(1, 1, 3, OIIO::TypeDesc::FLOAT);
  if (version > 0) spec.attribute("svbrdf:mip_version", version);
  ASSERT_TRUE(out->open(path.string(), spec));
  const float px[3] = {0.5f, 0.5f, 0.5f};
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, px));
  out->close();
}

std::string read_error(const std::filesystem::path& path) {
  try {
    read_mip_file(path);
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 2);
    return e.what();
  }
  return "";
}

TEST(MipFile, RefusesNewerVersionsForeignAndMissingFiles) {
  testing::TempDir dir;
  write_exr_with_version(dir / "newer.exr", kMipFileVersion + 1);
  std::string msg = read_error(dir / "newer.exr");
  EXPECT_NE(msg.find("newer.exr"), std::string::npos) << msg;
  EXPECT_NE(msg.find("version " + std::to_string(kMipFileVersion + 1) + " is newer"), std::string::npos) << msg;
  write_exr_with_version(dir / "plain.exr", 0);
  msg = read_error(dir / "plain.exr");
  EXPECT_NE(msg.find("not an svbrdf MIP file"), std::string::npos) << msg;
  msg = read_error(dir / "missing.exr");
  EXPECT_NE(msg.find("missing.exr"), std::string::npos) << msg;
  // A MIP file with a level cut away is inconsistent, not silently short.
  write_exr_with_version(dir / "short.exr", kMipFileVersion);
  EXPECT_NE(read_error(dir / "short.exr").find("short.exr"), std::string::npos);
}

// Calls f(input, level, spec, texels, the level's pixels as floats) for each level of a MIP file.
template <class F>
void for_each_level(const std::filesystem::path& from, F f) {
  std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(from.string());
  ASSERT_TRUE(in);
  for (int level = 0; in->seek_subimage(level, 0); ++level) {
    const OIIO::ImageSpec src = in->spec();
    const std::size_t texels = static_cast<std::size_t>(src.width) * src.height;
    std::vector<float> all(texels * static_cast<std::size_t>(src.nchannels));
    ASSERT_TRUE(in->read_image(level, 0, 0, src.nchannels, OIIO::TypeDesc::FLOAT, all.data()));
    f(*in, level, src, texels, all);
  }
  in->close();
}

// Writes one subimage a level from pixels in `format` (TypeUnknown: each channel in its spec's format),
// converted to the specs' formats.
template <class T>
void write_levels(const std::filesystem::path& to, const std::vector<OIIO::ImageSpec>& specs,
                  const std::vector<std::vector<T>>& pixels, OIIO::TypeDesc format) {
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(to.string());
  ASSERT_TRUE(out);
  ASSERT_TRUE(out->open(to.string(), static_cast<int>(specs.size()), specs.data()));
  for (std::size_t level = 0; level < specs.size(); ++level) {
    if (level > 0) {
      ASSERT_TRUE(out->open(to.string(), specs[level], OIIO::ImageOutput::AppendSubimage));
    }
    ASSERT_TRUE(out->write_image(format, pixels[level].data()));
  }
  ASSERT_TRUE(out->close());
}

// Copies a MIP file level by level, in every channel's own format or (all_float) every channel as a
// float — what `oiiotool -a -d float` makes of it — and without the attribute `drop` (if named), as
// `version` (if > 0).
void copy_mip_file(const std::filesystem::path& from, const std::filesystem::path& to, bool all_float, const char* drop,
                   int version = 0) {
  std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(from.string());
  ASSERT_TRUE(in);
  std::vector<OIIO::ImageSpec> specs;
  std::vector<std::vector<std::byte>> pixels;
  for (int level = 0; in->seek_subimage(level, 0); ++level) {
    OIIO::ImageSpec s = in->spec();
    const OIIO::TypeDesc format = all_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeUnknown;
    std::vector<std::byte> px(static_cast<std::size_t>(s.width) * s.height * (all_float ? std::size_t(s.nchannels) * 4 : s.pixel_bytes(true)));
    ASSERT_TRUE(in->read_image(level, 0, 0, s.nchannels, format, px.data()));
    if (all_float) s.set_format(OIIO::TypeDesc::FLOAT), s.channelformats.clear();
    if (drop) s.erase_attribute(drop);
    if (version > 0) s.attribute("svbrdf:mip_version", version);
    specs.push_back(s);
    pixels.push_back(std::move(px));
  }
  in->close();
  write_levels(to, specs, pixels, all_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeUnknown);
}

// A file whose normals' codes were converted to floats (they keep 24 of their 32 bits) is refused, not
// read with its normals off; so is one with radial corrections but no grid to read them on. A copy in
// the channels' own formats reads back as the original.
TEST(MipFile, RefusesCodesConvertedToFloatAndCorrectionsWithoutTheirGrid) {
  testing::TempDir dir;
  const MipData mip = build_mip(generate_material(MaterialRecipe{"metal-tray", "steel", 32, 24}).texels);
  write_mip_file(dir / "tray.exr", mip);
  copy_mip_file(dir / "tray.exr", dir / "copy.exr", false, nullptr);
  const MipData copy = read_mip_file(dir / "copy.exr");
  for (int level = 1; level < mip.levels(); ++level)
    EXPECT_TRUE(same_bits(copy.brdf.level(level).all_lobes(), mip.brdf.level(level).all_lobes())) << level;
  copy_mip_file(dir / "tray.exr", dir / "floats.exr", true, nullptr);
  std::string msg = read_error(dir / "floats.exr");
  EXPECT_NE(msg.find("floats.exr"), std::string::npos) << msg;
  EXPECT_NE(msg.find("level 1 channel lobe0.N.dir is float, not the 32-bit unsigned integer"), std::string::npos) << msg;
  copy_mip_file(dir / "tray.exr", dir / "nogrid.exr", false, "svbrdf:radial_inner");
  msg = read_error(dir / "nogrid.exr");
  EXPECT_NE(msg.find("nogrid.exr"), std::string::npos) << msg;
  EXPECT_NE(msg.find("level " + std::to_string(kFirstCorrectedLevel) + " has radial corrections but the file has no svbrdf:radial_inner"),
            std::string::npos) << msg;
}

// Version 7 added svbrdf:radial_outer (the grid's last node, 30°); version 6's grid ended at 10° and
// its files read on that grid. A version-7 file without the attribute is refused.
TEST(MipFile, ReadsTheRadialGridsOuterNodeAndVersionSixsTenDegrees) {
  testing::TempDir dir;
  const MipData mip = build_mip(generate_material(MaterialRecipe{"metal-tray", "steel", 32, 24}).texels);
  write_mip_file(dir / "tray.exr", mip);
  EXPECT_EQ(read_mip_file(dir / "tray.exr").brdf.radial_grid().outer_deg, float(RadialGrid::kOuterDeg));
  copy_mip_file(dir / "tray.exr", dir / "v6.exr", false, "svbrdf:radial_outer", 6);
  const MipData v6 = read_mip_file(dir / "v6.exr");
  EXPECT_EQ(v6.brdf.radial_grid().outer_deg, 10.0f);
  EXPECT_EQ(v6.brdf.radial_grid().inner, mip.brdf.radial_grid().inner);
  const RadialCorrection* c = v6.brdf.correction(kFirstCorrectedLevel, 0, 0);
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(std::memcmp(c, mip.brdf.correction(kFirstCorrectedLevel, 0, 0), sizeof(RadialCorrection)), 0);
  copy_mip_file(dir / "tray.exr", dir / "noouter.exr", false, "svbrdf:radial_outer");
  const std::string msg = read_error(dir / "noouter.exr");
  EXPECT_NE(msg.find("noouter.exr"), std::string::npos) << msg;
  EXPECT_NE(msg.find("svbrdf:radial_outer is 0.000000, not an angle in degrees"), std::string::npos) << msg;
}

// A lobe's normal decoded from its N.dir code and N.deficit as mip_file.h documents them, independently
// of stored_normal.cpp: signed 16-bit codes q (x low, y high), c = q/32767, the octahedral coordinate
// p = c·(1/16 + (15/16)|c|) in version 8 and p = c in versions 6 and 7, the lower half folded over the
// diagonals.
glm::dvec3 documented_normal(std::uint32_t code, float deficit, bool warped) {
  const auto coordinate = [&](std::uint16_t bits) {
    const double c = std::clamp(static_cast<std::int16_t>(bits) / 32767.0, -1.0, 1.0);
    return warped ? c * (1.0 / 16 + (15.0 / 16) * std::abs(c)) : c;
  };
  const double x = coordinate(static_cast<std::uint16_t>(code & 0xffffu)), y = coordinate(static_cast<std::uint16_t>(code >> 16));
  glm::dvec3 d(x, y, 1 - std::abs(x) - std::abs(y));
  if (d.z < 0) d = glm::dvec3((1 - std::abs(y)) * (x < 0 ? -1 : 1), (1 - std::abs(x)) * (y < 0 ? -1 : 1), d.z);
  return glm::normalize(d) * (1.0 - deficit);
}

// Version 8 warps the normals' codes toward the pole (stored_normal.h); a version-7 file's codes read on
// the linear map. The same codes, relabelled as version 7, must read as the linear decoding.
TEST(MipFile, ReadsNormalCodesAsTheirVersionWroteThem) {
  testing::TempDir dir;
  const MipData mip = build_mip(generate_material(MaterialRecipe{"metal-tray", "steel", 32, 24}).texels);
  write_mip_file(dir / "tray.exr", mip);
  copy_mip_file(dir / "tray.exr", dir / "v7.exr", false, nullptr, 7);
  const MipData v8 = read_mip_file(dir / "tray.exr"), v7 = read_mip_file(dir / "v7.exr");
  int compared = 0, differ = 0;
  for_each_level(dir / "tray.exr", [&](OIIO::ImageInput& in, int level, const OIIO::ImageSpec& src, std::size_t texels,
                                       const std::vector<float>& all) {
    if (level == 0) return;
    std::vector<std::uint32_t> codes(texels * static_cast<std::size_t>(src.nchannels));
    ASSERT_TRUE(in.read_image(level, 0, 0, src.nchannels, OIIO::TypeDesc::UINT, codes.data()));
    const int dir_channel = src.channelindex("lobe0.N.dir"), deficit_channel = src.channelindex("lobe0.N.deficit");
    ASSERT_GE(dir_channel, 0);
    ASSERT_GE(deficit_channel, 0);
    const int width = src.width;
    for (std::size_t t = 0; t < texels; ++t) {
      const std::size_t at = t * static_cast<std::size_t>(src.nchannels);
      const std::uint32_t code = codes[at + static_cast<std::size_t>(dir_channel)];
      const float deficit = all[at + static_cast<std::size_t>(deficit_channel)];
      const int i = static_cast<int>(t % static_cast<std::size_t>(width)), j = static_cast<int>(t / static_cast<std::size_t>(width));
      const glm::dvec3 n8(v8.brdf.texel(level, i, j)[0].normal), n7(v7.brdf.texel(level, i, j)[0].normal);
      const glm::dvec3 want8 = documented_normal(code, deficit, true), want7 = documented_normal(code, deficit, false);
      ASSERT_LT(glm::length(n8 - want8), 2e-7) << "level " << level << " texel " << t;
      ASSERT_LT(glm::length(n7 - want7), 2e-7) << "level " << level << " texel " << t;
      ++compared;
      differ += glm::length(want8 - want7) > 1e-6;
    }
  });
  EXPECT_GT(compared, 100);
  EXPECT_GT(differ, 0) << "no lobe's normal is off the pole: the two decodings cannot be told apart here";
}

// Rewrites a version-6 or -7 MIP file (their lobes are alike) as version 5 wrote it: the lobes' normals as three floats (N.X, N.Y,
// N.Z) where version 6 has an octahedral code and a length deficit (stored_normal.h), no radial
// corrections.
void write_as_version5(const std::filesystem::path& from, const std::filesystem::path& to) {
  std::vector<OIIO::ImageSpec> specs;
  std::vector<std::vector<float>> pixels;
  for_each_level(from, [&](OIIO::ImageInput& in, int level, const OIIO::ImageSpec& src, std::size_t texels,
                           const std::vector<float>& all) {
    // The codes, read as what they are (a float holds 24 bits of one).
    std::vector<std::uint32_t> codes(texels * static_cast<std::size_t>(src.nchannels));
    ASSERT_TRUE(in.read_image(level, 0, 0, src.nchannels, OIIO::TypeDesc::UINT, codes.data()));
    OIIO::ImageSpec dst = src;
    dst.channelnames.clear();
    dst.channelformats.clear();
    dst.erase_attribute("svbrdf:radial_inner");
    dst.erase_attribute("svbrdf:radial_outer");
    dst.attribute("svbrdf:mip_version", 5);
    // Each output channel: a source channel, or component `axis` of the normal whose code and deficit
    // are in channels `from` and `deficit`.
    struct Out {
      int from;
      int deficit = -1;
      int axis = -1;
    };
    std::vector<Out> outs;
    const auto find_channel = [&](const std::string& want) {
      for (int k = 0; k < src.nchannels; ++k)
        if (src.channelnames[static_cast<std::size_t>(k)] == want) return k;
      return -1;
    };
    for (int c = 0; c < src.nchannels; ++c) {
      const std::string& name = src.channelnames[static_cast<std::size_t>(c)];
      if (name.rfind("radial.", 0) == 0 || (name.size() > 10 && name.compare(name.size() - 10, 10, ".N.deficit") == 0)) continue;
      if (name.size() > 6 && name.compare(name.size() - 6, 6, ".N.dir") == 0) {
        const std::string lobe = name.substr(0, name.size() - 6);
        ASSERT_EQ(src.channelformat(c), OIIO::TypeDesc::UINT) << name;
        const int deficit = find_channel(lobe + ".N.deficit");
        ASSERT_GE(deficit, 0);
        for (int axis = 0; axis < 3; ++axis) {
          outs.push_back({c, deficit, axis});
          dst.channelnames.push_back(lobe + ".N." + "XYZ"[axis]);
          dst.channelformats.push_back(OIIO::TypeDesc::FLOAT);
        }
        continue;
      }
      outs.push_back({c});
      dst.channelnames.push_back(name);
      dst.channelformats.push_back(src.channelformat(c));
    }
    dst.nchannels = static_cast<int>(outs.size());
    std::vector<float> kept(texels * outs.size());
    for (std::size_t t = 0; t < texels; ++t)
      for (std::size_t k = 0; k < outs.size(); ++k) {
        const std::size_t at = t * static_cast<std::size_t>(src.nchannels);
        const Out& o = outs[k];
        kept[t * outs.size() + k] =
            o.axis < 0 ? all[at + static_cast<std::size_t>(o.from)]
                       : load_normal(StoredNormal{codes[at + static_cast<std::size_t>(o.from)], all[at + static_cast<std::size_t>(o.deficit)]})[o.axis];
      }
    specs.push_back(dst);
    pixels.push_back(std::move(kept));
  });
  write_levels(to, specs, pixels, OIIO::TypeDesc::FLOAT);
}

// Rewrites a version-5 MIP file as an older version wrote it: version 4 had no atoms (a mixture's shape
// code was its span, its skirt channel 1), version 3 no skirt channel, version 2 stored a lobe's shape as
// lobeK.alpha2_hi (float, 0: not a mixture) and lobeK.ggx (half, μ), version 1 had neither. The shape
// code is decoded here as mip_file.h documents it: > 0 is ln(α² upper end / α²), < −1 is −(1 + that)
// for a two-point mixture, else −μ. A mixture's atom has no place in the older versions and is dropped
// (they read it as the band alone, β = 1).
void write_as_older_version(const std::filesystem::path& from, const std::filesystem::path& to, int version) {
  std::vector<OIIO::ImageSpec> specs;
  std::vector<std::vector<float>> pixels;
  for_each_level(from, [&](OIIO::ImageInput&, int, const OIIO::ImageSpec& src, std::size_t texels,
                           const std::vector<float>& all) {
    OIIO::ImageSpec dst = src;
    dst.channelnames.clear();
    dst.channelformats.clear();
    // Each output channel: a source channel, α² from version 4's α, or (for version 2) a shape code's
    // α² upper end or μ.
    struct Out {
      int from;
      int alpha = -1;    // ≥ 0: the α channel, and `from` is the shape code: write the α² upper end
      bool ggx = false;  // write μ from the shape code `from`
      bool square = false;  // write from² (α² from α)
      bool span = false;    // write the shape code `from` as version 4 did (a mixture's span)
      int shape = -1;       // ≥ 0: `from` is the skirt channel and this its lobe's shape code (version 4)
    };
    // A shape code's mixture span (0: not a mixture).
    const auto span_of = [](float code) { return code > 0 ? code : code < -1 ? -code - 1 : 0.0f; };
    std::vector<Out> outs;
    for (int c = 0; c < src.nchannels; ++c) {
      const std::string& name = src.channelnames[static_cast<std::size_t>(c)];
      // The index of a source channel by name (−1: none), and the source channel c kept as it is named.
      const auto find_channel = [&](const std::string& want) {
        for (int k = 0; k < src.nchannels; ++k)
          if (src.channelnames[static_cast<std::size_t>(k)] == want) return k;
        return -1;
      };
      const auto keep = [&](const Out& o) {
        outs.push_back(o);
        dst.channelnames.push_back(name);
        dst.channelformats.push_back(src.channelformat(c));
      };
      // The skirt (version 4) is not in older files; version 4 wrote 1 there for mixtures.
      if (name.size() > 6 && name.compare(name.size() - 6, 6, ".skirt") == 0) {
        if (version == 4) {
          Out o{c};
          o.shape = find_channel(name.substr(0, name.size() - 6) + ".shape");
          ASSERT_GE(o.shape, 0);
          keep(o);
        }
        continue;
      }
      // Older versions store α² as a float where version 4 stores α as a half.
      if (name.size() > 6 && name.compare(name.size() - 6, 6, ".alpha") == 0 && version < 4) {
        outs.push_back({c, -1, false, true});
        dst.channelnames.push_back(name + "2");
        dst.channelformats.push_back(OIIO::TypeDesc::FLOAT);
        continue;
      }
      if (name.size() > 6 && name.compare(name.size() - 6, 6, ".shape") == 0 && version < 3) {
        if (version == 2) {
          const std::string lobe = name.substr(0, name.size() - 6);
          const int a2 = find_channel(lobe + ".alpha");
          ASSERT_GE(a2, 0);
          outs.push_back({c, a2, false});
          dst.channelnames.push_back(lobe + ".alpha2_hi");
          dst.channelformats.push_back(OIIO::TypeDesc::FLOAT);
          outs.push_back({c, -1, true});
          dst.channelnames.push_back(lobe + ".ggx");
          dst.channelformats.push_back(OIIO::TypeDesc::HALF);
        }
        continue;
      }
      if (name.size() > 6 && name.compare(name.size() - 6, 6, ".shape") == 0) {
        Out o{c};
        o.span = true;
        keep(o);
        continue;
      }
      keep(Out{c});
    }
    dst.nchannels = static_cast<int>(outs.size());
    dst.attribute("svbrdf:mip_version", version);
    std::vector<float> kept(texels * outs.size());
    for (std::size_t t = 0; t < texels; ++t)
      for (std::size_t k = 0; k < outs.size(); ++k) {
        const float* px = all.data() + t * static_cast<std::size_t>(src.nchannels);
        const float v = px[outs[k].from];
        float& o = kept[t * outs.size() + k];
        if (outs[k].alpha >= 0)
          o = span_of(v) > 0 ? static_cast<float>(double(px[outs[k].alpha] * px[outs[k].alpha]) * std::exp(double(span_of(v)))) : 0.0f;
        else if (outs[k].square)
          o = v * v;
        else if (outs[k].ggx)
          o = span_of(v) > 0 ? 1.0f : -v;
        else if (outs[k].span)
          o = span_of(v) > 0 ? span_of(v) : v;
        else if (outs[k].shape >= 0)
          o = span_of(px[outs[k].shape]) > 0 ? 1.0f : v;
        else
          o = v;
      }
    specs.push_back(dst);
    pixels.push_back(std::move(kept));
  });
  write_levels(to, specs, pixels, OIIO::TypeDesc::FLOAT);
}

// Version-5 files read with their normals as stored and no radial corrections; version-4, -3 and -2
// files with the lobe shapes they stored (mixtures without atoms; no skirt before version 4); version-1
// files (before the lobe shapes of lobe.h) as plain GGX lobes; every other channel as stored.
TEST(MipFile, ReadsOlderVersions) {
  testing::TempDir dir;
  // The fingerprinted tray at 64²: its pyramid holds every lobe shape, mixtures with atoms among them.
  const MipData mip = build_mip(generate_material(MaterialRecipe{"metal-tray", "steel", 64, 24}).texels);
  write_mip_file(dir / "v6.exr", mip);
  write_as_version5(dir / "v6.exr", dir / "v5.exr");
  int atoms = 0;
  for (int version : {1, 2, 3, 4, 5}) {
    std::string name = "v";  // appended, not concatenated: GCC 12 -O3 warns falsely otherwise (PR 105651)
    name += std::to_string(version);
    name += ".exr";
    const auto old = dir / name;
    if (version < 5) write_as_older_version(dir / "v5.exr", old, version);
    const MipData back = read_mip_file(old);
    ASSERT_EQ(back.levels(), mip.levels());
    for (int level = 1; level < mip.levels(); ++level) EXPECT_EQ(back.brdf.correction(level, 0, 0), nullptr);
    int shaped = 0;
    for (int level = 1; level < mip.levels(); ++level) {
      const std::vector<Lobe> a = mip.brdf.level(level).all_lobes();
      const std::vector<Lobe> b = back.brdf.level(level).all_lobes();
      ASSERT_EQ(a.size(), b.size());
      for (std::size_t k = 0; k < a.size(); ++k) {
        SCOPED_TRACE("version " + std::to_string(version) + " level " + std::to_string(level) + " lobe " + std::to_string(k));
        EXPECT_EQ(b[k].weight, a[k].weight);
        EXPECT_EQ(b[k].alpha2, a[k].alpha2);
        EXPECT_EQ(b[k].normal, a[k].normal);
        EXPECT_EQ(b[k].diffuse, a[k].diffuse);
        const bool mixture = a[k].alpha2_hi > 0;
        if (version == 1) {
          EXPECT_EQ(b[k].alpha2_hi, 0.0f);
          EXPECT_EQ(b[k].ggx, 1.0f);
        } else {
          EXPECT_EQ(b[k].alpha2_hi, a[k].alpha2_hi);
          // Before version 5 a mixture's atom is dropped: the band alone.
          EXPECT_EQ(b[k].ggx, mixture && version < 5 ? 1.0f : a[k].ggx);
        }
        EXPECT_EQ(b[k].skirt, version == 5 || (version == 4 && !mixture) ? a[k].skirt : 1.0f);
        shaped += mixture || a[k].ggx != 1.0f;
        atoms += version == 4 && mixture && a[k].ggx < 1.0f;
      }
    }
    EXPECT_GT(shaped, 0) << "the tray's pyramid should hold shaped lobes, or this test shows nothing";
  }
  EXPECT_GT(atoms, 0) << "the tray's pyramid should hold mixtures with atoms, or the version-4 case shows little";
}

}  // namespace
}  // namespace svbrdf

namespace svbrdf {
namespace {

// A MIP file's headers are checked before any level is read: a header that claims 4096² texels in a
// file cut to 4 KiB is refused from the file's size (OpenEXR needs 16 bytes of offset table and chunk
// header per chunk, and zlib at most 1032:1), in no time and with no allocation; a level 0 beyond
// --max-texels is refused from its header.
TEST(MipFile, HeadersAreCheckedBeforeAnyLevelIsRead) {
  const testing::TempDir dir;
  const auto path = dir / "claims.exr";
  {
    OIIO::ImageSpec spec(4096, 4096, 1, OIIO::TypeDesc::HALF);
    spec.attribute("compression", "zip");
    spec.attribute("svbrdf:mip_version", kMipFileVersion);
    spec.attribute("svbrdf:level", 0);
    auto out = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(out && out->open(path.string(), spec));
    std::vector<std::uint16_t> zeros(std::size_t(4096) * 4096, 0);
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::HALF, zeros.data()));
    ASSERT_TRUE(out->close());
  }
  std::filesystem::resize_file(path, 4096);
  try {
    read_mip_file(path);
    ADD_FAILURE() << "a 4 KiB file claiming 4096x4096 texels was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("truncated or corrupt"), std::string::npos) << e.what();
  }
  const std::uint64_t saved = resource_limits().max_texels;
  resource_limits().max_texels = 4096 * 4095;
  try {
    read_mip_file(path);
    ADD_FAILURE() << "a level 0 over --max-texels was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--max-texels"), std::string::npos) << e.what();
  }
  resource_limits().max_texels = saved;
}

}  // namespace
}  // namespace svbrdf
