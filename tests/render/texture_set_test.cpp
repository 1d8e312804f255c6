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

}  // namespace
}  // namespace svbrdf
