#pragma once
// KHR_draco_mesh_compression: a primitive whose attributes and indices are stored as one Draco mesh
// in a buffer view. Decoded with Debian's libdraco when the primitive is read; every count the Draco
// data states is checked against the accessors the primitive names before the values are used, and
// every face index against the decoded points, so that data which decodes but disagrees with the
// JSON is refused with its JSON path rather than read out of bounds.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>
#include <tiny_gltf.h>

namespace svbrdf::gltf {

// One decoded attribute: `count × components` floats, normalized integers already mapped to
// [0, 1] / [−1, 1] as glTF §3.11 says.
struct DecodedAttribute {
  std::vector<float> values;
  int components = 0;
};

// What a Draco-compressed primitive holds: the attributes its extension names (by glTF name:
// "POSITION", "TEXCOORD_0"), and the triangles as three point indices each.
struct DracoPrimitive {
  std::map<std::string, DecodedAttribute> attributes;
  std::vector<std::uint32_t> indices;
  std::size_t points = 0;
};

// Decodes `extension` (the primitive's "KHR_draco_mesh_compression" object) of primitive `p`, found
// at JSON path `where` ("meshes[0].primitives[1]") of `file`. Throws the input error
// "FILE: WHERE.extensions.KHR_draco_mesh_compression...: what" when the extension, its buffer view
// or the compressed data is malformed or disagrees with the primitive's accessors.
DracoPrimitive decode_draco(const tinygltf::Model& model, const tinygltf::Primitive& p,
                            const tinygltf::Value& extension, const std::filesystem::path& file,
                            const std::string& where);

// tinygltf 2.7 refuses a primitive whose indices accessor has no bufferView ("accessor[i] invalid
// bufferView"), which is how a Draco primitive's are written (KHR_draco_mesh_compression README,
// "accessors": they "must not define the bufferView"). Gives each such accessor of `document`, the
// JSON tinygltf is about to parse, a bufferView to satisfy it and returns their indices, for
// return_draco_index_views to take the views back from the parsed model.
std::vector<int> lend_draco_index_views(nlohmann::json& document);
void return_draco_index_views(const std::vector<int>& accessors, tinygltf::Model& model);

}  // namespace svbrdf::gltf
