// TextureSet, the renderer's level0 texture lookups (render/texture_set.h), against the textures
// module's sampler on the same float images.
#include <gtest/gtest.h>

#include "appearance/rng.h"
#include "render/texture_set.h"
#include "textures/color.h"

namespace svbrdf {
namespace {

// TextureSet's 8-bit path returns exactly what the textures module's nearest lookup of the float
// images returns (raw and linearized), for every wrap mode, power-of-two sides or not, any uv; an
// image with values between the 256 codes keeps the float path.
TEST(TextureSet, EightBitPathEqualsTheFloatLookup) {
  Rng rng(9, 4);
  Scene s;
  auto add = [&](int w, int h, int channels, bool eight_bit, WrapMode ws, WrapMode wt) {
    ImageDesc d;
    d.pixels = Image(w, h, channels);
    for (float& v : d.pixels.pixels)
      v = eight_bit ? float(rng.next_u32() % 256) / 255.0f : float(rng.next_u32() % 65536) / 65535.0f;
    s.images.push_back(std::move(d));
    TextureDesc t;
    t.image = int(s.images.size()) - 1;
    t.sampler.wrap_s = ws, t.sampler.wrap_t = wt;
    s.textures.push_back(t);
  };
  add(16, 8, 3, true, WrapMode::repeat, WrapMode::repeat);
  add(12, 7, 4, true, WrapMode::repeat, WrapMode::mirrored_repeat);
  add(8, 8, 1, true, WrapMode::clamp_to_edge, WrapMode::repeat);
  add(16, 16, 2, true, WrapMode::mirrored_repeat, WrapMode::clamp_to_edge);
  add(16, 16, 3, false, WrapMode::repeat, WrapMode::repeat);
  MaterialDesc m;
  m.base_color_texture.texture = 0;
  m.emissive_texture.texture = 1;
  m.metallic_roughness_texture.texture = 2;
  m.normal_texture.texture = 3;
  m.occlusion_texture.texture = 4;
  s.materials.push_back(m);
  m.base_color_texture.texture = 2;  // a gray image used for color too
  s.materials.push_back(m);
  const TextureSet set(s);
  const ColorConfig& color = ColorConfig::builtin();
  for (int t = 0; t < 5; ++t) {
    TextureRef r;
    r.texture = t;
    r.transform = TextureTransform::make({0.3f, -0.2f}, 0.4f, {1.5f, 2.0f});
    EXPECT_EQ(set.packed(r), t < 4) << "texture " << t;
    Sampler nearest = s.textures[std::size_t(t)].sampler;
    nearest.filter = FilterMode::nearest;
    Image lin = s.images[std::size_t(t)].pixels;
    color.srgb_texture_to_linear(lin);
    for (int n = 0; n < 500; ++n) {
      const float scale = n % 50 == 0 ? 1e8f : 5.0f;
      const glm::vec2 uv((rng.next_float() - 0.5f) * scale, (rng.next_float() - 0.5f) * scale);
      const glm::vec2 tuv = r.transform.apply(uv);
      EXPECT_EQ(set.lookup(r, uv, false), sample(s.images[std::size_t(t)].pixels, nearest, tuv)) << t << " at " << uv.x;
      if (t <= 2) {
        EXPECT_EQ(set.lookup(r, uv, true), sample(lin, nearest, tuv)) << t << " (linear) at " << uv.x;
      }
    }
  }
}

// The 8-bit form is made in bands of rows (TextureSet::kPackBandRows) in parallel: a code that stands
// for two values in two different bands, or in one, keeps the float path; codes first seen in
// different bands give one table, whose lookups equal the float lookups.
TEST(TextureSet, EightBitBandsAgree) {
  const int rows = 3 * TextureSet::kPackBandRows + 5;
  auto scene_of = [&](float last_texel) {
    Scene s;
    ImageDesc d;
    d.pixels = Image(4, rows, 3);
    for (std::size_t k = 0; k < d.pixels.pixels.size(); ++k) d.pixels.pixels[k] = float((k / 3) % 256) / 255.0f;
    d.pixels.pixels[0] = 10.0f / 255.0f;  // code 10 in the first band
    d.pixels.pixels[d.pixels.pixels.size() - 3] = last_texel;  // the last band's first channel
    s.images.push_back(std::move(d));
    TextureDesc t;
    t.image = 0;
    s.textures.push_back(t);
    MaterialDesc m;
    m.base_color_texture.texture = 0;
    s.materials.push_back(m);
    return s;
  };
  TextureRef r;
  r.texture = 0;
  // Code 10 again, 5e-4 codes off: within pack()'s tolerance of a code, but another value.
  EXPECT_FALSE(TextureSet(scene_of((10.0f + 5e-4f) / 255.0f)).packed(r));
  const Scene same = scene_of(10.0f / 255.0f);
  const TextureSet set(same);
  ASSERT_TRUE(set.packed(r));
  Sampler nearest = same.textures[0].sampler;
  nearest.filter = FilterMode::nearest;
  Image lin = same.images[0].pixels;
  ColorConfig::builtin().srgb_texture_to_linear(lin);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < 4; ++i) {
      const glm::vec2 uv((float(i) + 0.5f) / 4.0f, (float(j) + 0.5f) / float(rows));
      EXPECT_EQ(set.lookup(r, uv, false), sample(same.images[0].pixels, nearest, uv)) << i << ", " << j;
      EXPECT_EQ(set.lookup(r, uv, true), sample(lin, nearest, uv)) << i << ", " << j << " (linear)";
    }
  // Within one band: the same conflict in the first band's second texel.
  Scene one = scene_of(10.0f / 255.0f);
  one.images[0].pixels.pixels[3] = (10.0f + 5e-4f) / 255.0f;
  EXPECT_FALSE(TextureSet(one).packed(r));
}

}  // namespace
}  // namespace svbrdf
