#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>

#include "base/error.h"
#include "gltf/scene_reader.h"
#include "textures/image.h"
#include "gltf_samples.h"
#include "gltf_test_files.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;
using test::GltfQuad;
using test::TempDir;

using test::kSamples;
using test::SampleCounts;
using test::samples_dir;

// Loading must throw svbrdf::Error (bad input) whose one-line message names `what`.
void expect_error(const fs::path& file, const std::string& what) {
  try {
    load_gltf(file);
    ADD_FAILURE() << file << " loaded; expected an error naming " << what;
  } catch (const Error& e) {
    const std::string msg = e.what();
    if (std::getenv("SVBRDF_PRINT_ERRORS")) std::printf("%s\n", msg.c_str());  // to read them all at once
    EXPECT_EQ(e.exit_code(), 2) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << "message: " << msg << "\nexpected it to name: " << what;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line: " << msg;
    EXPECT_NE(msg.find(file.filename().string()), std::string::npos) << "names the file: " << msg;
  }
}

// ---- the sample models ---------------------------------------------------------------------------

class GltfSample : public ::testing::TestWithParam<SampleCounts> {};

TEST_P(GltfSample, LoadsWithItsCounts) {
  const SampleCounts& c = GetParam();
  const fs::path file = samples_dir() / c.file;
  if (!fs::exists(samples_dir())) GTEST_SKIP() << "no glTF samples at " << samples_dir() << " (../shared absent)";
  ASSERT_TRUE(fs::exists(file)) << file;
  const Scene s = load_gltf(file);
  EXPECT_EQ(s.meshes.size(), c.meshes);
  std::size_t prims = 0, tris = 0;
  for (const Mesh& m : s.meshes) {
    prims += m.primitives.size();
    for (const MeshPrimitive& p : m.primitives) {
      tris += p.triangle_count();
      EXPECT_EQ(p.normals.size(), p.positions.size()) << p.where;
      const MaterialDesc& mat = s.material_of(p);
      if (mat.normal_texture.present()) {
        EXPECT_EQ(p.tangents.size(), p.positions.size()) << p.where;
      }
    }
  }
  EXPECT_EQ(prims, c.primitives);
  EXPECT_EQ(tris, c.triangles);
  EXPECT_EQ(s.materials.size(), c.materials);
  EXPECT_EQ(s.textures.size(), c.textures);
  ASSERT_EQ(s.images.size(), c.images);
  // tinygltf reports success for missing external images; every image must really have decoded.
  for (const ImageDesc& im : s.images) {
    EXPECT_GT(im.pixels.width, 0) << im.where;
    EXPECT_GT(im.pixels.height, 0) << im.where;
    EXPECT_EQ(im.pixels.pixels.size(), std::size_t(im.pixels.width) * im.pixels.height * im.pixels.channels);
  }
  EXPECT_EQ(s.instances.size(), c.instances);
  EXPECT_EQ(s.cameras.size(), c.cameras);
  EXPECT_EQ(s.lights.size(), c.lights);
}

INSTANTIATE_TEST_SUITE_P(Samples, GltfSample, ::testing::ValuesIn(kSamples),
                         [](const ::testing::TestParamInfo<SampleCounts>& info) {
                           std::string n = info.param.file;
                           n = n.substr(0, n.find('/')) + (n.find(".glb") != std::string::npos ? "Glb" : "Gltf");
                           return n;
                         });

// TextureTransformMultiTest requires KHR_texture_transform and uses KHR_materials_clearcoat with
// transformed textures on both TEXCOORD sets: it loads without a warning, and each coat texture
// keeps its set and its transform.
TEST(GltfLoader, TextureTransformMultiTestReadsItsClearcoats) {
  const fs::path f = samples_dir() / "TextureTransformMultiTest/glTF/TextureTransformMultiTest.gltf";
  if (!fs::exists(f)) GTEST_SKIP() << "no glTF samples at " << samples_dir();
  const Scene s = load_gltf(f);
  for (const auto& w : s.warnings) ADD_FAILURE() << "warning: " << w;
  auto named = [&](const std::string& n) -> const MaterialDesc& {
    for (const MaterialDesc& m : s.materials)
      if (m.name == n) return m;
    throw std::runtime_error("no material " + n);
  };
  const MaterialDesc& t0 = named("ClearcoatTest0Mat");
  EXPECT_FLOAT_EQ(t0.clearcoat, 1.0f);
  EXPECT_NEAR(t0.clearcoat_roughness, 0.03f, 1e-6);
  ASSERT_TRUE(t0.clearcoat_texture.present());
  EXPECT_EQ(t0.clearcoat_texture.uv_set(), 0);
  // The file's transform: scale 0.35, rotation 90°, offset (0.705, 0.285): (1, 0) → (0.705, −0.065).
  const glm::vec2 t = t0.clearcoat_texture.transform.apply({1.0f, 0.0f});
  EXPECT_NEAR(t.x, 0.705f, 1e-5);
  EXPECT_NEAR(t.y, 0.285f - 0.35f, 1e-5);
  EXPECT_EQ(named("ClearcoatTest1Mat").clearcoat_texture.uv_set(), 1);
  EXPECT_TRUE(named("ClearcoatRoughTest0Mat").clearcoat_roughness_texture.present());
  EXPECT_TRUE(named("ClearcoatNormalTest1Mat").clearcoat_normal_texture.present());
  EXPECT_EQ(named("ClearcoatNormalTest1Mat").clearcoat_normal_texture.uv_set(), 1);
}

