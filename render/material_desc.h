#pragma once
// A glTF material as the renderer reads it (DESIGN.md, "Data through the house", step 1): the
// factors, and for every texture slot a reference to a texture with its uv set and
// KHR_texture_transform. Nothing here is decoded yet; textures are sampled at shading time.
#include <cmath>
#include <string>

#include <glm/glm.hpp>

#include "appearance/bsdf.h"

namespace svbrdf {

// KHR_texture_transform: uv' = T · R · S · uv with u' = cos·u + sin·v, v' = −sin·u + cos·v, the
// rotation the reference viewers use (KhronosGroup/glTF issue #1563: the README's GLSL listing is
// transposed) and the textures module's sampler (textures/sampler.h) adopts. A stand-in until that
// sampler is in main.
struct TextureTransform {
  glm::vec2 offset{0.0f};
  float rotation = 0.0f;  // radians
  glm::vec2 scale{1.0f};

  static TextureTransform make(glm::vec2 offset, float rotation, glm::vec2 scale) {
    TextureTransform t;
    t.offset = offset, t.rotation = rotation, t.scale = scale;
    t.cos_ = std::cos(rotation), t.sin_ = std::sin(rotation);
    return t;
  }
  bool is_identity() const { return offset == glm::vec2(0) && rotation == 0.0f && scale == glm::vec2(1); }
  glm::vec2 apply(glm::vec2 uv) const { return apply_linear(uv) + offset; }
  // The linear part, for carrying uv derivatives (footprints) through the transform.
  glm::vec2 apply_linear(glm::vec2 duv) const {
    const glm::vec2 su = duv * scale;
    return {cos_ * su.x + sin_ * su.y, -sin_ * su.x + cos_ * su.y};
  }

 private:
  float cos_ = 1.0f, sin_ = 0.0f;
};

// One texture slot of a material: which texture, which TEXCOORD_n, the transform, and the slot's
// scalar (normalTexture.scale, occlusionTexture.strength; 1 elsewhere).
struct TextureRef {
  int texture = -1;  // index into Scene::textures; −1 when the slot is empty
  int tex_coord = 0;
  TextureTransform transform;
  float scale = 1.0f;

  bool present() const { return texture >= 0; }
};

enum class AlphaMode { opaque, mask, blend };

struct MaterialDesc {
  std::string name;
  std::string where;  // "materials[3]", for messages

  // pbrMetallicRoughness. base_color is linear; its texture is sRGB-encoded color.
  Rgb base_color{1.0f};
  float base_alpha = 1.0f;
  TextureRef base_color_texture;
  float metallic = 1.0f;
  float roughness = 1.0f;
  TextureRef metallic_roughness_texture;  // B = metallic, G = roughness (data)

  TextureRef normal_texture;     // scale in TextureRef::scale
  TextureRef occlusion_texture;  // read but ignored: a path tracer computes occlusion itself

  Rgb emissive{0.0f};
  TextureRef emissive_texture;  // sRGB-encoded color
  float emissive_strength = 1.0f;  // KHR_materials_emissive_strength

  AlphaMode alpha_mode = AlphaMode::opaque;
  float alpha_cutoff = 0.5f;
  bool double_sided = false;

  float ior = 1.5f;  // KHR_materials_ior
  // KHR_materials_specular: the dielectric Fresnel's weight and F0 color.
  float specular = 1.0f;
  TextureRef specular_texture;  // A channel
  Rgb specular_color{1.0f};
  TextureRef specular_color_texture;  // RGB, sRGB-encoded color

  float transmission = 0.0f;  // KHR_materials_transmission
  TextureRef transmission_texture;  // R channel

  float diffuse_roughness = 0.0f;  // KHR_materials_diffuse_roughness (EON σ in [0, 1])
  TextureRef diffuse_roughness_texture;  // R channel

  bool unlit = false;  // KHR_materials_unlit

  // Does any texture slot that changes the surface's shape (alpha) need sampling at intersection time?
  bool alpha_tested() const { return alpha_mode != AlphaMode::opaque; }
};

}  // namespace svbrdf
