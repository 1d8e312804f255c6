#pragma once
// A glTF material as the renderer reads it (DESIGN.md, "Data through the house", step 1): the
// factors, and for every texture slot a reference to a texture with its uv set and
// KHR_texture_transform. Nothing here is decoded yet; textures are sampled at shading time.
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "appearance/bsdf.h"
#include "textures/sampler.h"

namespace svbrdf {

// One texture slot of a material: which texture, the textureInfo's TEXCOORD_n, its
// KHR_texture_transform (textures/sampler.h, with the extension's texCoord override), and the slot's
// scalar (normalTexture.scale, occlusionTexture.strength; 1 elsewhere).
struct TextureRef {
  int texture = -1;  // index into Scene::textures; −1 when the slot is empty
  int tex_coord = 0;
  TextureTransform transform;
  float scale = 1.0f;

  bool present() const { return texture >= 0; }
  // The TEXCOORD set to read: the transform's override if any, else the textureInfo's.
  int uv_set() const { return transform.effective_tex_coord(tex_coord); }
};

enum class AlphaMode { opaque, mask, blend };

// The index of refraction that stands for an infinite one (KHR_materials_ior: a file's ior 0, "the
// effective IOR becomes positive infinity and the Fresnel term must evaluate to 1.0"): in float,
// ((n − 1)/(n + 1))² and the exact dielectric Fresnel both round to 1 at this n, and n² stays finite,
// so no formula that divides by or squares the index makes an infinity or a NaN of it. Dispersion,
// which has no effect at an infinite index, is read as 0 there.
inline constexpr float kIorInfinity = 1e9f;

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

  // KHR_materials_ior: at least 1, at most kIorInfinity (the file's 0, and anything larger).
  float ior = 1.5f;
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

  // KHR_materials_clearcoat: the layer's weight (texture R) and roughness (texture G), and its own
  // normal map (none: the surface's normal before the base's normal map).
  float clearcoat = 0.0f;
  TextureRef clearcoat_texture;
  float clearcoat_roughness = 0.0f;
  TextureRef clearcoat_roughness_texture;
  TextureRef clearcoat_normal_texture;  // scale in TextureRef::scale

  // KHR_materials_sheen: the sheen color (× texture RGB, sRGB-encoded) and roughness (× texture A).
  Rgb sheen_color{0.0f};
  TextureRef sheen_color_texture;
  float sheen_roughness = 0.0f;
  TextureRef sheen_roughness_texture;

  // KHR_materials_iridescence: the film's weight (× texture R), ior, and thickness in nm: the
  // maximum, or mix(minimum, maximum, texture G) with the thickness texture.
  float iridescence = 0.0f;
  TextureRef iridescence_texture;
  float iridescence_ior = 1.3f;
  float iridescence_thickness_min = 100.0f;
  float iridescence_thickness_max = 400.0f;
  TextureRef iridescence_thickness_texture;

  // KHR_materials_dispersion: 20/V_d, V_d the Abbe number (0: none; appearance/dispersion.h).
  float dispersion = 0.0f;

  // KHR_materials_diffuse_transmission: the share of the diffuse base transmitted (× texture A) and
  // its color (× texture RGB, sRGB-encoded).
  float diffuse_transmission = 0.0f;
  TextureRef diffuse_transmission_texture;
  Rgb diffuse_transmission_color{1.0f};
  TextureRef diffuse_transmission_color_texture;

  // KHR_materials_volume: thicknessFactor > 0 makes the mesh the boundary of a volume (0: thin-walled).
  // A path tracer meets the real thickness along its rays, so thickness and its texture only
  // decide which; attenuationColor is the transmittance after attenuationDistance (render/medium_stack.h).
  float thickness = 0.0f;
  TextureRef thickness_texture;  // G
  float attenuation_distance = std::numeric_limits<float>::infinity();
  Rgb attenuation_color{1.0f};
  bool has_volume() const { return thickness > 0.0f; }

  // KHR_materials_anisotropy: strength (× texture B), the rotation of the direction (radians,
  // counter-clockwise from the tangent), and the texture's direction (RG, [0, 1] → [−1, 1]).
  float anisotropy_strength = 0.0f;
  float anisotropy_rotation = 0.0f;
  TextureRef anisotropy_texture;

  // Every texture slot with its glTF name (relative to the material), for the checks that concern
  // them all (the TEXCOORD sets a primitive must have).
  std::vector<std::pair<const char*, const TextureRef*>> texture_slots() const {
    return {{"pbrMetallicRoughness.baseColorTexture", &base_color_texture},
            {"pbrMetallicRoughness.metallicRoughnessTexture", &metallic_roughness_texture},
            {"normalTexture", &normal_texture},
            {"occlusionTexture", &occlusion_texture},
            {"emissiveTexture", &emissive_texture},
            {"KHR_materials_specular.specularTexture", &specular_texture},
            {"KHR_materials_specular.specularColorTexture", &specular_color_texture},
            {"KHR_materials_transmission.transmissionTexture", &transmission_texture},
            {"KHR_materials_diffuse_roughness.diffuseRoughnessTexture", &diffuse_roughness_texture},
            {"KHR_materials_clearcoat.clearcoatTexture", &clearcoat_texture},
            {"KHR_materials_clearcoat.clearcoatRoughnessTexture", &clearcoat_roughness_texture},
            {"KHR_materials_clearcoat.clearcoatNormalTexture", &clearcoat_normal_texture},
            {"KHR_materials_anisotropy.anisotropyTexture", &anisotropy_texture},
            {"KHR_materials_volume.thicknessTexture", &thickness_texture},
            {"KHR_materials_diffuse_transmission.diffuseTransmissionTexture", &diffuse_transmission_texture},
            {"KHR_materials_diffuse_transmission.diffuseTransmissionColorTexture", &diffuse_transmission_color_texture},
            {"KHR_materials_sheen.sheenColorTexture", &sheen_color_texture},
            {"KHR_materials_sheen.sheenRoughnessTexture", &sheen_roughness_texture},
            {"KHR_materials_iridescence.iridescenceTexture", &iridescence_texture},
            {"KHR_materials_iridescence.iridescenceThicknessTexture", &iridescence_thickness_texture}};
  }

  // Whether the shading frame needs a tangent space (a normal map, the coat's normal map, or the
  // anisotropy direction), and the TEXCOORD set it comes from (the first of those textures'; with
  // anisotropy and no texture, TEXCOORD_0).
  bool needs_tangents() const {
    return normal_texture.present() || clearcoat_normal_texture.present() || anisotropy_strength > 0.0f;
  }
  int tangent_uv_set() const {
    for (const TextureRef* r : {&normal_texture, &clearcoat_normal_texture, &anisotropy_texture})
      if (r->present()) return r->uv_set();
    return 0;
  }

  // Does any texture slot that changes the surface's shape (alpha) need sampling at intersection time?
  bool alpha_tested() const { return alpha_mode != AlphaMode::opaque; }

  // Whether a slot that holds sRGB-encoded color (base color, emissive, specular color) shows
  // texture `texture`: its image is then read through a scene-linear copy.
  bool shows_as_color(int texture) const {
    return base_color_texture.texture == texture || emissive_texture.texture == texture ||
           specular_color_texture.texture == texture;
  }
};

}  // namespace svbrdf
