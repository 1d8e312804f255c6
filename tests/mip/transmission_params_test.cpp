// The parameter pyramid's transmission (mip/param_pyramid.h: the mean T of the covered level-0 texels,
// KHR_materials_transmission thin-walled): level 0 given back as the texels' own floats; the coarse
// means against closed forms; the stored levels' shapes checked; the filters' mean over a footprint;
// level-0 lookups that are the texel's own lobe (exact_reference.h level0_lobe); and the MIP file's
// channel param.transmission and the records' word, each read back bit for bit.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "base/error.h"
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

// A w × h material with a transmission texture T(i, j) = ((i + 2j) mod 5)/4 (0 and 1 among its values)
// over a varied base: colours, dielectrics and metals, roughnesses and tilted normals; `anisotropic`
// adds an anisotropy of strength 0.6 (a layer stored before the transmission).
MaterialTexels transmitting(int w, int h, bool anisotropic = false) {
  MaterialTexels m(w, h);
  if (anisotropic) m.anisotropy_factor = 0.6f, m.anisotropy_direction_factor = glm::vec2(0.6f, 0.8f);
  m.transmission_factor = 1.0f;
  m.transmission.resize(m.size());
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const std::size_t k = m.index(i, j);
      m.base_color[k] = glm::vec3(0.2f + 0.05f * float(i % 7), 0.5f, 0.8f - 0.04f * float(j % 9));
      m.metallic[k] = (i + j) % 3 == 0 ? 1.0f : 0.0f;
      m.roughness[k] = 0.2f + 0.1f * float((i * j) % 6);
      m.normal[k] = glm::normalize(glm::vec3(0.1f * std::sin(float(i)), 0.1f * std::cos(float(j)), 1.0f));
      m.transmission[k] = float((i + 2 * j) % 5) / 4.0f;
    }
  return m;
}

// A uniform dielectric of T(i, j) = `f`(i, j), nothing else varying.
template <class F>
MaterialTexels transmission_texture(int w, int h, const F& f) {
  MaterialTexels m(w, h);
  m.transmission_factor = 1.0f;
  m.transmission.resize(m.size());
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const std::size_t k = m.index(i, j);
      m.base_color[k] = glm::vec3(0.6f, 0.5f, 0.4f), m.roughness[k] = 0.5f;
      m.transmission[k] = f(i, j);
    }
  return m;
}

// Level 0 as MaterialTexels gives back every texel's T as the same float, so its level-0 lobes are the
// original texels' bit for bit (transmission included) and a BRDF build from it is the same build; a
// material whose factor alone transmits gives its factor at every texel; one that does not transmit
// holds no transmission.
TEST(TransmissionParams, Level0TexelsGiveBackTheTexelsTransmission) {
  const MaterialTexels m = transmitting(6, 5);
  const ParamPyramid p = ParamPyramid::level0_only(m);
  ASSERT_TRUE(p.has_transmission());
  const MaterialTexels back = p.level0_texels();
  ASSERT_TRUE(back.has_transmission());
  int transmits = 0;
  for (std::size_t k = 0; k < m.size(); ++k) {
    EXPECT_EQ(std::bit_cast<std::uint32_t>(back.transmission_at(k)), std::bit_cast<std::uint32_t>(m.transmission_at(k)))
        << "texel " << k;
    const Lobe a = level0_lobe(m, k), b = level0_lobe(back, k);
    EXPECT_TRUE(same_bits(a, b)) << "texel " << k;
    transmits += a.transmission.g > 0.0f;
  }
  EXPECT_GT(transmits, 0);
  const MipData from_texels = build_mip(m), from_back = build_mip(back);
  for (int l = 1; l < from_texels.levels(); ++l) {
    const auto a = from_texels.brdf.level(l).all_lobes(), b = from_back.brdf.level(l).all_lobes();
    ASSERT_EQ(a.size(), b.size()) << "level " << l;
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(Lobe)), 0) << "level " << l;
  }

  MaterialTexels factor(3, 2);
  factor.transmission_factor = 0.7f;
  const MaterialTexels factor_back = ParamPyramid::build(factor).level0_texels();
  for (std::size_t k = 0; k < factor.size(); ++k) EXPECT_EQ(factor_back.transmission_at(k), 0.7f);

  const ParamPyramid none = ParamPyramid::build(MaterialTexels(3, 2));
  EXPECT_FALSE(none.has_transmission());
  EXPECT_EQ(none.transmission(1, 0, 0), nullptr);
  EXPECT_TRUE(none.transmission_level(0).empty());
  EXPECT_FALSE(none.level0_texels().has_transmission());
}

