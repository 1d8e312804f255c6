#include "textures/sampler.h"

#include <gtest/gtest.h>

#include <cmath>

#include "base/error.h"

namespace svbrdf {
namespace {

// OpenGL 4.6 §8.14.2, Table 8.20, written out independently: repeat i mod n, clamp to [0, n−1],
// mirrored repeat (n − 1) − mirror((i mod 2n) − n) with mirror(a) = a ≥ 0 ? a : −(1 + a).
int gl_wrap(int i, int n, WrapMode m) {
  const auto mod = [](int a, int b) { return ((a % b) + b) % b; };
  switch (m) {
    case WrapMode::repeat: return mod(i, n);
    case WrapMode::clamp_to_edge: return std::min(std::max(i, 0), n - 1);
    case WrapMode::mirrored_repeat: {
      const int a = mod(i, 2 * n) - n;
      return (n - 1) - (a >= 0 ? a : -(1 + a));
    }
  }
  return -1;
}

TEST(Sampler, WrapModesFollowOpenGL) {
  for (WrapMode m : {WrapMode::repeat, WrapMode::clamp_to_edge, WrapMode::mirrored_repeat})
    for (int n : {1, 2, 3, 4, 7})
      for (int i = -30; i <= 30; ++i) EXPECT_EQ(wrap_texel(i, n, m), gl_wrap(i, n, m)) << "i " << i << " n " << n;
  // A few by hand, n = 4: mirrored repeat reads 0 1 2 3 3 2 1 0 0 1 ...
  EXPECT_EQ(wrap_texel(4, 4, WrapMode::mirrored_repeat), 3);
  EXPECT_EQ(wrap_texel(7, 4, WrapMode::mirrored_repeat), 0);
  EXPECT_EQ(wrap_texel(-1, 4, WrapMode::mirrored_repeat), 0);
  EXPECT_EQ(wrap_texel(-1, 4, WrapMode::repeat), 3);
  EXPECT_EQ(wrap_texel(-1, 4, WrapMode::clamp_to_edge), 0);
}

TEST(Sampler, GltfCodes) {
  EXPECT_EQ(wrap_mode_from_gltf(10497, ""), WrapMode::repeat);
  EXPECT_EQ(wrap_mode_from_gltf(33071, ""), WrapMode::clamp_to_edge);
  EXPECT_EQ(wrap_mode_from_gltf(33648, ""), WrapMode::mirrored_repeat);
  for (WrapMode m : {WrapMode::repeat, WrapMode::clamp_to_edge, WrapMode::mirrored_repeat})
    EXPECT_EQ(wrap_mode_from_gltf(gltf_code(m), ""), m);
  EXPECT_EQ(filter_mode_from_gltf(9728, ""), FilterMode::nearest);
  EXPECT_EQ(filter_mode_from_gltf(9987, ""), FilterMode::bilinear);
  EXPECT_THROW(wrap_mode_from_gltf(1234, "samplers[0].wrapS"), Error);
  EXPECT_THROW(filter_mode_from_gltf(1, "samplers[0].magFilter"), Error);
}

// Texel (i, j) of this image holds i + 10·j in R, so every lookup can be checked by hand.
Image ramp(int w, int h) {
  Image img(w, h, 1);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) img.at(i, j, 0) = float(i + 10 * j);
  return img;
}

TEST(Sampler, NearestPicksTheTexelContainingUv) {
  const Image img = ramp(4, 4);
  const Sampler s{FilterMode::nearest, WrapMode::repeat, WrapMode::repeat};
  EXPECT_EQ(sample(img, s, {0.3f, 0.6f}).r, 1 + 10 * 2);     // u·4 = 1.2, v·4 = 2.4
  EXPECT_EQ(sample(img, s, {0.0f, 0.0f}).r, 0);              // uv (0, 0) is the top-left texel
  EXPECT_EQ(sample(img, s, {0.99f, 0.99f}).r, 3 + 10 * 3);
  EXPECT_EQ(sample(img, s, {1.3f, -0.1f}).r, 1 + 10 * 3);    // repeat: 5.2 → 1, −0.4 → 3
  const Sampler clamp{FilterMode::nearest, WrapMode::clamp_to_edge, WrapMode::mirrored_repeat};
  EXPECT_EQ(sample(img, clamp, {1.3f, 1.1f}).r, 3 + 10 * 3);  // clamp: 3; mirror: 4.4 → 4 → 3
  EXPECT_EQ(sample(img, clamp, {-5.0f, -0.1f}).r, 0 + 10 * 0);  // clamp: 0; mirror: −0.4 → −1 → 0
  // Far and non-finite coordinates stay inside the image.
  EXPECT_GE(sample(img, s, {1e30f, -1e30f}).r, 0);
  EXPECT_GE(sample(img, s, {NAN, INFINITY}).r, 0);
}

TEST(Sampler, BilinearIsExactOnLinearDataAndWrapsPerMode) {
  const Image img = ramp(4, 4);
  const Sampler s{FilterMode::bilinear, WrapMode::repeat, WrapMode::repeat};
  // Between texel centers, bilinear interpolation reproduces a linear function exactly:
  // texel space x = u·4, the value is (x − 0.5) + 10·(y − 0.5).
  for (float u : {0.125f, 0.2f, 0.5f, 0.77f, 0.875f})
    for (float v : {0.125f, 0.3f, 0.6f, 0.875f})
      EXPECT_NEAR(sample(img, s, {u, v}).r, (u * 4 - 0.5f) + 10 * (v * 4 - 0.5f), 1e-5) << u << " " << v;
  // At u = 0 the footprint straddles the left edge: texels −1 and 0, half each.
  const float v_center = 0.125f;  // row 0's center: no vertical blend
  EXPECT_NEAR(sample(img, s, {0.0f, v_center}).r, 0.5f * (3 + 0), 1e-6);  // repeat: texel −1 is 3
  EXPECT_NEAR(sample(img, Sampler{FilterMode::bilinear, WrapMode::clamp_to_edge, WrapMode::repeat}, {0.0f, v_center}).r, 0.0f, 1e-6);
  EXPECT_NEAR(sample(img, Sampler{FilterMode::bilinear, WrapMode::mirrored_repeat, WrapMode::repeat}, {0.0f, v_center}).r, 0.0f, 1e-6);
  // At u = 1: texels 3 and 4 → repeat 3 and 0; mirrored 3 and 3.
  EXPECT_NEAR(sample(img, s, {1.0f, v_center}).r, 0.5f * (3 + 0), 1e-6);
  EXPECT_NEAR(sample(img, Sampler{FilterMode::bilinear, WrapMode::mirrored_repeat, WrapMode::repeat}, {1.0f, v_center}).r, 3.0f, 1e-6);
}

// The nearest texel index is the texel containing t·n, wrapped; the power-of-two mask path agrees
// with the division; far-out and non-finite coordinates read a texel of the image.
TEST(Sampler, NearestTexelIndexWrapsTheContainingTexel) {
  for (WrapMode m : {WrapMode::repeat, WrapMode::clamp_to_edge, WrapMode::mirrored_repeat})
    for (int n : {3, 8}) {
      for (float t = -20.0f; t <= 20.0f; t += 0.0137f) {
        const int i = nearest_texel_index(t, n, m);
        EXPECT_EQ(i, wrap_texel(int(std::floor(t * float(n))), n, m)) << int(m) << " n " << n << " at " << t;
        if (m == WrapMode::repeat && n == 8) {
          EXPECT_EQ(nearest_texel_index(t, n, m, n - 1), i) << t;
        }
      }
      for (float t : {1e30f, -1e30f, 3e7f, NAN, INFINITY, -INFINITY}) {
        const int i = nearest_texel_index(t, n, m);
        EXPECT_TRUE(i >= 0 && i < n) << int(m) << " at " << t;
      }
    }
}

TEST(Sampler, TexelExpandsGrayAndFillsAlpha) {
  Image gray(1, 1, 1), gray_alpha(1, 1, 2), rgb(1, 1, 3), rgba(1, 1, 4);
  gray.pixels = {0.25f};
  gray_alpha.pixels = {0.25f, 0.5f};
  rgb.pixels = {0.1f, 0.2f, 0.3f};
  rgba.pixels = {0.1f, 0.2f, 0.3f, 0.4f};
  EXPECT_EQ(texel(gray, 0, 0), glm::vec4(0.25f, 0.25f, 0.25f, 1.0f));
  EXPECT_EQ(texel(gray_alpha, 0, 0), glm::vec4(0.25f, 0.25f, 0.25f, 0.5f));
  EXPECT_EQ(texel(rgb, 0, 0), glm::vec4(0.1f, 0.2f, 0.3f, 1.0f));
  EXPECT_EQ(texel(rgba, 0, 0), glm::vec4(0.1f, 0.2f, 0.3f, 0.4f));
}

void expect_uv(glm::vec2 got, glm::vec2 want) {
  EXPECT_NEAR(got.x, want.x, 1e-6) << "u";
  EXPECT_NEAR(got.y, want.y, 1e-6) << "v";
}

TEST(Sampler, KhrTextureTransform) {
  // The extension's first example: "only the lower left quadrant of the source image, rotated
  // clockwise 90°" — the unit square must land on u ∈ [0, 0.5], v ∈ [0.5, 1] (v down).
  const TextureTransform quadrant = TextureTransform::make({0.0f, 1.0f}, 1.57079632679f, {0.5f, 0.5f});
  expect_uv(quadrant.apply({0, 0}), {0.0f, 1.0f});
  expect_uv(quadrant.apply({1, 0}), {0.0f, 0.5f});
  expect_uv(quadrant.apply({1, 1}), {0.5f, 0.5f});
  expect_uv(quadrant.apply({0, 1}), {0.5f, 1.0f});
  // The second: offset (0, 1), scale (1, −1) flips v, "a bottom-left origin".
  const TextureTransform flip = TextureTransform::make({0.0f, 1.0f}, 0.0f, {1.0f, -1.0f});
  expect_uv(flip.apply({0.25f, 0.0f}), {0.25f, 1.0f});
  expect_uv(flip.apply({0.25f, 0.75f}), {0.25f, 0.25f});
  // Scale, then rotation, then offset (T·R·S): scale 2, offset (0.1, 0.2), no rotation.
  expect_uv(TextureTransform::make({0.1f, 0.2f}, 0.0f, {2.0f, 2.0f}).apply({0.3f, 0.4f}), {0.7f, 1.0f});
  // The linear part carries derivatives without the offset.
  expect_uv(quadrant.apply_linear({1, 0}), {0.0f, -0.5f});
  EXPECT_TRUE(TextureTransform{}.is_identity());
  EXPECT_FALSE(quadrant.is_identity());
  // texCoord: the extension's override wins over the textureInfo's.
  EXPECT_EQ(TextureTransform{}.effective_tex_coord(1), 1);
  EXPECT_EQ(TextureTransform::make({}, 0, {1, 1}, 0).effective_tex_coord(1), 0);

  // Through a lookup: the transformed uv reads the expected texel of a 2×2 image.
  Image quad(2, 2, 1);
  quad.pixels = {0, 1, 10, 11};
  TextureView view{&quad, Sampler{FilterMode::nearest, WrapMode::repeat, WrapMode::repeat}, quadrant, 0};
  EXPECT_EQ(view.lookup({0.1f, 0.1f}).r, 10);  // → (0.05, 0.95): the lower-left texel
  EXPECT_EQ(view.uv_set(), 0);
}

}  // namespace
}  // namespace svbrdf
