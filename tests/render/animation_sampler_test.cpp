// glTF 2.0 animation samplers (gltf/animation.h) against closed forms: LINEAR halfway between two
// keys is their mean; STEP holds a key's value up to the next key; CUBICSPLINE is the cubic Hermite
// polynomial of Appendix C written out here term by term; a rotation's LINEAR is slerp, so a 90° turn
// halfway is a 45° turn; times outside the keys clamp to the end values; a chain of nodes composes
// parent × child.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "gltf/animation.h"

namespace svbrdf {
namespace {

AnimationSampler vec3_sampler(Interpolation interpolation, std::vector<float> times, std::vector<float> values) {
  AnimationSampler s;
  s.interpolation = interpolation;
  s.components = 3;
  s.times = std::move(times);
  s.values = std::move(values);
  return s;
}

TEST(AnimationSampler, LinearHalfwayBetweenTwoKeysIsTheirMean) {
  const AnimationSampler s = vec3_sampler(Interpolation::linear, {1.0f, 3.0f, 4.0f}, {0, 0, 0, 2, -4, 10, 0, 0, 0});
  const auto v = sample(s, 2.0);
  EXPECT_DOUBLE_EQ(v[0], 1.0);
  EXPECT_DOUBLE_EQ(v[1], -2.0);
  EXPECT_DOUBLE_EQ(v[2], 5.0);
  // A quarter of the way: (1 − 1/4)·a + 1/4·b.
  EXPECT_DOUBLE_EQ(sample(s, 1.5)[2], 2.5);
  // On the second interval: from (2, −4, 10) at 3 s to 0 at 4 s.
  EXPECT_DOUBLE_EQ(sample(s, 3.75)[0], 0.5);
}

TEST(AnimationSampler, TimesOutsideTheKeysClampToTheFirstAndLastValue) {
  const AnimationSampler s = vec3_sampler(Interpolation::linear, {1.0f, 3.0f}, {7, 8, 9, 1, 2, 3});
  EXPECT_EQ(sample(s, 0.0)[0], 7.0);
  EXPECT_EQ(sample(s, -5.0)[2], 9.0);
  EXPECT_EQ(sample(s, 3.0)[0], 1.0);
  EXPECT_EQ(sample(s, 100.0)[1], 2.0);
  // One key: that value at every time.
  const AnimationSampler one = vec3_sampler(Interpolation::linear, {2.0f}, {4, 5, 6});
  EXPECT_EQ(sample(one, 0.0)[1], 5.0);
  EXPECT_EQ(sample(one, 9.0)[2], 6.0);
}

TEST(AnimationSampler, StepHoldsEachKeyUntilTheNext) {
  const AnimationSampler s = vec3_sampler(Interpolation::step, {0.0f, 1.0f, 2.0f}, {1, 1, 1, 5, 5, 5, 9, 9, 9});
  EXPECT_EQ(sample(s, 0.0)[0], 1.0);
  EXPECT_EQ(sample(s, 0.999)[0], 1.0);
  EXPECT_EQ(sample(s, 1.0)[0], 5.0);  // at a key, that key's value
  EXPECT_EQ(sample(s, 1.5)[1], 5.0);
  EXPECT_EQ(sample(s, 2.5)[2], 9.0);
}

TEST(AnimationSampler, CubicSplineIsAppendixCsHermitePolynomial) {
  // Keys at 1 s and 3 s (t_d = 2): per key in-tangent a, value v, out-tangent b, three components.
  const float a0[3] = {9, 9, 9}, v0[3] = {1, -2, 0.5f}, b0[3] = {3, 0.25f, -1};
  const float a1[3] = {-2, 4, 0.5f}, v1[3] = {4, 1, -3}, b1[3] = {8, 8, 8};
  std::vector<float> values;
  for (const float* e : {a0, v0, b0, a1, v1, b1}) values.insert(values.end(), e, e + 3);
  const AnimationSampler s = vec3_sampler(Interpolation::cubic_spline, {1.0f, 3.0f}, values);
  for (const double t : {1.0, 1.4, 2.0, 2.9}) {
    const double td = 2.0, u = (t - 1.0) / td;
    const auto got = sample(s, t);
    for (int i = 0; i < 3; ++i) {
      const double expected = (2 * u * u * u - 3 * u * u + 1) * v0[i] + td * (u * u * u - 2 * u * u + u) * b0[i] +
                              (-2 * u * u * u + 3 * u * u) * v1[i] + td * (u * u * u - u * u) * a1[i];
      EXPECT_NEAR(got[std::size_t(i)], expected, 1e-12) << "t " << t << " component " << i;
    }
  }
  // The ends clamp to the values, not the tangents.
  EXPECT_EQ(sample(s, 0.0)[0], 1.0);
  EXPECT_EQ(sample(s, 5.0)[2], -3.0);
}

// A unit quaternion (glTF's x, y, z, w) turning by `degrees` about +Y.
std::vector<float> turn_y(double degrees) {
  const double h = degrees * M_PI / 360.0;
  return {0.0f, float(std::sin(h)), 0.0f, float(std::cos(h))};
}

TEST(AnimationSampler, RotationLinearIsSlerpSoAQuarterTurnHalfwayIsAnEighth) {
  AnimationSampler s;
  s.components = 4;
  s.times = {0.0f, 2.0f};
  s.values = turn_y(0);
  const std::vector<float> end = turn_y(90);
  s.values.insert(s.values.end(), end.begin(), end.end());
  const auto q = sample(s, 1.0);
  // slerp at u = 1/2 of a 90° turn: 45° about +Y, (0, sin 22.5°, 0, cos 22.5°).
  const double h = 22.5 * M_PI / 180.0;
  EXPECT_NEAR(q[0], 0.0, 1e-7);
  EXPECT_NEAR(q[1], std::sin(h), 1e-7);
  EXPECT_NEAR(q[2], 0.0, 1e-7);
  EXPECT_NEAR(q[3], std::cos(h), 1e-7);
  // At u = 1/4 slerp turns by 22.5°; a componentwise lerp renormalised (nlerp) would turn by
  // 2·atan(¼ sin 45° / (¾ + ¼ cos 45°)) ≈ 21.6°.
  const auto quarter = sample(s, 0.5);
  EXPECT_NEAR(2.0 * std::atan2(quarter[1], quarter[3]) * 180.0 / M_PI, 22.5, 1e-5);
}

TEST(AnimationSampler, SlerpTakesTheShorterArc) {
  // q and −q are one rotation: from 0° to −(170° about +Y) is a 170° turn, not 190°.
  const glm::dquat a(1, 0, 0, 0);
  const double h = 170.0 * M_PI / 360.0;
  const glm::dquat b = -glm::dquat(std::cos(h), 0, std::sin(h), 0);
  const glm::dquat m = slerp_unit(a, b, 0.5);
  EXPECT_NEAR(2.0 * std::acos(std::abs(m.w)) * 180.0 / M_PI, 85.0, 1e-9);
}

TEST(AnimationSampler, CameraChainComposesParentThenChild) {
  CameraMotion motion;
  NodeMotion rig;
  rig.node = 0;
  rig.translation_sampler = vec3_sampler(Interpolation::linear, {0.0f, 1.0f}, {0, 0, 0, 10, 0, 0});
  NodeMotion camera;
  camera.node = 1;
  camera.translation = glm::dvec3(0, 0, 2);
  camera.rotation = glm::dquat(std::cos(M_PI / 4), 0, std::sin(M_PI / 4), 0);  // 90° about +Y
  motion.chain = {rig, camera};
  // At t = 0.5 the rig stands at (5, 0, 0); the camera 2 along the rig's +Z, turned by 90°: its −Z
  // (the view direction) becomes −X.
  const glm::dmat4 world = motion.to_world(0.5);
  const glm::dvec3 position(world * glm::dvec4(0, 0, 0, 1)), view(world * glm::dvec4(0, 0, -1, 0));
  EXPECT_NEAR(position.x, 5.0, 1e-12);
  EXPECT_NEAR(position.z, 2.0, 1e-12);
  EXPECT_NEAR(view.x, -1.0, 1e-12);
  EXPECT_NEAR(view.z, 0.0, 1e-12);
  EXPECT_EQ(camera_transform_fault(world), nullptr);
  // A zero scale cannot place a camera.
  motion.chain[1].scale = glm::dvec3(1, 0, 1);
  EXPECT_NE(camera_transform_fault(motion.to_world(0.5)), nullptr);
}

}  // namespace
}  // namespace svbrdf
