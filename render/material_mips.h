#pragma once
// The MIP texture filters of issue 6 for each material (../shared/spec/brdf-mip.md): the level-0
// texels of its base color, metallic-roughness and normal textures, decoded once from the images
// the renderer already holds (TextureSet), and the parameter and BRDF pyramids of the mip module
// built from them; and the lookups that turn a hit's uv and footprint into the lobes of a
// LobeMixtureBsdf in the geometric tangent frame (z = the interpolated normal before any normal map,
// x = the tangent, y = the glTF bitangent): the lobes carry the normal-mapped normals.
//
// The filters (TextureFilter, integrator.h):
//   level0  — the nearest texel at the exact uv (the sampler's wrap modes), f_eff of that texel as
//             brdf-mip.md writes it: one lobe, lobe_from_texel of the texel's parameters. This is
//             bit for bit the BRDF pyramid's level-0 lobe of that texel (mip/exact_reference.h
//             level0_lobe), so level0 and brdf agree exactly wherever brdf selects a level-0 texel.
//   param, toksvig, vmf — trilinear (anisotropic) filtering of the parameter pyramid, one lobe
//             (mip_lookup.h filter_params, param_lobe with the baseline's α widening).
//   brdf    — one texel among the filter's taps, chosen with probability equal to its weight by the
//             hit's selection number u (Pharr et al. 2024): that texel's lobes.
//
// Which materials take part ("active"): those whose BRDF the lobes model — the glTF metallic-
// roughness BRDF with KHR_materials_ior/specular/transmission/diffuse_roughness at their defaults and
// not unlit — and that have at least one of the three textures. Every other material is shaded by
// SurfaceBsdf with level0 lookups under every filter (an untextured one has nothing to filter); a
// textured one that is left out gets one warning saying why.
//
// One texel grid per material: the three textures must share their uv set, KHR_texture_transform
// and wrap modes. Their sizes may differ by integer factors along each axis: the smaller ones are
// replicated (nearest) onto the largest grid, which is exact — the texel of the small texture that
// contains a uv is the one whose replica contains it. Anything else (different uv sets, transforms,
// wrap modes, sizes that do not divide) leaves the material out, with a warning naming the textures.
//
// Wrap modes: the mip module's filter wraps with repeat (glTF's default). For clamp-to-edge and
// mirrored repeat the filters first bring uv into the texture (clamped; folded, then clamped) onto
// the level-0 texel centres, so level-0 bilinear taps are exactly the sampler's; at coarser levels
// taps within half the filter's width of such an edge may come from the opposite edge (documented
// approximation). level0 follows the sampler exactly.
//
// COLOR_0 multiplies base color (glTF). level0 and the parameter filters apply it exactly; a BRDF
// texel's lobes hold ρ and F0 already mixed with metallic, from which a tinted base color cannot be
// recovered, so a hit whose COLOR_0 is not white is shaded level0 under `brdf` (one warning per
// primitive, from the scene scan).
//
// Building: SceneMips::prepare(filter) builds, for every active material in parallel, the texels and
// what the filter needs (param pyramid for param/toksvig/vmf, BRDF pyramid for brdf), once; later
// calls for other filters add what is missing. Materials with the same textures, factors, uv set
// and transform share one build. Lookups allocate nothing and only read, so any
// number of threads may call them after prepare().
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mip/brdf_pyramid.h"
#include "mip/mip_lookup.h"
#include "mip/param_pyramid.h"
#include "gltf/scene.h"
#include "render/texture_set.h"
#include "textures/material_texels.h"

namespace svbrdf {

enum class TextureFilter { level0, param, toksvig, vmf, brdf };

class MaterialMip {
 public:
  // The uv set (TEXCOORD_n) the material's grid reads, and the grid's size in texels.
  int uv_set() const { return grid_.uv_set(); }
  Extent extent() const { return extent_; }
  // The level-0 parameters of texel (i, j) (MaterialTexels' values, one texel in one cache line).
  struct Texel {
    glm::vec3 base_color{1.0f};  // linear
    float metallic = 0.0f;
    glm::vec3 normal{0, 0, 1};  // unit, tangent space
    float roughness = 1.0f;     // perceptual
  };
  const Texel& texel(int i, int j) const { return level0_[static_cast<std::size_t>(j) * extent_.width + i]; }
  const ParamPyramid& param() const { return param_; }
  const BrdfPyramid& brdf() const { return brdf_; }

  // A footprint of the grid's uv set (before the texture transform) carried into texture space:
  // the transform applied to uv and to both derivatives.
  Footprint to_texture(const Footprint& uvset_footprint) const;

