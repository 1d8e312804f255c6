#pragma once
// The parameter pyramid, the baseline of ../shared/spec/brdf-mip.md (`param`): each coarse texel holds
// the means of the covered level-0 texels' linear base color, metallic and perceptual roughness, and
// the mean of their unit normals kept unnormalized, so that the normal is normalized once, when used.
// This is what ordinary MIP mapping of parameter textures (OpenImageIO's maketx, pbrt-v4's box
// pyramid) produces. Built level by level from the one below with weights equal to the covered
// level-0 counts, so every level holds exact means of level 0 (pyramid_shape.h for other sizes).
//
// The same storage serves the engine baselines, which widen α from the shortened mean normal:
//   `toksvig` — Toksvig 2005, "Mipmapping Normal Maps": for a mean normal of length r the Blinn–Phong
//     exponent s becomes s·r/(r + s(1 − r)), i.e. 1/s grows by (1 − r)/r; with 1/s ≈ α²/2 (Beckmann)
//     that is α² += 2(1 − r)/r.
//   `vmf` — the von Mises–Fisher fit that Filament ships: κ = (3r − r³)/(1 − r²) (Banerjee et al.
//     2005), α² += 2/κ.
#include <cmath>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "mip/lobe.h"
#include "mip/pyramid_shape.h"
#include "mip/texture_filter.h"
#include "textures/material_texels.h"

