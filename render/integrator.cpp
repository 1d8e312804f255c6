#include "render/integrator.h"

#include <algorithm>
#include <cmath>

#include "render/surface.h"
#include "render/surface_bsdf.h"

namespace svbrdf {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

float max3(const Rgb& c) { return std::max(c.x, std::max(c.y, c.z)); }

// Veach's power heuristic with β = 2 for one sample of each strategy.
float power_heuristic(float pa, float pb) {
  const float a = pa * pa, b = pb * pb;
  return a + b > 0.0f ? a / (a + b) : 0.0f;
}

// A new ray's origin: the hit point pushed off the surface along the geometric normal, toward the
// side the ray leaves on, by a few ulps of the coordinates plus a hair of the scene size.
glm::vec3 offset_origin(const glm::vec3& p, const glm::vec3& ng, const glm::vec3& dir, float extent) {
  const float m = std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z)));
  const float eps = 3e-6f * m + 1e-6f * extent;
  return p + (glm::dot(dir, ng) > 0.0f ? eps : -eps) * ng;
}

float base_color_level(const RenderWorld& w, const SurfacePoint& sp, const Footprint& fp) {
  const TextureRef& r = sp.material->base_color_texture;
  if (!r.present()) return 0.0f;
  const glm::vec2 size(w.textures->size(r));
  const glm::vec2 dx = r.transform.apply_linear(fp.duvdx) * size, dy = r.transform.apply_linear(fp.duvdy) * size;
  const float width = std::max(glm::length(dx), glm::length(dy));
  return width > 1.0f ? std::log2(width) : 0.0f;
}

}  // namespace

PathSample trace_path(const RenderWorld& w, const IntegratorSettings& s, float film_x, float film_y, Rng& rng) {
  PathSample out;
  CameraRay cr;
  if (s.footprints) cr = w.camera->generate(film_x, film_y);
  else cr.ray = w.camera->ray(film_x, film_y);
  Ray ray = cr.ray;
  Rgb beta(1.0f);
  bool last_impulse = true;  // the camera ray counts as an impulse: nothing else could have found what it sees
  float last_pdf = 0.0f;
  const bool env_on = !w.environment.black();
  auto u1 = [&] { return rng.next_float(); };
  auto seed = [&] { return (std::uint64_t(rng.next_u32()) << 32) | rng.next_u32(); };

  auto occluded = [&](const glm::vec3& o, const glm::vec3& d, float tmax) {
    const std::uint64_t sd = seed();
    ++out.rays;
    if (w.ray_log) w.ray_log->record(o, d, 0.0f, tmax, sd, true);
    return w.bvh->occluded(o, d, 0.0f, tmax, sd);
  };

  for (int depth = 0;; ++depth) {
    const std::uint64_t hit_seed = seed();
    if (w.ray_log) w.ray_log->record(ray.origin, ray.dir, ray.tnear, ray.tfar, hit_seed, false);
    const RayHit hit = w.bvh->intersect(ray.origin, ray.dir, ray.tnear, ray.tfar, hit_seed);
    ++out.rays;
    if (!hit.found()) {
      if (env_on) {
        float weight = 1.0f;
        if (!last_impulse) {
          if (s.light_sampling == LightSampling::nee) weight = 0.0f;
          else if (s.light_sampling == LightSampling::mis) weight = power_heuristic(last_pdf, w.environment.pdf(ray.dir));
        }
        if (weight > 0.0f) out.radiance += beta * w.environment.radiance(ray.dir) * weight;
      }
      break;
    }

    SurfacePoint sp = make_surface_point(*w.bvh, hit, ray.dir);
    apply_normal_map(sp, *w.textures);
    const ShadingParams sh = shading_params(sp, *w.textures);
    if (depth == 0) {
      out.albedo = sh.base_color;
      out.normal = sp.shading.n;
      out.depth = hit.t;
      if (s.footprints) {
        glm::vec3 dpdx, dpdy;
        camera_dp(sp, cr, dpdx, dpdy);
        out.mip_level = base_color_level(w, sp, footprint(sp, dpdx, dpdy));
      }
    }
    if (sh.unlit) {
      // KHR_materials_unlit: the base color is the radiance leaving toward the viewer; nothing scatters.
      out.radiance += beta * sh.base_color;
      break;
    }
    out.radiance += beta * sh.emission;
    if (depth >= s.max_depth) break;

    const SurfaceBsdf bsdf(sh);
    const glm::vec3 wo = sp.shading.to_local(-ray.dir);

    // Next-event estimation: every punctual light (they are delta lights: light sampling only).
    for (const LightDesc& light : w.lights) {
      const LightArrival a = arrive(light, sp.p);
      if (max3(a.irradiance) <= 0.0f || glm::dot(a.wi, sp.ng) <= 0.0f) continue;
      const glm::vec3 wi = sp.shading.to_local(a.wi);
      const Rgb f = bsdf.eval(wi, wo);
      if (max3(f) <= 0.0f) continue;
      const glm::vec3 o = offset_origin(sp.p, sp.ng, a.wi, w.scene_extent);
      const float tmax = std::isinf(a.distance) ? kInfinity : glm::length(light.position - o) * (1.0f - 1e-5f);
      if (!occluded(o, a.wi, tmax)) out.radiance += beta * f * a.irradiance * wi.z;
    }
    // Next-event estimation: the environment.
    if (env_on && s.light_sampling != LightSampling::bsdf) {
      float pdf_light = 0.0f;
      const glm::vec3 dir = w.environment.sample({u1(), u1()}, pdf_light);
      if (pdf_light > 0.0f && glm::dot(dir, sp.ng) > 0.0f) {
        const glm::vec3 wi = sp.shading.to_local(dir);
        const Rgb f = bsdf.eval(wi, wo);
        if (max3(f) > 0.0f) {
          if (!occluded(offset_origin(sp.p, sp.ng, dir, w.scene_extent), dir, kInfinity)) {
            const float weight =
                s.light_sampling == LightSampling::mis ? power_heuristic(pdf_light, bsdf.pdf(wi, wo)) : 1.0f;
            out.radiance += beta * f * w.environment.radiance(dir) * (wi.z * weight / pdf_light);
          }
        }
      }
    } else {
      u1(), u1();  // keep the random sequence's layout the same across strategies
    }

    // Continue the path by sampling the BSDF.
    const BsdfSample bs = bsdf.sample(wo, SampleU(u1(), u1(), u1()));
    if (bs.kind == SampleKind::absorbed) break;
    const glm::vec3 wi_world = sp.shading.to_world(bs.wi);
    // f_eff vanishes below the geometric surface (brdf-mip.md): a finite sample there is absorbed.
    if (bs.kind == SampleKind::finite && glm::dot(wi_world, sp.ng) <= 0.0f) break;
    beta *= bs.weight;
    if (!(max3(beta) > 0.0f) || !std::isfinite(max3(beta))) break;
    last_impulse = bs.kind == SampleKind::impulse;
    last_pdf = bs.pdf;
    ray = Ray{offset_origin(sp.p, sp.ng, wi_world, w.scene_extent), glm::normalize(wi_world), 0.0f, kInfinity};

    if (depth + 1 >= s.rr_depth) {
      const float q = std::min(0.95f, max3(beta));
      if (u1() >= q) break;
      beta /= q;
    }
  }
  return out;
}

}  // namespace svbrdf