  // The lobes the filter answers with at a hit, footprint in texture space (to_texture): a view into
  // the BRDF pyramid, or `scratch` holding one lobe. `tint` is COLOR_0's rgb, `u` ∈ [0, 1) the
  // selection number (brdf only). The filter's data must have been prepared.
  std::span<const Lobe> lobes(TextureFilter filter, const Footprint& texture_footprint, const Rgb& tint, float u,
                              Lobe& scratch) const;

  // lobes() in two steps, so that a caller can do other work while the texel's memory arrives (the
  // fetch into a large texture is most of a lookup's cost): choose() picks the texel — the brdf
  // filter's stochastic tap, or the nearest level-0 texel — and prefetches it; lobes_at() reads it.
  struct Choice {
    TextureFilter filter = TextureFilter::level0;
    Footprint footprint{};
    Rgb tint{1.0f};
    FilterTap tap{};  // level −1: the parameter filters' trilinear taps (read by lobes_at)
  };
  Choice choose(TextureFilter filter, const Footprint& texture_footprint, const Rgb& tint, float u) const;
  std::span<const Lobe> lobes_at(const Choice& choice, Lobe& scratch) const;
  // The chosen texel's radial correction (brdf filter, coarse levels), or null.
  const RadialCorrection* correction_at(const Choice& c) const {
    return c.tap.level >= 1 ? brdf_.correction(c.tap.level, c.tap.i, c.tap.j) : nullptr;
  }

  // The level-0 texel (column, row) nearest to a texture-space uv under the sampler's wrap modes.
  glm::ivec2 nearest_texel(glm::vec2 uv) const;

  // The continuous MIP level λ the filters read at a texture-space footprint (mip_lookup.h).
  float level(const Footprint& texture_footprint) const;

 private:
  friend class SceneMips;
  Footprint wrapped(const Footprint& f) const;

  TextureRef grid_;  // the slot whose uv set and transform the grid follows
  Sampler sampler_;
  Extent extent_{};
  // Level 0 as MaterialTexels holds it, stored a texel at a time for level0's lookups; the pyramids
  // are built from MaterialTexels made back from it (the same floats).
  std::vector<Texel> level0_;
  MaterialTexels texels() const;
  ParamPyramid param_;
  BrdfPyramid brdf_;
  bool has_texels_ = false, has_param_ = false, has_brdf_ = false;
};

class SceneMips {
 public:
  // Decides which materials take part (cheap: nothing is decoded yet). Both must outlive this.
  SceneMips(const Scene& scene, const TextureSet& textures);
  SceneMips(const SceneMips&) = delete;
  SceneMips& operator=(const SceneMips&) = delete;

  // Builds what `filter` needs for every active material (nothing for level0 beyond the texels).
  // Thread-safe and idempotent; throws svbrdf::Error (bad input) naming the image when one cannot
  // be decoded into texels.
  void prepare(TextureFilter filter);

  // The MIP data of material `index` (MeshPrimitive::material; −1 is glTF's default material) when
  // it takes part, else null.
  const MaterialMip* find(int index) const {
    if (index < 0 || index >= static_cast<int>(slot_.size())) return nullptr;
    const int slot = slot_[static_cast<std::size_t>(index)];
    return slot < 0 ? nullptr : &mips_[static_cast<std::size_t>(slot)];
  }

  // What a render under `filter` should say, one line each: the textured materials left out (every
  // MIP filter), and for brdf the primitives whose COLOR_0 keeps it at level0. None for level0.
  std::vector<std::string> warnings(TextureFilter filter) const;
  // Materials that take part, and the distinct MIP data they share (materials that differ only in
  // what the texels do not hold — alpha, emission, double-sidedness — share one).
  int active_count() const;
  int distinct_count() const { return static_cast<int>(mips_.size()); }

 private:
  const Scene& scene_;
  const TextureSet& textures_;
  std::vector<MaterialMip> mips_;       // distinct MIP data
  std::vector<int> slot_;                // per material: its entry in mips_, −1 when it does not take part
  std::vector<std::size_t> source_;      // per entry: the first material that uses it
  std::vector<std::string> warnings_;        // materials left out
  std::vector<std::string> tint_warnings_;   // COLOR_0 under brdf
  std::mutex mutex_;
};

// "level0", "param", "toksvig", "vmf", "brdf": the names svbrdf-render's --filter takes (the
// baselines' are the mip module's, baseline_name).
std::string_view filter_name(TextureFilter f);
std::optional<TextureFilter> parse_filter(std::string_view name);
std::vector<std::string> filter_names();

}  // namespace svbrdf
