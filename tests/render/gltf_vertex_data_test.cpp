// The data a primitive draws, held to what glTF 2.0 requires of it: values that would be drawn
// wrongly as given (NaN, a vertex outside the bounds its accessor states, a color past 1, the
// primitive restart index, a stride no view may have) are refused with the JSON path; data within
// the rules load. Each case breaks the small quad of gltf_test_files.h in one way.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "base/error.h"
#include "gltf/scene_reader.h"
#include "gltf_test_files.h"

namespace svbrdf {
namespace {

using test::GltfQuad;
using test::TempDir;

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const std::size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

// The quad's POSITION accessor with `members` added.
std::string with_position_members(const GltfQuad& q, const std::string& members) {
  return replaced(q.json(), R"("count": 4, "type": "VEC3"})", R"("count": 4, "type": "VEC3", )" + members + "}");
}

void expect_refused(const std::string& json, const std::string& expect) {
  TempDir dir;
  try {
    load_gltf(dir.write("q.gltf", json));
    ADD_FAILURE() << "loaded; expected a refusal naming " << expect;
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), Error::Kind::bad_input);
    EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
  }
}

// One test, not one per case: each test is a process that loads the suite's libraries (about a
// second), and these cases take milliseconds.
TEST(GltfVertexData, DataWithinTheRulesLoadsAndDataAgainstThemIsRefused) {
  TempDir dir;
  // Within the rules: positions inside their stated bounds; COLOR_0 (float VEC3, here the positions'
  // accessor: the quad's corners) within [0, 1].
  EXPECT_NO_THROW(load_gltf(dir.write("b.gltf", with_position_members(GltfQuad(), R"("min": [0, 0, 0], "max": [1, 1, 0])"))));
  GltfQuad colored;
  EXPECT_NO_THROW(load_gltf(dir.write("c.gltf", replaced(colored.json(), R"({"POSITION": 0})", R"({"POSITION": 0, "COLOR_0": 0})"))));

  // Vertex 1 is (1, 0, 0); the accessor says x never exceeds 0.5.
  expect_refused(with_position_members(GltfQuad(), R"("min": [0, 0, 0], "max": [0.5, 1, 0])"),
                 "attributes.POSITION: accessors[0] element 1 component 0 is 1, outside the accessor's min 0 and max 0.5");
  GltfQuad nan_uv;
  nan_uv.texcoords = {0, 0, 1, 0, std::numeric_limits<float>::quiet_NaN(), 1, 0, 1};
  expect_refused(nan_uv.json(), "attributes.TEXCOORD_0: accessors[2] element 2 is not finite");
  GltfQuad restart;
  restart.indices = {0, 1, 2, 0, 2, 65535};
  expect_refused(restart.json(), "meshes[0].primitives[0].indices: accessors[1] element 5 is 65535, the primitive restart value");
  expect_refused(replaced(GltfQuad().json(), R"("byteOffset": 0, "byteLength": 48})",
                          R"("byteOffset": 0, "byteLength": 48, "byteStride": 256})"),
                 "bufferViews[0].byteStride: is 256");
  expect_refused(replaced(GltfQuad().json(), R"("byteOffset": 48, "byteLength": 12})",
                          R"("byteOffset": 48, "byteLength": 12, "byteStride": 4})"),
                 "indices: accessors[1] reads bufferViews[1], which has a byteStride");
  expect_refused(with_position_members(GltfQuad(), R"("normalized": true)"),
                 "accessors[0] is normalized, which a FLOAT or UNSIGNED_INT accessor must not be");
  colored.positions[6] = 1.5f;  // vertex 2's x, and so its red
  expect_refused(replaced(colored.json(), R"({"POSITION": 0})", R"({"POSITION": 0, "COLOR_0": 0})"),
                 "attributes.COLOR_0: vertex 2 has a color component of 1.5");
}

}  // namespace
}  // namespace svbrdf
