#include "render/embree_scene.h"

#include <cassert>
#include <cmath>

#include "appearance/rng.h"
#include "base/error.h"

namespace svbrdf {

namespace {

glm::vec2 interpolate(const std::vector<glm::vec2>& a, const MeshPrimitive& p, unsigned tri, float b1, float b2) {
  const std::uint32_t* i = &p.indices[3 * std::size_t(tri)];
  return (1.0f - b1 - b2) * a[i[0]] + b1 * a[i[1]] + b2 * a[i[2]];
}

// Embree calls this for every candidate hit of a geometry that needs it (N = 1 for the single-ray
// queries used here); clearing valid[i] rejects the hit and traversal goes on behind it.
void surface_filter(const RTCFilterFunctionNArguments* args) {
  const auto* g = static_cast<const GeometryData*>(args->geometryUserPtr);
  const auto* ctx = reinterpret_cast<const TraceContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    if (g->cull_back) {
      // Embree's Ng follows the counter-clockwise winding (e1 × e2), the glTF front face; ray and Ng are
      // in the same (object or world) space here, so the sign of their dot product is the side.
      const float d = RTCHitN_Ng_x(args->hit, args->N, i) * RTCRayN_dir_x(args->ray, args->N, i) +
                      RTCHitN_Ng_y(args->hit, args->N, i) * RTCRayN_dir_y(args->ray, args->N, i) +
                      RTCHitN_Ng_z(args->hit, args->N, i) * RTCRayN_dir_z(args->ray, args->N, i);
      if (d > 0.0f) {
        args->valid[i] = 0;
        continue;
      }
    }
    if (g->material->alpha_mode == AlphaMode::opaque) continue;
    const unsigned tri = RTCHitN_primID(args->hit, args->N, i);
    float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
    if (g->flipped) std::swap(u, v);
    const float alpha = surface_alpha(*g, tri, u, v);
    if (g->material->alpha_mode == AlphaMode::mask) {
      if (alpha < g->material->alpha_cutoff) args->valid[i] = 0;
    } else {
      // Stochastic opacity: one uniform number per (ray, placed surface, triangle), so a path's
      // decision never depends on traversal order or thread, and two instances of a mesh decide apart.
      const std::uint64_t inst = RTCHitN_instID(args->hit, args->N, i, 0);
      const std::uint64_t h = mix64(ctx->seed ^ mix64((std::uint64_t(g->id) << 32) + tri + 1) ^ mix64(inst + 7));
      const float xi = static_cast<float>(h >> 40) * 0x1p-24f;
      if (xi >= alpha) args->valid[i] = 0;
    }
  }
}

}  // namespace

float surface_alpha(const GeometryData& g, unsigned triangle, float b1, float b2) {
  const MaterialDesc& m = *g.material;
  float alpha = m.base_alpha;
  const MeshPrimitive& p = *g.prim;
  if (m.base_color_texture.present()) {
    const glm::vec2 uv = interpolate(p.texcoords[m.base_color_texture.uv_set()], p, triangle, b1, b2);
    alpha *= g.textures->lookup(m.base_color_texture, uv, true).a;
  }
  if (!p.colors.empty()) {
    const std::uint32_t* i = &p.indices[3 * std::size_t(triangle)];
    alpha *= (1.0f - b1 - b2) * p.colors[i[0]].a + b1 * p.colors[i[1]].a + b2 * p.colors[i[2]].a;
  }
  return alpha;
}

RTCGeometry EmbreeScene::make_triangles(const MeshPrimitive& prim, const glm::dmat4* bake, bool flip,
                                        GeometryData* data) const {
  RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                        3 * sizeof(float), prim.positions.size()));
  auto* ix = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                           3 * sizeof(unsigned), prim.triangle_count()));
  if (!v || !ix) throw Error("Embree: cannot allocate geometry buffers for " + prim.where, Error::Kind::internal);
  for (std::size_t k = 0; k < prim.positions.size(); ++k) {
    glm::vec3 p = prim.positions[k];
    if (bake) p = glm::vec3(*bake * glm::dvec4(glm::dvec3(p), 1.0));
    v[3 * k] = p.x, v[3 * k + 1] = p.y, v[3 * k + 2] = p.z;
  }
  for (std::size_t t = 0; t < prim.triangle_count(); ++t) {
    ix[3 * t] = prim.indices[3 * t];
    ix[3 * t + 1] = prim.indices[3 * t + (flip ? 2 : 1)];
    ix[3 * t + 2] = prim.indices[3 * t + (flip ? 1 : 2)];
  }
  rtcSetGeometryUserData(g, data);
  if (data->cull_back || data->material->alpha_mode != AlphaMode::opaque) {
    rtcSetGeometryIntersectFilterFunction(g, surface_filter);
    rtcSetGeometryOccludedFilterFunction(g, surface_filter);
  }
  rtcCommitGeometry(g);
  return g;
}

