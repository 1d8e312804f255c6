#include "render/integrator.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "appearance/microfacet_normal_mapping.h"
#include "appearance/sampling.h"
#include "appearance/shading.h"
#include "appearance/dispersion.h"
#include "render/medium_stack.h"
#include "render/surface.h"
#include "appearance/gltf_surface_bsdf.h"

namespace svbrdf {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

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

// The MIP-level AOV of a material without MIP data: the level the same filter would read on its
// base color texture.
float texture_level(const RenderWorld& w, const SurfacePoint& sp, const glm::vec3& dpdx, const glm::vec3& dpdy) {
  const TextureRef& r = sp.material->base_color_texture;
  if (!r.present()) return 0.0f;
  const glm::ivec2 size = w.textures->size(r);
  const Extent e{size.x, size.y};
  const Footprint f = footprint(sp, r.uv_set(), dpdx, dpdy);
  const TextureTransform& t = r.transform;
  return mip_level(e, {t.apply(f.uv), t.apply_linear(f.duv_dx), t.apply_linear(f.duv_dy)});
}

// The shading normal a mixture stands for, for the normal AOV: the weighted mean of its lobes'.
glm::vec3 mean_normal(const LobeMixtureBsdf& b, const Frame& frame) {
  const glm::vec3 n = b.mean_normal();
  const float len = glm::length(n);
  return len > 0.0f ? frame.to_world(n / len) : frame.n;
}

// The path from its first hit on (trace_path traces the camera ray). Kept out of line: the camera
// rays that escape, most of a frame's samples where a model sits in front of the sky, then pay for a
// small function rather than for this one's frame and set-up (bench/results/render.md).
[[gnu::noinline]] void continue_path(const RenderWorld& w, const IntegratorSettings& s, const CameraRay& cr,
                                     const RayHit& first_hit, Rng& rng, PathSample& out) {
  const bool mip_filter = s.filter != TextureFilter::level0;
  const float fp_scale = s.footprint_scale > 0.0f ? s.footprint_scale : 1.0f;
  Ray ray = cr.ray;
  Rgb beta(1.0f);
  bool last_impulse = true;  // the camera ray counts as an impulse: nothing else could have found what it sees
  float last_pdf = 0.0f;
  const bool env_on = !w.environment.black();
  auto u1 = [&] { return rng.next_float(); };
  auto seed = [&] { return rng.next_u64(); };

  auto occluded = [&](const glm::vec3& o, const glm::vec3& d, float tmax) {
    const std::uint64_t sd = seed();
    ++out.rays;
    if (w.ray_log) w.ray_log->record(o, d, 0.0f, tmax, sd, true);
    return w.bvh->occluded(o, d, 0.0f, tmax, sd);
  };

  // Adds a contribution that lights the path's vertex `bounce` (0: the first hit, whose light is
  // direct); --clamp caps the indirect ones, scaling the colour as a whole so a firefly keeps its hue.
  auto add = [&](Rgb c, int bounce) {
    if (s.clamp > 0.0f && bounce >= 1) {
      const float m = max_channel(c);
      if (m > s.clamp) c *= s.clamp / m;
    }
    out.radiance += c;
  };
  const Emitters* emitters = w.emitters && !w.emitters->empty() ? w.emitters : nullptr;

  LobeMixtureBsdf lobe_bsdf;  // the hit's mixture under a MIP filter, reassigned at every hit
  MediumStack media;          // the volumes (KHR_materials_volume) the path is inside
  int channel = -1;           // the one RGB channel a path follows after a dispersive refraction
  RayHit hit = first_hit;
  for (int depth = 0;; ++depth) {
    if (depth > 0) {
      const std::uint64_t hit_seed = seed();
      if (w.ray_log) w.ray_log->record(ray.origin, ray.dir, ray.tnear, ray.tfar, hit_seed, false);
      hit = w.bvh->intersect(ray.origin, ray.dir, ray.tnear, ray.tfar, hit_seed);
      ++out.rays;
      // Beer–Lambert inside a volume, along the segment to the next boundary (ray.dir is unit).
      if (hit.found() && !media.empty()) beta *= media.transmittance(hit.t);
    }
    if (!hit.found()) {
      if (env_on) {
        const bool mis_weighted = !last_impulse && s.light_sampling == LightSampling::mis;
        if (last_impulse || s.light_sampling != LightSampling::nee) {
          float env_pdf = 0.0f;
          const Rgb env = w.environment.radiance(ray.dir, mis_weighted ? &env_pdf : nullptr);
          const float weight = mis_weighted ? power_heuristic(last_pdf, env_pdf) : 1.0f;
          if (weight > 0.0f) add(beta * env * weight, depth - 1);
        }
      }
      break;
    }

    SurfacePoint sp = make_surface_point(*w.bvh, hit, ray.dir);
    // The brdf filter's selection number: a dimension of every hit, drawn whatever the filter and
    // the material, so a pixel's random sequence has the same layout under every filter.
    const float u_select = u1();
    const MaterialMip* mip = w.mips ? w.mips->find(sp.geom->prim->material) : nullptr;
    const bool aov_footprint = depth == 0 && s.footprints;

    // The hit's position differentials: exact for the camera ray (Igehy 1999), pbrt-v4's
    // approximation from the camera for every later ray (Camera::approximate_dp).
    glm::vec3 dpdx(0.0f), dpdy(0.0f);
    if ((mip && mip_filter) || aov_footprint) {
      if (depth == 0) camera_dp(sp, cr, dpdx, dpdy);
      else w.camera->approximate_dp(sp.p, sp.ng, dpdx, dpdy);
      dpdx *= fp_scale, dpdy *= fp_scale;
    }
    if (depth == 0) out.depth = hit.t;

    // The texel the lobes come from is chosen, and its memory asked for, with the emission's; the
    // environment's shadow ray below is traced while they arrive (a texel of a large texture is a
    // cache miss, most of a lookup's cost).
    Footprint fp;
    MipTexture::Choice choice;
    if (mip) {
      fp = mip->to_texture(footprint(sp, mip->uv_set(), dpdx, dpdy));
      // COLOR_0, and a base colour texture held apart from the grid (material_mips.h), tint the texel.
      Rgb tint(sp.color);
      if (mip->separate_base_color())
        tint *= mip->base_color(s.filter, footprint(sp, mip->base_color_uv_set(), dpdx, dpdy));
      choice = mip->texture().choose(s.filter, fp, tint, u_select);
      prefetch_emission(sp, *w.textures);
      // A level-0 texel of a normal-mapped material (its base's or its coat's map) is shaded as a
      // material without MIP data shades it (below: the normal turned toward the viewer, or the
      // microsurface), not by its lone lobe, whose f_eff vanishes wherever the mapped normal turns from
      // the viewer.
      // So is one of a grid that is not exact at level 0 (material_mips.h level0_exact): its textures
      // are read as level0 reads them.
      if (choice.level == 0 &&
          (sp.material->normal_texture.present() || sp.material->clearcoat_normal_texture.present() || !mip->level0_exact()))
        mip = nullptr;
    }

    // Next-event estimation of the environment, its shadow ray first: the ray needs the hit's
    // position and geometric normal only, not the BSDF (the contribution is added below, once the
    // BSDF is known). Nothing is drawn where the path ends at this hit.
    const bool scatters = depth < s.max_depth && (mip || !sp.material->unlit);
    // A point on an emissive triangle, its shadow ray traced once the BSDF says the point matters.
    // Drawn whenever the scene has emitters, whatever the strategy, so the random sequence's layout
    // is the same under all three.
    EmitterSample emitter_sample;
    if (scatters && emitters) {
      const glm::vec3 u(u1(), u1(), u1());
      if (s.light_sampling != LightSampling::bsdf) emitter_sample = emitters->sample(sp.p, u);
    }
    glm::vec3 env_dir(0.0f);
    float env_pdf = 0.0f;
    Rgb env_radiance(0.0f);
    bool env_visible = false;
    // A material whose transmission is finite is lit from both sides of the surface, at level 0 or by
    // MIP lobes alike: KHR_materials_diffuse_transmission (mip/diffuse_transmission.h) and
    // KHR_materials_transmission on a thin wall (mip/lobe.h "Transmission").
    const bool lit_from_behind = sp.material->diffuse_transmission > 0.0f ||
                                 (sp.material->transmission > 0.0f && !sp.material->has_volume());
    if (scatters) {
      if (env_on && s.light_sampling != LightSampling::bsdf) {
        env_dir = w.environment.sample({u1(), u1(), u1()}, env_pdf, &env_radiance);
        env_visible = env_pdf > 0.0f && (lit_from_behind || glm::dot(env_dir, sp.ng) > 0.0f) &&
                      !occluded(offset_origin(sp.p, sp.ng, env_dir, w.scene_extent), env_dir, kInfinity);
      } else {
        u1(), u1(), u1();  // keep the random sequence's layout the same across strategies
      }
    }

    // The BSDF at the hit and the frame it works in. A material with MIP data is shaded by the
    // filter's lobes in the geometric tangent frame (the lobes carry the normal-mapped normals);
    // any other by SurfaceBsdf in its shading frame, or under NormalMapping::microfacet as the
    // microsurface of its mapped normal in the geometric tangent frame.
    int candidate = -1;                          // the channel a dispersive refraction here would follow
    float material_ior = sp.material->ior;       // the material's index for this path
    std::optional<SurfaceBsdf> surface_bsdf;
    std::optional<MicrofacetNormalMapping> normal_mapped;
    const Bsdf* bsdf = nullptr;
    Frame frame;
    Rgb emission(0.0f);
    if (mip) {
      frame = geometric_frame(sp);
      emission = emission_at(sp, *w.textures, -ray.dir);
      mip->texture().lookup(choice, lobe_bsdf);
      bsdf = &lobe_bsdf;
      if (depth == 0 && s.aovs) {
        out.albedo = base_color_at(sp, *w.textures);
        out.normal = mean_normal(lobe_bsdf, frame);
      }
      if (aov_footprint) out.mip_level = mip->texture().level(fp);
    } else {
      // A normal map tilts the shading normal off the surface's own (NormalMapping says how it shades).
      // The surface's own frame, which only the microsurface works in (taken before the map tilts it).
      const bool microfacet = s.normal_mapping == NormalMapping::microfacet;
      const Frame surface_frame = microfacet ? geometric_frame(sp) : Frame{};
      apply_normal_map(sp, *w.textures);
      if (s.normal_mapping == NormalMapping::shading) keep_reflection_above(sp, -ray.dir);
      ShadingParams sh = shading_params(sp, *w.textures);
      if (sp.material->has_volume()) {
        // Refraction between the medium the path is in and the one beyond this boundary. A
        // dispersive material refracts each channel by its own index: a path that has not chosen
        // its channel yet draws one here (u_select, which only MIP lookups use otherwise) and keeps
        // it if it refracts (KHR_materials_dispersion; appearance/dispersion.h).
        sh.thin_walled = false;
        if (sp.material->dispersion > 0.0f && channel < 0) candidate = std::min(2, int(3.0f * u_select));
        const int c = channel >= 0 ? channel : candidate;
        const float ior = c >= 0 ? dispersion_ior(sp.material->ior, sp.material->dispersion, kChannelWavelengthNm[c])
                                 : sp.material->ior;
        material_ior = ior;
        const float n_here = sp.front ? media.ior() : ior;
        const float n_beyond = sp.front ? ior : media.ior_outside(sp.material);
        sh.eta = n_beyond / n_here;
      }
      if (depth == 0) {
        out.albedo = sh.base_color;
        out.normal = sp.shading.n;
        if (aov_footprint) out.mip_level = texture_level(w, sp, dpdx, dpdy);
      }
      if (sh.unlit) {
        // KHR_materials_unlit: the base color is the radiance leaving toward the viewer; nothing scatters.
        add(beta * sh.base_color, depth - 1);
        break;
      }
      // The clear coat darkens what is under it, emission included (surface.h, emission_at).
      emission = sh.emission * (1.0f - clearcoat_blend(sh.clearcoat, glm::dot(-ray.dir, sp.ng)));
      bsdf = &surface_bsdf.emplace(sh);
      frame = sp.shading;
      if (microfacet) {
        const glm::vec3 wp = surface_frame.to_local(sp.shading.n);
        if (wp.z < 1.0f - 1e-6f) {
          bsdf = &normal_mapped.emplace(*bsdf, wp);
          frame = surface_frame;
        }
      }
    }
    // A single-sided surface emits from its front face only (glTF 2.0 §3.9.6). Emission found by a
    // BSDF-sampled ray is weighted against the emitters' own sampling of the same point.
    if (!sp.front && !sp.material->double_sided) emission = Rgb(0.0f);
    if (max_channel(emission) > 0.0f) {
      float weight = 1.0f;
      if (depth > 0 && !last_impulse && emitters) {
        const float light_pdf = s.light_sampling == LightSampling::bsdf ? 0.0f : emitters->pdf(hit, ray.dir);
        // A triangle emitter sampling never draws is found by BSDF sampling alone: full weight.
        if (light_pdf > 0.0f) weight = s.light_sampling == LightSampling::mis ? power_heuristic(last_pdf, light_pdf) : 0.0f;
      }
      if (weight > 0.0f) add(beta * emission * weight, depth - 1);
    }
    if (depth >= s.max_depth) break;

    const glm::vec3 wo = frame.to_local(-ray.dir);

    // The shading cosine of a light's direction, or 0 where the light cannot count: behind the
    // geometric surface unless the material transmits, and on the other side of the shading
    // normal than of the geometric one (an interpolated normal must not turn reflection into
    // transmission or back).
    auto light_cosine = [&](const glm::vec3& wi_world, const glm::vec3& wi) {
      const bool behind = glm::dot(wi_world, sp.ng) <= 0.0f;
      if (behind && !lit_from_behind) return 0.0f;
      return behind == (wi.z < 0.0f) ? std::abs(wi.z) : 0.0f;
    };

    // Next-event estimation: every punctual light (they are delta lights: light sampling only).
    for (const LightDesc& light : w.lights) {
      const LightArrival a = arrive(light, sp.p);
      if (max_channel(a.irradiance) <= 0.0f) continue;
      const glm::vec3 wi = frame.to_local(a.wi);
      const float cos_i = light_cosine(a.wi, wi);
      if (!(cos_i > 0.0f)) continue;
      const Rgb f = bsdf->eval(wi, wo);
      if (max_channel(f) <= 0.0f) continue;
      const glm::vec3 o = offset_origin(sp.p, sp.ng, a.wi, w.scene_extent);
      const float tmax = std::isinf(a.distance) ? kInfinity : glm::length(light.position - o) * (1.0f - 1e-5f);
      if (!occluded(o, a.wi, tmax)) add(beta * f * a.irradiance * cos_i, depth);
    }
    // Next-event estimation: the point drawn on an emissive triangle.
    if (emitter_sample.pdf > 0.0f && max_channel(emitter_sample.radiance) > 0.0f) {
      const glm::vec3 wi = frame.to_local(emitter_sample.wi);
      const float cos_i = light_cosine(emitter_sample.wi, wi);
      const Rgb f = cos_i > 0.0f ? bsdf->eval(wi, wo) : Rgb(0.0f);
      if (max_channel(f) > 0.0f) {
        const glm::vec3 o = offset_origin(sp.p, sp.ng, emitter_sample.wi, w.scene_extent);
        // Stop short of the emitter's own surface: the segment ends a relative hair before the point.
        if (!occluded(o, emitter_sample.wi, emitter_sample.distance * (1.0f - 1e-4f))) {
          const float weight =
              s.light_sampling == LightSampling::mis ? power_heuristic(emitter_sample.pdf, bsdf->pdf(wi, wo)) : 1.0f;
          add(beta * f * emitter_sample.radiance * (cos_i * weight / emitter_sample.pdf), depth);
        }
      }
    }
    // Next-event estimation: the environment, whose shadow ray was traced above.
    if (env_visible) {
      const glm::vec3 wi = frame.to_local(env_dir);
      const float cos_i = light_cosine(env_dir, wi);
      const Rgb f = cos_i > 0.0f ? bsdf->eval(wi, wo) : Rgb(0.0f);
      if (max_channel(f) > 0.0f) {
        const float weight = s.light_sampling == LightSampling::mis ? power_heuristic(env_pdf, bsdf->pdf(wi, wo)) : 1.0f;
        add(beta * f * env_radiance * (cos_i * weight / env_pdf), depth);
      }
    }

    // Continue the path by sampling the BSDF.
    const BsdfSample bs = bsdf->sample(wo, SampleU{u1(), u1(), u1()});  // braces: drawn left to right
    if (bs.kind == SampleKind::absorbed) break;
    const glm::vec3 wi_world = frame.to_world(bs.wi);
    // f_eff vanishes below the geometric surface (brdf-mip.md): a finite sample there is absorbed,
    // unless it is a transmission (below the shading normal too) of a material that transmits.
    if (bs.kind == SampleKind::finite && glm::dot(wi_world, sp.ng) <= 0.0f && !(lit_from_behind && bs.wi.z < 0.0f))
      break;
    beta *= bs.weight;
    if (!(max_channel(beta) > 0.0f) || !std::isfinite(max_channel(beta))) break;
    // A path that crosses a volume's boundary enters its medium through the front face and leaves
    // it through the back.
    if (bs.kind == SampleKind::impulse && sp.material->has_volume() && glm::dot(wi_world, sp.ng) < 0.0f) {
      if (sp.front) media.enter(sp.material, material_ior);
      else media.leave(sp.material);
      if (candidate >= 0) {
        // The path follows one channel, drawn with probability 1/3.
        channel = candidate;
        Rgb only(0.0f);
        only[channel] = 3.0f * beta[channel];
        beta = only;
      }
    }
    last_impulse = bs.kind == SampleKind::impulse;
    last_pdf = bs.pdf;
    ray = Ray{offset_origin(sp.p, sp.ng, wi_world, w.scene_extent), glm::normalize(wi_world), 0.0f, kInfinity};

    if (depth + 1 >= s.rr_depth) {
      const float q = std::min(0.95f, max_channel(beta));
      if (u1() >= q) break;
      beta /= q;
    }
  }
}

}  // namespace

