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

// The dielectric's specular layer at a texel (KHR_materials_specular and KHR_materials_ior): the
// specular weight s (specularFactor · specularTexture.a), the specular colour (specularColorFactor ·
// specularColorTexture.rgb, linear) and the ior. The plain glTF BRDF is s = 1, colour 1, ior 1.5.
struct SpecularLayer {
  float specular = 1.0f;
  glm::vec3 color{1.0f};
  float ior = 1.5f;

  bool plain() const { return specular == 1.0f && color == glm::vec3(1.0f) && ior == 1.5f; }
};

// The clear coat at a texel (KHR_materials_clearcoat): its weight (clearcoatFactor ·
// clearcoatTexture.r), perceptual roughness (clearcoatRoughnessFactor · clearcoatRoughnessTexture.g)
// and unit normal in the geometric tangent frame (clearcoatNormalTexture decoded with its scale or,
// without one, (0, 0, 1): the surface's normal before the base's normal map, as the extension says).
// Weight 0 is no coat.
struct CoatLayer {
  float weight = 0.0f;
  float roughness = 0.0f;
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
};

// The sheen at a texel (KHR_materials_sheen): its linear colour (sheenColorFactor ·
// sheenColorTexture.rgb) and perceptual roughness (sheenRoughnessFactor · sheenRoughnessTexture.a),
// about the texel's shading normal. Colour 0 is no sheen.
struct SheenLayer {
  glm::vec3 color{0.0f};
  float roughness = 0.0f;
};

// The anisotropy at a texel (KHR_materials_anisotropy): its strength (anisotropyStrength ·
// anisotropyTexture.b) and the unit direction of increased roughness in the geometric tangent frame's
// x–y plane (the glTF tangent and bitangent): (cos, sin) of anisotropyRotation, or the texture's RG
// mapped to [−1, 1], normalized and turned by it. Strength 0 is isotropic.
struct AnisotropyLayer {
  float strength = 0.0f;
  glm::vec2 direction{1.0f, 0.0f};
};

// The diffuse transmission at a texel (KHR_materials_diffuse_transmission): the share of the diffuse
// base transmitted (diffuseTransmissionFactor · diffuseTransmissionTexture.a, in [0, 1]) and the
// transmitted light's linear colour (diffuseTransmissionColorFactor · diffuseTransmissionColorTexture.rgb).
// Share 0 transmits nothing.
struct DiffuseTransmissionLayer {
  float share = 0.0f;
  glm::vec3 color{1.0f};
};

