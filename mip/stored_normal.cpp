#include "mip/stored_normal.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>

namespace svbrdf {

namespace {

constexpr double kScale = 32767.0;           // a coordinate in [−1, 1] as a 16-bit signed integer
constexpr double kDeficitStep = 0x1p-20;     // the deficit's grid below half-float spacing

double sign_not_zero(double x) { return x < 0 ? -1.0 : 1.0; }

// The octahedral coordinates of a unit direction: its projection onto |x| + |y| + |z| = 1, the lower
// half folded over the diagonals.
glm::dvec2 to_octahedron(const glm::dvec3& d) {
  const double l1 = std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
  glm::dvec2 p(d.x / l1, d.y / l1);
  if (d.z < 0) p = glm::dvec2((1 - std::abs(p.y)) * sign_not_zero(p.x), (1 - std::abs(p.x)) * sign_not_zero(p.y));
  return p;
}

glm::dvec3 from_octahedron(const glm::dvec2& p) {
  glm::dvec3 d(p.x, p.y, 1 - std::abs(p.x) - std::abs(p.y));
  if (d.z < 0) d.x = (1 - std::abs(p.y)) * sign_not_zero(p.x), d.y = (1 - std::abs(p.x)) * sign_not_zero(p.y);
  return glm::normalize(d);
}

std::uint32_t pack(int qx, int qy) {
  // On the square's edges the fold makes (x, ±1) and (−x, ±1) one direction, (±1, y) and (±1, −y)
  // too: one code for each, or a decoded normal could encode to the other.
  if (std::abs(qy) == 32767) qx = std::abs(qx);
  if (std::abs(qx) == 32767) qy = std::abs(qy);
  return static_cast<std::uint32_t>(static_cast<std::uint16_t>(static_cast<std::int16_t>(qx))) |
         static_cast<std::uint32_t>(static_cast<std::uint16_t>(static_cast<std::int16_t>(qy))) << 16;
}
glm::dvec2 unpack(std::uint32_t code) {
  const auto qx = static_cast<std::int16_t>(static_cast<std::uint16_t>(code & 0xffffu));
  const auto qy = static_cast<std::int16_t>(static_cast<std::uint16_t>(code >> 16));
  // −32768 is never written; clamped, it reads as −1 like −32767.
  return glm::clamp(glm::dvec2(qx, qy) / kScale, -1.0, 1.0);
}

}  // namespace

StoredNormal store_normal(const glm::vec3& normal) {
  const glm::dvec3 n(normal);
  const double len = glm::length(n);
  StoredNormal s;
  const double deficit = std::round(std::clamp(1.0 - len, 0.0, 1.0) / kDeficitStep) * kDeficitStep;
  s.deficit = glm::unpackHalf1x16(glm::packHalf1x16(static_cast<float>(deficit)));
  if (!(len > 1e-30)) {  // no direction (and NaN): the geometric normal, length 0
    s.direction = pack(0, 0);
    return s;
  }
  const glm::dvec3 d = n / len;
  const glm::dvec2 p = to_octahedron(d) * kScale;
  const int x0 = static_cast<int>(std::floor(p.x)), y0 = static_cast<int>(std::floor(p.y));
  double best = -2.0;
  for (int dy = 0; dy <= 1; ++dy)
    for (int dx = 0; dx <= 1; ++dx) {
      const int qx = std::clamp(x0 + dx, -32767, 32767), qy = std::clamp(y0 + dy, -32767, 32767);
      const double cosine = glm::dot(from_octahedron(glm::dvec2(qx, qy) / kScale), d);
      if (cosine > best) best = cosine, s.direction = pack(qx, qy);
    }
  return s;
}

glm::vec3 load_normal(const StoredNormal& stored) {
  return glm::vec3(from_octahedron(unpack(stored.direction)) * (1.0 - double(stored.deficit)));
}

}  // namespace svbrdf
