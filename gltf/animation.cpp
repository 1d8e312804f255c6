#include "gltf/animation.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace svbrdf {

namespace {

glm::dquat as_quat(const std::array<double, 4>& v) { return glm::dquat(v[3], v[0], v[1], v[2]); }  // glTF: x, y, z, w

}  // namespace

glm::dquat slerp_unit(const glm::dquat& a, const glm::dquat& b, double u) {
  // q and −q are one rotation: turning toward whichever of b and −b is nearer takes the shorter arc.
  double d = glm::dot(a, b);
  const glm::dquat e = d < 0.0 ? -b : b;
  d = std::min(std::abs(d), 1.0);
  const double theta = std::acos(d), s = std::sin(theta);
  // Keys a hair apart: sin θ → 0 and the weights below lose their digits; the chord is the arc there.
  if (s < 1e-9) return glm::normalize(a * (1.0 - u) + e * u);
  return glm::normalize(a * (std::sin((1.0 - u) * theta) / s) + e * (std::sin(u * theta) / s));
}

std::array<double, 4> sample(const AnimationSampler& s, double t) {
  const int c = s.components;
  const bool cubic = s.interpolation == Interpolation::cubic_spline;
  const std::size_t per_key = cubic ? 3 : 1;
  // Element `which` of key k (CUBICSPLINE: 0 in-tangent, 1 value, 2 out-tangent).
  const auto element = [&](std::size_t k, std::size_t which) {
    std::array<double, 4> v{};
    for (int i = 0; i < c; ++i) v[std::size_t(i)] = double(s.values[(k * per_key + which) * std::size_t(c) + std::size_t(i)]);
    return v;
  };
  const std::size_t value_at = cubic ? 1 : 0;
  std::array<double, 4> out{};
  const std::size_t last = s.times.size() - 1;
  if (!(t > double(s.times.front()))) {
    out = element(0, value_at);  // before the first key (and a NaN time): the first value
  } else if (t >= double(s.times.back())) {
    out = element(last, value_at);
  } else {
    // The keys around t: times[k] ≤ t < times[k + 1].
    const std::size_t k = std::size_t(std::upper_bound(s.times.begin(), s.times.end(), t,
                                                       [](double x, float key) { return x < double(key); }) -
                                      s.times.begin()) - 1;
    const double t0 = s.times[k], t1 = s.times[k + 1], td = t1 - t0, u = (t - t0) / td;
    if (s.interpolation == Interpolation::step) {
      out = element(k, 0);
    } else if (s.interpolation == Interpolation::linear) {
      const std::array<double, 4> a = element(k, 0), b = element(k + 1, 0);
      if (c == 4) {
        const glm::dquat q = slerp_unit(glm::normalize(as_quat(a)), glm::normalize(as_quat(b)), u);
        return {q.x, q.y, q.z, q.w};
      }
      for (int i = 0; i < c; ++i) out[std::size_t(i)] = (1.0 - u) * a[std::size_t(i)] + u * b[std::size_t(i)];
    } else {
      // Appendix C, cubic spline: p(u) = (2u³ − 3u² + 1)·v_k + t_d·(u³ − 2u² + u)·b_k + (−2u³ + 3u²)·v_k+1
      // + t_d·(u³ − u²)·a_k+1, with b_k key k's out-tangent and a_k+1 key k+1's in-tangent.
      const std::array<double, 4> vk = element(k, 1), bk = element(k, 2), ak1 = element(k + 1, 0), vk1 = element(k + 1, 1);
      const double u2 = u * u, u3 = u2 * u;
      const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
      for (int i = 0; i < c; ++i) {
        const std::size_t j = std::size_t(i);
        out[j] = h00 * vk[j] + td * h10 * bk[j] + h01 * vk1[j] + td * h11 * ak1[j];
      }
    }
  }
  if (c == 4) {
    // The file's keys need not be exactly unit (normalized integers are not); a spline between
    // unit keys is not unit either. A zero result is left as it is: the camera check refuses it.
    const double len = std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2] + out[3] * out[3]);
    if (len > 0.0)
      for (double& x : out) x /= len;
  }
  return out;
}

glm::dmat4 NodeMotion::local(double t) const {
  if (matrix) return *matrix;
  glm::dvec3 tr = translation, sc = scale;
  glm::dquat r = rotation;
  if (translation_sampler) {
    const auto v = sample(*translation_sampler, t);
    tr = glm::dvec3(v[0], v[1], v[2]);
  }
  if (rotation_sampler) r = as_quat(sample(*rotation_sampler, t));
  if (scale_sampler) {
    const auto v = sample(*scale_sampler, t);
    sc = glm::dvec3(v[0], v[1], v[2]);
  }
  return glm::scale(glm::translate(glm::dmat4(1.0), tr) * glm::mat4_cast(r), sc);
}

glm::dmat4 CameraMotion::to_world(double t) const {
  glm::dmat4 world(1.0);
  for (const NodeMotion& n : chain) world = world * n.local(t);
  return world;
}

const char* camera_transform_fault(const glm::dmat4& world) {
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row)
      if (!std::isfinite(world[col][row]) || std::abs(world[col][row]) > 1e18)
        return "with a transform that is not finite (or beyond 1e18)";
  const double det = glm::determinant(glm::dmat3(world));
  const double size = glm::length(glm::dvec3(world[0])) * glm::length(glm::dvec3(world[1])) *
                      glm::length(glm::dvec3(world[2]));
  if (!(std::abs(det) > 1e-12 * size) || !(size > 0))
    return "with a singular transform (a zero scale); a camera needs three independent axes";
  return nullptr;
}

}  // namespace svbrdf
