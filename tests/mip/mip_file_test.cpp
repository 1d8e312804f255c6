// The MIP file: a bit-identical round trip, OpenImageIO's tools list it, files of another version and
// foreign files are refused with a clear message.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

#include "base/error.h"
#include "base/resource_limits.h"
#include "mip/mip_file.h"
#include "textures/material_family.h"
#include "textures/random_material.h"
#include "tests/mip/synthetic_materials.h"
#include "tests/common/run_command.h"
#include "tests/common/temp_dir.h"
#include "tests/common/test_paths.h"

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
  int atoms = 0;   // roughness mixtures with an atom: the tray's texels in the mixed material
  std::size_t corrected = 0;  // texels with a radial correction
  // 512 × 260: level 0 alone (32 bytes a texel) outgrows the reader's 4 MiB band, so it reads a level in
  // several bands, each inflated while the one before is unpacked.
  for (auto [w, h] : {std::pair{16, 16}, std::pair{12, 5}, std::pair{64, 0}, std::pair{512, 260}}) {
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

// The one line that refuses a MIP file of another version than this build's.
std::string other_version_message(const std::filesystem::path& path, int version) {
  return path.string() + ": MIP file version " + std::to_string(version) + "; this build reads version " +
         std::to_string(kMipFileVersion) + " only — rebuild it with `svbrdf-bake mip ... --out " + path.string() + "`";
}

// A coated material's file (KHR_materials_clearcoat) carries its coat: the level-0 coat per texel, the
// parameter pyramid's coat means, each base lobe's coat share and the coat lobes, all read back bit for
// bit, so the coated texels evaluate as before the trip.
TEST(MipFile, ACoatedMaterialsRoundTripIsBitIdentical) {
  testing::TempDir dir;
  for (const int size : {16, 12}) {
    SCOPED_TRACE("size " + std::to_string(size));
    const MaterialTexels m = synthetic::orange_peel(size);
    const MipData a = build_mip(m);
    ASSERT_TRUE(a.brdf.has_coat());
    const auto path = dir / ("coat" + std::to_string(size) + ".exr");
    write_mip_file(path, a);
    const MipData b = read_mip_file(path);
    ASSERT_EQ(b.levels(), a.levels());
    ASSERT_TRUE(b.level0.has_coat());
    ASSERT_TRUE(b.brdf.has_coat());
    for (std::size_t k = 0; k < m.size(); ++k) {
      const CoatLayer x = m.coat_layer(k), y = b.level0.coat_layer(k);
      ASSERT_EQ(std::memcmp(&x, &y, sizeof x), 0) << "level-0 coat of texel " << k;
    }
    int coat_lobes = 0, shared = 0;
    for (int l = 0; l < a.levels(); ++l) {
      const auto ca = a.param.coat_level(l), cb = b.param.coat_level(l);
      ASSERT_EQ(ca.size(), cb.size());
      EXPECT_EQ(std::memcmp(ca.data(), cb.data(), ca.size_bytes()), 0) << "param coat level " << l;
      if (l == 0) continue;
      EXPECT_TRUE(same_bits(a.brdf.level(l).all_lobes(), b.brdf.level(l).all_lobes())) << "level " << l;
      const BrdfLevel &la = a.brdf.coat_level(l), &lb = b.brdf.coat_level(l);
      EXPECT_EQ(la.slots, lb.slots) << "coat level " << l;
      EXPECT_TRUE(same_bits(la.counts, lb.counts)) << "coat level " << l;
      EXPECT_TRUE(same_bits(la.all_lobes(), lb.all_lobes())) << "coat level " << l;
      coat_lobes += static_cast<int>(la.all_lobes().size());
      for (const Lobe& lobe : a.brdf.level(l).all_lobes()) shared += lobe.coat > 0;
    }
    EXPECT_GT(coat_lobes, 0);
    EXPECT_GT(shared, 0);
    // Coated texels evaluate alike (the coat's Fresnel, its lobes and the base's shares).
    const glm::dvec3 wi = glm::normalize(glm::dvec3(0.3, -0.2, 0.9)), wo = glm::normalize(glm::dvec3(-0.4, 0.1, 0.8));
    for (int l = 0; l < a.levels(); ++l)
      EXPECT_EQ(texel_eval(a, TextureFilter::brdf, l, 0, 0, wi, wo), texel_eval(b, TextureFilter::brdf, l, 0, 0, wi, wo))
          << "level " << l;
  }
}

// A material with a sheen (KHR_materials_sheen) carries it: the level-0 sheen per texel, the parameter
// pyramid's sheen means (which the BRDF pyramid's texels read), each base lobe's sheen share, all read
// back bit for bit, so the texels evaluate as before the trip; a textured sheen of the random family.
TEST(MipFile, ASheenMaterialsRoundTripIsBitIdentical) {
  testing::TempDir dir;
  std::uint64_t seed = 1;
  while (!draw_random_material(seed).sheen_textured) ++seed;
  for (const int size : {16, 12}) {
    SCOPED_TRACE("size " + std::to_string(size));
    const MaterialTexels m = random_material_texels(draw_random_material(seed), size);
    const MipData a = build_mip(m);
    ASSERT_TRUE(a.brdf.has_sheen());
    const auto path = dir / ("sheen" + std::to_string(size) + ".exr");
    write_mip_file(path, a);
    const MipData b = read_mip_file(path);
    ASSERT_EQ(b.levels(), a.levels());
    ASSERT_TRUE(b.level0.has_sheen());
    ASSERT_TRUE(b.brdf.has_sheen());
    for (std::size_t k = 0; k < m.size(); ++k) {
      const SheenLayer x = m.sheen_layer(k), y = b.level0.sheen_layer(k);
      ASSERT_EQ(std::memcmp(&x, &y, sizeof x), 0) << "level-0 sheen of texel " << k;
    }
    int shares = 0;
    for (int l = 0; l < a.levels(); ++l) {
      const auto pa = a.param.sheen_level(l), pb = b.param.sheen_level(l);
      ASSERT_EQ(pa.size(), pb.size());
      EXPECT_EQ(std::memcmp(pa.data(), pb.data(), pa.size_bytes()), 0) << "param sheen level " << l;
      if (l == 0) continue;
      const auto ba = a.brdf.sheen_level(l), bb = b.brdf.sheen_level(l);
      ASSERT_EQ(ba.size(), bb.size());
      EXPECT_EQ(std::memcmp(ba.data(), bb.data(), ba.size_bytes()), 0) << "brdf sheen level " << l;
      EXPECT_TRUE(same_bits(a.brdf.level(l).all_lobes(), b.brdf.level(l).all_lobes())) << "level " << l;
      for (const Lobe& lobe : a.brdf.level(l).all_lobes()) shares += lobe.sheen > 0;
    }
    EXPECT_GT(shares, 0);
    const glm::dvec3 wi = glm::normalize(glm::dvec3(0.3, -0.2, 0.9)), wo = glm::normalize(glm::dvec3(-0.4, 0.1, 0.8));
    for (int l = 0; l < a.levels(); ++l)
      for (const TextureFilter f : {TextureFilter::brdf, TextureFilter::param})
        EXPECT_EQ(texel_eval(a, f, l, 0, 0, wi, wo), texel_eval(b, f, l, 0, 0, wi, wo)) << "level " << l;
  }
}

// An anisotropic material (KHR_materials_anisotropy) carries it: the level-0 anisotropy per texel, the
// parameter pyramid's means, and every stretched lobe, read back bit for bit (the build rounds each
// stretch to its stored code, stored_lobe.h), so the texels evaluate as before the trip; a textured,
// swirling anisotropy of the random family.
TEST(MipFile, AnAnisotropicMaterialsRoundTripIsBitIdentical) {
  testing::TempDir dir;
  std::uint64_t seed = 1;
  while (!draw_random_material(seed).anisotropy_textured) ++seed;
  for (const int size : {16, 12}) {
    SCOPED_TRACE("size " + std::to_string(size));
    const MaterialTexels m = random_material_texels(draw_random_material(seed), size);
    const MipData a = build_mip(m);
    ASSERT_TRUE(a.param.has_anisotropy());
    const auto path = dir / ("anisotropy" + std::to_string(size) + ".exr");
    write_mip_file(path, a);
    const MipData b = read_mip_file(path);
    ASSERT_EQ(b.levels(), a.levels());
    ASSERT_TRUE(b.level0.has_anisotropy());
    for (std::size_t k = 0; k < m.size(); ++k) {
      const AnisotropyLayer x = m.anisotropy_layer(k), y = b.level0.anisotropy_layer(k);
      ASSERT_EQ(std::memcmp(&x, &y, sizeof x), 0) << "level-0 anisotropy of texel " << k;
    }
    int stretched = 0;
    for (int l = 0; l < a.levels(); ++l) {
      const auto pa = a.param.anisotropy_level(l), pb = b.param.anisotropy_level(l);
      ASSERT_EQ(pa.size(), pb.size());
      EXPECT_EQ(std::memcmp(pa.data(), pb.data(), pa.size_bytes()), 0) << "param anisotropy level " << l;
      if (l == 0) continue;
      EXPECT_TRUE(same_bits(a.brdf.level(l).all_lobes(), b.brdf.level(l).all_lobes())) << "level " << l;
      for (const Lobe& lobe : a.brdf.level(l).all_lobes()) stretched += lobe.stretch > 1.0f;
    }
    EXPECT_GT(stretched, 0);
    const glm::dvec3 wi = glm::normalize(glm::dvec3(0.3, -0.2, 0.9)), wo = glm::normalize(glm::dvec3(-0.4, 0.1, 0.8));
    for (int l = 0; l < a.levels(); ++l)
      for (const TextureFilter f : {TextureFilter::brdf, TextureFilter::param})
        EXPECT_EQ(texel_eval(a, f, l, 0, 0, wi, wo), texel_eval(b, f, l, 0, 0, wi, wo)) << "level " << l;
  }
}

TEST(MipFile, RefusesOtherVersionsForeignAndMissingFiles) {
  testing::TempDir dir;
  write_exr_with_version(dir / "newer.exr", kMipFileVersion + 1);
  std::string msg = read_error(dir / "newer.exr");
  EXPECT_NE(msg.find("newer.exr"), std::string::npos) << msg;
  EXPECT_EQ(msg, other_version_message(dir / "newer.exr", kMipFileVersion + 1));
  write_exr_with_version(dir / "plain.exr", 0);
  msg = read_error(dir / "plain.exr");
  EXPECT_NE(msg.find("not an svbrdf MIP file"), std::string::npos) << msg;
  msg = read_error(dir / "missing.exr");
  EXPECT_NE(msg.find("missing.exr"), std::string::npos) << msg;
  // A MIP file with a level cut away is inconsistent, not silently short.
  write_exr_with_version(dir / "short.exr", kMipFileVersion);
  EXPECT_NE(read_error(dir / "short.exr").find("short.exr"), std::string::npos);
}

// The fuzz target's seeds (fuzz/corpus/mip_file) are MIP files this build reads whole, the layers
// included: a seed refused at its version check would leave every mutation of it there, and the
// fuzzer would never reach the levels, the lobes or the checksum.
TEST(MipFile, TheFuzzCorpusSeedsAreFilesOfThisVersion) {
  const std::filesystem::path corpus = std::filesystem::path(SVBRDF_SOURCE_DIR) / "fuzz/corpus/mip_file";
  int files = 0;
  bool layered = false, transmits = false, diffuse = false;
  for (const auto& e : std::filesystem::directory_iterator(corpus)) {
    ++files;
    try {
      const MipData mip = read_mip_file(e.path());
      const bool all = mip.level0.has_coat() && mip.level0.has_sheen() && !mip.level0.plain_specular() &&
                       mip.level0.has_anisotropy();
      layered = layered || all;
      // The lobes' transmission channels (mip_file_channels.h) in a coarse level, beside every other layer's.
      transmits = transmits || (all && mip.level0.has_transmission() && mip.brdf.levels() > 1 &&
                                mip.brdf.level(1).transmission_layer());
      // And the lobes' diffuse transmission channels, likewise.
      diffuse = diffuse || (all && mip.level0.has_diffuse_transmission() && mip.brdf.levels() > 1 &&
                            mip.brdf.level(1).diffuse_transmission_layer());
    } catch (const Error& err) {
      ADD_FAILURE() << err.what();
    }
  }
  EXPECT_GE(files, 3);
  EXPECT_TRUE(layered) << "no seed carries the specular, coat, sheen and anisotropy layers";
  EXPECT_TRUE(transmits) << "no seed carries a thin wall's transmission with the other layers";
  EXPECT_TRUE(diffuse) << "no seed carries a diffuse transmission with the other layers";
}

// Sets the svbrdf:mip_version attribute of every part of a MIP file to `version`, in place: in each
// part's header (OpenEXR's "Technical Introduction": name, type name, size, value, uncompressed) the
// attribute is "svbrdf:mip_version\0int\0", a 4-byte size of 4 and a 4-byte little-endian value.
// Returns how many it patched.
int patch_version(const std::filesystem::path& path, std::int32_t version) {
  std::string bytes = testing::slurp(path);
  const std::string field("svbrdf:mip_version\0int\0\4\0\0\0", 27);
  int patched = 0;
  for (std::size_t at = bytes.find(field); at != std::string::npos; at = bytes.find(field, at + field.size())) {
    std::memcpy(bytes.data() + at + field.size(), &version, 4);
    ++patched;
  }
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  return patched;
}

// A valid MIP file whose version field says one less or one more than this build's is refused, by the
// library and by the programs (exit 2), with one line naming the file, its version, the version this
// build reads and the command that rebuilds it; with the field restored it reads again.
TEST(MipFile, RefusesTheVersionsBeforeAndAfterItsOwnWithTheWayToRebuild) {
  testing::TempDir dir;
  const MipData mip = build_mip(synthetic::tray(8));
  const auto path = dir / "tray.exr";
  write_mip_file(path, mip);
  for (const int version : {kMipFileVersion - 1, kMipFileVersion + 1}) {
    SCOPED_TRACE("version " + std::to_string(version));
    ASSERT_EQ(patch_version(path, version), mip.levels()) << "every part's header holds the version";
    const std::string want = other_version_message(path, version);
    EXPECT_EQ(read_error(path), want);
    EXPECT_EQ(want.find('\n'), std::string::npos);
    const testing::CommandResult r = testing::run_command(
        std::string("'") + SVBRDF_BAKE + "' eval '" + path.string() + "' --level 1 --texel 0 0 --mode brdf", dir.path(),
        "0 0 1 0 0 1\n");
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_NE(r.err.find(want), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  ASSERT_EQ(patch_version(path, kMipFileVersion), mip.levels());
  EXPECT_TRUE(same_bits(read_mip_file(path).brdf.level(1).all_lobes(), mip.brdf.level(1).all_lobes()));
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
// float — what `oiiotool -a -d float` makes of it — and without the attribute `drop` (if named).
void copy_mip_file(const std::filesystem::path& from, const std::filesystem::path& to, bool all_float, const char* drop) {
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

// Copies a MIP file as floats (copy_mip_file's all_float) without channel `name` in subimage `level`.
void copy_without_channel(const std::filesystem::path& from, const std::filesystem::path& to, int level,
                          const std::string& name) {
  std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(from.string());
  ASSERT_TRUE(in);
  std::vector<OIIO::ImageSpec> specs;
  std::vector<std::vector<float>> pixels;
  for (int l = 0; in->seek_subimage(l, 0); ++l) {
    OIIO::ImageSpec s = in->spec();
    const std::size_t texels = std::size_t(s.width) * s.height, n = std::size_t(s.nchannels);
    std::vector<float> px(texels * n);
    ASSERT_TRUE(in->read_image(l, 0, 0, s.nchannels, OIIO::TypeDesc::FLOAT, px.data()));
    const auto it = std::find(s.channelnames.begin(), s.channelnames.end(), name);
    if (l == level && it != s.channelnames.end()) {
      const std::size_t c = std::size_t(it - s.channelnames.begin());
      std::vector<float> kept;
      kept.reserve(texels * (n - 1));
      for (std::size_t t = 0; t < texels; ++t)
        for (std::size_t k = 0; k < n; ++k)
          if (k != c) kept.push_back(px[t * n + k]);
      px = std::move(kept);
      s.channelnames.erase(it);
      s.nchannels -= 1;
    }
    s.set_format(OIIO::TypeDesc::FLOAT), s.channelformats.clear();
    specs.push_back(s);
    pixels.push_back(std::move(px));
  }
  in->close();
  write_levels(to, specs, pixels, OIIO::TypeDesc::FLOAT);
}

// A layer's means are in every level or in none, as level 0 has them: a coarse level without a
// channel of them that level 0 has, or with one that level 0 lacks, is refused naming the level and
// the channel (the specular layer's, the coat's, the sheen's and the anisotropy's alike, one check).
TEST(MipFile, RefusesALayersMeansInSomeLevelsOnly) {
  testing::TempDir dir;
  std::uint64_t seed = 1;
  while (!draw_random_material(seed).sheen_textured) ++seed;
  write_mip_file(dir / "sheen.exr", build_mip(random_material_texels(draw_random_material(seed), 8)));
  copy_without_channel(dir / "sheen.exr", dir / "level1.exr", 1, "param.sheen.R");
  std::string msg = read_error(dir / "level1.exr");
  EXPECT_NE(msg.find("level1.exr"), std::string::npos) << msg;
  EXPECT_NE(msg.find("level 1 has no channel param.sheen.R but level 0 has"), std::string::npos) << msg;
  copy_without_channel(dir / "sheen.exr", dir / "level0.exr", 0, "param.sheen.R");
  msg = read_error(dir / "level0.exr");
  EXPECT_NE(msg.find("level 1 has channel param.sheen.R but level 0 has none"), std::string::npos) << msg;
}

// The radial grid's last node is read from svbrdf:radial_outer (30°); a file without it is refused.
TEST(MipFile, ReadsTheRadialGridsOuterNode) {
  testing::TempDir dir;
  const MipData mip = build_mip(generate_material(MaterialRecipe{"metal-tray", "steel", 32, 24}).texels);
  write_mip_file(dir / "tray.exr", mip);
  EXPECT_EQ(read_mip_file(dir / "tray.exr").brdf.radial_grid().outer_deg, float(RadialGrid::kOuterDeg));
  copy_mip_file(dir / "tray.exr", dir / "noouter.exr", false, "svbrdf:radial_outer");
  const std::string msg = read_error(dir / "noouter.exr");
  EXPECT_NE(msg.find("noouter.exr"), std::string::npos) << msg;
  EXPECT_NE(msg.find("svbrdf:radial_outer is 0.000000, not an angle in degrees"), std::string::npos) << msg;
}

// A lobe's normal decoded from its N.dir code and N.deficit as mip_file.h documents them, independently
// of stored_normal.cpp: signed 16-bit codes q (x low, y high), c = q/32767, the octahedral coordinate
// p = c·(1/16 + (15/16)|c|) (warped; p = c is the plain octahedral code), the lower half folded over
// the diagonals.
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

// The normals' codes read as mip_file.h documents them: warped toward the pole (stored_normal.h). Enough
// of the tray's lobes are off the pole that the warped and the plain octahedral decodings differ.
TEST(MipFile, ReadsNormalCodesAsDocumented) {
  testing::TempDir dir;
  const MipData mip = build_mip(generate_material(MaterialRecipe{"metal-tray", "steel", 32, 24}).texels);
  write_mip_file(dir / "tray.exr", mip);
  const MipData back = read_mip_file(dir / "tray.exr");
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
      const glm::dvec3 n(back.brdf.texel(level, i, j)[0].normal);
      const glm::dvec3 want = documented_normal(code, deficit, true), plain = documented_normal(code, deficit, false);
      ASSERT_LT(glm::length(n - want), 2e-7) << "level " << level << " texel " << t;
      ++compared;
      differ += glm::length(want - plain) > 1e-6;
    }
  });
  EXPECT_GT(compared, 100);
  EXPECT_GT(differ, 0) << "no lobe's normal is off the pole: the two decodings cannot be told apart here";
}

// What fuzzing found (fuzz/regressions/mip_file), each refused from its header before OpenEXR reads
// it, naming the attribute: a second part that states 1.1 GB for an attribute in a file of 2.9 KB,
// which OpenEXR allocated before failing at the end of the file; and a fourth part whose channel list
// runs past its stated size, which OpenEXR reads up to its end anyway and then takes other bytes for
// the next attribute's size (seconds and gigabytes again; its first part's channel list also states a
// pixel type OpenEXR does not define, which is met first); and channels of pixel types OpenEXR does
// not define, on which OpenImageIO aborts instead of refusing.
TEST(MipFile, HeadersThatWouldMakeOpenExrAllocateWhatTheFileStatesAreRefused) {
  const std::filesystem::path dir = std::filesystem::path(SVBRDF_SOURCE_DIR) / "fuzz/regressions/mip_file";
  for (const auto& [file, needle] : {std::pair{"attribute-larger-than-the-file.exr", "states 1148215651 bytes"},
                                     std::pair{"channel-list-past-its-size.exr", "\"channels\" of part 0 (chlist)"},
                                     std::pair{"channel-of-unknown-pixel-type.exr", "(chlist): a channel's pixel type is "}}) {
    SCOPED_TRACE(file);
    try {
      read_mip_file(dir / file);
      ADD_FAILURE() << "read";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("corrupt OpenEXR header: attribute"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_EQ(e.exit_code(), 2);
    }
  }
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
