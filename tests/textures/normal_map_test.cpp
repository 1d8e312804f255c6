#include "textures/normal_map.h"

#include <gtest/gtest.h>

#include <cmath>

#include "textures/height_field.h"

namespace svbrdf {
namespace {

void expect_vec(glm::vec3 got, glm::vec3 want, float tol = 1e-6f) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

// ../shared/spec/brdf-mip.md: n = normalize((2·rgb − 1)·(s, s, 1)), +Y up.
TEST(NormalMap, DecodesKnownColors) {
  expect_vec(decode_normal({0.5f, 0.5f, 1.0f}), {0, 0, 1});
  expect_vec(decode_normal({1.0f, 0.5f, 0.5f}), {1, 0, 0});
  expect_vec(decode_normal({0.5f, 1.0f, 0.5f}), {0, 1, 0});
  expect_vec(decode_normal({0.5f, 0.0f, 0.5f}), {0, -1, 0});
  // (0.8, 0.5, 0.9) → (0.6, 0, 0.8), already unit.
  expect_vec(decode_normal({0.8f, 0.5f, 0.9f}), {0.6f, 0.0f, 0.8f});
  // Scale 2 doubles the tangential part before normalizing: (1.2, 0, 0.8)/|·|.
  const float len = std::sqrt(1.2f * 1.2f + 0.8f * 0.8f);
  expect_vec(decode_normal({0.8f, 0.5f, 0.9f}, 2.0f), {1.2f / len, 0.0f, 0.8f / len});
  // Scale 0 flattens any texel.
  expect_vec(decode_normal({0.8f, 0.3f, 0.9f}, 0.0f), {0, 0, 1});
  // The degenerate mid-gray texel reads as the unperturbed normal.
  expect_vec(decode_normal({0.5f, 0.5f, 0.5f}), {0, 0, 1});
  // encode is decode's inverse for unit normals.
  const glm::vec3 n = glm::normalize(glm::vec3(-0.3f, 0.2f, 0.9f));
  expect_vec(decode_normal(encode_normal(n)), n);
}

// A periodic height field h = A·sin(2πx/L): central differences give exactly
// A·(2π/L)·cos(2πx/L)·sinc-like factor sin(2πΔ/L)/(2πΔ/L), and the normal is (−∂h/∂x, −∂h/∂y, 1).
TEST(NormalMap, NormalsFromHeightHavePhysicalSlopes) {
  const int n = 64;
  const double mm = 0.25, side = n * mm, amplitude = 0.1;  // 0.1 mm over a 16 mm period
  const double k = 2 * M_PI / side, discrete = std::sin(k * mm) / (k * mm);
  std::vector<float> h(n * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) h[j * n + i] = float(amplitude * std::sin(k * (i + 0.5) * mm));
  std::vector<glm::vec3> normals;
  normals_from_height(h, n, n, mm, normals);
  for (int i = 0; i < n; ++i) {
    const double slope = amplitude * k * std::cos(k * (i + 0.5) * mm) * discrete;
    const glm::vec3 want = glm::normalize(glm::vec3(float(-slope), 0.0f, 1.0f));
    expect_vec(normals[5 * n + i], want, 2e-6f);
  }
}

// +Y is up the image (toward row 0): a surface rising toward the image's bottom faces its top.
TEST(NormalMap, PlusYIsUpTheImage) {
  const int n = 16;
  const double mm = 0.5;
  std::vector<float> h(n * n);
  // A smooth periodic ramp in rows: rising with j (downward) around row 8.
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) h[j * n + i] = float(std::sin(2 * M_PI * j / n));
  std::vector<glm::vec3> normals;
  normals_from_height(h, n, n, mm, normals);
  // Around row 0 the height grows with j, so the surface faces up the image: n.y > 0.
  EXPECT_GT(normals[0 * n + 3].y, 0.5f);
  EXPECT_NEAR(normals[0 * n + 3].x, 0.0f, 1e-6f);
  // Around row 8 it falls with j: n.y < 0.
  EXPECT_LT(normals[8 * n + 3].y, -0.5f);
  const glm::vec2 s = height_slope(h, n, n, mm, 3, 0);
  EXPECT_NEAR(s.y, -(std::sin(2 * M_PI * 1 / n) - std::sin(2 * M_PI * -1 / n)) / (2 * mm), 1e-5);
}

}  // namespace
}  // namespace svbrdf
