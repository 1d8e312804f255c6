#pragma once
// Shading normals from a height field with physical dimensions. A surface z = h(x, y), lengths in
// mm, has the (unnormalized) normal (−∂h/∂x, −∂h/∂y, 1). In glTF's tangent frame +X is the image's
// right (+u) and +Y its up (toward row 0, −v), so with rows j counted from the top
//   ∂h/∂x ≈ (h[i+1, j] − h[i−1, j]) / (2Δ),  ∂h/∂y ≈ (h[i, j−1] − h[i, j+1]) / (2Δ),
// Δ = mm per texel, central differences on the periodic grid (the families' textures tile).
#include <vector>

#include <glm/glm.hpp>

namespace svbrdf {

// heights: width·height values in mm, row-major from the top row. normals is resized and filled
// with unit vectors. Parallel over rows; allocation only for the output.
void normals_from_height(const std::vector<float>& heights_mm, int width, int height, double mm_per_texel,
                         std::vector<glm::vec3>& normals);

// The slope (∂h/∂x, ∂h/∂y) at texel (i, j) as normals_from_height takes it (dimensionless).
glm::vec2 height_slope(const std::vector<float>& heights_mm, int width, int height, double mm_per_texel, int i, int j);

}  // namespace svbrdf
