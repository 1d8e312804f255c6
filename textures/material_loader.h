#pragma once
// A glTF metallic-roughness texture set → MaterialTexels, the decoded level-0 parameters of
// ../shared/spec/brdf-mip.md ("The material at level 0"):
//   base color = sRGB→linear(baseColorTexture.rgb, through OCIO) · baseColorFactor.rgb
//   metallic   = metallicRoughnessTexture.b · metallicFactor       (glTF: metal in B)
//   roughness  = metallicRoughnessTexture.g · roughnessFactor      (glTF: roughness in G)
//   normal     = normalize((2·normalTexture.rgb − 1)·(s, s, 1)), s = normalTexture.scale
// the specular layer of KHR_materials_specular and _ior, the clear coat of KHR_materials_clearcoat, the
// sheen of KHR_materials_sheen, the anisotropy of KHR_materials_anisotropy, the transmission of
// KHR_materials_transmission and the diffuse transmission of KHR_materials_diffuse_transmission
// (MaterialImages below).
// A missing texture contributes its factor alone (normal: (0, 0, 1)). All present textures must
// have the same size, which is the result's size (1×1 when there is none). Texels are read at
// their own (i, j): no filtering, no texture transform (the level-0 texel grid is the image's).
#include <filesystem>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "textures/color.h"
#include "textures/image.h"
#include "textures/material_texels.h"

