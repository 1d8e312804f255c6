#pragma once
// What the integrator knows at a hit: the world-space point and normals, the shading frame (with the
// normal map applied), texture coordinates and their footprint, and the material's parameters there.
#include <glm/glm.hpp>

#include "appearance/frame.h"
#include "appearance/gltf_surface_bsdf.h"
#include "mip/texture_filter.h"
#include "render/camera.h"
#include "render/embree_scene.h"

namespace svbrdf {

struct SurfacePoint {
  glm::vec3 p{0.0f};
  glm::vec3 ng{0.0f, 0.0f, 1.0f};  // geometric normal on the side the ray came from
  Frame shading;                   // z = shading normal (interpolated, normal-mapped), same side as ng
  glm::vec2 uv[2]{};               // TEXCOORD_0/1 (zero when absent)
  glm::vec4 color{1.0f};           // COLOR_0
  glm::vec3 dpdu[2]{}, dpdv[2]{};  // world ∂p/∂(u, v) of TEXCOORD_0/1 (zero when absent)
  glm::vec3 ns{0.0f, 0.0f, 1.0f};  // the interpolated normal before any normal map, same side as ng
  glm::vec3 tangent{0.0f};         // world TANGENT (or ∂p/∂u when absent), not normalized
  float bitangent_sign = 1.0f;     // B = sign·(N × T) in world space, N the front-face shading normal
  bool front = true;               // the ray hit the front face
  const GeometryData* geom = nullptr;
  const MaterialDesc* material = nullptr;
};

SurfacePoint make_surface_point(const EmbreeScene& bvh, const RayHit& hit, const glm::vec3& ray_dir);

// Applies the material's normal map to sp.shading (tangent space, +Y up, scale; glTF §3.9.3).
void apply_normal_map(SurfacePoint& sp, const TextureSet& textures);

// Turns sp.shading's normal just enough toward the viewer that the mirror reflection of `wo` (unit,
// toward the viewer) leaves above the geometric surface, by a margin: a shading normal that faces
// away from the viewer otherwise shades a surface the viewer sees as black. Nothing changes where the
// reflection already leaves above. The normal turns toward the geometric normal in their common
// plane, as Cycles' ensure_valid_reflection turns it (found here by bisection).
void keep_reflection_above(SurfacePoint& sp, const glm::vec3& wo);

// The material's parameters at the hit, in the frame sp.shading (call after apply_normal_map): the
// coat's normal and the anisotropy direction are expressed in it.
ShadingParams shading_params(const SurfacePoint& sp, const TextureSet& textures);
// The parts of shading_params that the MIP filters do not cover: emission, and the base color (for
// the albedo AOV), both at level0. Emission leaves toward `wo` (world, unit) through the clear coat,
// which darkens it by 1 − clearcoat·Fc (KHR_materials_clearcoat, "Emission"); Fc is taken at the
// geometric normal here and in light sampling alike, so both strategies see the same radiance.
Rgb emission_at(const SurfacePoint& sp, const TextureSet& textures, const glm::vec3& wo);
// The same at texture coordinates uv[0], uv[1] of a material (emitters.h samples points this way),
// seen at cosine `cos_view` to the geometric normal.
Rgb emission_at(const MaterialDesc& m, const glm::vec2 uv[2], const TextureSet& textures, float cos_view);
// Prefetches the texel emission_at will read, if it reads one.
void prefetch_emission(const SurfacePoint& sp, const TextureSet& textures);
Rgb base_color_at(const SurfacePoint& sp, const TextureSet& textures);

// The geometric tangent frame of brdf-mip.md at a hit, in which normal maps are defined: z = the
// interpolated normal before any normal map (on the side the ray came from), x = the tangent made
// orthogonal to it, y = the glTF bitangent (sign·N×T). A back-face hit negates all three, which
// mirrors a tangent-space normal exactly as apply_normal_map does. Call before apply_normal_map.
Frame geometric_frame(const SurfacePoint& sp);

// The texture footprint of TEXCOORD_`uv_set` at the hit (mip/texture_filter.h's Footprint: uv and
// its derivatives per pixel step), from the position derivatives by least squares on ∂p/∂u, ∂p/∂v
// (pbrt-v4 §10.1.1). Zero derivatives where the set is absent or degenerate.
Footprint footprint(const SurfacePoint& sp, int uv_set, const glm::vec3& dpdx, const glm::vec3& dpdy);

// The position differentials of a camera ray's two offset rays on the tangent plane at the hit.
// Secondary rays use Camera::approximate_dp instead (pbrt-v4's approximation).
void camera_dp(const SurfacePoint& sp, const CameraRay& cr, glm::vec3& dpdx, glm::vec3& dpdy);

}  // namespace svbrdf
