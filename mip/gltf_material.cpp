#include "mip/gltf_material.h"

#include <algorithm>
#include <cctype>

#include "appearance/shading.h"
#include "base/error.h"
#include "gltf/material_reader.h"
#include "textures/image.h"
#include "textures/material_loader.h"

namespace svbrdf {

MaterialTexels load_gltf_material_texels(const std::filesystem::path& path, const std::string& material,
                                         const ColorConfig& color) {
  const std::string file = path.string();
  gltf::Document doc = gltf::read_document(path);
  // The one material reader (gltf/material_reader.h): the file is checked as the renderer checks it.
  gltf::Materials m = gltf::read_materials(doc);
  // The material, by index (all digits) or by name.
  int mi = -1;
  const bool numeric = !material.empty() && std::all_of(material.begin(), material.end(), [](unsigned char c) { return std::isdigit(c); });
  if (numeric) {
    mi = material.size() < 9 ? std::stoi(material) : -1;
    if (mi < 0 || mi >= static_cast<int>(m.materials.size()))
      throw input_error("--material", "material " + material + " is out of range (" + file + " has " +
                                          std::to_string(m.materials.size()) + " materials)");
  } else {
    for (std::size_t i = 0; i < m.materials.size() && mi < 0; ++i)
      if (m.materials[i].name == material) mi = static_cast<int>(i);
    if (mi < 0) throw input_error("--material", file + " has no material named \"" + material + "\"");
  }
  const MaterialDesc& d = m.materials[static_cast<std::size_t>(mi)];
  const std::string why = mip_unsupported(d);
  if (!why.empty()) throw input_error(file + ": " + d.where, "has " + why + ", which the MIP lobes do not carry");
  // The image behind a texture slot, decoded once (stored encoded: colour slots are decoded from sRGB).
  auto image_of = [&](const TextureRef& r, bool) -> SlotImage {
    const auto image = static_cast<std::size_t>(m.textures[static_cast<std::size_t>(r.texture)].image);
    gltf::decode_image(doc, m, image);
    return {&m.images[image].pixels, false};
  };
  const MaterialImages in = material_images(d, image_of, file + ": ");
  return decode_material_texels(in, color);
}

std::string mip_unsupported(const MaterialDesc& m) {
  if (m.unlit) return "KHR_materials_unlit (no BRDF to filter)";
  // A factor of 0 is no layer whatever its texture (the factor multiplies it, render/surface.cpp).
  // A thin wall's transmission is a lobe's (mip/lobe.h "Transmission"); a volume's is a rough refraction,
  // which neither the lobes nor the renderer's level 0 model (it refracts as a smooth interface).
  if (m.transmission > 0.0f && m.has_volume()) return "KHR_materials_transmission into a KHR_materials_volume";
  if (m.diffuse_roughness > 0.0f) return "KHR_materials_diffuse_roughness (the MIP lobes are Lambertian)";
  if (m.iridescence > 0.0f) return "KHR_materials_iridescence (the MIP lobes' Fresnel is Schlick's)";
  return {};
}

MaterialImages material_images(const MaterialDesc& d, const std::function<SlotImage(const TextureRef&, bool color)>& image_of,
                               const std::string& prefix) {
  const auto image = [&](const TextureRef& r, bool color, bool* linear = nullptr) -> const Image* {
    if (!r.present()) return nullptr;
    const SlotImage s = image_of(r, color);
    if (linear) *linear = s.linear;
    return s.image;
  };
  const std::string at = prefix + d.where;
  MaterialImages in;
  in.base_color = image(d.base_color_texture, true, &in.base_color_is_linear);
  in.base_color_name = at + ".pbrMetallicRoughness.baseColorTexture";
  in.base_color_factor = glm::vec4(d.base_color, d.base_alpha);
  in.metallic_roughness = image(d.metallic_roughness_texture, false);
  in.metallic_roughness_name = at + ".pbrMetallicRoughness.metallicRoughnessTexture";
  in.metallic_factor = d.metallic;
  in.roughness_factor = d.roughness;
  in.normal = image(d.normal_texture, false);
  in.normal_name = at + ".normalTexture";
  in.normal_scale = d.normal_texture.scale;
  in.specular = image(d.specular_texture, false);
  in.specular_name = at + ".extensions.KHR_materials_specular.specularTexture";
  in.specular_factor = d.specular;
  in.specular_color = image(d.specular_color_texture, true, &in.specular_color_is_linear);
  in.specular_color_name = at + ".extensions.KHR_materials_specular.specularColorTexture";
  in.specular_color_factor = d.specular_color;
  in.ior = d.ior;
  if (d.clearcoat > 0.0f) {
    const std::string coat = at + ".extensions.KHR_materials_clearcoat.";
    in.clearcoat = image(d.clearcoat_texture, false);
    in.clearcoat_name = coat + "clearcoatTexture";
    in.clearcoat_factor = d.clearcoat;
    in.clearcoat_roughness = image(d.clearcoat_roughness_texture, false);
    in.clearcoat_roughness_name = coat + "clearcoatRoughnessTexture";
    in.clearcoat_roughness_factor = d.clearcoat_roughness;
    in.clearcoat_normal = image(d.clearcoat_normal_texture, false);
    in.clearcoat_normal_name = coat + "clearcoatNormalTexture";
    in.clearcoat_normal_scale = d.clearcoat_normal_texture.scale;
  }
  if (max_channel(d.sheen_color) > 0.0f) {
    const std::string sheen = at + ".extensions.KHR_materials_sheen.";
    in.sheen_color = image(d.sheen_color_texture, true, &in.sheen_color_is_linear);
    in.sheen_color_name = sheen + "sheenColorTexture";
    in.sheen_color_factor = d.sheen_color;
    in.sheen_roughness = image(d.sheen_roughness_texture, false);
    in.sheen_roughness_name = sheen + "sheenRoughnessTexture";
    in.sheen_roughness_factor = d.sheen_roughness;
  }
  if (d.anisotropy_strength > 0.0f) {
    in.anisotropy = image(d.anisotropy_texture, false);
    in.anisotropy_name = at + ".extensions.KHR_materials_anisotropy.anisotropyTexture";
    in.anisotropy_strength = d.anisotropy_strength;
    in.anisotropy_rotation = d.anisotropy_rotation;
  }
  if (d.transmission > 0.0f) {
    in.transmission = image(d.transmission_texture, false);
    in.transmission_name = at + ".extensions.KHR_materials_transmission.transmissionTexture";
    in.transmission_factor = d.transmission;
  }
  if (d.diffuse_transmission > 0.0f) {
    const std::string dt = at + ".extensions.KHR_materials_diffuse_transmission.";
    in.diffuse_transmission = image(d.diffuse_transmission_texture, false);
    in.diffuse_transmission_name = dt + "diffuseTransmissionTexture";
    in.diffuse_transmission_factor = d.diffuse_transmission;
    in.diffuse_transmission_color = image(d.diffuse_transmission_color_texture, true, &in.diffuse_transmission_color_is_linear);
    in.diffuse_transmission_color_name = dt + "diffuseTransmissionColorTexture";
    in.diffuse_transmission_color_factor = d.diffuse_transmission_color;
  }
  return in;
}

}  // namespace svbrdf
