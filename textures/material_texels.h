#pragma once
// The level-0 parameters of a glTF metallic-roughness material, one value per texel, already decoded:
// base color linear (sRGB decoded through OCIO, factors applied), metallic and perceptual roughness in
// [0, 1] (factors applied), the shading normal as a unit vector in the tangent frame (normal map
// decoded with its scale). This is what the MIP builds read (../shared/spec/brdf-mip.md, "The material
// at level 0") and what the procedural material families produce.
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace svbrdf {

struct MaterialTexels {
  int width = 0;
  int height = 0;
  std::vector<glm::vec3> base_color;  // linear Rec.709
  std::vector<float> metallic;
  std::vector<float> roughness;       // perceptual; α = roughness²
  std::vector<glm::vec3> normal;      // unit, tangent space, z up

  MaterialTexels() = default;
  MaterialTexels(int w, int h)
      : width(w),
        height(h),
        base_color(std::size_t(w) * h, glm::vec3(1)),
        metallic(std::size_t(w) * h, 0.0f),
        roughness(std::size_t(w) * h, 1.0f),
        normal(std::size_t(w) * h, glm::vec3(0, 0, 1)) {}

  // Texel (i, j): column i, row j counted from the top row of the stored image.
  std::size_t index(int i, int j) const { return std::size_t(j) * width + i; }
  std::size_t size() const { return std::size_t(width) * height; }
};

}  // namespace svbrdf
