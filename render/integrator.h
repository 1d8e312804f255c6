#pragma once
// Unidirectional path tracing (Kajiya 1986; CGPP ch. 32; pbrt-v4 §13.4) with next-event estimation
// to the punctual lights, the emissive triangles and the environment, multiple importance sampling
// with the power heuristic (Veach & Guibas 1995) between light sampling and BSDF sampling for the
// lights with area, Russian roulette and a maximum depth. One call traces one camera sample; everything random comes from the Rng passed in,
// so a pixel's value never depends on which thread traced it.
#include <cstdint>
#include <vector>

#include "appearance/rng.h"
#include "render/camera.h"
#include "render/embree_scene.h"
#include "render/emitters.h"
#include "render/lights.h"
#include "render/material_mips.h"
#include "render/ray_log.h"
#include "render/texture_set.h"

namespace svbrdf {

// How the lights with area (the environment and emissive triangles) are found; punctual lights
// are delta lights, always sampled.
enum class LightSampling {
  mis,   // by both strategies, weighted by the power heuristic
  nee,   // by light sampling only
  bsdf,  // by BSDF sampling only
};

// Everything a path reads, built once per render.
struct RenderWorld {
  const Scene* scene = nullptr;
  const TextureSet* textures = nullptr;
  const EmbreeScene* bvh = nullptr;
  const Camera* camera = nullptr;
  // The materials' MIP data (material_mips.h); render() prepares it for the filter it renders with.
  // Null: every material is shaded with level0 lookups.
  SceneMips* mips = nullptr;
  std::vector<LightDesc> lights;  // punctual lights, world space
  const Emitters* emitters = nullptr;  // emissive triangles sampled as lights; null: none
  Environment environment = Environment::uniform(Rgb(0.0f));
  float scene_extent = 1.0f;      // bounding-box diagonal, for ray offsets
  RayLog* ray_log = nullptr;      // when set, every traced ray is recorded (benchmarks)
};

// How a normal map's (or interpolated) shading normal shades a hit.
enum class NormalMapping {
  // The mapped normal itself, as the map's author saw it in Blender, Substance or a game engine,
  // turned toward the viewer where it faces away (keep_reflection_above, surface.h). Where it turns
  // from a light the surface is dark, as in Cycles.
  shading,
  // The mapped normal as one facet of a microsurface whose mean normal is the surface's (Schüssler
  // et al. 2017, appearance/microfacet_normal_mapping.h): never black where the surface is lit and no
  // energy lost, but a strong map is flattened under a low light.
  microfacet,
};

struct IntegratorSettings {
  int max_depth = 16;   // scattering events; 0 renders emission and the environment only
  int rr_depth = 3;     // Russian roulette from this depth on
  LightSampling light_sampling = LightSampling::mis;
  // Texture filtering (mip/texture_filter.h): brdf, the BRDF-averaged MIP, is svbrdf-render's default.
  TextureFilter filter = TextureFilter::brdf;
  // Compute the first hit's texture footprint for the MIP-level AOV. The MIP filters compute
  // footprints at every hit whatever this says; with neither, camera rays skip their differentials.
  bool footprints = true;
  // Compute the first hit's albedo and normal (the AOVs); render() sets it from RenderOptions::aovs.
  bool aovs = true;
  // The ray differentials are scaled by this before they become footprints: a pixel integrated by n
  // jittered samples needs each sample to filter only about 1/√n of it. render() sets 1/√spp when
  // this is 0 (resolve_footprint_scale); trace_path reads 0 as 1.
  float footprint_scale = 0.0f;
  NormalMapping normal_mapping = NormalMapping::shading;
  // The most radiance a path may carry back from one of its indirect light samples (after the
  // first bounce), per channel; 0: no clamp. A biased cap on fireflies, off unless asked for.
  float clamp = 0.0f;
  // Whether the camera sees the environment where its rays escape. Off (--transparent), they bring
  // back nothing and the pixel's alpha is what geometry covers; the environment lights the scene all
  // the same.
  bool background = true;
};

// One camera sample's results: radiance and the first hit's auxiliary values.
struct PathSample {
  Rgb radiance{0.0f};
  Rgb albedo{0.0f};
  glm::vec3 normal{0.0f};
  float depth = 0.0f;      // distance to the first hit (0 when the ray escapes)
  float mip_level = 0.0f;  // the MIP level λ the filters read at the first hit (MipTexture::level)
  // Whether the sample is opaque: its camera ray found geometry, or escaped to a background that is
  // drawn (an environment, not black, with IntegratorSettings::background). Its mean is the pixel's
  // alpha, by which its radiance is premultiplied as OpenEXR means RGBA.
  bool opaque = false;
  std::uint32_t rays = 0;  // rays traced (closest-hit and shadow)
};

PathSample trace_path(const RenderWorld& world, const IntegratorSettings& settings, float film_x, float film_y,
                      Rng& rng);

}  // namespace svbrdf