// ---- files the tests write -------------------------------------------------------------------

TEST(GltfLoader, ReadsAQuad) {
  TempDir dir;
  GltfQuad q;
  const Scene s = load_gltf(dir.write("quad.gltf", q.json()));
  ASSERT_EQ(s.meshes.size(), 1u);
  const MeshPrimitive& p = s.meshes[0].primitives.at(0);
  EXPECT_EQ(p.triangle_count(), 2u);
  ASSERT_EQ(s.instances.size(), 1u);
  EXPECT_EQ(s.material_of(p).where, "the default material");
  // No NORMAL: flat normals, the face normal (p1 − p0) × (p2 − p0) of the counter-clockwise quad = +z.
  for (const auto& n : p.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
  EXPECT_EQ(p.positions.size(), 6u) << "flat normals unweld the vertices";
  EXPECT_TRUE(s.warnings.empty());
}

TEST(GltfLoader, MissingBufferFile) {
  TempDir dir;
  GltfQuad q;
  q.buffer_uri = "missing.bin";
  expect_error(dir.write("m.gltf", q.json()), "missing.bin");
}

TEST(GltfLoader, ShortExternalBuffer) {
  TempDir dir;
  GltfQuad q;
  std::vector<unsigned char> b = q.bytes();
  b.resize(20);  // declared 60 bytes
  dir.write_bytes("short.bin", b);
  q.buffer_uri = "short.bin";
  q.buffer_length = long(q.bytes().size());
  expect_error(dir.write("s.gltf", q.json()), "short.bin");
}

TEST(GltfLoader, ShortEmbeddedBuffer) {
  TempDir dir;
  GltfQuad q;
  q.buffer_length = 4000;  // the data URI holds 60 bytes
  expect_error(dir.write("s.gltf", q.json()), "s.gltf");
}

TEST(GltfLoader, AccessorPastItsBufferView) {
  TempDir dir;
  GltfQuad q;
  q.position_count = 400;
  expect_error(dir.write("a.gltf", q.json()), "meshes[0].primitives[0].attributes.POSITION");
}

TEST(GltfLoader, AccessorIndexOutOfRange) {
  TempDir dir;
  GltfQuad q;
  q.position_accessor = "7";
  expect_error(dir.write("a.gltf", q.json()), "meshes[0].primitives[0].attributes.POSITION: names accessors[7]");
}

TEST(GltfLoader, IndicesPastVertexCount) {
  TempDir dir;
  GltfQuad q;
  q.indices = {0, 1, 2, 0, 2, 9};
  expect_error(dir.write("i.gltf", q.json()), "meshes[0].primitives[0].indices");
}

TEST(GltfLoader, NaNPosition) {
  TempDir dir;
  GltfQuad q;
  q.positions[4] = std::numeric_limits<float>::quiet_NaN();
  expect_error(dir.write("n.gltf", q.json()), "meshes[0].primitives[0].attributes.POSITION: accessors[0] element 1 is not finite");
}

// glTF 2.0 §3.7.2.1: triangle i is vertices 3i, 3i+1, 3i+2; a vertex past the last whole triangle
// belongs to none (the validator only warns).
TEST(GltfLoader, IndicesPastTheLastWholeTriangleBelongToNone) {
  TempDir dir;
  GltfQuad q;
  q.indices = {0, 1, 2, 0};
  const Scene s = load_gltf(dir.write("t.gltf", q.json()));
  EXPECT_EQ(s.meshes[0].primitives[0].triangle_count(), 1u);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("meshes[0].primitives[0]: 4 vertices"), std::string::npos) << s.warnings[0];
}

// Zero-area triangles are legal glTF: they load (and render as nothing) with one warning.
TEST(GltfLoader, ZeroAreaTrianglesLoadWithAWarning) {
  TempDir dir;
  GltfQuad q;
  q.indices = {0, 1, 2, 0, 0, 3, 1, 1, 1};
  const Scene s = load_gltf(dir.write("z.gltf", q.json()));
  EXPECT_EQ(s.meshes[0].primitives[0].triangle_count(), 3u);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("2 zero-area triangles"), std::string::npos) << s.warnings[0];
}

