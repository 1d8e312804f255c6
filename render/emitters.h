#pragma once
// Emissive triangles as lights: every triangle of a placed primitive whose material emits
// (emissiveFactor × KHR_materials_emissive_strength, times the emissive texture) can be sampled
// directly from a shading point — next-event estimation to area lights (CGPP §32.4; pbrt-v4 §12.5) —
// so a room lit by emissive panels converges as quickly as one lit by punctual lights.
//
// A triangle is chosen with probability proportional to its power, π·area·Y(mean emitted radiance)
// (× 2 when the material is doubleSided: it emits from both faces), by an alias table; a point on it
// uniformly by area. The mean radiance of a textured emitter is estimated from the texture at a few
// stratified points of the triangle: the estimate only shapes the choice, never the value, so an
// error in it costs variance, not bias. A triangle whose estimate is zero is never drawn; the
// integrator then gives the hits its BSDF sampling finds on it full weight (pdf() returns 0 there),
// which keeps every estimator unbiased.
//
// A single-sided emitter emits from its front face only (glTF 2.0 §3.9.6: its back face is not part
// of the surface); alphaMode MASK and BLEND scale the emitted radiance by the surface's presence,
// as the intersection filters do for rays that hit it.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "render/alias_table.h"
#include "render/embree_scene.h"

namespace svbrdf {

// A point drawn on an emitter as seen from a shading point x.
struct EmitterSample {
  glm::vec3 wi{0.0f};  // from x toward the point, unit
  float distance = 0.0f;
  Rgb radiance{0.0f};  // emitted from the point toward x (zero from a single-sided emitter's back)
  float pdf = 0.0f;    // solid-angle density at x; 0 when nothing was drawn
};

class Emitters {
 public:
  Emitters() = default;
  Emitters(const Scene& scene, const EmbreeScene& bvh, const TextureSet& textures);

  bool empty() const { return triangles_.empty(); }
  std::size_t triangle_count() const { return triangles_.size(); }
  // Σ of the triangles' power estimates (W, with the renderer's radiance in W/(m²·sr)).
  double total_power() const { return total_power_; }

  // A point on an emitter drawn from three uniforms: u.x and u.y choose the triangle (the alias
  // table's bucket and choice), u.y's remainder and u.z the point on it.
  EmitterSample sample(const glm::vec3& x, const glm::vec3& u) const;

  // The density (solid angle at the ray's origin) with which sample() draws the point that a ray
  // along unit `dir` hits at distance hit.t; 0 for a surface that is not an emitter or never drawn.
  float pdf(const RayHit& hit, const glm::vec3& dir) const;

 private:
  struct Triangle {
    glm::vec3 p0{0.0f}, e1{0.0f}, e2{0.0f};  // world-space vertex 0 and edges to vertices 1 and 2
    glm::vec3 n_front{0.0f};                  // unit front-face normal (counter-clockwise, glTF §3.7.2.1)
    float area = 0.0f;
    float probability = 0.0f;  // of being drawn by the alias table
    GeometryData geometry;     // the material, primitive and textures (for emission and alpha)
    unsigned index = 0;        // the triangle in its primitive
    bool two_sided = false;
  };
  // Emission at barycentrics (b1, b2) of triangle t seen at cosine cos_view to its normal (the
  // clear coat darkens it), before the side test, alpha included.
  Rgb emitted(const Triangle& t, float b1, float b2, float cos_view) const;

  std::vector<Triangle> triangles_;
  AliasTable table_;
  double total_power_ = 0.0;
  // (instance, primitive index in its mesh) → per triangle of the primitive, its entry in
  // triangles_ (−1: not an emitter, or never drawn).
  std::unordered_map<std::uint64_t, std::vector<std::int32_t>> by_primitive_;
  const Scene* scene_ = nullptr;
};

}  // namespace svbrdf
