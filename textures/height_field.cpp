#include "textures/height_field.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace svbrdf {

glm::vec2 height_slope(const std::vector<float>& h, int width, int height, double mm_per_texel, int i, int j) {
  const int il = i == 0 ? width - 1 : i - 1, ir = i == width - 1 ? 0 : i + 1;
  const int ju = j == 0 ? height - 1 : j - 1, jd = j == height - 1 ? 0 : j + 1;
  const auto at = [&](int x, int y) { return double(h[std::size_t(y) * width + x]); };
  const double inv = 1.0 / (2.0 * mm_per_texel);
  return {float((at(ir, j) - at(il, j)) * inv), float((at(i, ju) - at(i, jd)) * inv)};
}

void normals_from_height(const std::vector<float>& heights_mm, int width, int height, double mm_per_texel,
                         std::vector<glm::vec3>& normals) {
  normals.resize(std::size_t(width) * height);
  tbb::parallel_for(tbb::blocked_range<int>(0, height, 16), [&](const tbb::blocked_range<int>& r) {
    for (int j = r.begin(); j != r.end(); ++j)
      for (int i = 0; i < width; ++i) {
        const glm::vec2 s = height_slope(heights_mm, width, height, mm_per_texel, i, j);
        normals[std::size_t(j) * width + i] = glm::normalize(glm::vec3(-s.x, -s.y, 1.0f));
      }
  });
}

}  // namespace svbrdf
