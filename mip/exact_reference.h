#pragma once
// The exact reference F_L,ij of ../shared/spec/brdf-mip.md ("The ground truth at a coarse level"): the
// mean of f_eff over the level-0 texels that texel (i, j) of level L covers, by brute force, in double
// precision, parallel over the covered rows (oneTBB). A coated material's texels are the layered
// f_eff of coat_layer.h, and a material with a sheen's the sheen's layering under it (sheen_layer.h).
// Usable at any level; slow at coarse levels by
// nature (every covered texel is evaluated).
#include <glm/glm.hpp>

#include "mip/coat_layer.h"
#include "mip/diffuse_transmission.h"
#include "mip/direction_grid.h"
#include "mip/lobe.h"
#include "mip/pyramid_shape.h"
#include "mip/sheen_layer.h"
#include "textures/material_texels.h"

namespace svbrdf {

// The level-0 lobe of texel k of a material (exactly f_eff of that texel, its anisotropy, its
// thin-walled transmission and its diffuse transmission included).
inline Lobe level0_lobe(const MaterialTexels& m, std::size_t k) {
  const float transmission = m.has_transmission() ? m.transmission_at(k) : 0.0f;
  Lobe l = lobe_from_texel(m.base_color[k], m.metallic[k], m.roughness[k], m.normal[k], 1.0f, m.specular_layer(k),
                           m.anisotropy_layer(k), transmission);
  if (m.has_diffuse_transmission())
    add_diffuse_transmission(l, m.metallic[k], m.specular_layer(k), transmission, m.diffuse_transmission_layer(k));
  if (m.has_coat()) l.coat = std::clamp(m.coat_layer(k).weight, 0.0f, 1.0f);
  if (m.has_sheen()) l.sheen = sheen_share(m.sheen_layer(k));
  return l;
}

// The coat of level-0 texel k (coat_layer.h), its one coat lobe made into `scratch`; none for a
// material without a coat.
inline CoatTexel level0_coat(const MaterialTexels& m, std::size_t k, Lobe& scratch) {
  if (!m.has_coat()) return {};
  return level0_coat(m.coat_layer(k), scratch);
}

// f_eff of level-0 texel k of a material (its lobe, under its sheen and its coat) for a pair, in double
// precision.
glm::dvec3 level0_eval(const MaterialTexels& m, std::size_t k, const PairTerms<double>& p);
// The same for wi below and wo above the geometric surface: the texel's thin-walled transmission (lobe.h,
// "Transmission") and its diffuse transmission (diffuse_transmission.h) under its sheen's albedo scaling
// at the mirrored pair and its coat's 1 − c·Fc(wo), as the renderer's surface BSDF layers them
// (appearance/gltf_surface_bsdf.h); 0 without either.
glm::dvec3 level0_transmission_eval(const MaterialTexels& m, std::size_t k, const glm::dvec3& wi, const glm::dvec3& wo);
// table += scale · the same over the direction grid's pairs.
void accumulate_level0_double(const MaterialTexels& m, std::size_t k, double scale, std::span<glm::dvec3> table);

// The level-0 texels a texel of any level covers (power-of-two or not; pyramid_shape.h).
struct Coverage {
  Span columns, rows;
  long long count() const { return static_cast<long long>(columns.size()) * rows.size(); }
};
inline Coverage coverage(Extent level0, int level, int i, int j) {
  return {level0_span(level0.width, level, i), level0_span(level0.height, level, j)};
}

class ExactReference {
 public:
  // Keeps a reference: `texels` must outlive this object.
  explicit ExactReference(const MaterialTexels& texels) : texels_(texels) {}

  Extent level0() const { return {texels_.width, texels_.height}; }
  const MaterialTexels& texels() const { return texels_; }

  // F_L,ij(wi, wo), directions in the geometric tangent frame; wi below the surface: the transmission's.
  glm::dvec3 eval(int level, int i, int j, const glm::dvec3& wi, const glm::dvec3& wo) const;
  // F_L,ij over the metric's 4225 pairs (direction_grid.h).
  BrdfTable table(int level, int i, int j) const;

 private:
  const MaterialTexels& texels_;
};

}  // namespace svbrdf