// Stored levels (the MIP file's) make a pyramid when the transmission has every level at its size, and
// are refused naming the transmission's level otherwise.
TEST(TransmissionParams, FromLevelsChecksTheTransmissionsShape) {
  const ParamPyramid p = ParamPyramid::build(transmitting(4, 4));
  std::vector<std::vector<ParamTexel>> levels;
  std::vector<std::vector<float>> transmission;
  for (int l = 0; l < p.levels(); ++l) {
    levels.emplace_back(p.level(l).begin(), p.level(l).end());
    transmission.emplace_back(p.transmission_level(l).begin(), p.transmission_level(l).end());
  }
  const ParamPyramid q = ParamPyramid::from_levels(p.level0(), levels, {}, 1.5f, {}, {}, {}, transmission);
  ASSERT_TRUE(q.has_transmission());
  for (int l = 0; l < p.levels(); ++l)
    EXPECT_EQ(std::memcmp(q.transmission_level(l).data(), p.transmission_level(l).data(),
                          p.transmission_level(l).size_bytes()),
              0);
  const auto refused = [&](std::vector<std::vector<float>> t, const std::string& reason) {
    try {
      ParamPyramid::from_levels(p.level0(), levels, {}, 1.5f, {}, {}, {}, std::move(t));
      ADD_FAILURE() << "accepted: " << reason;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
    }
  };
  std::vector<std::vector<float>> short_level = transmission, fewer = transmission;
  short_level[1].pop_back();
  fewer.pop_back();
  refused(short_level, "the transmission's level 1 has the wrong size");
  refused(fewer, "the transmission's level 0 has the wrong size");
}

// A coarse texel's transmission is the mean of its level-0 texels': on 4 × 4 texels of
// T(i, j) = 0.1·i + 0.05·j², texel (a, b) of level 1 holds 0.1·(2a + ½) + 0.05·((2b)² + (2b + 1)²)/2 and
// level 2 holds 0.1·1.5 + 0.05·14/4 = 0.325; on 5 × 3 texels the last level holds 0.1·2 + 0.05·5/3.
// The parameter filters' lobe of a coarse texel transmits its mean as a texel of that T does, through
// the widened shape under toksvig.
TEST(TransmissionParams, CoarseTexelsHoldTheMeanOfTheirTexels) {
  const auto ramp = [](int i, int j) { return 0.1f * float(i) + 0.05f * float(j * j); };
  const ParamPyramid p = ParamPyramid::build(transmission_texture(4, 4, ramp));
  ASSERT_EQ(p.levels(), 3);
  ASSERT_TRUE(p.has_transmission());
  for (int b = 0; b < 2; ++b)
    for (int a = 0; a < 2; ++a)
      EXPECT_NEAR(*p.transmission(1, a, b), 0.1 * (2 * a + 0.5) + 0.05 * ((2 * b) * (2 * b) + (2 * b + 1) * (2 * b + 1)) / 2.0,
                  1e-6)
          << a << " " << b;
  EXPECT_NEAR(*p.transmission(2, 0, 0), 0.325, 1e-6);
  const ParamPyramid odd = ParamPyramid::build(transmission_texture(5, 3, ramp));
  EXPECT_NEAR(*odd.transmission(odd.levels() - 1, 0, 0), 0.2 + 0.05 * 5.0 / 3.0, 1e-6);

  const ParamTexel& t = p.texel(2, 0, 0);
  const float mean = *p.transmission(2, 0, 0);
  const Lobe got = param_lobes(t, TextureFilter::param, {}, nullptr, nullptr, nullptr, mean).base;
  const Lobe want = lobe_from_texel(t.base_color, t.metallic, t.roughness, glm::normalize(t.normal), 1.0f, {}, {}, mean);
  EXPECT_GT(want.transmission.r, 0.0f);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got.transmission[c], want.transmission[c], 1e-6f);
  EXPECT_EQ(got.transmission_alpha2, want.transmission_alpha2);
  EXPECT_EQ(param_lobes(t, TextureFilter::param, {}, nullptr).base.transmission, glm::vec3(0.0f));
  ParamTexel spread = t;
  spread.normal = glm::vec3(0.0f, 0.3f, 0.8f);
  const Lobe widened = param_lobe(spread, TextureFilter::toksvig, {}, {}, mean);
  EXPECT_GT(widened.alpha2, want.alpha2);
  EXPECT_EQ(widened.transmission_alpha2, widened.alpha2);
}

