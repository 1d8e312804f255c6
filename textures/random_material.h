#pragma once
// The random material family: a seeded family of level-0 texture sets on which the BRDF pyramid's
// constants are chosen and its error distribution is measured (docs/mip-algorithm.md, §8), so that no
// constant is tuned to one named material.
//
// A seed draws its ingredients from the distributions below (all independent; log-uniform where a
// quantity spans decades):
//   roughness  — a base population, perceptual roughness r1 log-uniform in [0.02, 1], varied by
//                noise of relative amplitude U[0, 0.15] on 16-texel features; with probability 1/2 a second
//                population r2 (smudges of a rougher or polished patches of a smoother film) a factor
//                U_log[2.5, 10] away from r1 (the other side where that leaves [0.02, 1]), covering
//                U[0.1, 0.6] of the texture in blotches U_log[3, 24] texels across, with sharp edges;
//   relief     — flat (p 0.15), hammered dents (0.3), bumps (0.3) or one-axis corrugation (0.25,
//                half ribbed, half brushed, along a row, a column or a diagonal); features
//                U_log[3, 32] texels across (corrugation period U_log[2, 16]); the steepest normal
//                tilted exactly U[5°, 35°]; with probability 1/2 the relief covers only U[0.3, 0.9]
//                of the texture and the rest is flat;
//   metal      — dielectric (p 0.35), metal (0.35), or both (0.3: metal on U[0.2, 0.8] of the
//                texture in patches U_log[4, 32] texels across, paint on metal);
//   colour     — a metal's F0 colour (any hue, saturation U[0, 0.4], value U[0.5, 0.98]) and a
//                dielectric's albedo (any hue, saturation U[0, 0.8], value U[0.03, 0.85]), each
//                varied by noise of relative amplitude U[0, 0.3] on features U_log[2, 32] texels;
//   sheen      — with probability 1/3 a KHR_materials_sheen: colour of any hue, saturation U[0, 0.6],
//                value U[0.2, 1], perceptual roughness U[0.1, 1]; with probability 1/2 textured: the
//                sheen covers U[0.2, 0.8] of the texture in patches U_log[3, 24] texels across (sharp
//                edges; none elsewhere) and its roughness varies by noise of relative amplitude
//                U[0, 0.3] on 16-texel features; otherwise its factors hold everywhere.
//   anisotropy — with probability 1/3 a KHR_materials_anisotropy: strength U[0.2, 1], direction at
//                U[0°, 180°); with probability 1/2 textured: the direction turned per texel by a smooth
//                field of amplitude U[0°, 90°] on features U_log[4, 32] texels (brushing that swirls),
//                the strength varied by noise of relative amplitude U[0, 0.5] on 16-texel features;
//   transmission — with probability 1/4 a thin-walled KHR_materials_transmission (a film: lobe.h
//                "Transmission"), factor U[0.2, 1]; with probability 1/2 textured: the factor
//                covers U[0.2, 0.8] of the texture in patches U_log[3, 24] texels across (sharp
//                edges; none elsewhere, a print on a clear film), otherwise it holds everywhere. Only
//                a seed with a dielectric part draws one: the model transmits (1 − m) of it, nothing
//                through metal, so an all-metal seed keeps none.
// Every ingredient has its own random stream, so an ingredient added later (a stream of its own)
// leaves every existing seed's texels unchanged.
//
// Sizes are in level-0 texels, so a level of the pyramid sees the same feature-to-footprint ratios
// at any texture size. Shares are exact: a mask ranks the texels by a noise field and takes its
// quantiles (2 % of the texels form a population's or the metal's edge, 20 % the relief's).
// Everything is a function of the seed and the size: the same texels on every machine and at any
// thread count (textures/noise.h). The texels are not quantized to image bit depths: this family
// feeds the MIP builds directly.
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "textures/material_texels.h"

namespace svbrdf {

enum class Relief { flat, dents, bumps, ribbed, brushed };
enum class MetalMix { dielectric, metal, both };

// What a seed drew.
struct RandomMaterialDraw {
  std::uint64_t seed = 0;
  // Roughness: the base population and its variation; the second population (share 0: none).
  float roughness = 0.5f;
  float roughness_variation = 0.0f;
  float second_roughness = 0.0f;
  float second_share = 0.0f;
  float second_feature = 0.0f;  // texels across a blotch
  // Relief: kind, feature size (texels; a corrugation's period), steepest tilt, covered share.
  Relief relief = Relief::flat;
  float relief_feature = 0.0f;
  float max_tilt_deg = 0.0f;
  float relief_share = 1.0f;
  glm::ivec2 corrugation_axis{1, 0};  // the direction the height varies along, in texels
  // Metal: which, and for both, the metal's share and patch size (texels).
  MetalMix metal = MetalMix::dielectric;
  float metal_share = 0.0f;
  float metal_feature = 0.0f;
  // Colour: linear Rec.709 metal F0 colour and dielectric albedo, relative noise amplitude, feature.
  glm::vec3 metal_color{1.0f};
  glm::vec3 dielectric_color{0.5f};
  float color_variation = 0.0f;
  float color_feature = 0.0f;
  // KHR_materials_sheen (colour 0: none): colour, roughness, and for a textured sheen its covered
  // share, patch size (texels) and relative roughness variation.
  glm::vec3 sheen_color{0.0f};
  float sheen_roughness = 0.0f;
  bool sheen_textured = false;
  float sheen_share = 1.0f;
  float sheen_feature = 0.0f;
  float sheen_roughness_variation = 0.0f;
  // KHR_materials_anisotropy (strength 0: none): strength, direction angle (radians) in the tangent
  // frame, and for a textured one the amplitude of its turn (degrees), the turn's feature size
  // (texels) and the strength's relative variation.
  float anisotropy = 0.0f;
  float anisotropy_rotation = 0.0f;
  bool anisotropy_textured = false;
  float anisotropy_swirl_deg = 0.0f;
  float anisotropy_feature = 0.0f;
  float anisotropy_variation = 0.0f;
  // KHR_materials_transmission (factor 0: none): factor, and for a textured one its covered share and
  // patch size (texels).
  float transmission = 0.0f;
  bool transmission_textured = false;
  float transmission_share = 1.0f;
  float transmission_feature = 0.0f;
  // KHR_materials_specular / KHR_materials_ior (specular weight, specular colour, ior) are drawn in
  // draw_random_material's stream kSpecularStream once MaterialTexels carries them.

  // One line: what the seed drew.
  std::string summary() const;
};

RandomMaterialDraw draw_random_material(std::uint64_t seed);

// The texture set of a draw at size × size texels (size ≥ 1).
MaterialTexels random_material_texels(const RandomMaterialDraw& draw, int size);

}  // namespace svbrdf
