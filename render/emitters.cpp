#include "render/emitters.h"

#include <algorithm>
#include <cmath>

#include "base/error.h"
#include "appearance/shading.h"
#include "base/math.h"
#include "render/surface.h"

namespace svbrdf {

namespace {

// Rec. 709 luminance: the power a triangle is chosen by is a scalar, and the eye's weighting of
// the channels is the one whose noise a viewer sees.
float luminance(const Rgb& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

std::uint64_t primitive_key(int instance, std::size_t primitive) {
  return (std::uint64_t(std::uint32_t(instance)) << 32) | std::uint64_t(primitive);
}

// A uniform point on a triangle by area from two uniforms: the weights of vertices 1 and 2 are
// b₁ = u₂·√u₁ and b₂ = 1 − √u₁ (Turk, "Generating random points in triangles", Graphics Gems 1990).
glm::vec2 uniform_barycentrics(float u1, float u2) {
  const float su = std::sqrt(u1);
  return {u2 * su, 1.0f - su};
}

// The stratified barycentrics (b₁, b₂) at which a textured emitter's mean radiance is estimated: the
// centroids of the 16 equal sub-triangles made by cutting each edge in four.
std::vector<glm::vec2> estimate_points() {
  std::vector<glm::vec2> pts;
  const int n = 4;
  for (int i = 0; i < n; ++i)
    for (int j = 0; i + j < n; ++j) {
      // Upward sub-triangle (i, j), (i+1, j), (i, j+1) and, where it fits, the downward one.
      pts.emplace_back((float(i) + 1.0f / 3.0f) / float(n), (float(j) + 1.0f / 3.0f) / float(n));
      if (i + j + 1 < n) pts.emplace_back((float(i) + 2.0f / 3.0f) / float(n), (float(j) + 2.0f / 3.0f) / float(n));
    }
  return pts;
}

}  // namespace

Emitters::Emitters(const Scene& scene, const EmbreeScene& bvh, const TextureSet& textures) : scene_(&scene) {
  const std::vector<glm::vec2> points = estimate_points();
  std::vector<float> power;
  for (std::size_t inst = 0; inst < scene.instances.size(); ++inst) {
    const Instance& instance = scene.instances[inst];
    if (instance.mesh < 0) continue;
    const Mesh& mesh = scene.meshes[std::size_t(instance.mesh)];
    const glm::mat4& m = bvh.to_world(int(inst));
    const glm::mat3& nm = bvh.normal_to_world(int(inst));
    for (std::size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
      const MeshPrimitive& prim = mesh.primitives[pi];
      const MaterialDesc& mat = scene.material_of(prim);
      if (mat.unlit || max_channel(mat.emissive * mat.emissive_strength) <= 0.0f) continue;
      std::vector<std::int32_t>& entries = by_primitive_[primitive_key(int(inst), pi)];
      entries.assign(prim.triangle_count(), -1);
      for (std::size_t k = 0; k < prim.triangle_count(); ++k) {
        const std::uint32_t* ix = &prim.indices[3 * k];
        Triangle t;
        const glm::vec3 a = prim.positions[ix[0]], b = prim.positions[ix[1]], c = prim.positions[ix[2]];
        t.p0 = glm::vec3(m * glm::vec4(a, 1.0f));
        t.e1 = glm::vec3(m * glm::vec4(b, 1.0f)) - t.p0;
        t.e2 = glm::vec3(m * glm::vec4(c, 1.0f)) - t.p0;
        t.area = 0.5f * glm::length(glm::cross(t.e1, t.e2));
        // The front face is counter-clockwise in the mesh's own space, whatever the transform's
        // determinant (as make_surface_point decides it); normals move with the inverse transpose.
        const glm::vec3 n = nm * glm::cross(b - a, c - a);
        const float nl = glm::length(n);
        if (!(t.area > 0.0f) || !std::isfinite(t.area) || !(nl > 0.0f) || !std::isfinite(nl)) continue;
        t.n_front = n / nl;
        t.geometry.prim = &prim;
        t.geometry.material = &mat;
        t.geometry.textures = &textures;
        t.index = unsigned(k);
        t.two_sided = mat.double_sided;
        Rgb mean(0.0f);
        if (mat.emissive_texture.present() || mat.alpha_mode != AlphaMode::opaque) {
          for (const glm::vec2& b12 : points) mean += emitted(t, b12.x, b12.y, 1.0f);
          mean /= float(points.size());
        } else {
          mean = mat.emissive * mat.emissive_strength;
        }
        const double p = kPiD * double(t.area) * double(luminance(mean)) * (t.two_sided ? 2.0 : 1.0);
        if (!(p > 0.0) || !std::isfinite(p)) continue;
        entries[k] = std::int32_t(triangles_.size());
        triangles_.push_back(t);
        power.push_back(float(p));
        total_power_ += p;
      }
    }
  }
  if (triangles_.size() >= std::size_t(INT32_MAX))
    throw Error("too many emissive triangles to sample: " + std::to_string(triangles_.size()), Error::Kind::internal);
  if (triangles_.empty()) return;
  table_ = AliasTable(power);
  for (std::size_t k = 0; k < triangles_.size(); ++k) triangles_[k].probability = float(table_.probability(k));
}

Rgb Emitters::emitted(const Triangle& t, float b1, float b2, float cos_view) const {
  const MeshPrimitive& prim = *t.geometry.prim;
  const MaterialDesc& mat = *t.geometry.material;
  const std::uint32_t* ix = &prim.indices[3 * std::size_t(t.index)];
  const float b0 = 1.0f - b1 - b2;
  glm::vec2 uv[2]{};
  for (int s = 0; s < 2; ++s)
    if (!prim.texcoords[s].empty())
      uv[s] = b0 * prim.texcoords[s][ix[0]] + b1 * prim.texcoords[s][ix[1]] + b2 * prim.texcoords[s][ix[2]];
  Rgb e = emission_at(mat, uv, *t.geometry.textures, cos_view);
  if (mat.alpha_mode != AlphaMode::opaque) {
    // The surface's presence at the point: MASK keeps it or cuts it; BLEND is there with probability
    // alpha, as the intersection filter decides for a ray (embree_scene.h).
    const float alpha = surface_alpha(t.geometry, t.index, b1, b2);
    e *= mat.alpha_mode == AlphaMode::mask ? (alpha >= mat.alpha_cutoff ? 1.0f : 0.0f) : std::clamp(alpha, 0.0f, 1.0f);
  }
  return e;
}

EmitterSample Emitters::sample(const glm::vec3& x, const glm::vec3& u) const {
  EmitterSample s;
  if (triangles_.empty()) return s;
  float u_rest = 0.0f;
  const Triangle& t = triangles_[table_.sample(u.x, u.y, u_rest)];
  const glm::vec2 b = uniform_barycentrics(u_rest, u.z);
  const glm::vec3 p = t.p0 + b.x * t.e1 + b.y * t.e2;
  const glm::vec3 d = p - x;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.0f)) return s;
  s.distance = std::sqrt(dist2);
  s.wi = d / s.distance;
  // The cosine at the emitter, positive when x sees its front face.
  const float cos_light = -glm::dot(t.n_front, s.wi);
  if (!(std::abs(cos_light) > 0.0f)) return s;
  // Area density probability/area, turned into solid angle at x by distance²/|cos| (pbrt-v4 §4.2.3).
  s.pdf = t.probability / t.area * dist2 / std::abs(cos_light);
  if (!std::isfinite(s.pdf)) {
    s.pdf = 0.0f;
    return s;
  }
  if (cos_light > 0.0f || t.two_sided) s.radiance = emitted(t, b.x, b.y, cos_light);
  return s;
}

float Emitters::pdf(const RayHit& hit, const glm::vec3& dir) const {
  if (triangles_.empty() || !hit.found() || hit.instance < 0) return 0.0f;
  const Mesh& mesh = scene_->meshes[std::size_t(scene_->instances[std::size_t(hit.instance)].mesh)];
  const std::size_t pi = std::size_t(hit.geom->prim - mesh.primitives.data());
  const auto it = by_primitive_.find(primitive_key(hit.instance, pi));
  if (it == by_primitive_.end() || hit.triangle >= it->second.size()) return 0.0f;
  const std::int32_t k = it->second[hit.triangle];
  if (k < 0) return 0.0f;
  const Triangle& t = triangles_[std::size_t(k)];
  const float cos_light = std::abs(glm::dot(t.n_front, dir));
  if (!(cos_light > 0.0f)) return 0.0f;
  const float p = t.probability / t.area * hit.t * hit.t / cos_light;
  return std::isfinite(p) ? p : 0.0f;
}

}  // namespace svbrdf
