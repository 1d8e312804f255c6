#include "appearance/frame.h"

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include "appearance/rng.h"

namespace svbrdf {
namespace {

// Random unit vectors over the whole sphere, poles included: the frame must be orthonormal,
// right-handed with z = n, and to_world must invert to_local.
TEST(Frame, FromNormalIsOrthonormalAndInvertible) {
  Rng rng(7, 1);
  std::vector<glm::vec3> normals = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, -1, 0}};
  for (int i = 0; i < 1000; ++i) {
    const float z = 2 * rng.next_float() - 1, phi = 2 * glm::pi<float>() * rng.next_float();
    const float r = std::sqrt(std::max(0.0f, 1 - z * z));
    normals.push_back({r * std::cos(phi), r * std::sin(phi), z});
  }
  for (const glm::vec3& n : normals) {
    const Frame f = Frame::from_normal(n);
    EXPECT_NEAR(glm::length(f.s), 1, 1e-5);
    EXPECT_NEAR(glm::length(f.t), 1, 1e-5);
    EXPECT_NEAR(glm::dot(f.s, f.t), 0, 1e-5);
    EXPECT_NEAR(glm::dot(f.s, f.n), 0, 1e-5);
    EXPECT_NEAR(glm::dot(glm::cross(f.s, f.t), n), 1, 1e-5) << "frame must be right-handed";
    const glm::vec3 w = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
    const glm::vec3 back = f.to_world(f.to_local(w));
    EXPECT_NEAR(glm::length(back - w), 0, 1e-5);
    EXPECT_NEAR(f.to_local(n).z, 1, 1e-5) << "the normal is local z";
  }
}

TEST(Frame, TangentIsKeptInThePlane) {
  const glm::vec3 n = glm::normalize(glm::vec3(0, 0.2f, 1));
  const Frame f = Frame::from_normal_tangent(n, {1, 0, 0});
  EXPECT_NEAR(f.s.x, 1, 1e-6);
  EXPECT_NEAR(glm::dot(f.s, n), 0, 1e-6);
  // A tangent parallel to n falls back to an arbitrary but valid frame.
  const Frame g = Frame::from_normal_tangent(n, n);
  EXPECT_NEAR(glm::dot(g.s, n), 0, 1e-5);
  EXPECT_NEAR(glm::length(g.s), 1, 1e-5);
}

TEST(Rng, UniformMeanAndRange) {
  Rng rng(1234, 5);
  double sum = 0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const float u = rng.next_float();
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
    sum += u;
  }
  // mean of U(0,1) is 1/2 with standard error 1/sqrt(12 n) ≈ 9e-4: 5 sigma.
  EXPECT_NEAR(sum / n, 0.5, 5 * 0.000913);
  Rng a(99, 3), b(99, 3), c(99, 4);
  EXPECT_EQ(a.next_u32(), b.next_u32()) << "same seed and stream, same numbers";
  EXPECT_NE(Rng(99, 3).next_u32(), c.next_u32()) << "another stream, other numbers";
}

// next_u64 is two next_u32 draws, the first in the high word, whatever the compiler.
TEST(Rng, SixtyFourBitsAreTwoDrawsInOrder) {
  Rng a(7, 11), b(7, 11);
  for (int i = 0; i < 4; ++i) {
    const std::uint64_t hi = b.next_u32(), lo = b.next_u32();
    EXPECT_EQ(a.next_u64(), (hi << 32) | lo);
  }
}

}  // namespace
}  // namespace svbrdf