EmbreeScene::EmbreeScene(const EmbreeDevice& device, const Scene& scene, const TextureSet& textures)
    : device_(device.get()) {
  top_ = rtcNewScene(device_);
  rtcSetSceneFlags(top_, RTC_SCENE_FLAG_ROBUST);

  // How many nodes place each mesh decides world-space geometry versus instancing.
  std::vector<int> uses(scene.meshes.size(), 0);
  for (const Instance& in : scene.instances) ++uses[static_cast<std::size_t>(in.mesh)];

  std::uint32_t next_geometry_id = 0;
  auto data_for = [&](const MeshPrimitive& p, int instance, bool flipped) {
    GeometryData d;
    d.prim = &p;
    d.material = &scene.material_of(p);
    d.textures = &textures;
    d.instance = instance;
    d.flipped = flipped;
    d.cull_back = !d.material->double_sided && d.material->transmission == 0.0f;
    d.id = next_geometry_id++;
    return d;
  };

  // Instanced meshes: one BLAS each.
  mesh_scenes_.assign(scene.meshes.size(), nullptr);
  mesh_geometry_.resize(scene.meshes.size());
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    if (uses[m] < 2) continue;
    const auto& prims = scene.meshes[m].primitives;
    mesh_geometry_[m].reserve(prims.size());
    for (const MeshPrimitive& p : prims) mesh_geometry_[m].push_back(data_for(p, -1, false));
    RTCScene s = rtcNewScene(device_);
    rtcSetSceneFlags(s, RTC_SCENE_FLAG_ROBUST);
    for (std::size_t k = 0; k < prims.size(); ++k) {
      if (prims[k].triangle_count() == 0) continue;
      RTCGeometry g = make_triangles(prims[k], nullptr, false, &mesh_geometry_[m][k]);
      rtcAttachGeometryByID(s, g, static_cast<unsigned>(k));
      rtcReleaseGeometry(g);
    }
    rtcCommitScene(s);
    mesh_scenes_[m] = s;
  }

  std::size_t world_count = 0;
  for (const Instance& in : scene.instances)
    if (uses[static_cast<std::size_t>(in.mesh)] < 2)
      world_count += scene.meshes[static_cast<std::size_t>(in.mesh)].primitives.size();
  world_geometry_.reserve(world_count);  // Embree keeps pointers into it

  to_world_.resize(scene.instances.size());
  normal_to_world_.resize(scene.instances.size());
  instance_mesh_.resize(scene.instances.size());
  unsigned next_id = 0;
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& in = scene.instances[i];
    to_world_[i] = glm::mat4(in.to_world);
    normal_to_world_[i] = glm::mat3(glm::transpose(glm::inverse(glm::dmat3(in.to_world))));
    instance_mesh_[i] = in.mesh;
    const auto m = static_cast<std::size_t>(in.mesh);
    if (uses[m] >= 2) {
      RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
      rtcSetGeometryInstancedScene(g, mesh_scenes_[m]);
      rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &to_world_[i][0][0]);
      rtcCommitGeometry(g);
      rtcAttachGeometryByID(top_, g, next_id);
      rtcReleaseGeometry(g);
      top_index_.push_back(int(i));
      ++next_id;
      empty_ = false;
    } else {
      // A transform with negative determinant mirrors the mesh; glTF then counts the clockwise
      // winding as front (§3.7.2.1). Reversing the index order keeps Embree's e1 × e2 on the front.
      const bool flip = glm::determinant(glm::dmat3(in.to_world)) < 0.0;
      for (const MeshPrimitive& p : scene.meshes[m].primitives) {
        if (p.triangle_count() == 0) continue;
        world_geometry_.push_back(data_for(p, int(i), flip));
        RTCGeometry g = make_triangles(p, &in.to_world, flip, &world_geometry_.back());
        rtcAttachGeometryByID(top_, g, next_id);
        rtcReleaseGeometry(g);
        top_index_.push_back(int(world_geometry_.size() - 1));
        ++next_id;
        empty_ = false;
      }
    }
  }
  rtcCommitScene(top_);
  if (rtcGetDeviceError(device_) != RTC_ERROR_NONE)
    throw Error("Embree: building the scene failed (see the message above)", Error::Kind::internal);
  RTCBounds b;
  rtcGetSceneBounds(top_, &b);
  if (!empty_) {
    bounds_min_ = {b.lower_x, b.lower_y, b.lower_z};
    bounds_max_ = {b.upper_x, b.upper_y, b.upper_z};
  }
}

