// The Khronos glTF-Validator's own test assets (../shared/data/gltf-validator-tests) against the one
// glTF reader. Beside each asset lies the validator's report: its errors, each with a code and a JSON
// pointer. The expected outcome comes from that report, not from the reader:
// - an asset with no errors loads, or is refused only for a reason listed in kValidRefused;
// - an asset with an error the renderer would draw wrongly is refused, as bad input, in one line that
//   starts with the file's name;
// - an asset whose every error is harmless (kTolerated, or inside an object the report itself calls
//   unused) may load or be refused, but only as bad input in one line;
// and nothing crashes or throws anything but svbrdf::Error. The loader runs in-process (the scene
// as svbrdf-render gets it, images decoded); one test runs the program on a few refused assets for
// its exit code and its one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "appearance/fresnel.h"
#include "base/error.h"
#include "gltf/scene_reader.h"
#include "render_program.h"
#include "gltf_test_files.h"
#include "tests/common/test_paths.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;

fs::path suite_dir() { return fs::path(SVBRDF_SHARED_DIR) / "data" / "gltf-validator-tests"; }

// The validator's errors that cannot make the image wrong, all in this one table. An error matches
// an entry when its code is the entry's (or the entry names none), its JSON pointer starts with the
// entry's prefix ('#' stands for an index) and its message contains the entry's text.
struct Tolerated {
  const char* code;
  const char* pointer;
  const char* message;
  const char* why;
};
constexpr Tolerated kTolerated[] = {
    {"", "/animations", "", "animations are not read: the file's static pose is drawn"},
    {"ACCESSOR_ANIMATION_INPUT_NEGATIVE", "", "", "the keyframe times of an animation, which is not read"},
    {"ACCESSOR_ANIMATION_INPUT_NON_INCREASING", "", "", "the keyframe times of an animation, which is not read"},
    {"ACCESSOR_ANIMATION_SAMPLER_OUTPUT_NON_NORMALIZED_QUATERNION", "", "", "an animation's output, not read"},
    {"", "/skins", "", "skins are not applied: skinned meshes are drawn in their bind pose"},
    {"NODE_SKIN_NO_SCENE", "", "", "a skin's joints outside the scene: skins are not applied"},
    {"ACCESSOR_JOINTS_INDEX_OOB", "", "", "JOINTS_n are a skin's, which is not applied"},
    {"ACCESSOR_JOINTS_INDEX_DUPLICATE", "", "", "JOINTS_n are a skin's, which is not applied"},
    {"ACCESSOR_WEIGHTS_NEGATIVE", "", "", "WEIGHTS_n are a skin's, which is not applied"},
    {"ACCESSOR_WEIGHTS_NON_NORMALIZED", "", "", "WEIGHTS_n are a skin's, which is not applied"},
    {"EMPTY_ENTITY", "", "", "an empty array or object reads as an absent one, which glTF allows"},
    {"UNEXPECTED_EXTENSION_OBJECT", "", "", "an extension object where its extension has no meaning is never read"},
    {"UNDECLARED_EXTENSION", "", "", "an extension the file forgot to list in extensionsUsed is read where it stands, "
                                     "or, when not supported, ignored as an optional one"},
    {"NON_REQUIRED_EXTENSION", "", "", "KHR_mesh_quantization is read whether extensionsRequired lists it or not"},
    {"DUPLICATE_ELEMENTS", "/extensions", "", "an extension listed twice in extensionsUsed or extensionsRequired is "
                                              "one extension"},
    {"TYPE_MISMATCH", "/extensions/KHR_invalid", "", "the root object of an extension the renderer does not know is "
                                                     "never read"},
    {"UNDEFINED_PROPERTY", "/extensions/KHR_lights_punctual", "'lights'",
     "KHR_lights_punctual without its lights array defines no lights, as the renderer reads it"},
    {"INVALID_JSON", "", "BOM", "a byte-order mark before the JSON text is skipped; the text is read as written"},
    {"IMAGE_MIME_TYPE_INVALID", "/images", "", "an image is decoded by the signature of its bytes, whatever mimeType "
                                                "says"},
    {"GLB_CHUNK_LENGTH_UNALIGNED", "", "", "chunks are read at the lengths they state; the padding locates nothing"},
    {"GLB_DUPLICATE_CHUNK", "", "0x004e4942", "only the first BIN chunk is buffers[0]; a second is never read"},
};