TEST(GltfLoader, MaterialIndexOutOfRange) {
  TempDir dir;
  GltfQuad q;
  q.primitive_extra = R"(, "material": 3)";
  expect_error(dir.write("m.gltf", q.json()), "meshes[0].primitives[0].material: names materials[3]");
}

TEST(GltfLoader, TextureSourceOutOfRange) {
  TempDir dir;
  GltfQuad q;
  q.texcoords = {0, 0, 1, 0, 1, 1, 0, 1};
  q.materials = R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])";
  q.primitive_extra = R"(, "material": 0)";
  q.top_extra = R"(, "textures": [{"source": 3}])";
  expect_error(dir.write("t.gltf", q.json()), "textures[0].source: names images[3]");
}

TEST(GltfLoader, MaterialTextureIndexOutOfRange) {
  TempDir dir;
  GltfQuad q;
  q.texcoords = {0, 0, 1, 0, 1, 1, 0, 1};
  q.materials = R"([{"normalTexture": {"index": 2}}])";
  q.primitive_extra = R"(, "material": 0)";
  expect_error(dir.write("t.gltf", q.json()), "materials[0].normalTexture.index: names textures[2]");
}

TEST(GltfLoader, MissingImageFile) {
  TempDir dir;
  GltfQuad q;
  q.top_extra = R"(, "images": [{"uri": "nowhere.png"}])";
  expect_error(dir.write("i.gltf", q.json()), "images[0]: cannot read the image file 'nowhere.png'");
}

TEST(GltfLoader, CorruptImage) {
  TempDir dir;
  dir.write("bad.png", "this is not a PNG file at all");
  GltfQuad q;
  q.top_extra = R"(, "images": [{"uri": "bad.png"}], "textures": [{"source": 0}])";
  expect_error(dir.write("i.gltf", q.json()), "images[0]");
}

TEST(GltfLoader, NodeCycle) {
  TempDir dir;
  GltfQuad q;
  q.nodes = R"([{"mesh": 0, "children": [1]}, {"children": [2]}, {"children": [0]}])";
  expect_error(dir.write("c.gltf", q.json()), "cycle");
}

TEST(GltfLoader, NodeWithTwoParents) {
  TempDir dir;
  GltfQuad q;
  q.nodes = R"([{"children": [2]}, {"children": [2]}, {"mesh": 0}])";
  q.scene_nodes = "[0, 1]";
  expect_error(dir.write("p.gltf", q.json()), "nodes[1].children: names nodes[2]");
}

TEST(GltfLoader, ChildIndexOutOfRange) {
  TempDir dir;
  GltfQuad q;
  q.nodes = R"([{"mesh": 0, "children": [5]}])";
  expect_error(dir.write("c.gltf", q.json()), "nodes[0].children[0]: names nodes[5]");
}

TEST(GltfLoader, UnsupportedRequiredExtension) {
  TempDir dir;
  GltfQuad q;
  q.top_extra = R"(, "extensionsUsed": ["KHR_texture_basisu"], "extensionsRequired": ["KHR_texture_basisu"])";
  expect_error(dir.write("e.gltf", q.json()), "KHR_texture_basisu");
}

TEST(GltfLoader, UnsupportedOptionalExtensionWarnsOnce) {
  TempDir dir;
  GltfQuad q;
  q.top_extra = R"(, "extensionsUsed": ["EXT_lights_image_based", "KHR_texture_transform"])";
  const Scene s = load_gltf(dir.write("e.gltf", q.json()));
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("EXT_lights_image_based"), std::string::npos);
}

// An optional extension on materials that the project does not read: one warning per material,
// naming the material and the extension, instead of one for the file.
TEST(GltfLoader, UnsupportedMaterialExtensionWarnsOncePerMaterial) {
  TempDir dir;
  GltfQuad q;
  q.materials = R"([{"name": "Skin", "extensions": {"KHR_materials_subsurface_x": {}}},
                    {"name": "Cloth", "extensions": {"KHR_materials_subsurface_x": {}, "KHR_materials_sheen": {}}},
                    {"name": "Plain"}])";
  q.primitive_extra = R"(, "material": 0)";
  q.top_extra = R"(, "extensionsUsed": ["KHR_materials_subsurface_x", "KHR_materials_sheen"])";
  const Scene s = load_gltf(dir.write("e.gltf", q.json()));
  ASSERT_EQ(s.warnings.size(), 2u);
  EXPECT_NE(s.warnings[0].find("materials[0] 'Skin'"), std::string::npos) << s.warnings[0];
  EXPECT_NE(s.warnings[1].find("materials[1] 'Cloth'"), std::string::npos) << s.warnings[1];
  for (const auto& w : s.warnings) EXPECT_NE(w.find("KHR_materials_subsurface_x"), std::string::npos) << w;
}

