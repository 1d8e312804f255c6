#pragma once
// The scene's triangles in one Embree 3 BVH. A mesh placed by one node is put into the top-level
// scene in world space; a mesh placed by several nodes is built once and instanced. Intersection
// filters do what glTF asks of the surface itself: back faces of single-sided materials are culled
// (glTF 2.0 §3.9.6, "doubleSided"), alphaMode MASK cuts at alphaCutoff and BLEND is stochastic
// opacity (a surface is hit with probability alpha), for camera, path and shadow rays alike.
// Materials with KHR_materials_transmission are never culled: refracted paths see them from inside.
#include <cstdint>
#include <limits>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include "render/embree_device.h"
#include "gltf/scene.h"
#include "render/texture_set.h"

namespace svbrdf {

// What a hit on one Embree geometry refers to (the geometry's user data).
struct GeometryData {
  const MeshPrimitive* prim = nullptr;
  const MaterialDesc* material = nullptr;
  const TextureSet* textures = nullptr;
  int instance = -1;      // Scene::instances index of world-space geometry; −1 inside an instanced mesh
  bool flipped = false;   // Embree holds triangle (i0, i2, i1): a mirroring transform was baked in
  bool cull_back = false;
  std::uint32_t id = 0;   // stable across runs (a pointer is not): seeds stochastic opacity
};

// A ray query's result: where along the ray, which triangle of which placed primitive, and the
// barycentrics of vertices 1 and 2 in the primitive's own index order.
struct RayHit {
  float t = std::numeric_limits<float>::infinity();
  const GeometryData* geom = nullptr;
  int instance = -1;  // Scene::instances index
  unsigned triangle = 0;
  float b1 = 0, b2 = 0;
  bool found() const { return geom != nullptr; }
};

// The ray's random seed for stochastic opacity travels with Embree's intersect context.
struct TraceContext {
  RTCIntersectContext embree;
  std::uint64_t seed = 0;
};

// The opacity of a material at a point: base color alpha · factor · COLOR_0 alpha (glTF §3.9.2).
float surface_alpha(const GeometryData& g, unsigned triangle, float b1, float b2);

class EmbreeScene {
 public:
  EmbreeScene(const EmbreeDevice& device, const Scene& scene, const TextureSet& textures);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // The closest hit in (tnear, tfar); `seed` drives stochastic opacity.
  RayHit intersect(const glm::vec3& origin, const glm::vec3& dir, float tnear, float tfar, std::uint64_t seed) const {
    return intersect_components(origin.x, origin.y, origin.z, dir.x, dir.y, dir.z, tnear, tfar, seed);
  }
  // Whether anything blocks the segment (tnear, tfar) along the ray.
  bool occluded(const glm::vec3& origin, const glm::vec3& dir, float tnear, float tfar, std::uint64_t seed) const {
    return occluded_components(origin.x, origin.y, origin.z, dir.x, dir.y, dir.z, tnear, tfar, seed);
  }

  RTCScene handle() const { return top_; }
  glm::vec3 bounds_min() const { return bounds_min_; }
  glm::vec3 bounds_max() const { return bounds_max_; }
  bool empty() const { return empty_; }

  // Object-to-world of a Scene instance, as floats, and its normal matrix (inverse transpose).
  const glm::mat4& to_world(int instance) const { return to_world_[static_cast<std::size_t>(instance)]; }
  const glm::mat3& normal_to_world(int instance) const { return normal_to_world_[static_cast<std::size_t>(instance)]; }

 private:
  // intersect and occluded (inline, above) take the ray's components one by one: a vector passed by
  // value is read as 8 + 4 bytes, and where the caller wrote it a float at a time that read stalls
  // store-to-load forwarding, once per ray (bench/results/render.md).
  RayHit intersect_components(float ox, float oy, float oz, float dx, float dy, float dz, float tnear, float tfar,
                              std::uint64_t seed) const;
  bool occluded_components(float ox, float oy, float oz, float dx, float dy, float dz, float tnear, float tfar,
                           std::uint64_t seed) const;
  RTCGeometry make_triangles(const MeshPrimitive& prim, const glm::dmat4* bake, bool flip, GeometryData* data) const;

  RTCDevice device_;
  RTCScene top_ = nullptr;
  std::vector<RTCScene> mesh_scenes_;            // instanced meshes' BLAS (null for meshes used once)
  std::vector<std::vector<GeometryData>> mesh_geometry_;  // per mesh, per primitive (instanced meshes)
  std::vector<GeometryData> world_geometry_;     // per top-level geomID of world-space geometry
  std::vector<int> top_index_;  // per top-level geomID: the instance (instanced mesh) or world_geometry_ index
  std::vector<int> instance_mesh_;               // per Scene instance: its mesh
  std::vector<glm::mat4> to_world_;
  std::vector<glm::mat3> normal_to_world_;
  glm::vec3 bounds_min_{0.0f}, bounds_max_{0.0f};
  bool empty_ = true;
};

}  // namespace svbrdf
