#include "mip/stored_normal.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

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

// The point of the octahedron |x| + |y| + |z| = 1 with coordinates p (a direction, not unit).
glm::dvec3 octahedron_point(const glm::dvec2& p) {
  glm::dvec3 d(p.x, p.y, 1 - std::abs(p.x) - std::abs(p.y));
  if (d.z < 0) d.x = (1 - std::abs(p.y)) * sign_not_zero(p.x), d.y = (1 - std::abs(p.x)) * sign_not_zero(p.y);
  return d;
}
glm::dvec3 from_octahedron(const glm::dvec2& p) { return glm::normalize(octahedron_point(p)); }

// The warped code (stored_normal.h): an octahedral coordinate p is p(c) = c·(a + (1 − a)·|c|) of the
// code's coordinate c ∈ [−1, 1], a = kPoleSlope, which maps 0 to 0 and ±1 to ±1 (the square and its
// folds stay where they were). c(p) is the positive root of (1 − a)c² + a·c − |p| = 0, written without
// the cancellation of (−a + √…) near p = 0.
constexpr double kPoleSlope = 1.0 / 16;
double code_of(double p) {
  const double m = std::abs(p);
  return std::copysign(2.0 * m / (kPoleSlope + std::sqrt(kPoleSlope * kPoleSlope + 4.0 * (1.0 - kPoleSlope) * m)), p);
}
double octahedral_of(double c) { return c * (kPoleSlope + (1.0 - kPoleSlope) * std::abs(c)); }

// The code's coordinates for octahedral coordinates p, and back.
glm::dvec2 code_coordinates(const glm::dvec2& p) { return glm::dvec2(code_of(p.x), code_of(p.y)); }
glm::dvec2 octahedral_coordinates(const glm::dvec2& c) { return glm::dvec2(octahedral_of(c.x), octahedral_of(c.y)); }

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
  return octahedral_coordinates(glm::clamp(glm::dvec2(qx, qy) / kScale, -1.0, 1.0));
}

}  // namespace

StoredNormal store_normal(const glm::vec3& normal) {
  const glm::dvec3 n(normal);
  const double len = glm::length(n);
  StoredNormal s;
  if (!(len > 1e-30)) {  // no direction (or not a number): length 0 along the geometric normal
    s.direction = pack(0, 0);
    s.deficit = 1.0f;
    return s;
  }
  // (Casts, not std::round and std::floor: those are calls on the SSE2 baseline.)
  const double deficit = static_cast<double>(static_cast<std::int64_t>(std::clamp(1.0 - len, 0.0, 1.0) / kDeficitStep + 0.5)) * kDeficitStep;
  s.deficit = glm::unpackHalf1x16(glm::packHalf1x16(static_cast<float>(deficit)));
  // The code nearest on the sphere among the four around the direction's coordinates; nearest in
  // the coordinates alone can be 1.5× farther where the map stretches. Compared by cos² = (v·d)²/|v|²
  // of the unnormalized octahedron points (all four are within a cell of d, so v·d > 0).
  const glm::dvec3 d = n / len;
  const glm::dvec2 p = code_coordinates(to_octahedron(d)) * kScale;
  const int x0 = static_cast<int>(p.x + 32768.0) - 32768, y0 = static_cast<int>(p.y + 32768.0) - 32768;  // floor
  double best = -1.0;
  for (int dy = 0; dy <= 1; ++dy)
    for (int dx = 0; dx <= 1; ++dx) {
      const int qx = std::clamp(x0 + dx, -32767, 32767), qy = std::clamp(y0 + dy, -32767, 32767);
      const glm::dvec3 v = octahedron_point(octahedral_coordinates(glm::dvec2(qx, qy) / kScale));
      const double c = glm::dot(v, d), score = c > 0 ? c * c / glm::dot(v, v) : -1.0;
      if (score > best) best = score, s.direction = pack(qx, qy);
    }
  return s;
}

glm::vec3 load_normal(const StoredNormal& stored) {
  return glm::vec3(from_octahedron(unpack(stored.direction)) * (1.0 - double(stored.deficit)));
}

}  // namespace svbrdf
