#pragma once
// EXT_meshopt_compression: buffer views whose bytes are stored compressed elsewhere (another buffer's
// byte range) and decoded into the view's own place with Debian's libmeshoptimizer. Works on the
// document, before any accessor is read, so every reader of the document sees plain buffer views.
//
// Read in two steps around tinygltf's parse. First, from the JSON (exact 64-bit numbers: tinygltf
// keeps an extension's numbers as int), the compressed views with every rule of the extension's
// "JSON schema updates" checked, and the fallback buffers: a buffer with no uri that is not a .glb's
// binary chunk holds no bytes in the file (EXT_meshopt_compression README, "Fallback buffers"), which
// tinygltf 2.7 refuses; each is given to tinygltf as a 4-byte data: URI and sized after the parse.
// Second, after the parse, the views are decoded into their buffers.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>
#include <tiny_gltf.h>

namespace svbrdf::gltf {

struct MeshoptView {
  int view = -1;  // the bufferViews index
  int source_buffer = -1;
  std::uint64_t source_offset = 0, source_length = 0;
  std::uint64_t stride = 0, count = 0;
  enum class Mode { attributes, triangles, indices } mode = Mode::attributes;
  enum class Filter { none, octahedral, quaternion, exponential } filter = Filter::none;
};

struct MeshoptPlan {
  std::vector<MeshoptView> views;
  std::vector<std::pair<int, std::uint64_t>> fallback_buffers;  // buffer index, byteLength
  bool empty() const { return views.empty() && fallback_buffers.empty(); }
};

// Reads the compressed views and fallback buffers of `document` (the whole glTF JSON), and rewrites
// each fallback buffer in it as a small data: URI for tinygltf. `binary`: the file is a .glb, whose
// buffer 0 without uri is its binary chunk. Throws the input error "FILE: JSON path: what".
MeshoptPlan plan_meshopt(nlohmann::json& document, bool binary, const std::filesystem::path& file);

// After tinygltf's parse: sizes each fallback buffer to its byteLength and decodes every compressed
// view into its place. Throws the input error "FILE: bufferViews[i].extensions.EXT_meshopt_compression:
// what" for data that does not decode.
void decode_meshopt(const MeshoptPlan& plan, tinygltf::Model& model, const std::filesystem::path& file);

}  // namespace svbrdf::gltf