// Valid assets refused anyway, each for a reason the message names.
struct ValidRefused {
  const char* asset;    // under the suite's folder
  const char* message;  // in the one line
  const char* why;
};
constexpr ValidRefused kValidRefused[] = {
    {"base/data/asset/min_version_valid.gltf", "asset.minVersion", "glTF 2.0 §5.3: a file whose minVersion is 2.1 "
                                                                    "needs a reader of glTF 2.1; this one reads 2.0"},
    {"base/data/root/named_objects.gltf", "buffers[0], which has no uri",
     "the mesh reads a buffer with no uri in a .gltf: the file does not hold the bytes it draws"},
    {"base/data/root/unused_objects.gltf", "buffers[0], which has no uri",
     "the mesh reads a buffer with no uri in a .gltf: the file does not hold the bytes it draws"},
};

bool pointer_matches(const std::string& pointer, const std::string& pattern) {
  std::size_t p = 0;
  for (const char c : pattern) {
    if (c == '#') {
      const std::size_t start = p;
      while (p < pointer.size() && std::isdigit(static_cast<unsigned char>(pointer[p]))) ++p;
      if (p == start) return false;
    } else if (p >= pointer.size() || pointer[p++] != c) {
      return false;
    }
  }
  return true;
}

struct ReportError {
  std::string code, pointer, message;
};

// The report's errors that are not tolerated: neither in kTolerated nor inside an object the same
// report calls unused (UNUSED_OBJECT): the renderer draws the default scene's meshes, materials and
// their textures, and reads what they name.
// A message's JSON pointer, empty where it has none (a const json's operator[] on a missing key is
// undefined behaviour: find, not [] on the reports).
std::string pointer_of(const nlohmann::json& m) {
  const auto it = m.find("pointer");
  return it != m.end() && it->is_string() ? it->get<std::string>() : std::string();
}

std::vector<ReportError> untolerated_errors(const nlohmann::json& report) {
  const nlohmann::json& messages = report.at("issues").at("messages");
  std::vector<std::string> unused;
  for (const auto& m : messages)
    if (m.value("code", "") == "UNUSED_OBJECT" && !pointer_of(m).empty()) unused.push_back(pointer_of(m));
  std::vector<ReportError> out;
  for (const auto& m : messages) {
    if (m.value("severity", 9) != 0) continue;
    ReportError e{m.value("code", ""), pointer_of(m), m.value("message", "")};
    const bool in_unused = std::any_of(unused.begin(), unused.end(), [&](const std::string& u) {
      return e.pointer == u || e.pointer.rfind(u + "/", 0) == 0;
    });
    const bool listed = std::any_of(std::begin(kTolerated), std::end(kTolerated), [&](const Tolerated& t) {
      return (!*t.code || e.code == t.code) && pointer_matches(e.pointer, t.pointer) &&
             e.message.find(t.message) != std::string::npos;
    });
    if (!in_unused && !listed) out.push_back(e);
  }
  return out;
}

struct Asset {
  fs::path path;
  std::string name;  // relative to the suite's folder
  int errors = 0;
  std::vector<ReportError> untolerated;
};

std::vector<Asset> assets() {
  std::vector<Asset> out;
  for (const auto& e : fs::recursive_directory_iterator(suite_dir())) {
    const std::string ext = e.path().extension().string();
    if (!e.is_regular_file() || (ext != ".gltf" && ext != ".glb")) continue;
    Asset a;
    a.path = e.path();
    a.name = fs::relative(e.path(), suite_dir()).generic_string();
    std::ifstream in(e.path().string() + ".report.json");
    const nlohmann::json report = nlohmann::json::parse(in);
    a.errors = report.at("issues").at("numErrors").get<int>();
    a.untolerated = untolerated_errors(report);
    out.push_back(std::move(a));
  }
  std::sort(out.begin(), out.end(), [](const Asset& a, const Asset& b) { return a.name < b.name; });
  return out;
}

const ValidRefused* valid_refusal(const std::string& name) {
  for (const auto& r : kValidRefused)
    if (name == r.asset) return &r;
  return nullptr;
}

std::string describe(const std::vector<ReportError>& errors) {
  std::string s;
  for (const auto& e : errors) s += " " + e.code + " at '" + e.pointer + "';";
  return s;
}