namespace svbrdf {

struct ParamTexel {
  glm::vec3 base_color{0.0f};  // mean, linear
  float metallic = 0.0f;       // mean
  float roughness = 0.0f;      // mean perceptual roughness
  glm::vec3 normal{0, 0, 1};   // mean of unit normals, unnormalized (length ≤ 1)
};

// A texel's mean specular layer (KHR_materials_specular; textures/material_texels.h): the mean weight s and
// the mean specular colour, beside the ParamTexel of a material whose layer is not plain.
struct ParamSpecular {
  float specular = 1.0f;
  glm::vec3 color{1.0f};
};

// A texel's mean clear coat (KHR_materials_clearcoat; textures/material_texels.h CoatLayer): the mean
// weight, the mean perceptual roughness and the mean of the unit coat normals kept unnormalized, beside
// the ParamTexel of a material with a coat (level 0: the texel's own).
struct ParamCoat {
  float clearcoat = 0.0f;
  float roughness = 0.0f;
  glm::vec3 normal{0, 0, 1};
};

// The single lobe a parameter texel stands for under a filter that reads this pyramid (param,
// toksvig, vmf; texture_filter.h): f_eff of one glTF texel with the mean parameters and normal =
// normalize(mean normal) (weight 1, unit normal), α widened for the engine baselines. Any other
// filter reads as param (no widening). `layer` is the texel's specular layer (plain by default).
// `aniso` is the texel's mean anisotropy (none by default), whose stretch the lobe takes as a level-0
// texel's (lobe.h lobe_from_texel), the filter's widening added to its α² as to an isotropic one's.
// `transmission` is the texel's mean transmission T (none by default), which the lobe carries as a
// level-0 texel of it does (lobe.h lobe_from_texel, "Transmission"); `diffuse_transmission` its mean
// diffuse transmission (none by default), which the lobe carries as a level-0 texel of it does
// (diffuse_transmission.h add_diffuse_transmission).
Lobe param_lobe(const ParamTexel& t, TextureFilter filter, const SpecularLayer& layer = {},
                const AnisotropyLayer& aniso = {}, float transmission = 0.0f,
                const DiffuseTransmissionLayer& diffuse_transmission = {});
// The coat lobe (coat_layer.h) a parameter texel's mean coat stands for under the same filter: weight
// the mean clearcoat, normal = normalize(mean coat normal), α from the mean roughness, widened as
// param_lobe widens the base's from the coat normals' shortened mean. The base lobe's coat share
// (Lobe::coat) is the mean clearcoat.
Lobe param_coat_lobe(const ParamCoat& c, TextureFilter filter);

// A parameter texel as the filters that read this pyramid shade it: param_lobe of its mean parameters
// and specular layer and, for a material with a coat (`coat` not null), under the coated material of its
// mean coat — the coat lobe param_coat_lobe makes, the base lobe's coat share the mean clearcoat. At
// level 0 these are the texel's own lobes, level0_lobe's and level0_coat's (exact_reference.h).
// A material with a sheen (`sheen` not null) shades the mean sheen over the base lobe, whose sheen share
// (Lobe::sheen) is max of the mean colour (sheen_layer.h).
struct ParamLobes {
  Lobe base;
  Lobe coat;             // valid where `coated`
  bool coated = false;
  SheenLayer sheen;      // the mean sheen (colour 0: none)
};
// A material with an anisotropy (`aniso` not null) shades its mean (anisotropy_from_below), one that
// transmits its mean transmission (0 for a material that does not), one that transmits diffusely
// (`diffuse_transmission` not null) its mean diffuse transmission (diffuse_transmission_mean).
ParamLobes param_lobes(const ParamTexel& t, TextureFilter filter, const SpecularLayer& layer, const ParamCoat* coat,
                       const SheenLayer* sheen = nullptr, const AnisotropyLayer* aniso = nullptr,
                       float transmission = 0.0f, const DiffuseTransmissionLayer* diffuse_transmission = nullptr);

// The mean of diffuse transmissions (KHR_materials_diffuse_transmission) from their weighted sums: the
// share the mean of the shares, Σw·d, and the colour the share-weighted mean Σw·d·C / Σw·d, so that the
// mean's d·C (what τd and τd90 are linear in, diffuse_transmission.h) is the mean of the texels' d·C. A
// texel's colour without a share changes nothing it shades, and takes no part; where no texel has a
// share the colour is white (the extension's default). `total` is Σw.
inline DiffuseTransmissionLayer diffuse_transmission_mean(double total, double share, const glm::dvec3& share_color) {
  if (!(share > 0)) return {static_cast<float>(share / total), glm::vec3(1.0f)};
  return {static_cast<float>(share / total), glm::vec3(share_color / share)};
}

// The sheen means of level `level` ≥ 1 from those of level − 1: each the mean of its children's colours
// and perceptual roughnesses weighted by the level-0 texels they cover, in double, as the parameters'.
std::vector<SheenLayer> sheen_from_below(Extent level0, int level, const std::vector<SheenLayer>& fine);

// The anisotropy's means of level `level` ≥ 1 from those of level − 1 (KHR_materials_anisotropy): the
// direction is axial (φ and φ + π stretch alike), so the children's strengths s and angles φ average as
// s·(cos 2φ, sin 2φ), weighted by the level-0 texels they cover; the mean's length is the strength and
// half its angle the direction. Children stretched across each other cancel toward isotropy, as their
// mean parameter should.
std::vector<AnisotropyLayer> anisotropy_from_below(Extent level0, int level, const std::vector<AnisotropyLayer>& fine);
// An anisotropy as the axial vector those means add, s·(cos 2φ, sin 2φ), and a mean of such vectors
// (divided by its weight) back: its length the strength, half its angle the direction.
inline glm::dvec2 axial_anisotropy(const AnisotropyLayer& a) {
  const double c = a.direction.x, s = a.direction.y;
  return double(a.strength) * glm::dvec2(c * c - s * s, 2 * c * s);
}
inline AnisotropyLayer from_axial_anisotropy(const glm::dvec2& v) {
  const double len = glm::length(v);
  if (!(len > 0)) return AnisotropyLayer{};
  const double phi = 0.5 * std::atan2(v.y, v.x);
  return AnisotropyLayer{static_cast<float>(len), glm::vec2(static_cast<float>(std::cos(phi)), static_cast<float>(std::sin(phi)))};
}

class ParamPyramid {
 public:
  ParamPyramid() = default;
  static ParamPyramid build(const MaterialTexels& level0);
  // Level 0 alone: the texels' parameters, one texel in one half cache line, which is all the level0
  // filter reads. build_coarse_levels() completes the pyramid later.
  static ParamPyramid level0_only(const MaterialTexels& level0);
  void build_coarse_levels();
  bool complete() const { return levels() == level_count(level0_); }
  // Level 0 as MaterialTexels (the form the BRDF build reads): the same floats.
  MaterialTexels level0_texels() const;
  // From stored levels (the MIP file), and the specular layer's (empty for a plain layer) and ior;
  // throws svbrdf::Error when the shapes do not form a pyramid.
  static ParamPyramid from_levels(Extent level0, std::vector<std::vector<ParamTexel>> levels,
                                  std::vector<std::vector<ParamSpecular>> specular = {}, float ior = 1.5f,
                                  std::vector<std::vector<ParamCoat>> coat = {},
                                  std::vector<std::vector<SheenLayer>> sheen = {},
                                  std::vector<std::vector<AnisotropyLayer>> anisotropy = {},
                                  std::vector<std::vector<float>> transmission = {},
                                  std::vector<std::vector<DiffuseTransmissionLayer>> diffuse_transmission = {});

