// The MIP data as records (mip/mip_records.h): a texture that reads its texels from records answers
// every lookup as the texture in memory that wrote them, bit for bit (the records hold the
// pyramids' values: their floats and the MIP file's codes, to which the build rounds its lobes); the
// layout's text round-trips and parse refuses what is not one; a record that holds garbage reads
// nothing outside itself.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "mip/mip.h"
#include "mip/mip_records.h"
#include "tests/mip/memory_records.h"
#include "textures/random_material.h"

namespace svbrdf {
namespace {

using testing_records::Records;

// A random-family material with a textured sheen, given a specular layer, a patchy clear coat, a
// transmission and a diffuse transmission (formulas of the texel index), so every part of a record is
// exercised.
MaterialTexels layered(int size) {
  std::uint64_t seed = 1;
  while (!draw_random_material(seed).sheen_textured || !draw_random_material(seed).anisotropy_textured) ++seed;
  MaterialTexels m = random_material_texels(draw_random_material(seed), size);
  m.specular.resize(m.size());
  m.specular_color.resize(m.size());
  m.clearcoat.resize(m.size());
  m.clearcoat_roughness.resize(m.size());
  m.clearcoat_normal.resize(m.size());
  m.clearcoat_factor = 1.0f;
  m.ior = 1.45f;
  for (std::size_t k = 0; k < m.size(); ++k) {
    m.specular[k] = 0.5f + 0.5f * float(k % 3) / 2.0f;
    m.specular_color[k] = glm::vec3(1.0f, 0.8f + 0.1f * float(k % 2), 0.9f);
    m.clearcoat[k] = (k / 5) % 2 ? 1.0f : 0.3f;
    m.clearcoat_roughness[k] = (k / 7) % 2 ? 0.05f : 0.3f;
    const float a = 0.2f * std::sin(float(k));
    m.clearcoat_normal[k] = glm::normalize(glm::vec3(a, -0.5f * a, 1.0f));
  }
  // A thin-walled transmission in stripes (its τ90 ≠ 0 under the specular layer above), on a base at most
  // half metal (a metal transmits nothing).
  m.transmission_factor = 1.0f;
  m.transmission.resize(m.size());
  for (std::size_t k = 0; k < m.size(); ++k) m.transmission[k] = (k / 4) % 2 ? 0.8f : 0.0f, m.metallic[k] *= 0.5f;
  // A diffuse transmission in stripes across the transmission's (its τd90 ≠ 0 under the specular layer).
  m.diffuse_transmission_factor = 1.0f;
  m.diffuse_transmission.resize(m.size());
  m.diffuse_transmission_color.resize(m.size());
  for (std::size_t k = 0; k < m.size(); ++k) {
    m.diffuse_transmission[k] = (k / 3) % 3 == 0 ? 0.0f : 0.3f * float((k / 3) % 3);
    m.diffuse_transmission_color[k] = glm::vec3(0.9f, 0.4f + 0.2f * float(k % 2), 0.6f);
  }
  return m;
}

bool same_lobes(std::span<const Lobe> a, std::span<const Lobe> b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size_bytes()) == 0);
}

// Lookups of both textures at random footprints, with and without a tint: the same lobes, coat lobes
// and sheen, and the same mixture's value.
void expect_same_lookups(const MipTexture& memory, const MipTexture& records, bool tint) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  int coarse = 0;
  for (int n = 0; n < 3000; ++n) {
    const float scale = std::exp2(-8.0f + 9.0f * u01(rng));
    Footprint f{{2.0f * u01(rng) - 0.5f, 2.0f * u01(rng) - 0.5f},
                {scale, 0.3f * scale * u01(rng)},
                {0.0f, scale * (0.2f + u01(rng))}};
    const Rgb t = tint && n % 2 ? Rgb(0.9f, 0.5f, 0.7f) : Rgb(1.0f);
    const float u = u01(rng);
    for (const TextureFilter filter : {TextureFilter::level0, TextureFilter::param, TextureFilter::toksvig,
                                       TextureFilter::vmf, TextureFilter::brdf}) {
      SCOPED_TRACE(std::string(filter_name(filter)) + " lookup " + std::to_string(n));
      const MipTexture::Choice a = memory.choose(filter, f, t, u), b = records.choose(filter, f, t, u);
      ASSERT_EQ(a.level, b.level);
      ASSERT_EQ(a.i, b.i);
      ASSERT_EQ(a.j, b.j);
      coarse += a.level >= 1;
      MipTexture::Scratch sa, sb;
      ASSERT_TRUE(same_lobes(memory.lobes(a, sa), records.lobes(b, sb)));
      ASSERT_TRUE(same_lobes(memory.coat(a, sa), records.coat(b, sb)));
      const SheenLayer *ha = memory.sheen(a, sa), *hb = records.sheen(b, sb);
      ASSERT_EQ(ha == nullptr, hb == nullptr);
      if (ha) {
        ASSERT_EQ(std::memcmp(ha, hb, sizeof *ha), 0);
      }
      LobeMixtureBsdf ma, mb;
      memory.lookup(a, ma);
      records.lookup(b, mb);
      const glm::vec3 wi = glm::normalize(glm::vec3(0.3f, -0.2f, 0.9f)),
                      wo = glm::normalize(glm::vec3(-0.1f, 0.1f, 0.8f));
      const Rgb ea = ma.eval(wi, wo), eb = mb.eval(wi, wo);
      ASSERT_EQ(std::memcmp(&ea, &eb, sizeof ea), 0);
      const Rgb ca = memory.base_color(filter, f), cb = records.base_color(filter, f);
      ASSERT_EQ(std::memcmp(&ca, &cb, sizeof ca), 0);
    }
  }
  EXPECT_GT(coarse, 1000);  // the BRDF pyramid's records were read, not only level 0's
}

