#include "render/texel_inputs.h"

#include "appearance/shading.h"

namespace svbrdf {

bool same_transform(const TextureTransform& a, const TextureTransform& b) {
  return a.offset == b.offset && a.scale == b.scale && a.rotation() == b.rotation();
}

namespace {

bool same_ref(const TextureRef& a, const TextureRef& b) {
  return a.texture == b.texture && (!a.present() || (a.uv_set() == b.uv_set() && same_transform(a.transform, b.transform)));
}

}  // namespace

std::vector<TexelInput> texel_inputs(const MaterialDesc& m) {
  // The arguments decode_material_texels takes (SceneMips::prepare fills MaterialImages from these).
  // A new texel input goes here.
  std::vector<TexelInput> in{
      {"baseColorTexture", &m.base_color_texture, true, {}},
      {"metallicRoughnessTexture", &m.metallic_roughness_texture, false, {}},
      {"normalTexture", &m.normal_texture, false, {}},
      // Alpha is not a texel input: MaterialTexels holds no alpha.
      {"baseColorFactor", nullptr, false, {m.base_color.r, m.base_color.g, m.base_color.b}},
      {"metallicFactor", nullptr, false, {m.metallic}},
      {"roughnessFactor", nullptr, false, {m.roughness}},
      {"normalTexture.scale", nullptr, false, {m.normal_texture.scale}},
      // KHR_materials_specular and KHR_materials_ior (MaterialTexels::specular_layer).
      {"specularTexture", &m.specular_texture, false, {}},
      {"specularColorTexture", &m.specular_color_texture, true, {}},
      {"specularFactor", nullptr, false, {m.specular}},
      {"specularColorFactor", nullptr, false, {m.specular_color.r, m.specular_color.g, m.specular_color.b}},
      {"ior", nullptr, false, {m.ior}},
  };
  // KHR_materials_clearcoat (MaterialTexels::coat_layer): read only where the coat has a weight, as
  // decode_material_texels reads it, so a material without one neither waits on nor is kept off the
  // grid by coat textures it does not use.
  if (m.clearcoat > 0.0f) {
    const std::vector<TexelInput> coat{
        {"clearcoatFactor", nullptr, false, {m.clearcoat}},
        {"clearcoatTexture", &m.clearcoat_texture, false, {}},
        {"clearcoatRoughnessFactor", nullptr, false, {m.clearcoat_roughness}},
        {"clearcoatRoughnessTexture", &m.clearcoat_roughness_texture, false, {}},
        {"clearcoatNormalTexture", &m.clearcoat_normal_texture, false, {}},
        {"clearcoatNormalTexture.scale", nullptr, false, {m.clearcoat_normal_texture.scale}},
    };
    in.insert(in.end(), coat.begin(), coat.end());
  }
  // KHR_materials_sheen (MaterialTexels::sheen_layer): likewise only where its colour is not black.
  if (max_channel(m.sheen_color) > 0.0f) {
    const std::vector<TexelInput> sheen{
        {"sheenColorFactor", nullptr, false, {m.sheen_color.r, m.sheen_color.g, m.sheen_color.b}},
        {"sheenColorTexture", &m.sheen_color_texture, true, {}},
        {"sheenRoughnessFactor", nullptr, false, {m.sheen_roughness}},
        {"sheenRoughnessTexture", &m.sheen_roughness_texture, false, {}},
    };
    in.insert(in.end(), sheen.begin(), sheen.end());
  }
  // KHR_materials_anisotropy (MaterialTexels::anisotropy_layer): likewise only where it has a strength.
  if (m.anisotropy_strength > 0.0f) {
    const std::vector<TexelInput> anisotropy{
        {"anisotropyStrength", nullptr, false, {m.anisotropy_strength}},
        {"anisotropyRotation", nullptr, false, {m.anisotropy_rotation}},
        {"anisotropyTexture", &m.anisotropy_texture, false, {}},
    };
    in.insert(in.end(), anisotropy.begin(), anisotropy.end());
  }
  // KHR_materials_transmission (MaterialTexels::transmission_at): likewise only where its factor is not 0.
  if (m.transmission > 0.0f) {
    const std::vector<TexelInput> transmission{
        {"transmissionFactor", nullptr, false, {m.transmission}},
        {"transmissionTexture", &m.transmission_texture, false, {}},
    };
    in.insert(in.end(), transmission.begin(), transmission.end());
  }
  // KHR_materials_diffuse_transmission (MaterialTexels::diffuse_transmission_layer): likewise only where
  // its factor is not 0.
  if (m.diffuse_transmission > 0.0f) {
    const Rgb& c = m.diffuse_transmission_color;
    const std::vector<TexelInput> diffuse_transmission{
        {"diffuseTransmissionFactor", nullptr, false, {m.diffuse_transmission}},
        {"diffuseTransmissionTexture", &m.diffuse_transmission_texture, false, {}},
        {"diffuseTransmissionColorFactor", nullptr, false, {c.r, c.g, c.b}},
        {"diffuseTransmissionColorTexture", &m.diffuse_transmission_color_texture, true, {}},
    };
    in.insert(in.end(), diffuse_transmission.begin(), diffuse_transmission.end());
  }
  return in;
}

bool same_texels(const MaterialDesc& a, const MaterialDesc& b) {
  const std::vector<TexelInput> x = texel_inputs(a), y = texel_inputs(b);
  if (x.size() != y.size()) return false;  // one has a coat, a sheen, anisotropy or transmission, the other none
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (x[i].texture && !same_ref(*x[i].texture, *y[i].texture)) return false;
    if (x[i].values != y[i].values) return false;
  }
  return true;
}

}  // namespace svbrdf
