#include "scenes/geometry.h"

#include <cmath>

#include "base/error.h"
#include "base/math.h"

namespace svbrdf {

TriangleMesh rectangle(const glm::dvec3& center, const glm::dvec3& right, const glm::dvec3& up, double width,
                       double height, double uv_per_m, const glm::dvec2& uv_origin) {
  const glm::dvec3 n = glm::normalize(glm::cross(right, up));
  TriangleMesh m;
  // Corners (x, y) in (right, up) units of half sizes: bottom-left, bottom-right, top-right, top-left.
  const double hx = width / 2, hy = height / 2;
  const glm::dvec2 corners[4] = {{-hx, -hy}, {hx, -hy}, {hx, hy}, {-hx, hy}};
  for (const glm::dvec2& c : corners) {
    m.positions.push_back(glm::vec3(center + right * c.x + up * c.y));
    m.normals.push_back(glm::vec3(n));
    m.tangents.push_back(glm::vec4(glm::vec3(glm::normalize(right)), 1.0f));
    // u grows to the right from the left edge, v grows downward from the top edge.
    m.uvs.push_back(glm::vec2(uv_origin + glm::dvec2(c.x + hx, hy - c.y) * uv_per_m));
  }
  for (auto& v : m.normals) v = glm::normalize(v);
  for (auto& t : m.tangents) t = glm::vec4(glm::normalize(glm::vec3(t)), 1.0f);
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

TriangleMesh box(const glm::dvec3& s, double uv_per_m) {
  const glm::dvec3 h = s / 2.0;
  const glm::dvec3 X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1);
  TriangleMesh m;
  // Each face: centre, right, up with cross(right, up) the outward normal; sizes along right, up.
  // Side faces keep +Y up (texture rows horizontal), top and bottom faces run along x and z.
  m.append(rectangle({0, 0, h.z}, X, Y, s.x, s.y, uv_per_m));     // +Z
  m.append(rectangle({0, 0, -h.z}, -X, Y, s.x, s.y, uv_per_m));   // −Z
  m.append(rectangle({h.x, 0, 0}, -Z, Y, s.z, s.y, uv_per_m));    // +X
  m.append(rectangle({-h.x, 0, 0}, Z, Y, s.z, s.y, uv_per_m));    // −X
  m.append(rectangle({0, h.y, 0}, X, -Z, s.x, s.z, uv_per_m));    // +Y
  m.append(rectangle({0, -h.y, 0}, X, Z, s.x, s.z, uv_per_m));    // −Y
  return m;
}

TriangleMesh tray(const glm::dvec3& s, double rim, double plate, double uv_per_m) {
  TriangleMesh m;
  const auto place = [&](TriangleMesh part, const glm::dvec3& offset) {
    for (auto& p : part.positions) p += glm::vec3(offset);
    m.append(part);
  };
  place(box({s.x, plate, s.z}, uv_per_m), {0, plate / 2, 0});
  const double rim_h = s.y - plate;
  place(box({s.x, rim_h, rim}, uv_per_m), {0, plate + rim_h / 2, s.z / 2 - rim / 2});
  place(box({s.x, rim_h, rim}, uv_per_m), {0, plate + rim_h / 2, -s.z / 2 + rim / 2});
  place(box({rim, rim_h, s.z - 2 * rim}, uv_per_m), {s.x / 2 - rim / 2, plate + rim_h / 2, 0});
  place(box({rim, rim_h, s.z - 2 * rim}, uv_per_m), {-s.x / 2 + rim / 2, plate + rim_h / 2, 0});
  return m;
}

double CorrugatedRoof::max_slope_deg() const {
  return std::atan(2 * kPiD * amplitude_m / period_m) * 180 / kPiD;
}

glm::dvec3 roof_normal(const CorrugatedRoof& r, double x) {
  const double k = 2 * kPiD / r.period_m;
  const double dzdx = -r.amplitude_m * k * std::sin(k * x);
  return glm::normalize(glm::dvec3(-dzdx, 0.0, 1.0));
}

glm::dvec3 roof_mesh_normal(const CorrugatedRoof& r, double x) {
  const double step = r.period_m / r.segments;
  const double s = std::floor(x / step);
  const double t = x / step - s;
  return glm::normalize((1 - t) * roof_normal(r, s * step) + t * roof_normal(r, (s + 1) * step));
}

TriangleMesh corrugated_roof(const CorrugatedRoof& r) {
  if (r.periods < 2 || r.periods % 2 || r.segments < 2 || !(r.period_m > 0) || !(r.width_m > 0))
    throw Error("corrugated roof: periods must be even and ≥ 2, segments ≥ 2, sizes positive", Error::Kind::internal);
  TriangleMesh m;
  const int columns = r.periods * r.segments + 1;
  const double step = r.period_m / r.segments;
  const double x0 = -r.length_m() / 2;
  const double k = 2 * kPiD / r.period_m;
  for (int i = 0; i < columns; ++i) {
    // x from the integer column index so that x0 + i·step hits crests exactly where it should.
    const double x = x0 + i * step;
    const double z = r.amplitude_m * std::cos(k * (i % r.segments) * step);
    const glm::vec3 n = glm::vec3(roof_normal(r, (i % r.segments) * step));
    for (double y : {-r.width_m / 2, r.width_m / 2}) {
      m.positions.push_back(glm::vec3(float(x), float(y), float(z)));
      m.normals.push_back(glm::normalize(n));
    }
  }
  for (int i = 0; i + 1 < columns; ++i) {
    const auto a = std::uint32_t(2 * i), b = a + 2;  // a: (x_i, −W/2), a+1: (x_i, +W/2)
    m.indices.insert(m.indices.end(), {a, b, b + 1, a, b + 1, a + 1});
  }
  return m;
}

}  // namespace svbrdf