TEST(GltfLoader, BadAlphaMode) {
  TempDir dir;
  GltfQuad q;
  q.materials = R"([{"alphaMode": "SOMETIMES"}])";
  q.primitive_extra = R"(, "material": 0)";
  expect_error(dir.write("a.gltf", q.json()), "materials[0].alphaMode");
}

TEST(GltfLoader, NotJson) {
  TempDir dir;
  expect_error(dir.write("x.gltf", "{ this is not json"), "x.gltf");
}

TEST(GltfLoader, MissingFile) { expect_error("/nonexistent/dir/none.gltf", "none.gltf"); }

TEST(GltfLoader, GlbWithShortBinChunk) {
  TempDir dir;
  GltfQuad q;
  std::string json = q.json();
  // The JSON's buffer becomes the GLB's BIN chunk, which is cut short.
  const auto a = json.find("\"uri\": \""), b = json.find('"', a + 8);
  json.erase(a, b - a + 3);
  std::vector<unsigned char> bin = q.bytes();
  bin.resize(16);
  expect_error(dir.write_bytes("short.glb", test::make_glb(json, bin)), "short.glb");
}

// An image in a buffer view that reaches past the buffer: tinygltf 2.7 would hand over bytes past
// the end; the loader refuses before reading them.
TEST(GltfLoader, ImageBufferViewPastTheBuffer) {
  TempDir dir;
  GltfQuad q;
  std::string json = q.json();
  const auto a = json.find("\"uri\": \""), b = json.find('"', a + 8);
  json.erase(a, b - a + 3);
  json.replace(json.find("], \"accessors\""), 1, ", {\"buffer\": 0, \"byteOffset\": 40, \"byteLength\": 5000}]");
  json.pop_back();
  json += R"(, "images": [{"bufferView": 2, "mimeType": "image/png"}]})";
  expect_error(dir.write_bytes("img.glb", test::make_glb(json, q.bytes())), "bufferViews[2]");
}

TEST(GltfLoader, GlbRoundTrip) {
  TempDir dir;
  GltfQuad q;
  std::string json = q.json();
  const auto a = json.find("\"uri\": \""), b = json.find('"', a + 8);
  json.erase(a, b - a + 3);
  const Scene s = load_gltf(dir.write_bytes("ok.glb", test::make_glb(json, q.bytes())));
  EXPECT_EQ(s.meshes.at(0).primitives.at(0).triangle_count(), 2u);
  EXPECT_EQ(s.meshes[0].primitives[0].positions[2], glm::vec3(1, 1, 0));
}

// ---- attribute decoding --------------------------------------------------------------------