namespace svbrdf {

// The images as stored (base color still sRGB-encoded), e.g. decoded from a .glb by the render
// module; names are what error messages call them ("scene.glb: images[2]"). Images are borrowed.
struct MaterialImages {
  const Image* base_color = nullptr;
  std::string base_color_name = "base color texture";
  bool base_color_is_linear = false;  // true: already scene-linear (a float image), no sRGB decode
  glm::vec4 base_color_factor{1.0f};  // linear RGBA; alpha is not part of MaterialTexels
  const Image* metallic_roughness = nullptr;
  std::string metallic_roughness_name = "metallic-roughness texture";
  float metallic_factor = 1.0f;
  float roughness_factor = 1.0f;
  const Image* normal = nullptr;
  std::string normal_name = "normal texture";
  float normal_scale = 1.0f;
  // KHR_materials_specular and KHR_materials_ior (MaterialTexels::specular_layer):
  //   specular       = specularTexture.a · specularFactor, clamped to [0, 1] as the renderer shades it
  //   specular color = sRGB→linear(specularColorTexture.rgb) · specularColorFactor
  const Image* specular = nullptr;
  std::string specular_name = "specular texture";
  float specular_factor = 1.0f;
  const Image* specular_color = nullptr;
  std::string specular_color_name = "specular color texture";
  bool specular_color_is_linear = false;  // as base_color_is_linear
  glm::vec3 specular_color_factor{1.0f};
  float ior = 1.5f;
  // KHR_materials_clearcoat (MaterialTexels::coat_layer), each clamped to [0, 1] as the renderer shades it:
  //   clearcoat           = clearcoatTexture.r · clearcoatFactor
  //   clearcoat roughness = clearcoatRoughnessTexture.g · clearcoatRoughnessFactor
  //   clearcoat normal    = normalize((2·clearcoatNormalTexture.rgb − 1)·(s, s, 1)), or (0, 0, 1)
  const Image* clearcoat = nullptr;
  std::string clearcoat_name = "clearcoat texture";
  float clearcoat_factor = 0.0f;
  const Image* clearcoat_roughness = nullptr;
  std::string clearcoat_roughness_name = "clearcoat roughness texture";
  float clearcoat_roughness_factor = 0.0f;
  const Image* clearcoat_normal = nullptr;
  std::string clearcoat_normal_name = "clearcoat normal texture";
  float clearcoat_normal_scale = 1.0f;
  // KHR_materials_sheen (MaterialTexels::sheen_layer), read only where the colour factor is not black:
  //   sheen colour     = sRGB→linear(sheenColorTexture.rgb) · sheenColorFactor
  //   sheen roughness  = sheenRoughnessTexture.a · sheenRoughnessFactor, clamped to [0, 1]
  const Image* sheen_color = nullptr;
  std::string sheen_color_name = "sheen color texture";
  bool sheen_color_is_linear = false;  // as base_color_is_linear
  glm::vec3 sheen_color_factor{0.0f};
  const Image* sheen_roughness = nullptr;
  std::string sheen_roughness_name = "sheen roughness texture";
  float sheen_roughness_factor = 0.0f;
  // KHR_materials_anisotropy (MaterialTexels::anisotropy_layer), read only where the strength is not 0,
  // as render/surface.cpp shades it (θ = anisotropy_rotation, radians counter-clockwise from the tangent):
  //   strength  = anisotropyTexture.b · anisotropyStrength, B clamped to [0, 1]
  //   direction = R(θ)·normalize(2·anisotropyTexture.rg − 1), or R(θ)·(1, 0) without the texture
  //               (and where its RG is (0.5, 0.5): no direction to normalize, the renderer's choice)
  const Image* anisotropy = nullptr;
  std::string anisotropy_name = "anisotropy texture";
  float anisotropy_strength = 0.0f;
  float anisotropy_rotation = 0.0f;
  // KHR_materials_transmission (MaterialTexels::transmission_at), read only where the factor is not 0,
  // as render/surface.cpp shades it and SurfaceBsdf clamps it:
  //   transmission = transmissionTexture.r · transmissionFactor, clamped to [0, 1] (R is linear data)
  const Image* transmission = nullptr;
  std::string transmission_name = "transmission texture";
  float transmission_factor = 0.0f;
  // KHR_materials_diffuse_transmission (MaterialTexels::diffuse_transmission_layer), read only where the
  // factor is not 0, as render/surface.cpp shades it and SurfaceBsdf clamps it:
  //   share  = diffuseTransmissionTexture.a · diffuseTransmissionFactor, clamped to [0, 1]
  //   colour = sRGB→linear(diffuseTransmissionColorTexture.rgb) · diffuseTransmissionColorFactor
  const Image* diffuse_transmission = nullptr;
  std::string diffuse_transmission_name = "diffuse transmission texture";
  float diffuse_transmission_factor = 0.0f;
  const Image* diffuse_transmission_color = nullptr;
  std::string diffuse_transmission_color_name = "diffuse transmission color texture";
  bool diffuse_transmission_color_is_linear = false;  // as base_color_is_linear
  glm::vec3 diffuse_transmission_color_factor{1.0f};
};

// Throws svbrdf::Error naming the image for different sizes or a normal map with fewer than three
// channels, and for factors glTF does not allow (negative, or metallic/roughness above 1).
MaterialTexels decode_material_texels(const MaterialImages& images, const ColorConfig& color = ColorConfig::builtin());

// The same from files (any format OpenImageIO reads); each path is read once. A base color stored
// as integers (PNG, JPEG, 8/16-bit TIFF) is sRGB-encoded, as glTF defines; one stored as floats
// (OpenEXR, Radiance HDR, float TIFF) is taken as scene-linear, as those formats are by convention.
struct MaterialFiles {
  std::optional<std::filesystem::path> base_color;
  glm::vec4 base_color_factor{1.0f};
  std::optional<std::filesystem::path> metallic_roughness;
  float metallic_factor = 1.0f;
  float roughness_factor = 1.0f;
  std::optional<std::filesystem::path> normal;
  float normal_scale = 1.0f;
};

// Throws svbrdf::Error naming the file for a missing, truncated or corrupt image and for the
// conditions of decode_material_texels.
MaterialTexels load_material_texels(const MaterialFiles& files, const ColorConfig& color = ColorConfig::builtin());

}  // namespace svbrdf
