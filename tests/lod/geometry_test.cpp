// Scene geometry by its properties: faces point outward and wind counter-clockwise, texels keep
// their physical size on every face, tangents follow +u with the bitangent toward −v (glTF), and the
// tile roof is the height field z = A·cos(2πx/P) with its exact normals.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "scenes/geometry.h"

namespace svbrdf {
namespace {

constexpr double kPi = std::numbers::pi;

// Per triangle: winding against the vertex normal, uv scale along every edge, tangent frame.
void expect_textured_frame(const TriangleMesh& m, double uv_per_m) {
  ASSERT_EQ(m.indices.size() % 3, 0u);
  for (std::size_t t = 0; t < m.indices.size(); t += 3) {
    const auto i0 = m.indices[t], i1 = m.indices[t + 1], i2 = m.indices[t + 2];
    const glm::dvec3 p0 = m.positions[i0], p1 = m.positions[i1], p2 = m.positions[i2];
    const glm::dvec3 n = m.normals[i0];
    EXPECT_NEAR(glm::length(n), 1.0, 1e-6);
    EXPECT_GT(glm::dot(glm::cross(p1 - p0, p2 - p0), n), 0.0) << "triangle " << t / 3 << " winds clockwise";
    // Texels are square and of the same physical size: |Δuv| = uv_per_m · |Δp| along every edge.
    for (auto [a, b] : {std::pair{i0, i1}, {i1, i2}, {i2, i0}}) {
      const double dp = glm::length(glm::dvec3(m.positions[a]) - glm::dvec3(m.positions[b]));
      const double duv = glm::length(glm::dvec2(m.uvs[a]) - glm::dvec2(m.uvs[b]));
      EXPECT_NEAR(duv, uv_per_m * dp, 1e-4 * (1 + uv_per_m * dp));
    }
    // The tangent is the direction of +u on the surface, the bitangent cross(n, t)·w that of −v.
    const glm::dvec3 tan = glm::dvec3(m.tangents[i0]);
    const glm::dvec3 bit = glm::cross(n, tan) * double(m.tangents[i0].w);
    const glm::dvec2 w0 = m.uvs[i0], w1 = m.uvs[i1], w2 = m.uvs[i2];
    // dp/du and dp/dv from the triangle (the textbook tangent construction).
    const glm::dvec3 e1 = p1 - p0, e2 = p2 - p0;
    const glm::dvec2 d1 = w1 - w0, d2 = w2 - w0;
    const double det = d1.x * d2.y - d2.x * d1.y;
    ASSERT_NE(det, 0.0);
    const glm::dvec3 dpdu = (e1 * d2.y - e2 * d1.y) / det, dpdv = (e2 * d1.x - e1 * d2.x) / det;
    EXPECT_NEAR(glm::dot(glm::normalize(dpdu), tan), 1.0, 1e-5);
    EXPECT_NEAR(glm::dot(glm::normalize(dpdv), bit), -1.0, 1e-5);
  }
}

TEST(Geometry, RectangleCornersAndUvOrigin) {
  const TriangleMesh r = rectangle({1, 2, 3}, {1, 0, 0}, {0, 1, 0}, 2.0, 4.0, 0.5, {0.25, 0.75});
  ASSERT_EQ(r.positions.size(), 4u);
  // The top-left corner (−right, +up) carries uv_origin; the bottom-right one origin + (w, h)·k.
  for (std::size_t i = 0; i < 4; ++i) {
    if (r.positions[i] == glm::vec3(0, 4, 3)) {
      EXPECT_EQ(r.uvs[i], glm::vec2(0.25f, 0.75f));
    }
    if (r.positions[i] == glm::vec3(2, 0, 3)) {
      EXPECT_EQ(r.uvs[i], glm::vec2(1.25f, 2.75f));
    }
  }
  expect_textured_frame(r, 0.5);
}

TEST(Geometry, BoxFacesPointOutwardWithPhysicalTexels) {
  const glm::dvec3 size(0.6, 0.4, 0.3);
  const TriangleMesh b = box(size, 19.53125);  // a 512-texel texture at 0.1 mm per texel
  EXPECT_EQ(b.positions.size(), 24u);
  EXPECT_EQ(b.indices.size(), 36u);
  for (std::size_t i = 0; i < b.positions.size(); ++i) {
    const glm::dvec3 p = b.positions[i];
    EXPECT_NEAR(std::abs(p.x), size.x / 2, 1e-6);
    EXPECT_NEAR(std::abs(p.y), size.y / 2, 1e-6);
    EXPECT_NEAR(std::abs(p.z), size.z / 2, 1e-6);
    // The normal is the axis of the face the vertex lies on, pointing away from the centre.
    const glm::dvec3 n = b.normals[i];
    EXPECT_NEAR(glm::dot(n, p / (size / 2.0)), 1.0, 1e-6);
  }
  expect_textured_frame(b, 19.53125);
}

TEST(Geometry, TrayIsFiveBoxes) {
  const TriangleMesh t = tray({0.5, 0.03, 0.36}, 0.01, 0.004, 10.0);
  EXPECT_EQ(t.indices.size(), 5u * 36u);
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (const glm::vec3& p : t.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  EXPECT_NEAR(lo.y, 0.0f, 1e-6f);
  EXPECT_NEAR(hi.y, 0.03f, 1e-6f);
  EXPECT_NEAR(hi.x - lo.x, 0.5f, 1e-6f);
  EXPECT_NEAR(hi.z - lo.z, 0.36f, 1e-6f);
  expect_textured_frame(t, 10.0);
}

TEST(Geometry, RoofIsTheCosineHeightFieldWithExactNormals) {
  CorrugatedRoof r;
  r.period_m = 0.2;
  r.amplitude_m = 0.022;
  r.segments = 16;
  r.periods = 6;
  r.width_m = 1.5;
  const TriangleMesh m = corrugated_roof(r);
  ASSERT_EQ(m.positions.size(), std::size_t(2 * (r.periods * r.segments + 1)));
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    const glm::dvec3 p = m.positions[i];
    const double k = 2 * kPi / r.period_m;
    EXPECT_NEAR(p.z, r.amplitude_m * std::cos(k * p.x), 1e-6);
    EXPECT_NEAR(std::abs(p.y), r.width_m / 2, 1e-6);
    // n ∝ (−dz/dx, 0, 1) with dz/dx = −A·k·sin(kx).
    const glm::dvec3 n = glm::normalize(glm::dvec3(r.amplitude_m * k * std::sin(k * p.x), 0, 1));
    EXPECT_NEAR(glm::dot(glm::dvec3(m.normals[i]), n), 1.0, 1e-6);
  }
  // Triangles face up and their facet normals lie between the vertex normals' slopes.
  for (std::size_t t = 0; t < m.indices.size(); t += 3) {
    const glm::dvec3 p0 = m.positions[m.indices[t]], p1 = m.positions[m.indices[t + 1]], p2 = m.positions[m.indices[t + 2]];
    EXPECT_GT(glm::cross(p1 - p0, p2 - p0).z, 0.0);
  }
  EXPECT_NEAR(r.max_slope_deg(), std::atan(2 * kPi * 0.022 / 0.2) * 180 / kPi, 1e-9);
  EXPECT_NEAR(r.max_slope_deg(), 34.65, 0.01);
}

TEST(Geometry, RoofShadingNormalInterpolatesAcrossEachStrip) {
  CorrugatedRoof r;
  r.segments = 8;
  const double step = r.period_m / r.segments;
  for (int s = -3; s < 12; ++s) {
    const double x0 = s * step;
    // At the vertices: the exact normal. Half way: the normalized mean of the two.
    EXPECT_NEAR(glm::dot(roof_mesh_normal(r, x0), roof_normal(r, x0)), 1.0, 1e-12);
    const glm::dvec3 mid = glm::normalize(roof_normal(r, x0) + roof_normal(r, x0 + step));
    EXPECT_NEAR(glm::dot(roof_mesh_normal(r, x0 + step / 2), mid), 1.0, 1e-12);
  }
  // Over a period the normals' slopes cancel: the mean normal is +Z (the roof is flat on average).
  glm::dvec3 sum(0.0);
  const int n = 1000;
  for (int i = 0; i < n; ++i) sum += roof_mesh_normal(r, (i + 0.5) * r.period_m / n);
  EXPECT_NEAR(sum.x / n, 0.0, 1e-9);
  EXPECT_NEAR(sum.y / n, 0.0, 1e-12);
}

}  // namespace
}  // namespace svbrdf
