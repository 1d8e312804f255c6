#include "render/surface.h"

#include <algorithm>
#include <cmath>

#include "appearance/shading.h"
#include "textures/normal_map.h"

namespace svbrdf {

namespace {

// Whether emission_at reads the emissive texture: it has one, and a factor that is not black.
bool reads_emission_texture(const MaterialDesc& m) {
  return m.emissive_texture.present() && m.emissive * m.emissive_strength != Rgb(0.0f);
}

template <typename T>
T lerp3(const std::vector<T>& a, const std::uint32_t* i, float b0, float b1, float b2) {
  return b0 * a[i[0]] + b1 * a[i[1]] + b2 * a[i[2]];
}

glm::vec3 normalize_or(const glm::vec3& v, const glm::vec3& fallback) {
  const float l = glm::length(v);
  return l > 0.0f && std::isfinite(l) ? v / l : fallback;
}

// Keeps a shading normal on the geometric normal's side, so no light leaks through a surface
// whose interpolated normals lean past the horizon.
glm::vec3 same_side(const glm::vec3& ns, const glm::vec3& ng) {
  const float c = glm::dot(ns, ng);
  if (c >= 1e-3f) return ns;
  return glm::normalize(ns + (1e-3f - c) * ng);
}

}  // namespace

SurfacePoint make_surface_point(const EmbreeScene& bvh, const RayHit& hit, const glm::vec3& ray_dir) {
  SurfacePoint sp;
  sp.geom = hit.geom;
  sp.material = hit.geom->material;
  const MeshPrimitive& prim = *hit.geom->prim;
  const std::uint32_t* i = &prim.indices[3 * std::size_t(hit.triangle)];
  const float b1 = hit.b1, b2 = hit.b2, b0 = 1.0f - b1 - b2;
  const glm::mat4& m = bvh.to_world(hit.instance);
  const glm::mat3& nm = bvh.normal_to_world(hit.instance);
  const glm::mat3 m3(m);

  const glm::vec3 p0 = prim.positions[i[0]], p1 = prim.positions[i[1]], p2 = prim.positions[i[2]];
  sp.p = glm::vec3(m * glm::vec4(b0 * p0 + b1 * p1 + b2 * p2, 1.0f));
  // The front face is counter-clockwise in the mesh's own space (glTF §3.7.2.1), whatever the
  // transform's determinant; normals transform with the inverse transpose.
  const glm::vec3 ng_front = normalize_or(nm * glm::cross(p1 - p0, p2 - p0), glm::vec3(0, 0, 1));
  sp.front = glm::dot(ng_front, ray_dir) < 0.0f;
  const glm::vec3 ns_front = normalize_or(nm * lerp3(prim.normals, i, b0, b1, b2), ng_front);

  for (int s = 0; s < 2; ++s)
    if (!prim.texcoords[s].empty()) sp.uv[s] = lerp3(prim.texcoords[s], i, b0, b1, b2);
  if (!prim.colors.empty()) sp.color = lerp3(prim.colors, i, b0, b1, b2);

  // ∂p/∂u, ∂p/∂v of each TEXCOORD set from the triangle's edges (pbrt-v4 §6.5.3).
  glm::vec3 tangent_hint(0.0f);
  for (int s = 0; s < 2; ++s) {
    if (prim.texcoords[s].empty()) continue;
    const glm::vec2 t0 = prim.texcoords[s][i[0]], t1 = prim.texcoords[s][i[1]], t2 = prim.texcoords[s][i[2]];
    const glm::vec2 d1 = t1 - t0, d2 = t2 - t0;
    const glm::vec3 e1 = m3 * (p1 - p0), e2 = m3 * (p2 - p0);
    const float det = d1.x * d2.y - d1.y * d2.x;
    if (std::abs(det) > 1e-20f) {
      sp.dpdu[s] = (d2.y * e1 - d1.y * e2) / det;
      sp.dpdv[s] = (-d2.x * e1 + d1.x * e2) / det;
    }
  }
  if (!prim.tangents.empty()) {
    const glm::vec4 t = lerp3(prim.tangents, i, b0, b1, b2);
    tangent_hint = m3 * glm::vec3(t);
    // B = w·(N × T) in the mesh's space; carried to the world it keeps or flips its handedness.
    const glm::vec3 n_obj = lerp3(prim.normals, i, b0, b1, b2);
    const glm::vec3 b_world = m3 * ((t.w < 0.0f ? -1.0f : 1.0f) * glm::cross(n_obj, glm::vec3(t)));
    sp.bitangent_sign = glm::dot(b_world, glm::cross(ns_front, tangent_hint)) < 0.0f ? -1.0f : 1.0f;
  } else {
    tangent_hint = sp.dpdu[0];
  }
  sp.tangent = tangent_hint;

  glm::vec3 ns = same_side(ns_front, ng_front), ng = ng_front;
  if (!sp.front) ns = -ns, ng = -ng;
  sp.ng = ng;
  sp.ns = ns;
  sp.shading = Frame::from_normal_tangent(ns, normalize_or(tangent_hint, glm::vec3(0.0f)));
  return sp;
}

namespace {

// The normal a tangent-space normal map `map` makes of the unmapped normal `ns` at the hit (glTF
// §3.9.3: +Y up, the map's scale), both on the side the ray came from; ns itself where the primitive
// has no tangent space.
glm::vec3 mapped_normal(const SurfacePoint& sp, const glm::vec3& ns, const TextureRef& map, const TextureSet& textures) {
  if (sp.geom->prim->tangents.empty()) return ns;  // the loader makes tangents wherever a map is used
  const glm::vec3 rgb = glm::vec3(textures.lookup(map, sp.uv[map.uv_set()], false));
  const glm::vec3 t = decode_normal(rgb, map.scale);
  // The tangent frame of the front face (a back face mirrors the mapped normal with it).
  const glm::vec3 n = sp.front ? ns : -ns;
  const glm::vec3 tan = normalize_or(sp.tangent - n * glm::dot(n, sp.tangent), sp.shading.s);
  const glm::vec3 b = sp.bitangent_sign * glm::cross(n, tan);
  glm::vec3 mapped = normalize_or(t.x * tan + t.y * b + t.z * n, n);
  if (!sp.front) mapped = -mapped;
  return same_side(mapped, sp.ng);
}

// The unit direction (dx, dy) of the front face's tangent space (T, B = sign·N×T) in sp.shading's
// frame, projected on its tangent plane.
glm::vec2 tangent_space_direction(const SurfacePoint& sp, const glm::vec2& d) {
  const glm::vec3 n = sp.front ? sp.ns : -sp.ns;
  const glm::vec3 tan = normalize_or(sp.tangent - n * glm::dot(n, sp.tangent), sp.shading.s);
  const glm::vec3 b = sp.bitangent_sign * glm::cross(n, tan);
  const glm::vec3 local = sp.shading.to_local(d.x * tan + d.y * b);
  const glm::vec2 xy(local.x, local.y);
  const float len = glm::length(xy);
  return len > 1e-12f && std::isfinite(len) ? xy / len : glm::vec2(1.0f, 0.0f);
}

}  // namespace

void apply_normal_map(SurfacePoint& sp, const TextureSet& textures) {
  const MaterialDesc& m = *sp.material;
  if (!m.normal_texture.present()) return;
  sp.shading = Frame::from_normal_tangent(mapped_normal(sp, sp.shading.n, m.normal_texture, textures), sp.shading.s);
}

void keep_reflection_above(SurfacePoint& sp, const glm::vec3& wo) {
  const glm::vec3 n = sp.shading.n, ng = sp.ng;
  const float cos_o = glm::dot(wo, ng);
  if (!(cos_o > 0.0f)) return;  // seen from below the geometric surface: nothing to keep above
  // The margin: the reflection at least this far above the horizon (in cosine), never more than
  // most of the view's own elevation, so a grazing view keeps a grazing reflection.
  const float margin = std::min(0.9f * cos_o, 0.01f);
  auto reflection_height = [&](const glm::vec3& m) { return glm::dot(2.0f * glm::dot(wo, m) * m - wo, ng); };
  if (reflection_height(n) >= margin) return;
  // The normal turned toward ng in their common plane, n(t) ∝ (1 − t)·n + t·ng, just enough: at t = 1
  // the reflection is wo's mirror about ng, cos_o ≥ margin above, so the smallest t that reaches the
  // margin is found by bisection (24 halvings: to float precision).
  float lo = 0.0f, hi = 1.0f;
  for (int i = 0; i < 24; ++i) {
    const float mid = 0.5f * (lo + hi);
    if (reflection_height(normalize_or((1.0f - mid) * n + mid * ng, ng)) >= margin) hi = mid;
    else lo = mid;
  }
  sp.shading = Frame::from_normal_tangent(normalize_or((1.0f - hi) * n + hi * ng, ng), sp.shading.s);
}

ShadingParams shading_params(const SurfacePoint& sp, const TextureSet& textures) {
  const MaterialDesc& m = *sp.material;
  ShadingParams sh;
  auto tex = [&](const TextureRef& r, bool color) { return textures.lookup(r, sp.uv[r.uv_set()], color); };
  sh.base_color = m.base_color * Rgb(sp.color);
  if (m.base_color_texture.present()) sh.base_color *= Rgb(tex(m.base_color_texture, true));
  sh.metallic = m.metallic;
  sh.roughness = m.roughness;
  if (m.metallic_roughness_texture.present()) {
    const glm::vec4 mr = tex(m.metallic_roughness_texture, false);
    sh.metallic *= mr.b;  // glTF: metalness in B, roughness in G
    sh.roughness *= mr.g;
  }
  sh.emission = m.emissive * m.emissive_strength;
  if (m.emissive_texture.present()) sh.emission *= Rgb(tex(m.emissive_texture, true));
  sh.ior = m.ior;
  sh.specular = m.specular;
  if (m.specular_texture.present()) sh.specular *= tex(m.specular_texture, false).a;
  sh.specular_color = m.specular_color;
  if (m.specular_color_texture.present()) sh.specular_color *= Rgb(tex(m.specular_color_texture, true));
  sh.transmission = m.transmission;
  if (m.transmission_texture.present()) sh.transmission *= tex(m.transmission_texture, false).r;
  sh.diffuse_roughness = m.diffuse_roughness;
  if (m.diffuse_roughness_texture.present()) sh.diffuse_roughness *= tex(m.diffuse_roughness_texture, false).r;
  sh.unlit = m.unlit;
  // KHR_materials_diffuse_transmission: the share × texture A, the color × texture RGB (sRGB-encoded).
  sh.diffuse_transmission = m.diffuse_transmission;
  if (m.diffuse_transmission_texture.present()) sh.diffuse_transmission *= tex(m.diffuse_transmission_texture, false).a;
  if (sh.diffuse_transmission > 0.0f) {
    sh.diffuse_transmission_color = m.diffuse_transmission_color;
    if (m.diffuse_transmission_color_texture.present())
      sh.diffuse_transmission_color *= Rgb(tex(m.diffuse_transmission_color_texture, true));
  }
  // KHR_materials_sheen: color × texture RGB (sRGB-encoded), roughness × texture A.
  sh.sheen_color = m.sheen_color;
  if (m.sheen_color_texture.present()) sh.sheen_color *= Rgb(tex(m.sheen_color_texture, true));
  if (max_channel(sh.sheen_color) > 0.0f) {
    sh.sheen_roughness = m.sheen_roughness;
    if (m.sheen_roughness_texture.present()) sh.sheen_roughness *= tex(m.sheen_roughness_texture, false).a;
  }
  // KHR_materials_iridescence: weight × texture R; thickness mix(min, max, texture G), or max.
  sh.iridescence = m.iridescence;
  if (m.iridescence_texture.present()) sh.iridescence *= tex(m.iridescence_texture, false).r;
  if (sh.iridescence > 0.0f) {
    sh.iridescence_ior = m.iridescence_ior;
    sh.iridescence_thickness = m.iridescence_thickness_max;
    if (m.iridescence_thickness_texture.present())
      sh.iridescence_thickness = glm::mix(m.iridescence_thickness_min, m.iridescence_thickness_max,
                                          tex(m.iridescence_thickness_texture, false).g);
  }
  // KHR_materials_clearcoat: weight × texture R, roughness × texture G, the coat's own normal map
  // or, without one, the surface's normal before the base's map.
  sh.clearcoat = m.clearcoat;
  if (m.clearcoat_texture.present()) sh.clearcoat *= tex(m.clearcoat_texture, false).r;
  if (sh.clearcoat > 0.0f) {
    sh.clearcoat_roughness = m.clearcoat_roughness;
    if (m.clearcoat_roughness_texture.present()) sh.clearcoat_roughness *= tex(m.clearcoat_roughness_texture, false).g;
    const glm::vec3 nc =
        m.clearcoat_normal_texture.present() ? mapped_normal(sp, sp.ns, m.clearcoat_normal_texture, textures) : sp.ns;
    sh.clearcoat_normal = sp.shading.to_local(nc);
  }
  // KHR_materials_anisotropy: strength × texture B; the direction (cos, sin) of the rotation, or the
  // texture's RG mapped to [−1, 1], normalized, and turned by the rotation.
  sh.anisotropy = m.anisotropy_strength;
  if (sh.anisotropy > 0.0f) {
    const float c = std::cos(m.anisotropy_rotation), s = std::sin(m.anisotropy_rotation);
    glm::vec2 d(c, s);
    if (m.anisotropy_texture.present()) {
      const glm::vec4 a = tex(m.anisotropy_texture, false);
      const glm::vec2 t = normalize_or(glm::vec3(2.0f * a.r - 1.0f, 2.0f * a.g - 1.0f, 0.0f), glm::vec3(1, 0, 0));
      d = glm::vec2(c * t.x - s * t.y, s * t.x + c * t.y);
      sh.anisotropy *= a.b;
    }
    sh.anisotropy_direction = tangent_space_direction(sp, d);
  }
  return sh;
}

Rgb emission_at(const SurfacePoint& sp, const TextureSet& textures, const glm::vec3& wo) {
  return emission_at(*sp.material, sp.uv, textures, glm::dot(wo, sp.ng));
}

Rgb emission_at(const MaterialDesc& m, const glm::vec2 uv[2], const TextureSet& textures, float cos_view) {
  Rgb e = m.emissive * m.emissive_strength;
  if (reads_emission_texture(m)) e *= Rgb(textures.lookup(m.emissive_texture, uv[m.emissive_texture.uv_set()], true));
  if (m.clearcoat > 0.0f && max_channel(e) > 0.0f) {
    float c = m.clearcoat;
    if (m.clearcoat_texture.present()) c *= textures.lookup(m.clearcoat_texture, uv[m.clearcoat_texture.uv_set()], false).r;
    e *= 1.0f - clearcoat_blend(c, cos_view);
  }
  return e;
}

void prefetch_emission(const SurfacePoint& sp, const TextureSet& textures) {
  const MaterialDesc& m = *sp.material;
  if (reads_emission_texture(m)) textures.prefetch(m.emissive_texture, sp.uv[m.emissive_texture.uv_set()]);
}

Rgb base_color_at(const SurfacePoint& sp, const TextureSet& textures) {
  const MaterialDesc& m = *sp.material;
  Rgb c = m.base_color * Rgb(sp.color);
  if (m.base_color_texture.present())
    c *= Rgb(textures.lookup(m.base_color_texture, sp.uv[m.base_color_texture.uv_set()], true));
  return c;
}

Frame geometric_frame(const SurfacePoint& sp) {
  // sp.shading is (T, N×T, N) about the normal on the ray's side, T the tangent made orthogonal to
  // it. The front face's frame is (T, B, N) with B = sign·N×T; a back face negates all three, and
  // N×T flips with N: both cases keep sign·(shading t) and the shading normal.
  const Frame& f = sp.shading;
  const glm::vec3 b = sp.bitangent_sign * f.t;
  return sp.front ? Frame{f.s, b, f.n} : Frame{-f.s, b, f.n};
}

Footprint footprint(const SurfacePoint& sp, int uv_set, const glm::vec3& dpdx, const glm::vec3& dpdy) {
  Footprint f;
  const int s = uv_set == 1 ? 1 : 0;
  f.uv = sp.uv[s];
  const glm::vec3 &dpdu = sp.dpdu[s], &dpdv = sp.dpdv[s];
  // Least squares: dp ≈ dpdu·du + dpdv·dv, solved through the 2×2 normal equations.
  const float a = glm::dot(dpdu, dpdu), b = glm::dot(dpdu, dpdv), c = glm::dot(dpdv, dpdv);
  const float det = a * c - b * b;
  if (!(std::abs(det) > 1e-30f)) return f;
  auto solve = [&](const glm::vec3& dp) {
    const float r0 = glm::dot(dpdu, dp), r1 = glm::dot(dpdv, dp);
    const glm::vec2 d((c * r0 - b * r1) / det, (a * r1 - b * r0) / det);
    return std::isfinite(d.x) && std::isfinite(d.y) ? d : glm::vec2(0.0f);
  };
  f.duv_dx = solve(dpdx);
  f.duv_dy = solve(dpdy);
  return f;
}

void camera_dp(const SurfacePoint& sp, const CameraRay& cr, glm::vec3& dpdx, glm::vec3& dpdy) {
  auto on_plane = [&](const glm::vec3& o, const glm::vec3& d) {
    const float denom = glm::dot(sp.ng, d);
    if (std::abs(denom) < 1e-12f) return sp.p;
    return o + d * (glm::dot(sp.ng, sp.p - o) / denom);
  };
  dpdx = on_plane(cr.dx_origin, cr.dx_dir) - sp.p;
  dpdy = on_plane(cr.dy_origin, cr.dy_dir) - sp.p;
}

}  // namespace svbrdf