  int levels() const { return static_cast<int>(levels_.size()); }
  Extent level0() const { return level0_; }
  Extent extent(int level) const { return level_extent(level0_, level); }
  std::span<const ParamTexel> level(int level) const { return levels_[static_cast<std::size_t>(level)]; }
  const ParamTexel& texel(int level, int i, int j) const {
    return levels_[static_cast<std::size_t>(level)][static_cast<std::size_t>(j) * extent(level).width + i];
  }
  static constexpr int kBytesPerTexel = 8 * 4;  // 8 floats

  // The specular layer, held apart so that the plain material's texel stays in half a cache line: a
  // pyramid of its means beside the parameters' when it is not plain, and the material's ior.
  bool plain_specular() const { return specular_.empty() && ior_ == 1.5f; }
  float ior() const { return ior_; }
  std::span<const ParamSpecular> specular_level(int level) const {
    return specular_.empty() ? std::span<const ParamSpecular>() : specular_[static_cast<std::size_t>(level)];
  }
  SpecularLayer specular(int level, int i, int j) const {
    if (specular_.empty()) return {1.0f, glm::vec3(1.0f), ior_};
    const ParamSpecular& s =
        specular_[static_cast<std::size_t>(level)][static_cast<std::size_t>(j) * extent(level).width + i];
    return {s.specular, s.color, ior_};
  }
  static constexpr int kBytesPerSpecularTexel = 4 * 4;  // 4 floats, where the layer is not plain

  // The clear coat, a pyramid of its means beside the parameters' for a material with one (empty
  // otherwise), held apart as the specular layer is.
  bool has_coat() const { return !coat_.empty(); }
  std::span<const ParamCoat> coat_level(int level) const {
    return coat_.empty() ? std::span<const ParamCoat>() : coat_[static_cast<std::size_t>(level)];
  }
  const ParamCoat* coat(int level, int i, int j) const {
    if (coat_.empty()) return nullptr;
    return &coat_[static_cast<std::size_t>(level)][static_cast<std::size_t>(j) * extent(level).width + i];
  }
  static constexpr int kBytesPerCoatTexel = 5 * 4;  // 5 floats, for a material with a coat

  // The sheen (KHR_materials_sheen), a pyramid of its means beside the parameters' for a material with
  // one (empty otherwise): the mean linear colour and perceptual roughness (sheen_from_below). The BRDF
  // pyramid's texels read the same means (sheen_layer.h).
  bool has_sheen() const { return !sheen_.empty(); }
  std::span<const SheenLayer> sheen_level(int level) const {
    return sheen_.empty() ? std::span<const SheenLayer>() : sheen_[static_cast<std::size_t>(level)];
  }
  const SheenLayer* sheen(int level, int i, int j) const {
    if (sheen_.empty()) return nullptr;
    return &sheen_[static_cast<std::size_t>(level)][static_cast<std::size_t>(j) * extent(level).width + i];
  }
  static constexpr int kBytesPerSheenTexel = 4 * 4;  // 4 floats, for a material with a sheen