EmbreeScene::~EmbreeScene() {
  rtcReleaseScene(top_);
  for (RTCScene s : mesh_scenes_)
    if (s) rtcReleaseScene(s);
}

namespace {

// Debian's Embree 3 asserts (SIGABRT) on a ray with a NaN or infinite component. Cameras and
// geometry are validated when the scene is read, so none should arrive: a debug build stops on one,
// a release build treats it as a ray that hits nothing, never handing it to Embree. tfar may be
// +inf (an unbounded ray).
bool finite_ray(float ox, float oy, float oz, float dx, float dy, float dz, float tnear, float tfar) {
  const bool ok = std::isfinite(ox + oy + oz) && std::isfinite(dx + dy + dz) && std::isfinite(tnear) &&
                  !std::isnan(tfar) && (dx != 0.0f || dy != 0.0f || dz != 0.0f);
  assert(ok && "a non-finite ray reached the Embree scene");
  return ok;
}

}  // namespace

RayHit EmbreeScene::intersect_components(float ox, float oy, float oz, float dx, float dy, float dz, float tnear,
                                         float tfar, std::uint64_t seed) const {
  if (!finite_ray(ox, oy, oz, dx, dy, dz, tnear, tfar)) return RayHit{};
  TraceContext ctx;
  rtcInitIntersectContext(&ctx.embree);
  ctx.seed = seed;
  RTCRayHit rh;
  rh.ray.org_x = ox, rh.ray.org_y = oy, rh.ray.org_z = oz;
  rh.ray.dir_x = dx, rh.ray.dir_y = dy, rh.ray.dir_z = dz;
  rh.ray.tnear = tnear, rh.ray.tfar = tfar;
  rh.ray.time = 0, rh.ray.mask = ~0u, rh.ray.id = 0, rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(top_, &ctx.embree, &rh);
  RayHit out;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return out;
  out.t = rh.ray.tfar;
  out.triangle = rh.hit.primID;
  if (rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID) {
    const int inst = top_index_[rh.hit.instID[0]];
    out.instance = inst;
    out.geom = &mesh_geometry_[static_cast<std::size_t>(instance_mesh_[static_cast<std::size_t>(inst)])][rh.hit.geomID];
  } else {
    out.geom = &world_geometry_[static_cast<std::size_t>(top_index_[rh.hit.geomID])];
    out.instance = out.geom->instance;
  }
  out.b1 = rh.hit.u, out.b2 = rh.hit.v;
  if (out.geom->flipped) std::swap(out.b1, out.b2);
  return out;
}

bool EmbreeScene::occluded_components(float ox, float oy, float oz, float dx, float dy, float dz, float tnear,
                                      float tfar, std::uint64_t seed) const {
  if (!finite_ray(ox, oy, oz, dx, dy, dz, tnear, tfar)) return false;
  TraceContext ctx;
  rtcInitIntersectContext(&ctx.embree);
  ctx.seed = seed;
  RTCRay r;
  r.org_x = ox, r.org_y = oy, r.org_z = oz;
  r.dir_x = dx, r.dir_y = dy, r.dir_z = dz;
  r.tnear = tnear, r.tfar = tfar;
  r.time = 0, r.mask = ~0u, r.id = 0, r.flags = 0;
  rtcOccluded1(top_, &ctx.embree, &r);
  return r.tfar < 0.0f;  // Embree sets tfar to −inf on a hit
}

}  // namespace svbrdf