PathSample trace_path(const RenderWorld& w, const IntegratorSettings& s, float film_x, float film_y, Rng& rng) {
  PathSample out;
  CameraRay cr;
  // The lens point (Shirley and Chiu's concentric map of the unit square onto the disk), drawn only for
  // a thin lens, so that a pinhole render reads the random numbers it always read.
  const glm::vec2 lens =
      w.camera->has_lens() ? sample_concentric_disk({rng.next_float(), rng.next_float()}) : glm::vec2(0.0f);
  if (s.footprints || s.filter != TextureFilter::level0) cr = w.camera->generate(film_x, film_y, lens);
  else cr.ray = w.camera->ray(film_x, film_y, lens);
  const Ray& ray = cr.ray;
  const std::uint64_t hit_seed = rng.next_u64();
  if (w.ray_log) w.ray_log->record(ray.origin, ray.dir, ray.tnear, ray.tfar, hit_seed, false);
  const RayHit hit = w.bvh->intersect(ray.origin, ray.dir, ray.tnear, ray.tfar, hit_seed);
  out.rays = 1;
  if (hit.found()) {
    out.opaque = true;
    continue_path(w, s, cr, hit, rng, out);
  } else if (s.background && !w.environment.black()) {
    // What the camera sees of the environment: an impulse's view, weight 1 under every strategy.
    out.opaque = true;
    out.radiance = w.environment.radiance(ray.dir, nullptr);
  }
  return out;
}

}  // namespace svbrdf
