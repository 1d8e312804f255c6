#pragma once
// The MIP lookups under the renderer's facade (mip.h): from a texture coordinate and its footprint
// (texture_filter.h) to the taps of the filter, to one texel of the BRDF pyramid or to filtered
// parameters.
//
// The filter: trilinear MIP mapping, anisotropic with up to `max_probes` probes along the
// footprint's major axis (the GPU scheme: the level comes from the minor axis, or from major /
// max_probes when the footprint is more elongated than that). Each probe is bilinear on two
// adjacent levels, each level read with the texture's wrap modes per axis as a GPU reads it
// (textures/sampler.h wrap_texel: clamp-to-edge repeats the level's edge texel, mirrored repeat
// mirrors the level); texel centres at (i + 0.5)/width as glTF samples. At most
// 8 probes × 2 levels × 4 texels = 64 taps, their weights summing to 1.
//
//  (1) lookup_brdf — filtering after shading (Pharr et al. 2024, "Filtering After Shading with
//      Stochastic Texture Filtering"): one tap is chosen with probability equal to its weight and
//      that texel's whole mixture is returned. Exact in expectation for any per-texel mixture: the
//      mean over u of the returned BSDF is the filter-weighted mean of the texels' BSDFs.
//  (2) lookup_param — deterministic trilinear filtering of the parameter pyramid (linear base
//      color, metallic, roughness and the unnormalized normal, normalized once), what ordinary MIP
//      mapping does; with a baseline's α widening.
// Both allocate nothing and only read the pyramids, so any number of threads may call them.
#include <array>

#include <glm/glm.hpp>

#include "mip/brdf_pyramid.h"
#include "mip/lobe_mixture_bsdf.h"
#include "mip/mip_data.h"
#include "mip/param_pyramid.h"
#include "mip/texture_filter.h"
#include "textures/sampler.h"