  // The anisotropy (KHR_materials_anisotropy), a pyramid of its means beside the parameters' for a
  // material with one (empty otherwise): strength and unit direction (anisotropy_from_below); level 0's
  // are the texels' own, which a level-0 lookup shades.
  bool has_anisotropy() const { return !anisotropy_.empty(); }
  std::span<const AnisotropyLayer> anisotropy_level(int level) const {
    return anisotropy_.empty() ? std::span<const AnisotropyLayer>() : anisotropy_[static_cast<std::size_t>(level)];
  }
  const AnisotropyLayer* anisotropy(int level, int i, int j) const {
    if (anisotropy_.empty()) return nullptr;
    return &anisotropy_[static_cast<std::size_t>(level)][static_cast<std::size_t>(j) * extent(level).width + i];
  }
  static constexpr int kBytesPerAnisotropyTexel = 3 * 4;  // 3 floats, for an anisotropic material

  // The transmission (KHR_materials_transmission, thin-walled), a pyramid of its means beside the
  // parameters' for a material that transmits (empty otherwise): the mean T of the covered level-0
  // texels, linear in them as the parameters are (lobe.h: τ and τ90 are linear in T); level 0's are
  // the texels' own.
  bool has_transmission() const { return !transmission_.empty(); }
  std::span<const float> transmission_level(int level) const {
    return transmission_.empty() ? std::span<const float>() : transmission_[static_cast<std::size_t>(level)];
  }
  const float* transmission(int level, int i, int j) const {
    if (transmission_.empty()) return nullptr;
    return &transmission_[static_cast<std::size_t>(level)][static_cast<std::size_t>(j) * extent(level).width + i];
  }
  static constexpr int kBytesPerTransmissionTexel = 4;  // 1 float, for a material that transmits

  // The diffuse transmission (KHR_materials_diffuse_transmission), a pyramid of its means beside the
  // parameters' for a material that transmits diffusely (empty otherwise): the mean share of the covered
  // level-0 texels and their share-weighted mean colour (diffuse_transmission_mean); level 0's are the
  // texels' own.
  bool has_diffuse_transmission() const { return !diffuse_transmission_.empty(); }
  std::span<const DiffuseTransmissionLayer> diffuse_transmission_level(int level) const {
    return diffuse_transmission_.empty() ? std::span<const DiffuseTransmissionLayer>()
                                         : diffuse_transmission_[static_cast<std::size_t>(level)];
  }
  const DiffuseTransmissionLayer* diffuse_transmission(int level, int i, int j) const {
    if (diffuse_transmission_.empty()) return nullptr;
    return &diffuse_transmission_[static_cast<std::size_t>(level)][static_cast<std::size_t>(j) * extent(level).width + i];
  }
  static constexpr int kBytesPerDiffuseTransmissionTexel = 4 * 4;  // 4 floats, for a material that has one

 private:
  Extent level0_{};
  std::vector<std::vector<ParamTexel>> levels_;
  std::vector<std::vector<ParamSpecular>> specular_;  // empty: a plain layer (factors 1)
  std::vector<std::vector<ParamCoat>> coat_;          // empty: no coat
  std::vector<std::vector<SheenLayer>> sheen_;        // empty: no sheen
  std::vector<std::vector<AnisotropyLayer>> anisotropy_;  // empty: isotropic
  std::vector<std::vector<float>> transmission_;          // empty: no transmission
  std::vector<std::vector<DiffuseTransmissionLayer>> diffuse_transmission_;  // empty: none
  float ior_ = 1.5f;
};

}  // namespace svbrdf
