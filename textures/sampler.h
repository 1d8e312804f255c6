#pragma once
// Texture lookups the way glTF 2.0 samplers define them (§3.8.4 "Samplers") plus
// KHR_texture_transform. Texture space: uv (0, 0) is the image's top-left corner, u grows to the
// right (columns i), v downward (rows j); texel (i, j) covers [i, i+1)/width × [j, j+1)/height, so
// its center is ((i + 0.5)/width, (j + 0.5)/height). Lookups allocate nothing.
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "textures/image.h"

namespace svbrdf {

// glTF sampler wrapS / wrapT: REPEAT 10497, CLAMP_TO_EDGE 33071, MIRRORED_REPEAT 33648.
enum class WrapMode { repeat, clamp_to_edge, mirrored_repeat };
// magFilter NEAREST 9728 / LINEAR 9729; the minification filters reduce to their within-level part
// here (MIP selection is the mip module's business).
enum class FilterMode { nearest, bilinear };

// The wrap modes of one texture, along u (s) and v (t), for lookups that need no filter mode.
struct WrapModes {
  WrapMode s = WrapMode::repeat;
  WrapMode t = WrapMode::repeat;
};

struct Sampler {
  FilterMode filter = FilterMode::bilinear;
  WrapMode wrap_s = WrapMode::repeat;  // along u (columns)
  WrapMode wrap_t = WrapMode::repeat;  // along v (rows)
  WrapModes wrap() const { return {wrap_s, wrap_t}; }
};

// glTF enum codes → modes; throw svbrdf::Error naming `where` for codes glTF does not define.
WrapMode wrap_mode_from_gltf(int code, const std::string& where);
FilterMode filter_mode_from_gltf(int code, const std::string& where);  // mag or min filter code
// The glTF code of a wrap mode (for writers).
int gltf_code(WrapMode mode);

// The wrap modes are honoured here and nowhere else: the sampler below, the renderer's level0 texel
// fetches (nearest_texel_index) and the MIP lookups at every level (texel_coordinate, wrap_texel)
// all read texel indices through these functions.

// The texel index an integer texel coordinate i (any integer) reads along an axis of n texels.
// Mirrored repeat follows OpenGL 4.6 §8.14.2: the pattern 0..n-1, n-1..0 with period 2n. Inline:
// the MIP lookups call it several times per hit.
inline int wrap_texel(int i, int n, WrapMode mode) {
  if (static_cast<unsigned>(i) < static_cast<unsigned>(n)) return i;  // inside: no division (the common case)
  switch (mode) {
    case WrapMode::repeat: {
      const int r = i % n;
      return r < 0 ? r + n : r;
    }
    case WrapMode::clamp_to_edge: return i < 0 ? 0 : n - 1;
    case WrapMode::mirrored_repeat: {
      const int period = 2 * n;
      int r = i % period;
      if (r < 0) r += period;
      return r < n ? r : period - 1 - r;
    }
  }
  return 0;
}

// Texel space along an axis of n texels: x = t·n, texel i covering [i, i+1). Far-out coordinates are
// brought near the texture first, so that huge or non-finite ones cannot overflow an int conversion:
// repeat and mirrored repeat are periodic in 2n texels, clamp-to-edge is constant past the edges, and
// a non-finite coordinate reads as 0.
inline float texel_coordinate(float t, int n, WrapMode mode) {
  const float x = t * static_cast<float>(n);
  if (!std::isfinite(x)) return 0.0f;
  if (mode == WrapMode::clamp_to_edge) return std::min(std::max(x, -1.0f), static_cast<float>(n) + 1.0f);
  return std::fabs(x) > 16777216.0f ? std::fmod(x, static_cast<float>(2 * n)) : x;
}

// The texel index along one axis of n texels that coordinate t (texture space, after any transform)
// falls in: the nearest lookup's texel. `mask` = n − 1 when the mode is repeat and n a power of two
// (a fast path: the same index for |t·n| < 2^24, without a division), else −1.
inline int nearest_texel_index(float t, int n, WrapMode mode, int mask = -1) {
  const float x = t * static_cast<float>(n);
  if (mask >= 0 && std::fabs(x) < 16777216.0f) return static_cast<int>(std::floor(x)) & mask;
  return wrap_texel(static_cast<int>(std::floor(texel_coordinate(t, n, mode))), n, mode);
}

// Per-texel access for the MIP builds and the families: (i, j) must be inside the image. Gray
// reads as R = G = B, gray+alpha as (g, g, g, a); a missing alpha reads 1; channels past 4 are ignored.
glm::vec4 texel(const Image& image, int i, int j);

// A lookup at uv (after any texture transform): nearest picks the texel containing uv; bilinear
// weighs the four texels whose centers surround uv. Wrap modes apply per axis to texel indices.
glm::vec4 sample(const Image& image, const Sampler& sampler, glm::vec2 uv);

// KHR_texture_transform on a textureInfo: uv' = T(offset) · R(rotation) · S(scale) · uv.
// The rotation matrix is the one the extension's example ("the lower left quadrant, rotated
// clockwise 90°") and the reference implementations (glTF-Sample-Viewer, Babylon.js, three.js,
// Blender) use: u' = cos·u + sin·v, v' = −sin·u + cos·v, counter-clockwise in glTF's v-down uv
// space (KhronosGroup/glTF issue #1563 documents that the GLSL listing's matrix is transposed).
struct TextureTransform {
  glm::vec2 offset{0.0f};
  glm::vec2 scale{1.0f};
  int tex_coord = -1;  // the extension's texCoord override; −1: none

  static TextureTransform make(glm::vec2 offset, float rotation, glm::vec2 scale, int tex_coord = -1) {
    TextureTransform t;
    t.offset = offset;
    t.scale = scale;
    t.tex_coord = tex_coord;
    t.set_rotation(rotation);
    return t;
  }
  // The rotation is kept with its cosine and sine, so lookups need no trigonometry.
  void set_rotation(float radians) {
    rotation_ = radians;
    cos_ = std::cos(radians);
    sin_ = std::sin(radians);
  }
  float rotation() const { return rotation_; }
  bool is_identity() const { return offset == glm::vec2(0.0f) && rotation_ == 0.0f && scale == glm::vec2(1.0f); }

  glm::vec2 apply(glm::vec2 uv) const { return apply_linear(uv) + offset; }
  // The linear part R·S, for carrying uv derivatives (footprints) through the transform.
  glm::vec2 apply_linear(glm::vec2 duv) const {
    const glm::vec2 s = duv * scale;
    return {cos_ * s.x + sin_ * s.y, -sin_ * s.x + cos_ * s.y};
  }
  // The texture coordinate set to read: the override if present, else the textureInfo's.
  int effective_tex_coord(int texture_info_tex_coord) const { return tex_coord >= 0 ? tex_coord : texture_info_tex_coord; }

 private:
  float rotation_ = 0.0f, cos_ = 1.0f, sin_ = 0.0f;
};

// One texture as a material slot uses it: the image, its sampler, the slot's transform and texCoord.
// The image is borrowed and must outlive the view.
struct TextureView {
  const Image* image = nullptr;
  Sampler sampler;
  TextureTransform transform;
  int tex_coord = 0;  // the textureInfo's texCoord

  int uv_set() const { return transform.effective_tex_coord(tex_coord); }
  // Looks up the uv of set uv_set() (the caller picks it), after the transform.
  glm::vec4 lookup(glm::vec2 uv) const { return sample(*image, sampler, transform.apply(uv)); }
};

}  // namespace svbrdf
