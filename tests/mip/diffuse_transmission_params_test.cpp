// The parameter pyramid's diffuse transmission (mip/param_pyramid.h: the mean share of the covered level-0
// texels and their share-weighted mean colour, KHR_materials_diffuse_transmission): level 0 given back as
// the texels' own floats; the coarse means against closed forms; the filters' mean over a footprint;
// level-0 lookups that are the texel's own lobe (exact_reference.h level0_lobe); and the MIP file's
// channels param.diffuseTransmission* and the records' words, each read back bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "mip/diffuse_transmission.h"
#include "mip/exact_reference.h"
#include "mip/mip.h"
#include "mip/mip_file.h"
#include "mip/mip_lookup.h"
#include "mip/mip_records.h"
#include "mip/param_pyramid.h"
#include "tests/common/temp_dir.h"
#include "tests/mip/memory_records.h"

namespace svbrdf {
namespace {

bool same_bits(const Lobe& a, const Lobe& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// A w × h dielectric (metallic 0, plain layer, no transmission) of diffuse transmission share d(i, j) and
// colour C(i, j); `varied` gives it colours, metals, roughnesses, normals, a transmission and a specular
// layer too, so every factor of τd (diffuse_transmission.h) varies.
template <class D, class C>
MaterialTexels diffuse_texture(int w, int h, const D& d, const C& c, bool varied = false) {
  MaterialTexels m(w, h);
  m.diffuse_transmission_factor = 1.0f;
  m.diffuse_transmission.resize(m.size());
  m.diffuse_transmission_color.resize(m.size());
  if (varied) {
    m.transmission_factor = 1.0f, m.transmission.resize(m.size());
    m.ior = 1.4f, m.specular.assign(m.size(), 0.7f), m.specular_color.assign(m.size(), glm::vec3(1.0f, 0.9f, 0.8f));
  }
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const std::size_t k = m.index(i, j);
      m.base_color[k] = glm::vec3(0.6f, 0.5f, 0.4f), m.roughness[k] = 0.5f;
      m.diffuse_transmission[k] = d(i, j), m.diffuse_transmission_color[k] = c(i, j);
      if (varied) {
        m.base_color[k] = glm::vec3(0.2f + 0.05f * float(i % 7), 0.5f, 0.8f - 0.04f * float(j % 9));
        m.metallic[k] = (i + j) % 3 == 0 ? 0.5f : 0.0f;
        m.roughness[k] = 0.2f + 0.1f * float((i * j) % 6);
        m.normal[k] = glm::normalize(glm::vec3(0.1f * std::sin(float(i)), 0.1f * std::cos(float(j)), 1.0f));
        m.transmission[k] = float((i + 2 * j) % 3) / 4.0f;
      }
    }
  return m;
}
float ramp(int i, int j) { return 0.1f * float(i) + 0.05f * float(j * j); }
glm::vec3 rainbow(int i, int j) { return {0.2f + 0.2f * float(i % 4), 0.9f - 0.1f * float(j), 0.5f}; }
MaterialTexels varied(int w, int h) {
  return diffuse_texture(w, h, [](int i, int j) { return float((i + 2 * j) % 5) / 4.0f; }, rainbow, true);
}

// Level 0 as MaterialTexels gives back every texel's share and colour as the same floats, so its level-0
// lobes are the original texels' bit for bit; a material without one holds none.
TEST(DiffuseTransmissionParams, Level0TexelsGiveBackTheTexelsDiffuseTransmission) {
  const MaterialTexels m = varied(6, 5);
  const ParamPyramid p = ParamPyramid::level0_only(m);
  ASSERT_TRUE(p.has_diffuse_transmission());
  const MaterialTexels back = p.level0_texels();
  ASSERT_TRUE(back.has_diffuse_transmission());
  int transmits = 0;
  for (std::size_t k = 0; k < m.size(); ++k) {
    const DiffuseTransmissionLayer a = m.diffuse_transmission_layer(k), b = back.diffuse_transmission_layer(k);
    EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << "texel " << k;
    const Lobe la = level0_lobe(m, k), lb = level0_lobe(back, k);
    EXPECT_TRUE(same_bits(la, lb)) << "texel " << k;
    transmits += diffuse_transmits(la);
  }
  EXPECT_GT(transmits, 0);
  const ParamPyramid none = ParamPyramid::build(MaterialTexels(3, 2));
  EXPECT_FALSE(none.has_diffuse_transmission());
  EXPECT_EQ(none.diffuse_transmission(1, 0, 0), nullptr);
  EXPECT_FALSE(none.level0_texels().has_diffuse_transmission());
}

// A coarse texel's share is the mean of its texels' and its colour their share-weighted mean, so that
// on a plain dielectric the parameter filters' lobe transmits τd = 0.96·mean(d·C) exactly
// (diffuse_transmission.h: τd = (1 − m)·(1 − T)·d·0.96·C): on 4 × 4 texels of d = 0.1·i + 0.05·j² and
// C(i, j) = rainbow, checked at levels 1 and 2 against the sums over the covered texels. A texel whose
// children have no share holds share 0 and white.
TEST(DiffuseTransmissionParams, CoarseTexelsHoldTheShareWeightedMean) {
  const ParamPyramid p = ParamPyramid::build(diffuse_texture(4, 4, ramp, rainbow));
  ASSERT_EQ(p.levels(), 3);
  for (int level = 1; level <= 2; ++level) {
    const int n = 1 << level;
    for (int b = 0; b < 4 / n; ++b)
      for (int a = 0; a < 4 / n; ++a) {
        double share = 0;
        glm::dvec3 dc(0);
        for (int j = b * n; j < (b + 1) * n; ++j)
          for (int i = a * n; i < (a + 1) * n; ++i) share += ramp(i, j), dc += double(ramp(i, j)) * glm::dvec3(rainbow(i, j));
        share /= n * n, dc /= n * n;
        const DiffuseTransmissionLayer& d = *p.diffuse_transmission(level, a, b);
        EXPECT_NEAR(d.share, share, 1e-6) << level << " " << a << " " << b;
        const Lobe l = param_lobes(p.texel(level, a, b), TextureFilter::param, {}, nullptr, nullptr, nullptr, 0.0f,
                                   p.diffuse_transmission(level, a, b))
                           .base;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(l.diffuse_transmission[c], 0.96 * dc[c], 1e-6) << level << " " << c;
        EXPECT_EQ(l.diffuse_transmission90, glm::vec3(0.0f));
      }
  }
  const ParamPyramid dark = ParamPyramid::build(diffuse_texture(2, 2, [](int, int) { return 0.0f; }, rainbow));
  EXPECT_EQ(dark.diffuse_transmission(1, 0, 0)->share, 0.0f);
  EXPECT_EQ(dark.diffuse_transmission(1, 0, 0)->color, glm::vec3(1.0f));
}

// The filters' mean over a footprint: d = 0.2 + 0.6·u of one colour on 16 × 16 texels averages back to
// 0.2 + 0.6·u at the footprint's centre (as the transmission's, transmission_params_test.cpp), its colour
// that colour; the parameter filter's lookup shades a texel of that mean (mip.cpp); a material without
// one filters to share 0.
TEST(DiffuseTransmissionParams, TheFiltersAverageTheDiffuseTransmission) {
  const glm::vec3 color(0.8f, 0.3f, 0.6f);
  const MaterialTexels m = diffuse_texture(
      16, 16, [](int i, int) { return 0.2f + 0.6f * (float(i) + 0.5f) / 16.0f; }, [&](int, int) { return color; });
  const ParamPyramid p = ParamPyramid::build(m);
  const Footprint f{{0.4f, 0.55f}, {6.0f / 16, 0.0f}, {0.0f, 3.0f / 16}};
  DiffuseTransmissionLayer d;
  filter_params(p, f, {}, kMaxProbes, nullptr, nullptr, nullptr, nullptr, nullptr, &d);
  EXPECT_NEAR(d.share, 0.2 + 0.6 * 0.4, 1e-6);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(d.color[c], color[c], 1e-6);
  filter_params(ParamPyramid::build(MaterialTexels(4, 4)), f, {}, kMaxProbes, nullptr, nullptr, nullptr, nullptr,
                nullptr, &d);
  EXPECT_EQ(d.share, 0.0f);

  MipTexture texture(m, WrapMode::repeat, WrapMode::repeat, TextureFilter::param);
  MipTexture::Scratch scratch;
  const MipTexture::Choice c = texture.choose(TextureFilter::param, f, Rgb(1.0f), 0.5f);
  ASSERT_EQ(c.level, -1);
  const Lobe got = texture.lobes(c, scratch)[0];
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(got.diffuse_transmission[k], 0.96 * 0.44 * color[k], 1e-5);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(got.diffuse[k], (1.0 - 0.44) * (0.6 - 0.1 * k), 1e-5);
}

// A level-0 lookup of a diffusely transmitting texel is its level-0 lobe, bit for bit: the level0
// filter's nearest texel and the brdf filter's level-0 taps.
TEST(DiffuseTransmissionParams, ALevel0LookupIsTheTexelsLevel0Lobe) {
  const MaterialTexels m = varied(8, 8);
  const MipTexture texture(m, WrapMode::repeat, WrapMode::repeat, TextureFilter::brdf);
  int transmits = 0;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) {
      const Footprint f{{(float(i) + 0.5f) / 8, (float(j) + 0.5f) / 8}, {1e-3f, 0}, {0, 1e-3f}};
      for (const TextureFilter filter : {TextureFilter::level0, TextureFilter::brdf}) {
        MipTexture::Scratch scratch;
        const MipTexture::Choice c = texture.choose(filter, f, Rgb(1.0f), 0.37f);
        ASSERT_EQ(c.level, 0);
        const std::span<const Lobe> lobes = texture.lobes(c, scratch);
        ASSERT_EQ(lobes.size(), 1u);
        const Lobe want = level0_lobe(m, m.index(c.i, c.j));
        EXPECT_TRUE(same_bits(lobes[0], want)) << filter_name(filter) << " texel " << c.i << " " << c.j;
        transmits += diffuse_transmits(want);
      }
    }
  EXPECT_GT(transmits, 0);
}

// The MIP file carries the means in param.diffuseTransmission and .R/G/B, every level, read back bit for
// bit, and level 0's texels transmit as before the trip; a parameter texel counts their 16 bytes.
TEST(DiffuseTransmissionParams, TheMipFileCarriesTheMeans) {
  testing::TempDir dir;
  const MaterialTexels m = varied(8, 6);
  const MipData a = build_mip(m);
  EXPECT_EQ(bytes_per_texel(a, TextureFilter::param, 1), (8 + 4 + 1 + 4) * 4);  // parameters, specular, T, d and C
  const auto path = dir / "diffuse.exr";
  write_mip_file(path, a);
  const MipData b = read_mip_file(path);
  ASSERT_TRUE(b.param.has_diffuse_transmission());
  ASSERT_EQ(b.levels(), a.levels());
  for (int l = 0; l < a.levels(); ++l) {
    const auto da = a.param.diffuse_transmission_level(l), db = b.param.diffuse_transmission_level(l);
    ASSERT_EQ(da.size(), db.size());
    EXPECT_EQ(std::memcmp(da.data(), db.data(), da.size_bytes()), 0) << "level " << l;
  }
  ASSERT_TRUE(b.level0.has_diffuse_transmission());
  for (std::size_t k = 0; k < m.size(); ++k) EXPECT_TRUE(same_bits(level0_lobe(m, k), level0_lobe(b.level0, k)));
}

// The records hold the means in four words after the transmission's, which the layout's text names and
// parse reads back; a texture read from them answers the parameter filters' and level 0's lookups with
// the lobes of the texture in memory, bit for bit.
TEST(DiffuseTransmissionParams, TheRecordsCarryTheMeans) {
  const MaterialTexels m = varied(12, 10);
  const MipTexture memory(m, WrapMode::repeat, WrapMode::mirrored_repeat, TextureFilter::param);
  const MipRecordLayout layout = memory.record_layout();
  ASSERT_TRUE(layout.diffuse_transmission);
  EXPECT_EQ(layout.param_words(), 8 + 4 + 1 + 4);
  const std::string key(64, 'a'), text = layout.describe(key);
  EXPECT_NE(text.find(" diffuse_transmission 1 "), std::string::npos) << text;
  std::string why;
  const std::optional<MipRecordLayout> parsed = MipRecordLayout::parse(text, key, &why);
  ASSERT_TRUE(parsed) << why;
  EXPECT_TRUE(parsed->diffuse_transmission);
  const MipTexture records(*parsed, std::make_unique<testing_records::Records>(memory, *parsed), WrapMode::repeat,
                           WrapMode::mirrored_repeat);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  int transmits = 0;
  for (int n = 0; n < 400; ++n) {
    const float scale = std::exp2(-6.0f + 6.0f * u01(rng));
    const Footprint f{{u01(rng), u01(rng)}, {scale, 0.2f * scale * u01(rng)}, {0.0f, scale}};
    for (const TextureFilter filter : {TextureFilter::level0, TextureFilter::param, TextureFilter::toksvig}) {
      MipTexture::Scratch sa, sb;
      const std::span<const Lobe> a = memory.lobes(memory.choose(filter, f, Rgb(1.0f), 0.5f), sa),
                                  b = records.lobes(records.choose(filter, f, Rgb(1.0f), 0.5f), sb);
      ASSERT_EQ(a.size(), b.size());
      ASSERT_TRUE(same_bits(a[0], b[0])) << filter_name(filter) << " lookup " << n;
      transmits += diffuse_transmits(a[0]);
    }
  }
  EXPECT_GT(transmits, 600);
}

}  // namespace
}  // namespace svbrdf