// Normalized integer texcoords (glTF §3.11): unsigned byte c → c/255, signed short c → max(c/32767, −1).
TEST(GltfLoader, NormalizedIntegerAttributes) {
  TempDir dir;
  GltfQuad q;
  std::vector<unsigned char> bin = q.bytes();
  const std::size_t uv_off = bin.size();
  const unsigned char uv8[8] = {0, 255, 51, 102, 255, 0, 128, 64};
  bin.insert(bin.end(), uv8, uv8 + 8);
  const std::size_t col_off = bin.size();
  const std::int16_t col[16] = {32767, -32768, 0, 16384, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  test::append_bytes(bin, std::vector<std::int16_t>(col, col + 16));
  std::string json = q.json();
  const std::string uri = "data:application/octet-stream;base64," + test::base64(bin);
  const auto a = json.find("data:"), b = json.find('"', a);
  json.replace(a, b - a, uri);
  const auto bl = json.find("\"byteLength\": ") + 14, ble = json.find('}', bl);
  json.replace(bl, ble - bl, std::to_string(bin.size()));
  json.replace(json.find("\"POSITION\": 0"), 13, "\"POSITION\": 0, \"TEXCOORD_0\": 2, \"TANGENT\": 3");
  json.replace(json.rfind("]"), 1,
               ", {\"bufferView\": 2, \"componentType\": 5121, \"normalized\": true, \"count\": 4, \"type\": \"VEC2\"}"
               ", {\"bufferView\": 3, \"componentType\": 5122, \"normalized\": true, \"count\": 4, \"type\": \"VEC4\"}]");
  json.replace(json.find("], \"accessors\""), 1,
               ", {\"buffer\": 0, \"byteOffset\": " + std::to_string(uv_off) + ", \"byteLength\": 8}" +
                   ", {\"buffer\": 0, \"byteOffset\": " + std::to_string(col_off) + ", \"byteLength\": 32}]");
  const Scene s = load_gltf(dir.write("n.gltf", json));
  const MeshPrimitive& p = s.meshes[0].primitives[0];
  // Flat normals unweld: triangle 0 is vertices 0, 1, 2.
  ASSERT_EQ(p.texcoords[0].size(), 6u);
  EXPECT_FLOAT_EQ(p.texcoords[0][0].x, 0.0f);
  EXPECT_FLOAT_EQ(p.texcoords[0][0].y, 1.0f);
  EXPECT_FLOAT_EQ(p.texcoords[0][1].x, 0.2f);
  EXPECT_FLOAT_EQ(p.texcoords[0][1].y, 0.4f);
  // A signed normalized attribute (KHR_mesh_quantization allows SHORT for TANGENT; COLOR_0 is unsigned).
  ASSERT_EQ(p.tangents.size(), 6u);
  EXPECT_FLOAT_EQ(p.tangents[0].x, 1.0f);
  EXPECT_FLOAT_EQ(p.tangents[0].y, -1.0f) << "−32768 clamps to −1";
  EXPECT_FLOAT_EQ(p.tangents[0].w, 16384.0f / 32767.0f);
}

// Sparse accessors (glTF §3.6.2.3): an accessor with no buffer view is zeros, then substituted.
TEST(GltfLoader, SparseAccessor) {
  TempDir dir;
  GltfQuad q;
  std::vector<unsigned char> bin = q.bytes();
  const std::size_t off = bin.size();
  const std::uint8_t sidx[4] = {2, 0, 0, 0};  // index 2, padded
  bin.insert(bin.end(), sidx, sidx + 4);
  const float sval[3] = {5, 6, 7};
  test::append_bytes(bin, std::vector<float>(sval, sval + 3));
  std::string json = q.json();
  const auto a = json.find("data:"), b = json.find('"', a);
  json.replace(a, b - a, "data:application/octet-stream;base64," + test::base64(bin));
  const auto bl = json.find("\"byteLength\": ") + 14, ble = json.find('}', bl);
  json.replace(bl, ble - bl, std::to_string(bin.size()));
  json.replace(json.find("], \"accessors\""), 1,
               ", {\"buffer\": 0, \"byteOffset\": " + std::to_string(off) + ", \"byteLength\": 16}]");
  const std::string dense = "{\"bufferView\": 0, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\"}";
  json.replace(json.find(dense), dense.size(),
               "{\"bufferView\": 0, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\", \"sparse\": {\"count\": 1, "
               "\"indices\": {\"bufferView\": 2, \"componentType\": 5121}, \"values\": {\"bufferView\": 2, \"byteOffset\": 4}}}");
  const Scene s = load_gltf(dir.write("s.gltf", json));
  EXPECT_EQ(s.meshes[0].primitives[0].positions[2], glm::vec3(5, 6, 7));
  EXPECT_EQ(s.meshes[0].primitives[0].positions[1], glm::vec3(1, 0, 0));
}

// Node transforms: a child's world matrix is parent · child; TRS is T · R · S (glTF §3.5.2).
TEST(GltfLoader, NodeTransforms) {
  TempDir dir;
  GltfQuad q;
  // Parent: translation (1, 2, 3). Child: rotation of 90° about z, scale 2, as TRS.
  q.nodes = R"([{"translation": [1, 2, 3], "children": [1]},
                {"mesh": 0, "rotation": [0, 0, 0.7071067811865476, 0.7071067811865476], "scale": [2, 2, 2]},
                {"mesh": 0, "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 4,5,6,1]}])";
  q.scene_nodes = "[0, 2]";
  const Scene s = load_gltf(dir.write("t.gltf", q.json()));
  ASSERT_EQ(s.instances.size(), 2u);
  // (1, 0, 0) → scale (2, 0, 0) → rotate 90° about z (0, 2, 0) → translate (1, 4, 3).
  const glm::dvec4 p = s.instances[0].to_world * glm::dvec4(1, 0, 0, 1);
  EXPECT_NEAR(p.x, 1.0, 1e-12);
  EXPECT_NEAR(p.y, 4.0, 1e-12);
  EXPECT_NEAR(p.z, 3.0, 1e-12);
  const glm::dvec4 m = s.instances[1].to_world * glm::dvec4(0, 0, 0, 1);
  EXPECT_EQ(glm::dvec3(m), glm::dvec3(4, 5, 6)) << "matrix is column-major";
}

TEST(GltfLoader, TriangleStripAndFan) {
  TempDir dir;
  GltfQuad q;
  q.indices = {0, 1, 3, 2};
  q.primitive_extra = R"(, "mode": 5)";
  const Scene strip = load_gltf(dir.write("s.gltf", q.json()));
  ASSERT_EQ(strip.meshes[0].primitives[0].triangle_count(), 2u);
  // Both triangles keep the strip's winding: flat normals all +z.
  for (const auto& n : strip.meshes[0].primitives[0].normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
  q.indices = {0, 1, 2, 3};
  q.primitive_extra = R"(, "mode": 6)";
  const Scene fan = load_gltf(dir.write("f.gltf", q.json()));
  ASSERT_EQ(fan.meshes[0].primitives[0].triangle_count(), 2u);
  for (const auto& n : fan.meshes[0].primitives[0].normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
}

TEST(GltfLoader, MaterialExtensionsAndTextureTransform) {
  TempDir dir;
  GltfQuad q;
  q.texcoords = {0, 0, 1, 0, 1, 1, 0, 1};
  Image px(1, 1, 3);
  write_image(dir.path() / "px.png", px, PixelFormat::uint8);
  q.materials = R"([{"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 1, 0.75], "metallicFactor": 0.2,
     "roughnessFactor": 0.3, "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform":
     {"offset": [0.5, 0.25], "rotation": 1.5707963267948966, "scale": [2, 3], "texCoord": 0}}}},
     "alphaMode": "MASK", "alphaCutoff": 0.4, "doubleSided": true, "emissiveFactor": [1, 0.5, 0],
     "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 5}, "KHR_materials_ior": {"ior": 1.33},
       "KHR_materials_specular": {"specularFactor": 0.5, "specularColorFactor": [1, 0.5, 0.25]},
       "KHR_materials_transmission": {"transmissionFactor": 0.9},
       "KHR_materials_diffuse_roughness": {"diffuseRoughnessFactor": 0.7}, "KHR_materials_unlit": {}}}])";
  q.primitive_extra = R"(, "material": 0)";
  q.top_extra = R"(, "textures": [{"source": 0}], "images": [{"uri": "px.png"}])";
  const Scene s = load_gltf(dir.write("m.gltf", q.json()));
  ASSERT_EQ(s.materials.size(), 1u);
  const MaterialDesc& m = s.materials[0];
  EXPECT_EQ(m.base_color, Rgb(0.5f, 0.25f, 1.0f));
  EXPECT_FLOAT_EQ(m.base_alpha, 0.75f);
  EXPECT_FLOAT_EQ(m.metallic, 0.2f);
  EXPECT_FLOAT_EQ(m.roughness, 0.3f);
  EXPECT_EQ(m.alpha_mode, AlphaMode::mask);
  EXPECT_FLOAT_EQ(m.alpha_cutoff, 0.4f);
  EXPECT_TRUE(m.double_sided);
  EXPECT_FLOAT_EQ(m.emissive_strength, 5.0f);
  EXPECT_FLOAT_EQ(m.ior, 1.33f);
  EXPECT_FLOAT_EQ(m.specular, 0.5f);
  EXPECT_EQ(m.specular_color, Rgb(1.0f, 0.5f, 0.25f));
  EXPECT_FLOAT_EQ(m.transmission, 0.9f);
  EXPECT_FLOAT_EQ(m.diffuse_roughness, 0.7f);
  EXPECT_TRUE(m.unlit);
  ASSERT_TRUE(m.base_color_texture.present());
  // uv (1, 0): scale → (2, 0); rotation 90° (u' = cos·u + sin·v, v' = −sin·u + cos·v) → (0, −2);
  // offset → (0.5, −1.75).
  const glm::vec2 t = m.base_color_texture.transform.apply({1.0f, 0.0f});
  EXPECT_NEAR(t.x, 0.5f, 1e-6);
  EXPECT_NEAR(t.y, -1.75f, 1e-6);
  ASSERT_EQ(s.images.size(), 1u);
  EXPECT_EQ(s.images[0].pixels.width, 1);
}