TEST(GltfConformance, EveryValidatorAssetLoadsOrIsRefusedAsItsReportSays) {
  if (!fs::exists(suite_dir()))
    GTEST_SKIP() << "the glTF-Validator's test assets are not here (" << suite_dir()
                 << "); a clone without ../shared/data/gltf-validator-tests";
  int valid_loaded = 0, valid_refused = 0, refused = 0, tolerated_loaded = 0, tolerated_refused = 0;
  const std::vector<Asset> all = assets();
  ASSERT_GT(all.size(), 300u) << "the suite is incomplete";
  for (const Asset& a : all) {
    SCOPED_TRACE(a.name);
    std::string error;
    try {
      const Scene scene = load_gltf(a.path);
    } catch (const Error& e) {
      error = e.what();
      EXPECT_EQ(e.kind(), Error::Kind::bad_input) << error;
      EXPECT_EQ(error.find('\n'), std::string::npos) << "more than one line: " << error;
      EXPECT_EQ(error.rfind(a.path.string() + ": ", 0), 0u) << "does not start with the file: " << error;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "threw something other than svbrdf::Error: " << e.what();
      continue;
    }
    const bool loaded = error.empty();
    if (a.errors == 0) {
      const ValidRefused* r = valid_refusal(a.name);
      if (r) {
        EXPECT_FALSE(loaded) << "listed in kValidRefused (" << r->why << ") but loads: drop it from the list";
        EXPECT_NE(error.find(r->message), std::string::npos) << error;
      } else {
        EXPECT_TRUE(loaded) << "a valid file refused: " << error;
      }
      (loaded ? valid_loaded : valid_refused)++;
    } else if (!a.untolerated.empty()) {
      EXPECT_FALSE(loaded) << "loads despite" << describe(a.untolerated);
      refused += !loaded;
    } else {
      (loaded ? tolerated_loaded : tolerated_refused)++;
    }
  }
  std::cout << all.size() << " assets: " << valid_loaded << " valid load, " << valid_refused
            << " valid refused for a listed reason; " << refused << " invalid refused; " << tolerated_loaded
            << " with only tolerated errors load, " << tolerated_refused << " of them are refused\n";
}

// KHR_materials_ior's valid asset: ior 2, the default 1.5, and 0, which the extension's text makes
// an infinite index whose Fresnel term "MUST evaluate to 1.0 independently of the view or light
// direction".
TEST(GltfConformance, IorZeroIsAnInfiniteIndexWithFresnelOne) {
  const fs::path file = suite_dir() / "ext/KHR_materials_ior/data/material/valid.gltf";
  if (!fs::exists(file)) GTEST_SKIP() << "the glTF-Validator's test assets are not here (" << suite_dir() << ")";
  const Scene s = load_gltf(file);
  ASSERT_EQ(s.materials.size(), 3u);
  EXPECT_EQ(s.materials[0].ior, 2.0f);
  EXPECT_EQ(s.materials[1].ior, 1.5f);
  const float n = s.materials[2].ior;
  EXPECT_EQ(fresnel_f0(n), 1.0f);
  for (const float c : {1.0f, 0.7f, 0.3f, 0.05f}) EXPECT_NEAR(fresnel_dielectric(c, n), 1.0f, 1e-6f) << c;
}

// The program's side of a refusal: exit 2 and one line, for assets refused at each stage of the
// reader (the container, the JSON, a reference, the data).
TEST(GltfConformance, RefusedAssetsExitTwoWithOneLine) {
  if (!fs::exists(suite_dir()))
    GTEST_SKIP() << "the glTF-Validator's test assets are not here (" << suite_dir() << ")";
  for (const char* name : {"base/data/glb/invalid_magic.glb", "base/data/json/invalid_syntax.gltf",
                           "base/data/node/node_loop.gltf", "base/data/asset/1_0_version.gltf"}) {
    SCOPED_TRACE(name);
    test::TempDir dir;
    const test::RenderRun r = test::render({(suite_dir() / name).string(), "--res", "8x6", "--spp", "1", "-q",
                                            "--mip-cache", "off", "-o", (dir.path() / "o.exr").string()},
                                           dir.path());
    EXPECT_EQ(r.end.code, 2) << r.err;
    EXPECT_EQ(test::line_count(r.err), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir.path() / "o.exr"));
  }
}

}  // namespace
}  // namespace svbrdf
