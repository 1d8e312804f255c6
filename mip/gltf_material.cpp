#include "mip/gltf_material.h"

#include <algorithm>
#include <cctype>

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
  // The image behind a texture slot, decoded once.
  auto image_of = [&](const TextureRef& r) -> const Image* {
    if (!r.present()) return nullptr;
    const auto image = static_cast<std::size_t>(m.textures[static_cast<std::size_t>(r.texture)].image);
    gltf::decode_image(doc, m, image);
    return &m.images[image].pixels;
  };
  MaterialImages in;
  in.base_color = image_of(d.base_color_texture);
  in.base_color_name = file + ": base color texture of " + d.where;
  in.base_color_factor = glm::vec4(d.base_color, d.base_alpha);
  in.metallic_roughness = image_of(d.metallic_roughness_texture);
  in.metallic_roughness_name = file + ": metallic-roughness texture of " + d.where;
  in.metallic_factor = d.metallic;
  in.roughness_factor = d.roughness;
  in.normal = image_of(d.normal_texture);
  in.normal_name = file + ": normal texture of " + d.where;
  in.normal_scale = d.normal_texture.scale;
  return decode_material_texels(in, color);
}

}  // namespace svbrdf
