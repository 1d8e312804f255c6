#pragma once
// Reading glTF accessors with every bound checked (glTF 2.0 §3.6.2): the accessor, its buffer view
// and buffer must exist, the view must lie inside the buffer and every element inside the view,
// sparse indices must be in range. Errors name the JSON path that referenced the accessor (e.g.
// "meshes[2].primitives[0].attributes.POSITION"). Part of the one glTF reader, beside the document
// (gltf/document.h); a count is checked against the bytes present and the resource limits before
// anything is allocated.
#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

namespace svbrdf::gltf {

// The element shapes an attribute may have (TINYGLTF_TYPE_*), e.g. {VEC3} for POSITION, {VEC3, VEC4}
// for COLOR_0.
struct AccessorShape {
  std::vector<int> types;
  // Component types allowed; empty = any of the six glTF allows (KHR_mesh_quantization widens them).
  std::vector<int> component_types;
};

// The components per element of accessor `index` (3 for VEC3), after checking that it exists, has one
// of `shape`'s types and component types and a count within [1, 2^32). For data that does not come
// from the accessor's own buffer view (a KHR_draco_mesh_compression primitive's, decoded elsewhere).
int accessor_components(const tinygltf::Model& model, int index, const AccessorShape& shape, const std::string& where);

// Reads accessor `index` as floats, `count × components` of them, components per element taken
// from its type. Normalized integers map to [0, 1] / [−1, 1] as glTF §3.11 says; other integers
// convert to their value. The values must be finite and within the accessor's min and max where it
// states them. Throws svbrdf::Error "where: ..." on any violation.
std::vector<float> read_floats(const tinygltf::Model& model, int index, const AccessorShape& shape,
                               const std::string& where, int* components_out);

// Reads an index accessor (SCALAR of UNSIGNED_BYTE/SHORT/INT).
std::vector<std::uint32_t> read_indices(const tinygltf::Model& model, int index, const std::string& where);

// The number of elements of accessor `index` (checked to exist).
std::size_t element_count(const tinygltf::Model& model, int index, const std::string& where);

}  // namespace svbrdf::gltf