TEST(GltfLoader, ReadsTheLayerExtensions) {
  TempDir dir;
  GltfQuad q;
  q.texcoords = {0, 0, 1, 0, 1, 1, 0, 1};
  Image px(1, 1, 4);
  write_image(dir.path() / "px.png", px, PixelFormat::uint8);
  q.materials = R"([{"extensions": {
       "KHR_materials_clearcoat": {"clearcoatFactor": 0.7, "clearcoatRoughnessFactor": 0.2,
         "clearcoatTexture": {"index": 0}, "clearcoatNormalTexture": {"index": 0, "scale": 0.5}},
       "KHR_materials_anisotropy": {"anisotropyStrength": 0.6, "anisotropyRotation": 1.25,
         "anisotropyTexture": {"index": 0}},
       "KHR_materials_sheen": {"sheenColorFactor": [0.5, 0.25, 1], "sheenRoughnessFactor": 0.3,
         "sheenRoughnessTexture": {"index": 0}},
       "KHR_materials_iridescence": {"iridescenceFactor": 0.8, "iridescenceIor": 1.4,
         "iridescenceThicknessMinimum": 50, "iridescenceThicknessMaximum": 600,
         "iridescenceThicknessTexture": {"index": 0}},
       "KHR_materials_volume": {"thicknessFactor": 0.02, "attenuationDistance": 0.5,
         "attenuationColor": [0.9, 0.5, 0.25]},
       "KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 0.35,
         "diffuseTransmissionColorFactor": [1, 0.5, 0], "diffuseTransmissionTexture": {"index": 0}}}},
     {"extensions": {"KHR_materials_clearcoat": {}, "KHR_materials_anisotropy": {}, "KHR_materials_sheen": {},
       "KHR_materials_iridescence": {}, "KHR_materials_volume": {}, "KHR_materials_diffuse_transmission": {}}}])";
  q.primitive_extra = R"(, "material": 0)";
  q.top_extra = R"(, "textures": [{"source": 0}], "images": [{"uri": "px.png"}],
      "extensionsUsed": ["KHR_materials_clearcoat", "KHR_materials_anisotropy", "KHR_materials_sheen",
                         "KHR_materials_iridescence", "KHR_materials_volume", "KHR_materials_diffuse_transmission"])";
  const Scene s = load_gltf(dir.write("m.gltf", q.json()));
  EXPECT_TRUE(s.warnings.empty());
  ASSERT_EQ(s.materials.size(), 2u);
  const MaterialDesc& m = s.materials[0];
  EXPECT_FLOAT_EQ(m.clearcoat, 0.7f);
  EXPECT_FLOAT_EQ(m.clearcoat_roughness, 0.2f);
  EXPECT_TRUE(m.clearcoat_texture.present());
  EXPECT_FALSE(m.clearcoat_roughness_texture.present());
  EXPECT_FLOAT_EQ(m.clearcoat_normal_texture.scale, 0.5f);
  EXPECT_FLOAT_EQ(m.anisotropy_strength, 0.6f);
  EXPECT_FLOAT_EQ(m.anisotropy_rotation, 1.25f);
  EXPECT_TRUE(m.anisotropy_texture.present());
  EXPECT_EQ(m.sheen_color, Rgb(0.5f, 0.25f, 1.0f));
  EXPECT_FLOAT_EQ(m.sheen_roughness, 0.3f);
  EXPECT_TRUE(m.sheen_roughness_texture.present());
  EXPECT_FALSE(m.sheen_color_texture.present());
  EXPECT_FLOAT_EQ(m.iridescence, 0.8f);
  EXPECT_FLOAT_EQ(m.iridescence_ior, 1.4f);
  EXPECT_FLOAT_EQ(m.iridescence_thickness_min, 50.0f);
  EXPECT_FLOAT_EQ(m.iridescence_thickness_max, 600.0f);
  EXPECT_TRUE(m.iridescence_thickness_texture.present());
  EXPECT_TRUE(m.has_volume());
  EXPECT_FLOAT_EQ(m.attenuation_distance, 0.5f);
  EXPECT_EQ(m.attenuation_color, Rgb(0.9f, 0.5f, 0.25f));
  EXPECT_FLOAT_EQ(m.diffuse_transmission, 0.35f);
  EXPECT_EQ(m.diffuse_transmission_color, Rgb(1.0f, 0.5f, 0.0f));
  EXPECT_TRUE(m.diffuse_transmission_texture.present());
  // A normal map, a coat normal map or anisotropy needs a tangent space: the loader makes one.
  EXPECT_FALSE(s.meshes[0].primitives[0].tangents.empty());
  // The extensions' defaults (their schemas): no coat, no anisotropy.
  EXPECT_FLOAT_EQ(s.materials[1].clearcoat, 0.0f);
  EXPECT_FLOAT_EQ(s.materials[1].clearcoat_roughness, 0.0f);
  EXPECT_FLOAT_EQ(s.materials[1].anisotropy_strength, 0.0f);
  EXPECT_EQ(s.materials[1].sheen_color, Rgb(0.0f));
  EXPECT_FLOAT_EQ(s.materials[1].iridescence, 0.0f);
  EXPECT_FLOAT_EQ(s.materials[1].iridescence_ior, 1.3f);
  EXPECT_FLOAT_EQ(s.materials[1].iridescence_thickness_min, 100.0f);
  EXPECT_FLOAT_EQ(s.materials[1].iridescence_thickness_max, 400.0f);
  EXPECT_FALSE(s.materials[1].has_volume());  // thicknessFactor 0: thin-walled
  EXPECT_TRUE(std::isinf(s.materials[1].attenuation_distance));
  EXPECT_FLOAT_EQ(s.materials[1].diffuse_transmission, 0.0f);
}

