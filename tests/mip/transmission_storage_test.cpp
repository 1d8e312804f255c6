// A thin-walled transmission through the MIP file (mip/mip_file.h): every lobe's τ, τ90 and α_T read back
// bit for bit (the build rounds them to the file's halves, stored_lobe.h), in the channels the file
// lists, only in the levels that carry them, and counted in the texels' bytes; the texels transmit as
// before the trip.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "mip/lobe_mixture_bsdf.h"
#include "mip/mip_file.h"
#include "mip/stored_lobe.h"
#include "tests/mip/file_channels.h"
#include "textures/random_material.h"
#include "tests/common/temp_dir.h"

namespace svbrdf {
namespace {

using testing_files::channels_of;
using testing_files::Channels;
using testing_files::expect_same_texel_value;

// A dielectric of the random family given a transmission that varies by texel (stripes that transmit
// nothing, 0.35 or 0.9) and, where `layered`, a specular layer that is not plain (so τ90 ≠ 0).
MaterialTexels transmitting(int size, bool layered) {
  std::uint64_t seed = 1;
  while (draw_random_material(seed).metal != MetalMix::dielectric) ++seed;
  MaterialTexels m = random_material_texels(draw_random_material(seed), size);
  m.transmission_factor = 1.0f;
  m.transmission.resize(m.size());
  for (std::size_t k = 0; k < m.size(); ++k) m.transmission[k] = (k / 3) % 3 == 0 ? 0.0f : (k / 3) % 3 == 1 ? 0.35f : 0.9f;
  if (layered) {
    m.ior = 1.4f;
    m.specular.assign(m.size(), 0.6f);
    m.specular_color.assign(m.size(), glm::vec3(1.0f, 0.9f, 0.8f));
  }
  return m;
}

// Seed 26 of the random family: an anisotropic glossy film brushed along a diagonal, part of it
// transmitting, whose merged lobes' transmission stretch is not their reflection's (lobe.h "Transmission").
constexpr std::uint64_t kAnisotropicSeed = 26;

TEST(TransmissionStorage, TheMipFileCarriesTheLobesTransmissionBitForBit) {
  testing::TempDir dir;
  ASSERT_GT(draw_random_material(kAnisotropicSeed).transmission, 0.0f);
  ASSERT_GT(draw_random_material(kAnisotropicSeed).anisotropy, 0.0f);
  int stretched_levels = 0;
  for (const int variant : {0, 1, 2}) {
    const bool layered = variant == 1;
    SCOPED_TRACE(variant == 2 ? "anisotropic" : layered ? "specular layer" : "plain layer");
    const MipData a = build_mip(variant == 2 ? random_material_texels(draw_random_material(kAnisotropicSeed), 16)
                                             : transmitting(16, layered));
    const auto path = dir / ("variant" + std::to_string(variant) + ".exr");
    write_mip_file(path, a);
    const MipData b = read_mip_file(path);
    ASSERT_EQ(b.levels(), a.levels());
    int transmitting_lobes = 0, with_t90 = 0;
    for (int l = 1; l < a.levels(); ++l) {
      SCOPED_TRACE("level " + std::to_string(l));
      const std::vector<Lobe> la = a.brdf.level(l).all_lobes(), lb = b.brdf.level(l).all_lobes();
      ASSERT_EQ(la.size(), lb.size());
      EXPECT_EQ(std::memcmp(la.data(), lb.data(), la.size() * sizeof(Lobe)), 0);
      for (const Lobe& lobe : la) {
        transmitting_lobes += transmits(lobe);
        with_t90 += lobe.transmission90 != glm::vec3(0.0f);
        if (transmits(lobe)) {
          EXPECT_GT(lobe.transmission_alpha2, 0.0f);
        }
      }
      // The channels: τ and α_T where some lobe transmits, τ90 where some lobe's is not 0; every byte
      // beside the parameters' is one bytes_per_texel counts.
      const Channels c = channels_of(path, l);
      const int slots = a.brdf.level(l).slots;
      EXPECT_EQ(c.has("lobe0.transmission.alpha"), a.brdf.level(l).transmission_layer());
      EXPECT_EQ(c.has("lobe0.transmission90.R"), a.brdf.level(l).transmission90_layer());
      const bool t_stretch = a.brdf.level(l).transmission_stretch_layer();
      stretched_levels += t_stretch;
      EXPECT_EQ(c.has("lobe0.transmission.stretch"), t_stretch);
      EXPECT_EQ(c.bytes_of("lobe", ".transmission.stretch"), t_stretch ? slots * kBytesPerTransmissionStretch : 0);
      EXPECT_EQ(c.bytes_of("lobe", ".transmission."),
                (a.brdf.level(l).transmission_layer() ? slots * kBytesPerTransmission : 0) +
                    (t_stretch ? slots * kBytesPerTransmissionStretch : 0));
      EXPECT_EQ(c.bytes_of("lobe", ".transmission90."), a.brdf.level(l).transmission90_layer() ? slots * kBytesPerTransmission90 : 0);
      int stored = 0;
      for (std::size_t k = 0; k < c.names.size(); ++k) stored += c.names[k].rfind("param.", 0) == 0 ? 0 : c.bytes[k];
      EXPECT_EQ(a.brdf.bytes_per_texel(l), stored);
      // The texels transmit as before the trip: the first that transmits, seen straight through for the
      // glossy anisotropic film.
      const glm::vec3 wo = glm::normalize(glm::vec3(-0.1f, 0.2f, 0.9f));
      const glm::vec3 wi = variant == 2 ? -wo : glm::normalize(glm::vec3(0.2f, -0.3f, -0.9f));
      expect_same_texel_value(a, b, l, wi, wo, [](const Lobe& x) { return transmits(x); });
    }
    EXPECT_GT(transmitting_lobes, 0);
    // The plain layer's τ90 is 0 (lobe.h lobe_from_texel), and a file of one stores none.
    if (layered) {
      EXPECT_GT(with_t90, 0);
    } else {
      EXPECT_EQ(with_t90, 0);
    }
  }
  EXPECT_GT(stretched_levels, 0);
}

// A material that transmits nowhere stores no transmission channel (its file is as before the layer).
TEST(TransmissionStorage, AMaterialWithoutOneStoresNone) {
  testing::TempDir dir;
  MaterialTexels m = transmitting(8, true);
  m.transmission_factor = 0.0f;
  m.transmission.clear();
  const MipData a = build_mip(m);
  const auto path = dir / "none.exr";
  write_mip_file(path, a);
  for (int l = 1; l < a.levels(); ++l) {
    EXPECT_FALSE(a.brdf.level(l).transmission_layer());
    EXPECT_EQ(channels_of(path, l).bytes_of("lobe", "transmission"), 0) << "level " << l;
  }
}

// round_to_stored keeps τ, τ90 and α_T as the file's halves: rounding again changes nothing, and α_T
// is within a half's rounding of its value (2^-11 relative on α_T: a half's 10 fraction bits).
TEST(TransmissionStorage, RoundingIsIdempotentAndHalfPrecise) {
  Lobe l = lobe_from_texel(glm::vec3(0.7f, 0.4f, 0.2f), 0.0f, 0.31f, glm::vec3(0, 0, 1), 1.0f,
                           SpecularLayer{0.6f, glm::vec3(1.0f, 0.9f, 0.8f), 1.4f}, {}, 0.73f);
  const Lobe exact = l;
  round_to_stored(l);
  Lobe again = l;
  round_to_stored(again);
  EXPECT_EQ(std::memcmp(&l, &again, sizeof l), 0);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(l.transmission[c], exact.transmission[c], 1e-3 * exact.transmission[c]);
    EXPECT_NEAR(l.transmission90[c], exact.transmission90[c], 1e-3 * exact.transmission90[c]);
    EXPECT_GT(exact.transmission90[c], 0.0f);
  }
  EXPECT_NE(l.transmission_alpha2, exact.transmission_alpha2);  // 0.31⁴ is no square of a half
  EXPECT_NEAR(std::sqrt(l.transmission_alpha2), std::sqrt(exact.transmission_alpha2),
              0x1p-11 * std::sqrt(exact.transmission_alpha2));
}

// The transmission's stretch is rounded as the reflection's (stored_lobe.h): ln r to a half, the
// direction to a step of π/2^20; idempotent.
TEST(TransmissionStorage, TheTransmissionsStretchRoundsAsTheReflections) {
  Lobe l = lobe_from_texel(glm::vec3(0.7f, 0.4f, 0.2f), 0.0f, 0.31f, glm::vec3(0, 0, 1), 1.0f, {},
                           AnisotropyLayer{0.6f, glm::normalize(glm::vec2(0.3f, 0.8f))}, 0.73f);
  l.transmission_stretch = 2.7f;
  l.transmission_stretch_dir = glm::normalize(glm::vec2(-0.6f, 0.5f));
  const Lobe exact = l;
  round_to_stored(l);
  Lobe again = l;
  round_to_stored(again);
  EXPECT_EQ(std::memcmp(&l, &again, sizeof l), 0);
  EXPECT_NE(l.transmission_stretch, exact.transmission_stretch);
  EXPECT_NEAR(std::log(l.transmission_stretch), std::log(exact.transmission_stretch), 0x1p-11 * std::log(2.7));
  const double turn = std::abs(std::atan2(l.transmission_stretch_dir.y, l.transmission_stretch_dir.x) -
                               std::atan2(exact.transmission_stretch_dir.y, exact.transmission_stretch_dir.x));
  EXPECT_LE(turn, 3.14159265358979 / (1 << 21) + 1e-6);
  // Its own channels: not the reflection's stretch.
  EXPECT_NE(l.transmission_stretch, l.stretch);
}

}  // namespace
}  // namespace svbrdf
