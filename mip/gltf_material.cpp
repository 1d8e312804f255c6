#include "mip/gltf_material.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <span>
#include <vector>

#include "base/error.h"
#include "gltf/document.h"
#include "textures/image.h"
#include "textures/material_loader.h"

namespace svbrdf {

MaterialTexels load_gltf_material_texels(const std::filesystem::path& path, const std::string& material,
                                         const ColorConfig& color) {
  const std::string file = path.string();
  gltf::Document doc = gltf::read_document(path);
  const tinygltf::Model& model = doc.model;
  // The material, by index (all digits) or by name.
  int mi = -1;
  const bool numeric = !material.empty() && std::all_of(material.begin(), material.end(), [](unsigned char c) { return std::isdigit(c); });
  if (numeric) {
    mi = material.size() < 9 ? std::stoi(material) : -1;
    if (mi < 0 || mi >= static_cast<int>(model.materials.size()))
      throw input_error("--material", "material " + material + " is out of range (" + file + " has " +
                                          std::to_string(model.materials.size()) + " materials)");
  } else {
    for (std::size_t i = 0; i < model.materials.size() && mi < 0; ++i)
      if (model.materials[i].name == material) mi = static_cast<int>(i);
    if (mi < 0) throw input_error("--material", file + " has no material named \"" + material + "\"");
  }
  const tinygltf::Material& m = model.materials[static_cast<std::size_t>(mi)];
  const std::string mwhere = file + ": " + gltf::json_index("materials", mi);
  // Decoded images by glTF image index, read once each.
  std::vector<Image> images(model.images.size());
  std::vector<bool> decoded(model.images.size(), false);
  auto image_of = [&](int texture, const std::string& where) -> const Image* {
    if (texture < 0) return nullptr;
    if (texture >= static_cast<int>(model.textures.size()))
      throw input_error(where, "names " + gltf::json_index("textures", texture) + ", but the file has " + std::to_string(model.textures.size()));
    const int source = model.textures[static_cast<std::size_t>(texture)].source;
    if (source < 0 || source >= static_cast<int>(model.images.size()))
      throw input_error(where, gltf::json_index("textures", texture) + " has no image source");
    const auto s = static_cast<std::size_t>(source);
    const std::string iwhere = file + ": " + gltf::json_index("images", source);
    if (!decoded[s]) {
      const gltf::ImageBytes& kept = doc.images[s];
      if (!kept.error.empty()) throw input_error(iwhere, kept.error);
      if (!kept.loaded || kept.bytes.empty()) {
        const std::string& uri = model.images[s].uri;
        throw input_error(iwhere, uri.empty() ? "has no image data" : "cannot read the image file '" + uri + "'");
      }
      const auto& b = kept.bytes;
      images[s] = read_image_from_memory(std::as_bytes(std::span(b.data(), b.size())), model.images[s].mimeType,
                                         model.images[s].uri.empty() ? iwhere : iwhere + " ('" + model.images[s].uri + "')");
      decoded[s] = true;
    }
    return &images[s];
  };
  const auto& pbr = m.pbrMetallicRoughness;
  MaterialImages in;
  in.base_color = image_of(pbr.baseColorTexture.index, mwhere + ".pbrMetallicRoughness.baseColorTexture");
  in.base_color_name = file + ": base color texture of " + gltf::json_index("materials", mi);
  if (pbr.baseColorFactor.size() == 4)
    in.base_color_factor = glm::vec4(float(pbr.baseColorFactor[0]), float(pbr.baseColorFactor[1]),
                                     float(pbr.baseColorFactor[2]), float(pbr.baseColorFactor[3]));
  in.metallic_roughness = image_of(pbr.metallicRoughnessTexture.index, mwhere + ".pbrMetallicRoughness.metallicRoughnessTexture");
  in.metallic_roughness_name = file + ": metallic-roughness texture of " + gltf::json_index("materials", mi);
  in.metallic_factor = static_cast<float>(pbr.metallicFactor);
  in.roughness_factor = static_cast<float>(pbr.roughnessFactor);
  in.normal = image_of(m.normalTexture.index, mwhere + ".normalTexture");
  in.normal_name = file + ": normal texture of " + gltf::json_index("materials", mi);
  in.normal_scale = static_cast<float>(m.normalTexture.scale);
  return decode_material_texels(in, color);
}

}  // namespace svbrdf
