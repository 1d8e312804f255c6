#include "textures/sampler.h"

#include <algorithm>
#include <cmath>

#include "base/error.h"

namespace svbrdf {

WrapMode wrap_mode_from_gltf(int code, const std::string& where) {
  switch (code) {
    case 10497: return WrapMode::repeat;
    case 33071: return WrapMode::clamp_to_edge;
    case 33648: return WrapMode::mirrored_repeat;
    default: throw input_error(where, "unknown sampler wrap mode " + std::to_string(code));
  }
}

FilterMode filter_mode_from_gltf(int code, const std::string& where) {
  switch (code) {
    case 9728:  // NEAREST
    case 9984:  // NEAREST_MIPMAP_NEAREST
    case 9986:  // NEAREST_MIPMAP_LINEAR
      return FilterMode::nearest;
    case 9729:  // LINEAR
    case 9985:  // LINEAR_MIPMAP_NEAREST
    case 9987:  // LINEAR_MIPMAP_LINEAR
      return FilterMode::bilinear;
    default: throw input_error(where, "unknown sampler filter " + std::to_string(code));
  }
}

int gltf_code(WrapMode mode) {
  switch (mode) {
    case WrapMode::repeat: return 10497;
    case WrapMode::clamp_to_edge: return 33071;
    case WrapMode::mirrored_repeat: return 33648;
  }
  return 10497;
}

glm::vec4 texel(const Image& image, int i, int j) {
  const float* p = image.pixels.data() + (std::size_t(j) * image.width + i) * image.channels;
  switch (image.channels) {
    case 1: return {p[0], p[0], p[0], 1.0f};
    case 2: return {p[0], p[0], p[0], p[1]};
    case 3: return {p[0], p[1], p[2], 1.0f};
    default: return {p[0], p[1], p[2], p[3]};
  }
}

glm::vec4 sample(const Image& image, const Sampler& sampler, glm::vec2 uv) {
  const int w = image.width, h = image.height;
  if (sampler.filter == FilterMode::nearest)
    return texel(image, nearest_texel_index(uv.x, w, sampler.wrap_s),
                 nearest_texel_index(uv.y, h, sampler.wrap_t));
  const float x = texel_coordinate(uv.x, w, sampler.wrap_s), y = texel_coordinate(uv.y, h, sampler.wrap_t);
  // Bilinear: the four texels whose centers (i + 0.5) surround (x, y).
  const float fx = x - 0.5f, fy = y - 0.5f;
  const float x0 = std::floor(fx), y0 = std::floor(fy);
  const float tx = fx - x0, ty = fy - y0;
  const int i0 = wrap_texel(int(x0), w, sampler.wrap_s), i1 = wrap_texel(int(x0) + 1, w, sampler.wrap_s);
  const int j0 = wrap_texel(int(y0), h, sampler.wrap_t), j1 = wrap_texel(int(y0) + 1, h, sampler.wrap_t);
  const glm::vec4 top = glm::mix(texel(image, i0, j0), texel(image, i1, j0), tx);
  const glm::vec4 bottom = glm::mix(texel(image, i0, j1), texel(image, i1, j1), tx);
  return glm::mix(top, bottom, ty);
}

}  // namespace svbrdf