// The filters' mean transmission over a footprint: T linear in u, T = 0.2 + 0.6·u on 16 × 16 texels,
// which the box means keep linear at every level and the bilinear taps and the probes along the axis
// average back to 0.2 + 0.6·u at the footprint's centre (2 probes between levels 1 and 2, away from the
// edges);
// a footprint past the last level holds the mean of all texels, 0.5. The parameter filter's lookup
// shades a texel of that T (mip.cpp), and a material without a transmission filters to 0.
TEST(TransmissionParams, TheFiltersAverageTheTransmission) {
  const MaterialTexels m = transmission_texture(16, 16, [](int i, int) { return 0.2f + 0.6f * (float(i) + 0.5f) / 16.0f; });
  const ParamPyramid p = ParamPyramid::build(m);
  const Footprint f{{0.4f, 0.55f}, {6.0f / 16, 0.0f}, {0.0f, 3.0f / 16}};
  float t = -1.0f;
  filter_params(p, f, {}, kMaxProbes, nullptr, nullptr, nullptr, nullptr, &t);
  EXPECT_NEAR(t, 0.2 + 0.6 * 0.4, 1e-6);
  filter_params(p, {{0.4f, 0.55f}, {100.0f, 0.0f}, {0.0f, 100.0f}}, {}, kMaxProbes, nullptr, nullptr, nullptr,
                nullptr, &t);
  EXPECT_NEAR(t, 0.5, 1e-6);
  filter_params(ParamPyramid::build(MaterialTexels(4, 4)), f, {}, kMaxProbes, nullptr, nullptr, nullptr, nullptr, &t);
  EXPECT_EQ(t, 0.0f);

  MipTexture texture(m, WrapMode::repeat, WrapMode::repeat, TextureFilter::param);
  MipTexture::Scratch scratch;
  const MipTexture::Choice c = texture.choose(TextureFilter::param, f, Rgb(1.0f), 0.5f);
  ASSERT_EQ(c.level, -1);
  const Lobe got = texture.lobes(c, scratch)[0];
  const Lobe want = lobe_from_texel(glm::vec3(0.6f, 0.5f, 0.4f), 0.0f, 0.5f, glm::vec3(0, 0, 1), 1.0f, {}, {}, 0.44f);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(got.transmission[k], want.transmission[k], 1e-5f);
  EXPECT_NEAR(got.transmission_alpha2, want.transmission_alpha2, 1e-6f);
}

// A level-0 lookup of a transmitting texel is its level-0 lobe (exact_reference.h level0_lobe), bit for
// bit: the level0 filter's nearest texel, and the brdf filter's level-0 taps.
TEST(TransmissionParams, ALevel0LookupIsTheTexelsLevel0Lobe) {
  const MaterialTexels m = transmitting(8, 8);
  const MipTexture texture(m, WrapMode::repeat, WrapMode::repeat, TextureFilter::brdf);
  int transmits = 0, brdf = 0;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) {
      const Footprint f{{(float(i) + 0.5f) / 8, (float(j) + 0.5f) / 8}, {1e-3f, 0}, {0, 1e-3f}};
      for (const TextureFilter filter : {TextureFilter::level0, TextureFilter::brdf}) {
        MipTexture::Scratch scratch;
        const MipTexture::Choice c = texture.choose(filter, f, Rgb(1.0f), 0.37f);
        ASSERT_EQ(c.level, 0);
        brdf += filter == TextureFilter::brdf;
        const std::span<const Lobe> lobes = texture.lobes(c, scratch);
        ASSERT_EQ(lobes.size(), 1u);
        const Lobe want = level0_lobe(m, m.index(c.i, c.j));
        EXPECT_TRUE(same_bits(lobes[0], want)) << filter_name(filter) << " texel " << c.i << " " << c.j;
        transmits += want.transmission.g > 0.0f;
      }
    }
  EXPECT_GT(transmits, 0);
  EXPECT_GT(brdf, 0);
}