TEST(GltfLoader, LayerExtensionsOutOfRange) {
  TempDir dir;
  GltfQuad q;
  q.primitive_extra = R"(, "material": 0)";
  q.materials = R"([{"extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1.5}}}])";
  expect_error(dir.write("c.gltf", q.json()), "materials[0].extensions.KHR_materials_clearcoat.clearcoatFactor");
  q.materials = R"([{"extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": -0.1}}}])";
  expect_error(dir.write("a.gltf", q.json()), "materials[0].extensions.KHR_materials_anisotropy.anisotropyStrength");
  q.materials = R"([{"extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1, "clearcoatTexture": {"index": 3}}}}])";
  expect_error(dir.write("t.gltf", q.json()), "KHR_materials_clearcoat.clearcoatTexture.index");
  q.materials = R"([{"extensions": {"KHR_materials_sheen": {"sheenColorFactor": [0.5, 2, 0]}}}])";
  expect_error(dir.write("s.gltf", q.json()), "KHR_materials_sheen.sheenColorFactor");
  q.materials = R"([{"extensions": {"KHR_materials_iridescence": {"iridescenceIor": 0.5}}}])";
  expect_error(dir.write("i.gltf", q.json()), "KHR_materials_iridescence.iridescenceIor");
  q.materials = R"([{"extensions": {"KHR_materials_volume": {"thicknessFactor": 1, "attenuationDistance": 0}}}])";
  expect_error(dir.write("v.gltf", q.json()), "KHR_materials_volume.attenuationDistance");
  q.materials = R"([{"extensions": {"KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 2}}}])";
  expect_error(dir.write("d.gltf", q.json()), "KHR_materials_diffuse_transmission.diffuseTransmissionFactor");
}