struct MaterialTexels {
  int width = 0;
  int height = 0;
  std::vector<glm::vec3> base_color;  // linear Rec.709
  std::vector<float> metallic;
  std::vector<float> roughness;       // perceptual; α = roughness²
  std::vector<glm::vec3> normal;      // unit, tangent space, z up
  // The specular layer, per texel where it varies: `specular` and `specular_color` are empty for a
  // material whose factor holds everywhere (specular_factor, specular_color_factor); ior has no texture.
  std::vector<float> specular;
  std::vector<glm::vec3> specular_color;  // linear Rec.709
  float specular_factor = 1.0f;
  glm::vec3 specular_color_factor{1.0f};
  float ior = 1.5f;
  // The clear coat, per texel where a texture makes it vary (as the specular layer): `clearcoat`,
  // `clearcoat_roughness` and `clearcoat_normal` are empty where the factor (or (0, 0, 1)) holds.
  std::vector<float> clearcoat;
  std::vector<float> clearcoat_roughness;
  std::vector<glm::vec3> clearcoat_normal;  // unit, tangent space, z up
  float clearcoat_factor = 0.0f;
  float clearcoat_roughness_factor = 0.0f;
  // The sheen, per texel where a texture makes it vary (as the coat): `sheen_color` and
  // `sheen_roughness` are empty where the factor holds.
  std::vector<glm::vec3> sheen_color;  // linear Rec.709
  std::vector<float> sheen_roughness;
  glm::vec3 sheen_color_factor{0.0f};
  float sheen_roughness_factor = 0.0f;
  // The anisotropy, per texel where a texture makes it vary (as the sheen): `anisotropy` and
  // `anisotropy_direction` are empty where the factor and the rotation's direction hold.
  std::vector<float> anisotropy;
  std::vector<glm::vec2> anisotropy_direction;  // unit, tangent space
  float anisotropy_factor = 0.0f;
  glm::vec2 anisotropy_direction_factor{1.0f, 0.0f};
  // The transmission (KHR_materials_transmission: transmissionFactor · transmissionTexture.r, linear,
  // in [0, 1]), per texel where its texture makes it vary (as the anisotropy): `transmission` is empty
  // where the factor holds. 0 transmits nothing.
  std::vector<float> transmission;
  float transmission_factor = 0.0f;
  // The diffuse transmission, per texel where its textures make it vary (as the transmission):
  // `diffuse_transmission` and `diffuse_transmission_color` are empty where the factors hold.
  std::vector<float> diffuse_transmission;
  std::vector<glm::vec3> diffuse_transmission_color;  // linear Rec.709
  float diffuse_transmission_factor = 0.0f;
  glm::vec3 diffuse_transmission_color_factor{1.0f};

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
  // Texel k's specular layer, and whether every texel has the plain one.
  SpecularLayer specular_layer(std::size_t k) const {
    return {specular.empty() ? specular_factor : specular[k],
            specular_color.empty() ? specular_color_factor : specular_color[k], ior};
  }
  // Texel k's clear coat, and whether the material has one at all.
  CoatLayer coat_layer(std::size_t k) const {
    return {clearcoat.empty() ? clearcoat_factor : clearcoat[k],
            clearcoat_roughness.empty() ? clearcoat_roughness_factor : clearcoat_roughness[k],
            clearcoat_normal.empty() ? glm::vec3(0.0f, 0.0f, 1.0f) : clearcoat_normal[k]};
  }
  bool has_coat() const { return clearcoat_factor > 0.0f; }
  // Texel k's sheen, and whether the material has one at all.
  SheenLayer sheen_layer(std::size_t k) const {
    return {sheen_color.empty() ? sheen_color_factor : sheen_color[k],
            sheen_roughness.empty() ? sheen_roughness_factor : sheen_roughness[k]};
  }
  bool has_sheen() const {
    return sheen_color_factor.r > 0.0f || sheen_color_factor.g > 0.0f || sheen_color_factor.b > 0.0f;
  }
  // Texel k's anisotropy, and whether the material has any.
  AnisotropyLayer anisotropy_layer(std::size_t k) const {
    return {anisotropy.empty() ? anisotropy_factor : anisotropy[k],
            anisotropy_direction.empty() ? anisotropy_direction_factor : anisotropy_direction[k]};
  }
  bool has_anisotropy() const { return anisotropy_factor > 0.0f; }
  // Texel k's transmission, and whether the material transmits at all.
  float transmission_at(std::size_t k) const { return transmission.empty() ? transmission_factor : transmission[k]; }
  bool has_transmission() const { return transmission_factor > 0.0f; }
  // Texel k's diffuse transmission, and whether the material transmits diffusely at all.
  DiffuseTransmissionLayer diffuse_transmission_layer(std::size_t k) const {
    return {diffuse_transmission.empty() ? diffuse_transmission_factor : diffuse_transmission[k],
            diffuse_transmission_color.empty() ? diffuse_transmission_color_factor : diffuse_transmission_color[k]};
  }
  bool has_diffuse_transmission() const { return diffuse_transmission_factor > 0.0f; }
  bool plain_specular() const {
    return specular.empty() && specular_color.empty() &&
           SpecularLayer{specular_factor, specular_color_factor, ior}.plain();
  }
};

}  // namespace svbrdf
