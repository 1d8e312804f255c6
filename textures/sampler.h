#pragma once
// Texture lookups the way glTF 2.0 samplers define them (§3.8.4 "Samplers") plus
// KHR_texture_transform. Texture space: uv (0, 0) is the image's top-left corner, u grows to the
// right (columns i), v downward (rows j); texel (i, j) covers [i, i+1)/width × [j, j+1)/height, so
// its center is ((i + 0.5)/width, (j + 0.5)/height). Lookups allocate nothing.
#include <cmath>

#include <glm/glm.hpp>

#include "textures/image.h"

namespace svbrdf {

// glTF sampler wrapS / wrapT: REPEAT 10497, CLAMP_TO_EDGE 33071, MIRRORED_REPEAT 33648.
enum class WrapMode { repeat, clamp_to_edge, mirrored_repeat };
// magFilter NEAREST 9728 / LINEAR 9729; the minification filters reduce to their within-level part
// here (MIP selection is the mip module's business).
enum class FilterMode { nearest, bilinear };

struct Sampler {
  FilterMode filter = FilterMode::bilinear;
  WrapMode wrap_s = WrapMode::repeat;  // along u (columns)
  WrapMode wrap_t = WrapMode::repeat;  // along v (rows)
};

// glTF enum codes → modes; throw svbrdf::Error naming `where` for codes glTF does not define.
WrapMode wrap_mode_from_gltf(int code, const std::string& where);
FilterMode filter_mode_from_gltf(int code, const std::string& where);  // mag or min filter code
// The glTF code of a wrap mode (for writers).
int gltf_code(WrapMode mode);

// The texel index an integer texel coordinate i (any integer) reads along an axis of n texels.
// Mirrored repeat follows OpenGL 4.6 §8.14.2: the pattern 0..n-1, n-1..0 with period 2n.
int wrap_texel(int i, int n, WrapMode mode);

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