namespace svbrdf {

inline constexpr int kMaxProbes = 8;

struct FilterTap {
  int level = 0;
  int i = 0;  // column
  int j = 0;  // row from the top
  float weight = 0.0f;
};

struct FilterTaps {
  std::array<FilterTap, kMaxProbes * 8> taps{};
  int count = 0;
  float level = 0.0f;  // the continuous level λ chosen
  int probes = 1;
};

// The filter's taps over a pyramid of `levels` levels on a level-0 image of `level0` texels.
FilterTaps filter_taps(Extent level0, int levels, const Footprint& footprint, WrapModes wrap = {},
                       int max_probes = kMaxProbes);
// Their continuous level λ alone (FilterTaps::level), which depends on the footprint's axes only.
float filter_level(Extent level0, int levels, const Footprint& footprint, int max_probes = kMaxProbes);

// The tap whose cumulative weight interval contains u ∈ [0, 1).
FilterTap select_tap(const FilterTaps& taps, float u);
// One tap with probability equal to its weight in filter_taps, chosen in O(1) from u ∈ [0, 1) stage by
// stage (probe, level, column, row) without listing the taps: what lookup_brdf uses.
FilterTap select_tap(Extent level0, int levels, const Footprint& footprint, float u, WrapModes wrap = {},
                     int max_probes = kMaxProbes);

// (1) One texel's mixture, chosen with probability equal to its filter weight.
LobeMixtureBsdf lookup_brdf(const MipData& mip, const Footprint& footprint, float u, WrapModes wrap = {},
                            int max_probes = kMaxProbes);

// (2) The trilinear-filtered parameters as one lobe (wrap it in LobeMixtureBsdf to shade).
// With `specular`, also the same filter's mean of the specular layer (the material's when it is plain);
// with `coat`, of the clear coat (ParamCoat{} for a material without one); with `sheen`, of the sheen
// (SheenLayer{}, colour 0, for a material without one); with `anisotropy`, of the anisotropy as
// param_pyramid.h anisotropy_from_below averages it (AnisotropyLayer{}, strength 0, for a material
// without one); with `transmission`, of the mean transmission (0 for a material that does not transmit);
// with `diffuse_transmission`, of the diffuse transmission as param_pyramid.h diffuse_transmission_mean
// averages it (share 0 for a material without one).
ParamTexel filter_params(const ParamPyramid& pyramid, const Footprint& footprint, WrapModes wrap = {},
                         int max_probes = kMaxProbes, SpecularLayer* specular = nullptr, ParamCoat* coat = nullptr,
                         SheenLayer* sheen = nullptr, AnisotropyLayer* anisotropy = nullptr,
                         float* transmission = nullptr, DiffuseTransmissionLayer* diffuse_transmission = nullptr);
// The same over any store of a parameter pyramid's texels:
// `texel(level, i, j, specular, coat, sheen, anisotropy, transmission, diffuse_transmission)`
// gives a ParamTexel and fills the layers asked for (not null); the pyramid's level 0, its level count
// and ior, and which layers it has, given. filter_params is this over ParamPyramid; the out-of-core
// texture (mip.h) reads records with it, so both sum the same values in the same order.
struct ParamStore {
  Extent level0{};
  int levels = 0;
  float ior = 1.5f;
  bool specular = false, coat = false, sheen = false, anisotropy = false, transmission = false;
  bool diffuse_transmission = false;
};
template <class Texel>
ParamTexel filter_params_of(const ParamStore& store, const Texel& texel, const Footprint& footprint,
                            WrapModes wrap, int max_probes, SpecularLayer* specular, ParamCoat* coat,
                            SheenLayer* sheen, AnisotropyLayer* anisotropy = nullptr,
                            float* transmission = nullptr, DiffuseTransmissionLayer* diffuse_transmission = nullptr) {
  ParamTexel sum;
  sum.normal = glm::vec3(0.0f);
  if (specular) *specular = {1.0f, glm::vec3(1.0f), store.ior};
  if (coat) *coat = {};
  if (sheen) *sheen = {};
  if (anisotropy) *anisotropy = {};
  if (transmission) *transmission = 0.0f;
  if (diffuse_transmission) *diffuse_transmission = {};
  if (store.levels == 0) return sum;
  const FilterTaps taps = filter_taps(store.level0, store.levels, footprint, wrap, max_probes);
  const bool layer = specular && store.specular;
  if (layer) specular->specular = 0.0f, specular->color = glm::vec3(0.0f);
  const bool coated = coat && store.coat;
  if (coated) coat->normal = glm::vec3(0.0f);
  const bool sheened = sheen && store.sheen;
  const bool stretched = anisotropy && store.anisotropy;
  const bool transmits = transmission && store.transmission;
  const bool diffuse = diffuse_transmission && store.diffuse_transmission;
  ParamSpecular s;
  ParamCoat c;
  SheenLayer h;
  AnisotropyLayer a;
  float tr = 0.0f;
  DiffuseTransmissionLayer dt;
  double dt_total = 0, dt_share = 0;  // Σ weight, Σ weight·d
  glm::dvec3 dt_color(0.0);            // Σ weight·d·C (param_pyramid.h diffuse_transmission_mean)
  glm::dvec2 axial(0.0);  // Σ weight·axial_anisotropy (param_pyramid.h)
  for (int k = 0; k < taps.count; ++k) {
    const FilterTap& t = taps.taps[static_cast<std::size_t>(k)];
    const ParamTexel& p =
        texel(t.level, t.i, t.j, layer ? &s : nullptr, coated ? &c : nullptr, sheened ? &h : nullptr,
              stretched ? &a : nullptr, transmits ? &tr : nullptr, diffuse ? &dt : nullptr);
    sum.base_color += t.weight * p.base_color;
    sum.metallic += t.weight * p.metallic;
    sum.roughness += t.weight * p.roughness;
    sum.normal += t.weight * p.normal;
    if (layer) {
      specular->specular += t.weight * s.specular;
      specular->color += t.weight * s.color;
    }
    if (coated) {
      coat->clearcoat += t.weight * c.clearcoat;
      coat->roughness += t.weight * c.roughness;
      coat->normal += t.weight * c.normal;
    }
    if (sheened) {
      sheen->color += t.weight * h.color;
      sheen->roughness += t.weight * h.roughness;
    }
    if (stretched) axial += double(t.weight) * axial_anisotropy(a);
    if (transmits) *transmission += t.weight * tr;
    if (diffuse) {
      dt_total += t.weight;
      dt_share += double(t.weight) * dt.share;
      dt_color += (double(t.weight) * dt.share) * glm::dvec3(dt.color);
    }
  }
  if (stretched) *anisotropy = from_axial_anisotropy(axial);
  if (diffuse && dt_total > 0) *diffuse_transmission = diffuse_transmission_mean(dt_total, dt_share, dt_color);
  return sum;
}
Lobe lookup_param(const ParamPyramid& pyramid, const Footprint& footprint,
                  TextureFilter filter = TextureFilter::param, WrapModes wrap = {}, int max_probes = kMaxProbes);

}  // namespace svbrdf
