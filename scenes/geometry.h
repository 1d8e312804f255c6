#pragma once
// The shapes scenes are made of: textured rectangles and boxes whose texture coordinates keep the
// material's physical scale (one texel is mm_per_texel millimetres on every face, the texture
// repeating), and the corrugated tile roof of Exercise 27.11(c).
#include <glm/glm.hpp>

#include "gltf/writer.h"

namespace svbrdf {

// A rectangle centred at `center`, spanned by the unit directions `right` (texture +u) and `up`
// (texture −v, the normal map's +Y), facing cross(right, up), `width` × `height` metres.
// Texture coordinates: `uv_per_m` texture repeats per metre, the top-left corner (−right, +up) at
// `uv_origin`. Counter-clockwise seen from the front; tangent = right, w = +1.
TriangleMesh rectangle(const glm::dvec3& center, const glm::dvec3& right, const glm::dvec3& up, double width,
                       double height, double uv_per_m, const glm::dvec2& uv_origin = {0.0, 0.0});

// An axis-aligned box centred at the origin with sides `size` (x, y, z) metres: six rectangles
// facing out. Each face's texture runs along its own axes at `uv_per_m`, so texels stay square and
// of the same physical size on every face.
TriangleMesh box(const glm::dvec3& size, double uv_per_m);

// A tray: a base plate of `size.x` × `size.z` and `plate` metres thick under a rim `rim` wide
// rising to `size.y`, all as boxes, centred on the origin in x and z with its bottom at y = 0.
TriangleMesh tray(const glm::dvec3& size, double rim, double plate, double uv_per_m);

// The tile roof of Exercise 27.11(c): the height field z(x) = A·cos(2πx/P) — rows of channel and
// cover tiles, the corrugation of a Spanish tile roof as one smooth profile — over x ∈ [−L/2, L/2]
// (L = periods·P, periods even so the mesh starts and ends on a crest) and y ∈ [−W/2, W/2], facing
// +Z, ridges along y. Each period is `segments` strips; vertex normals are the height field's exact
// normals, so the shading normal at x is their linear interpolation across the strip, normalized
// (what a renderer with smooth shading sees). The profile's steepest slope is atan(2πA/P).
struct CorrugatedRoof {
  double period_m = 0.2;
  double amplitude_m = 0.02;
  int segments = 16;
  int periods = 2;
  double width_m = 1.0;

  double length_m() const { return periods * period_m; }
  double max_slope_deg() const;
};

TriangleMesh corrugated_roof(const CorrugatedRoof& roof);

// The exact normal of the height field at x.
glm::dvec3 roof_normal(const CorrugatedRoof& roof, double x);
// The mesh's shading normal at x: the interpolation of its two vertex normals, normalized.
glm::dvec3 roof_mesh_normal(const CorrugatedRoof& roof, double x);

}  // namespace svbrdf