// The MIP file carries the parameter pyramid's transmission in param.transmission, every level, read
// back bit for bit with the parameters, and level 0's texels transmit as before the trip. (The lobes'
// own transmission is the BRDF pyramid's, not compared here.) The parameter filters count its float
// in a texel's bytes.
TEST(TransmissionParams, TheMipFileCarriesTheMeans) {
  testing::TempDir dir;
  for (const int size : {8, 6}) {
    SCOPED_TRACE("size " + std::to_string(size));
    const MaterialTexels m = transmitting(size, size, true);
    const MipData a = build_mip(m);
    // A parameter texel's bytes: the parameters' 8 floats, the anisotropy's 3 and the transmission's 1.
    EXPECT_EQ(bytes_per_texel(a, TextureFilter::param, 1), (8 + 3 + 1) * 4);
    const auto path = dir / ("transmission" + std::to_string(size) + ".exr");
    write_mip_file(path, a);
    const MipData b = read_mip_file(path);
    ASSERT_TRUE(b.param.has_transmission());
    ASSERT_EQ(b.levels(), a.levels());
    for (int l = 0; l < a.levels(); ++l) {
      const auto ta = a.param.transmission_level(l), tb = b.param.transmission_level(l);
      ASSERT_EQ(ta.size(), tb.size());
      EXPECT_EQ(std::memcmp(ta.data(), tb.data(), ta.size_bytes()), 0) << "level " << l;
      const auto pa = a.param.level(l), pb = b.param.level(l);
      EXPECT_EQ(std::memcmp(pa.data(), pb.data(), pa.size_bytes()), 0) << "level " << l;
    }
    ASSERT_TRUE(b.level0.has_transmission());
    for (std::size_t k = 0; k < m.size(); ++k) EXPECT_TRUE(same_bits(level0_lobe(m, k), level0_lobe(b.level0, k)));
  }
}

// The records hold the transmission's mean in one word after the parameters' 8 and the anisotropy's 3,
// which the layout's text names and parse reads back; a texture read from them answers the parameter
// filters' and level 0's lookups with the lobes of the texture in memory, bit for bit.
TEST(TransmissionParams, TheRecordsCarryTheMeans) {
  const MaterialTexels m = transmitting(12, 10, true);
  const MipTexture memory(m, WrapMode::repeat, WrapMode::mirrored_repeat, TextureFilter::param);
  const MipRecordLayout layout = memory.record_layout();
  ASSERT_TRUE(layout.transmission);
  EXPECT_EQ(layout.param_words(), 8 + 3 + 1);
  const std::string key(64, 'a'), text = layout.describe(key);
  EXPECT_NE(text.find(" transmission 1 "), std::string::npos) << text;
  std::string why;
  const std::optional<MipRecordLayout> parsed = MipRecordLayout::parse(text, key, &why);
  ASSERT_TRUE(parsed) << why;
  EXPECT_TRUE(parsed->transmission);
  EXPECT_EQ(parsed->describe(key), text);
  const MipTexture records(*parsed, std::make_unique<testing_records::Records>(memory, *parsed), WrapMode::repeat,
                           WrapMode::mirrored_repeat);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  int transmits = 0;
  for (int n = 0; n < 400; ++n) {
    const float scale = std::exp2(-6.0f + 6.0f * u01(rng));
    const Footprint f{{u01(rng), u01(rng)}, {scale, 0.2f * scale * u01(rng)}, {0.0f, scale}};
    const Rgb tint = n % 2 ? Rgb(0.9f, 0.5f, 0.7f) : Rgb(1.0f);
    for (const TextureFilter filter : {TextureFilter::level0, TextureFilter::param, TextureFilter::toksvig}) {
      MipTexture::Scratch sa, sb;
      const std::span<const Lobe> a = memory.lobes(memory.choose(filter, f, tint, 0.5f), sa),
                                  b = records.lobes(records.choose(filter, f, tint, 0.5f), sb);
      ASSERT_EQ(a.size(), b.size());
      ASSERT_TRUE(same_bits(a[0], b[0])) << filter_name(filter) << " lookup " << n;
      transmits += a[0].transmission.g > 0.0f;
    }
  }
  EXPECT_GT(transmits, 600);
}

}  // namespace
}  // namespace svbrdf
