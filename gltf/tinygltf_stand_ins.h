#pragma once
// What Debian's tinygltf 2.7 refuses of valid glTF 2.0, and how the document gets past it without a
// second reader: tinygltf parses a copy of the JSON in which each such part has a stand-in it
// accepts, and the model it returns is put back to what the file says.
// - A buffer with no uri that is not a .glb's binary chunk (glTF 2.0 §5.10: uri is optional), and a
//   buffer whose uri names no local file (a URL with a scheme: nothing is fetched from a network):
//   tinygltf refuses the first and tries to open the second as a file. The stand-in is a 4-byte
//   data: URI; after the parse the buffer holds no bytes, so a view that reads it is refused as a
//   short buffer, and one nothing reads costs nothing.
// - A data: URI whose media type tinygltf does not know (image/webp, EXT_texture_webp) or that is not
//   base64 (RFC 2397 allows percent-encoded bytes): decoded here and given as base64 octet-stream.
// - A primitive's indices accessor without a bufferView (zeros, §3.6.2.2, possibly with sparse
//   values): tinygltf requires a view. The primitive is given without indices and they are put back.
// - An integer written as a float with no fraction ("byteLength": 4.0; JSON has one number type, and
//   the validator accepts it): tinygltf refuses it; given as the integer.
// - An accessor type outside glTF's seven (the validator warns, VALUE_NOT_IN_LIST; tinygltf refuses
//   the file even when nothing uses the accessor): given as SCALAR; after the parse its type is -1,
//   so reading it is refused and leaving it unused is not.
// KHR_draco_mesh_compression's and EXT_meshopt_compression's own stand-ins are their modules'.
#include <array>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>
#include <tiny_gltf.h>

namespace svbrdf::gltf {

struct StandIns {
  std::vector<std::pair<int, std::string>> empty_buffers;  // buffers given a placeholder uri, and their own
  std::vector<std::array<int, 3>> removed_indices;  // mesh, primitive, accessor
  std::vector<int> unknown_types;                   // accessors given as SCALAR
  bool rewritten = false;                           // whether the JSON was changed at all
};

// Rewrites `document` (the whole glTF JSON) in place. `binary`: the file is a .glb, whose buffer 0
// without a uri is its binary chunk.
StandIns lend_stand_ins(nlohmann::json& document, bool binary);

// After tinygltf's parse: the model as the file states it.
void return_stand_ins(const StandIns& lent, tinygltf::Model& model);

}  // namespace svbrdf::gltf
