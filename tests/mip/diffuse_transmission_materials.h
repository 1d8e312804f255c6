#pragma once
// Test helper: a random-family material given a diffuse transmission (KHR_materials_diffuse_transmission,
// mip/diffuse_transmission.h) in patches, for the layer's pyramid and storage tests.
#include <cstdint>
#include <vector>

#include "appearance/rng.h"
#include "textures/material_texels.h"
#include "textures/random_material.h"

namespace svbrdf::testing_materials {

// A random-family material (textures/random_material.h, its normals, roughness and metal) given a diffuse
// transmission: 4 × 4-texel patches of share 0 or U[0.2, 1] and a random colour, and, with
// `transmission`, a thin-walled transmission on every third patch, from the seed's own stream.
inline MaterialTexels diffusely_transmitting(std::uint64_t seed, int size, bool transmission) {
  MaterialTexels m = random_material_texels(draw_random_material(seed), size);
  // Without the family's sheen: a coarse texel's sheen is its own approximation (sheen_layer.h), not
  // what these tests measure.
  m.sheen_color_factor = glm::vec3(0.0f), m.sheen_color.clear(), m.sheen_roughness.clear();
  Rng rng(seed, 12);
  const int patches = (size / 4) * (size / 4);
  std::vector<DiffuseTransmissionLayer> patch(static_cast<std::size_t>(patches));
  std::vector<float> thin(static_cast<std::size_t>(patches), 0.0f);
  for (int k = 0; k < patches; ++k) {
    DiffuseTransmissionLayer& d = patch[static_cast<std::size_t>(k)];
    d.share = rng.next_float() < 0.25f ? 0.0f : 0.2f + 0.8f * rng.next_float();
    d.color = {rng.next_float(), rng.next_float(), rng.next_float()};
    if (transmission && k % 3 == 0) thin[static_cast<std::size_t>(k)] = 0.3f + 0.7f * rng.next_float();
  }
  m.diffuse_transmission_factor = 1.0f;
  m.diffuse_transmission.resize(m.size());
  m.diffuse_transmission_color.resize(m.size());
  if (transmission) m.transmission_factor = 1.0f, m.transmission.resize(m.size());
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const std::size_t p = std::size_t(j / 4) * (size / 4) + i / 4, k = m.index(i, j);
      m.diffuse_transmission[k] = patch[p].share, m.diffuse_transmission_color[k] = patch[p].color;
      if (transmission) m.transmission[k] = thin[p];
    }
  return m;
}

}  // namespace svbrdf::testing_materials
