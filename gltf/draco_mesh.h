#pragma once
// The Draco decoder behind an interface of plain types, built as the shared library svbrdf_draco
// with every symbol of Debian's libdraco kept inside it: that library exports its own copy of
// tinygltf and stb, which must never meet the reader's (cmake/Dependencies.cmake). Nothing here
// knows glTF; gltf/draco_decode.h checks the result against the primitive's accessors.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace svbrdf::gltf {

// One attribute asked for: its Draco unique id and the components per point the glTF accessor has.
struct DracoRequest {
  std::uint32_t unique_id = 0;
  int components = 0;
};

struct DracoMesh {
  std::size_t points = 0;
  std::vector<std::uint32_t> indices;      // three per triangle, each checked below `points`
  std::vector<std::vector<float>> values;  // per request: points × components, normalized integers mapped
                                           // to [0, 1] / [−1, 1]
};

struct DracoOutcome {
  std::string error;   // empty: decoded
  int request = -1;    // the request the error is about, −1: the data as a whole
};

// Decodes the Draco triangle mesh in `data` (`size` bytes) and the attributes `requests` name.
__attribute__((visibility("default"))) DracoOutcome decode_draco_mesh(const unsigned char* data, std::size_t size,
                                                                      const std::vector<DracoRequest>& requests,
                                                                      DracoMesh& out);

}  // namespace svbrdf::gltf
