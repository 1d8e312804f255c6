// A diffuse transmission (KHR_materials_diffuse_transmission, mip/diffuse_transmission.h) through the MIP
// file (mip/mip_file.h): every lobe's τd and τd90 read back bit for bit (the build rounds them to the
// file's halves, stored_lobe.h), in the channels the file lists, only in the levels that carry them, and
// counted in the texels' bytes; the texels transmit as before the trip. A material without one stores no
// channel of it.
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <cstring>
#include <string>
#include <vector>

#include "mip/diffuse_transmission.h"
#include "mip/lobe_mixture_bsdf.h"
#include "mip/mip_file.h"
#include "mip/mip_records.h"
#include "mip/stored_lobe.h"
#include "tests/common/temp_dir.h"
#include "tests/mip/diffuse_transmission_materials.h"
#include "tests/mip/file_channels.h"

namespace svbrdf {
namespace {

using testing_files::channels_of;
using testing_files::Channels;
using testing_files::expect_same_texel_value;
using testing_materials::diffusely_transmitting;

// The layer's material of seed 6 with, where `layered`, a specular layer that is not plain (so τd90 ≠ 0),
// and, where `thin`, a thin-walled transmission beside it (the two share nothing in the file), none
// otherwise (not the family's own either).
MaterialTexels material(bool layered, bool thin) {
  MaterialTexels m = diffusely_transmitting(6, 16, thin);
  if (!thin) m.transmission_factor = 0.0f, m.transmission.clear();
  if (layered) {
    m.ior = 1.4f;
    m.specular.assign(m.size(), 0.6f);
    m.specular_color.assign(m.size(), glm::vec3(1.0f, 0.9f, 0.8f));
  }
  return m;
}

TEST(DiffuseTransmissionStorage, TheMipFileCarriesTheLobesDiffuseTransmissionBitForBit) {
  testing::TempDir dir;
  for (const int variant : {0, 1, 2}) {
    const bool layered = variant >= 1, thin = variant == 2;
    SCOPED_TRACE(thin ? "with a thin wall" : layered ? "specular layer" : "plain layer");
    const MipData a = build_mip(material(layered, thin));
    const auto path = dir / ("variant" + std::to_string(variant) + ".exr");
    write_mip_file(path, a);
    const MipData b = read_mip_file(path);
    ASSERT_EQ(b.levels(), a.levels());
    int transmitting_lobes = 0, with_t90 = 0;
    for (int l = 1; l < a.levels(); ++l) {
      SCOPED_TRACE("level " + std::to_string(l));
      const BrdfLevel& level = a.brdf.level(l);
      const std::vector<Lobe> la = level.all_lobes(), lb = b.brdf.level(l).all_lobes();
      ASSERT_EQ(la.size(), lb.size());
      EXPECT_EQ(std::memcmp(la.data(), lb.data(), la.size() * sizeof(Lobe)), 0);
      for (const Lobe& lobe : la) {
        transmitting_lobes += diffuse_transmits(lobe);
        with_t90 += lobe.diffuse_transmission90 != glm::vec3(0.0f);
      }
      // τd where some lobe transmits diffusely, τd90 where some lobe's is not 0; every byte beside the
      // parameters' is one bytes_per_texel counts.
      const Channels c = channels_of(path, l);
      const int slots = level.slots;
      EXPECT_EQ(c.has("lobe0.diffuseTransmission.R"), level.diffuse_transmission_layer());
      EXPECT_EQ(c.has("lobe0.diffuseTransmission90.R"), level.diffuse_transmission90_layer());
      EXPECT_EQ(c.bytes_of("lobe", ".diffuseTransmission."),
                level.diffuse_transmission_layer() ? slots * kBytesPerDiffuseTransmission : 0);
      EXPECT_EQ(c.bytes_of("lobe", ".diffuseTransmission90."),
                level.diffuse_transmission90_layer() ? slots * kBytesPerDiffuseTransmission90 : 0);
      EXPECT_EQ(c.has("lobe0.transmission.R"), thin);
      int stored = 0;
      for (std::size_t k = 0; k < c.names.size(); ++k) stored += c.names[k].rfind("param.", 0) == 0 ? 0 : c.bytes[k];
      EXPECT_EQ(a.brdf.bytes_per_texel(l), stored);
      // The texels transmit as before the trip: the first that transmits diffusely, lit from below.
      const glm::vec3 wo = glm::normalize(glm::vec3(-0.1f, 0.2f, 0.9f));
      const glm::vec3 wi = glm::normalize(glm::vec3(0.2f, -0.3f, -0.9f));
      expect_same_texel_value(a, b, l, wi, wo, [](const Lobe& x) { return diffuse_transmits(x); });
    }
    EXPECT_GT(transmitting_lobes, 0);
    // The plain layer's τd90 is 0 (diffuse_transmission.h add_diffuse_transmission), and a file of one
    // stores none.
    if (layered) {
      EXPECT_GT(with_t90, 0);
    } else {
      EXPECT_EQ(with_t90, 0);
    }
  }
}

// The renderer's out-of-core records (mip/mip_records.h) hold the same channels: every lobe of every
// coarse texel decodes bit for bit, and the layout's text says which levels carry the layer.
TEST(DiffuseTransmissionStorage, TheRecordsCarryTheLobesDiffuseTransmissionBitForBit) {
  const MipData a = build_mip(material(true, true));
  const MipRecordLayout layout = MipRecordLayout::of(a.param, &a.brdf);
  std::string why;
  const std::optional<MipRecordLayout> parsed = MipRecordLayout::parse(layout.describe("k"), "k", &why);
  ASSERT_TRUE(parsed) << why;
  int transmitting_lobes = 0;
  for (int l = 1; l < a.levels(); ++l) {
    SCOPED_TRACE("level " + std::to_string(l));
    const MipRecordLayout::Level& v = parsed->level[static_cast<std::size_t>(l)];
    EXPECT_EQ(v.lobe_diffuse_transmission, a.brdf.level(l).diffuse_transmission_layer());
    EXPECT_EQ(v.lobe_diffuse_transmission90, a.brdf.level(l).diffuse_transmission90_layer());
    const Extent e = a.extent(l);
    const std::size_t words = static_cast<std::size_t>(layout.words(l));
    std::vector<std::uint32_t> records(std::size_t(e.width) * std::size_t(e.height) * words);
    encode_records(layout, a.param, &a.brdf, l, 0, e.height, records.data());
    for (int j = 0; j < e.height; ++j)
      for (int i = 0; i < e.width; ++i) {
        Lobe lobes[8], coat[8], scratch;
        RadialCorrection correction;
        const RecordTexel t = decode_brdf(*parsed, l, records.data() + (std::size_t(j) * e.width + i) * words, lobes,
                                          coat, correction);
        const std::span<const Lobe> want = brdf_texel(a, l, i, j, scratch);
        ASSERT_EQ(std::size_t(t.lobes), want.size());
        EXPECT_EQ(std::memcmp(lobes, want.data(), want.size_bytes()), 0) << i << " " << j;
        for (const Lobe& x : want) transmitting_lobes += diffuse_transmits(x);
      }
  }
  EXPECT_GT(transmitting_lobes, 0);
}

// A material that transmits nowhere diffusely stores no channel of it: its file is as before the layer.
TEST(DiffuseTransmissionStorage, AMaterialWithoutOneStoresNone) {
  testing::TempDir dir;
  MaterialTexels m = material(true, true);
  m.diffuse_transmission_factor = 0.0f;
  m.diffuse_transmission.clear();
  m.diffuse_transmission_color.clear();
  const MipData a = build_mip(m);
  const auto path = dir / "none.exr";
  write_mip_file(path, a);
  for (int l = 1; l < a.levels(); ++l) {
    EXPECT_FALSE(a.brdf.level(l).diffuse_transmission_layer());
    EXPECT_FALSE(a.brdf.level(l).diffuse_transmission90_layer());
    EXPECT_EQ(channels_of(path, l).bytes_of("lobe", "diffuseTransmission"), 0) << "level " << l;
  }
}

// round_to_stored keeps τd and τd90 as the file's halves: rounding again changes nothing, and each is
// within a half's rounding of its value (2^-11 relative: a half's 10 fraction bits).
TEST(DiffuseTransmissionStorage, RoundingIsIdempotentAndHalfPrecise) {
  const SpecularLayer layer{0.6f, glm::vec3(1.0f, 0.9f, 0.8f), 1.4f};
  Lobe l = lobe_from_texel(glm::vec3(0.7f, 0.4f, 0.2f), 0.1f, 0.31f, glm::vec3(0, 0, 1), 1.0f, layer);
  add_diffuse_transmission(l, 0.1f, layer, 0.0f, DiffuseTransmissionLayer{0.63f, glm::vec3(0.9f, 0.35f, 0.55f)});
  const Lobe exact = l;
  round_to_stored(l);
  Lobe again = l;
  round_to_stored(again);
  EXPECT_EQ(std::memcmp(&l, &again, sizeof l), 0);
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(exact.diffuse_transmission90[c], 0.0f);
    EXPECT_NEAR(l.diffuse_transmission[c], exact.diffuse_transmission[c], 0x1p-11 * exact.diffuse_transmission[c]);
    EXPECT_NEAR(l.diffuse_transmission90[c], exact.diffuse_transmission90[c], 0x1p-11 * exact.diffuse_transmission90[c]);
  }
}

}  // namespace
}  // namespace svbrdf