TEST(MipRecords, LookupsEqualTheTextureInMemoryBitForBit) {
  for (const int size : {32, 24}) {
    SCOPED_TRACE("size " + std::to_string(size));
    const MaterialTexels m = layered(size);
    for (const bool tint : {false, true}) {
      MipTexture memory(m, WrapMode::repeat, WrapMode::mirrored_repeat, TextureFilter::brdf, tint);
      memory.prepare(TextureFilter::param);
      const MipRecordLayout layout = memory.record_layout();
      ASSERT_TRUE(layout.brdf && layout.coat && layout.sheen && layout.specular);
      ASSERT_TRUE(layout.level[1].lobe_transmission && layout.level[1].lobe_transmission90);
      ASSERT_TRUE(layout.level[1].lobe_diffuse_transmission && layout.level[1].lobe_diffuse_transmission90);
      ASSERT_EQ(layout.tint, tint);
      const MipTexture records(layout, std::make_unique<Records>(memory, layout), WrapMode::repeat,
                               WrapMode::mirrored_repeat);
      EXPECT_TRUE(records.prepared(TextureFilter::brdf));
      EXPECT_EQ(records.tintable(), tint);
      expect_same_lookups(memory, records, tint);
    }
  }
}

// A plain material's texture built for the parameter filters alone: records without the BRDF
// pyramid's, which serve level0 and the parameter filters and say that brdf is not prepared.
TEST(MipRecords, TheParameterPyramidAloneServesTheParameterFilters) {
  const MaterialTexels m = random_material_texels(draw_random_material(3), 20);
  const MipTexture memory(m, WrapMode::clamp_to_edge, WrapMode::repeat, TextureFilter::param);
  const MipRecordLayout layout = memory.record_layout();
  EXPECT_FALSE(layout.brdf);
  const MipTexture records(layout, std::make_unique<Records>(memory, layout), WrapMode::clamp_to_edge,
                           WrapMode::repeat);
  EXPECT_FALSE(records.prepared(TextureFilter::brdf));
  EXPECT_TRUE(records.prepared(TextureFilter::vmf));
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  for (int n = 0; n < 500; ++n) {
    const float scale = std::exp2(-6.0f + 6.0f * u01(rng));
    const Footprint f{{u01(rng), u01(rng)}, {scale, 0.0f}, {0.0f, scale}};
    for (const TextureFilter filter : {TextureFilter::level0, TextureFilter::param, TextureFilter::toksvig}) {
      MipTexture::Scratch sa, sb;
      ASSERT_TRUE(same_lobes(memory.lobes(memory.choose(filter, f, Rgb(1.0f), 0.5f), sa),
                             records.lobes(records.choose(filter, f, Rgb(1.0f), 0.5f), sb)));
    }
  }
}

TEST(MipRecords, TheLayoutsTextRoundTripsAndParseRefusesOthers) {
  const MaterialTexels m = layered(16);
  MipTexture memory(m, WrapMode::repeat, WrapMode::repeat, TextureFilter::brdf);
  memory.prepare(TextureFilter::param);
  const MipRecordLayout a = memory.record_layout();
  const std::string key(64, 'a'), text = a.describe(key);
  std::string why;
  const std::optional<MipRecordLayout> b = MipRecordLayout::parse(text, key, &why);
  ASSERT_TRUE(b) << why;
  EXPECT_EQ(b->describe(key), text);
  for (int l = 0; l < a.levels; ++l) EXPECT_EQ(b->words(l), a.words(l)) << "level " << l;
  // Another key, another format, levels that do not form the pyramid, slots past kMaxLobes, a level
  // missing or one too many: each refused with its reason.
  const auto refused = [&](const std::string& t, const std::string& k, const std::string& reason) {
    std::string w;
    EXPECT_FALSE(MipRecordLayout::parse(t, k, &w)) << t;
    EXPECT_NE(w.find(reason), std::string::npos) << w;
  };
  refused(text, std::string(64, 'b'), "another key");
  refused("svbrdf mip records 1" + text.substr(20), key, "not a MIP record layout");
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    t.replace(t.find(from), from.size(), to);
    return t;
  };
  refused(replaced(" levels 5 ", " levels 6 "), key, "do not form a pyramid");
  refused(replaced(" level 0 0 ", " level 9 0 "), key, "slots it cannot have");
  refused(text.substr(0, text.rfind(" level ")), key, "fewer levels");
  refused(text + " level 1 1 0 0 0 0", key, "more levels");
}

// A record whose counts are garbage reads its own slots and no further.
TEST(MipRecords, GarbageCountsReadNoFurtherThanTheSlots) {
  const MaterialTexels m = layered(16);
  MipTexture memory(m, WrapMode::repeat, WrapMode::repeat, TextureFilter::brdf);
  memory.prepare(TextureFilter::param);
  const MipRecordLayout layout = memory.record_layout();
  Records records(memory, layout);
  const int l = 1;
  std::vector<std::uint32_t> one(records.levels_[l].begin(), records.levels_[l].begin() + layout.words(l));
  one[std::size_t(layout.param_words())] = 0xFFFFFFFFu;
  Lobe lobes[kMaxLobes], coat[kMaxLobes];
  RadialCorrection correction;
  const RecordTexel t = decode_brdf(layout, l, one.data(), lobes, coat, correction);
  EXPECT_EQ(t.lobes, layout.level[l].slots);
  EXPECT_EQ(t.coat_lobes, layout.level[l].coat_slots);
}

}  // namespace
}  // namespace svbrdf