TEST(GltfLoader, FactorOutOfRange) {
  TempDir dir;
  GltfQuad q;
  q.materials = R"([{"pbrMetallicRoughness": {"roughnessFactor": 1.5}}])";
  q.primitive_extra = R"(, "material": 0)";
  expect_error(dir.write("f.gltf", q.json()), "materials[0].pbrMetallicRoughness.roughnessFactor");
}

TEST(GltfLoader, LightsAndCameras) {
  TempDir dir;
  GltfQuad q;
  q.nodes = R"([{"mesh": 0}, {"camera": 0, "translation": [0, 0, 5]},
                {"translation": [0, 3, 0], "rotation": [-0.7071067811865476, 0, 0, 0.7071067811865476],
                 "extensions": {"KHR_lights_punctual": {"light": 0}}}])";
  q.scene_nodes = "[0, 1, 2]";
  q.top_extra = R"(, "cameras": [{"type": "orthographic", "orthographic": {"xmag": 2, "ymag": 1, "znear": 0.1, "zfar": 10}}],
    "extensionsUsed": ["KHR_lights_punctual"],
    "extensions": {"KHR_lights_punctual": {"lights": [{"type": "spot", "intensity": 7, "color": [1, 0.5, 0.25],
      "range": 20, "spot": {"innerConeAngle": 0.1, "outerConeAngle": 0.5}}]}})";
  const Scene s = load_gltf(dir.write("l.gltf", q.json()));
  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(s.cameras[0].type, CameraDesc::Type::orthographic);
  EXPECT_FLOAT_EQ(s.cameras[0].xmag, 2.0f);
  ASSERT_EQ(s.lights.size(), 1u);
  const LightDesc& l = s.lights[0];
  EXPECT_EQ(l.type, LightDesc::Type::spot);
  // 7 cd as the extension defines it: 7/683 W/sr; with --light-units radiometric, 7 W/sr.
  EXPECT_FLOAT_EQ(l.intensity, float(7.0 / 683.0));
  LoadOptions radiometric;
  radiometric.light_units = LightUnits::radiometric;
  EXPECT_FLOAT_EQ(load_gltf(dir.path() / "l.gltf", radiometric).lights[0].intensity, 7.0f);
  EXPECT_FLOAT_EQ(l.range, 20.0f);
  EXPECT_NEAR(l.position.y, 3.0f, 1e-6);
  // −90° about x turns the light's local −Z into −Y: it shines down.
  EXPECT_NEAR(l.direction.y, -1.0f, 1e-6);
  EXPECT_NEAR(l.direction.z, 0.0f, 1e-6);
}

}  // namespace
}  // namespace svbrdf
