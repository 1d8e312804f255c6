// KHR_materials_variants: a small file with two variants mapping two primitives to other materials;
// the reader selects, per primitive, the material the named variant maps it to, and refuses a name
// the file does not have with one line listing the names it has.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "base/error.h"
#include "gltf/scene_reader.h"
#include "gltf_test_files.h"
#include "render_program.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;

// Materials 0 "plain", 1 "red", 2 "blue", 3 "green". Primitive 0 is plain, red in "Red", blue in
// "Blue"; primitive 1 is green, blue in "Red", and keeps green in "Blue" (no mapping names it).
std::string variants_file(const std::string& p0_mappings = R"([{"material": 1, "variants": [0]}, {"material": 2, "variants": [1]}])") {
  test::GltfQuad q;
  q.materials = R"([{"name": "plain"}, {"name": "red"}, {"name": "blue"}, {"name": "green"}])";
  nlohmann::json j = nlohmann::json::parse(q.json());
  nlohmann::json p0 = j["meshes"][0]["primitives"][0], p1 = p0;
  p0["material"] = 0;
  p0["extensions"]["KHR_materials_variants"]["mappings"] = nlohmann::json::parse(p0_mappings);
  p1["material"] = 3;
  p1["extensions"]["KHR_materials_variants"]["mappings"] = nlohmann::json::parse(R"([{"material": 2, "variants": [0]}])");
  j["meshes"][0]["primitives"] = nlohmann::json::array({p0, p1});
  j["extensions"]["KHR_materials_variants"]["variants"] = nlohmann::json::parse(R"([{"name": "Red"}, {"name": "Blue"}])");
  j["extensionsUsed"] = nlohmann::json::array({"KHR_materials_variants"});
  j["extensionsRequired"] = nlohmann::json::array({"KHR_materials_variants"});
  return j.dump();
}

std::pair<int, int> materials_of(const fs::path& file, const std::string& variant) {
  LoadOptions o;
  o.variant = variant;
  const Scene s = load_gltf(file, o);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  return {s.meshes.at(0).primitives.at(0).material, s.meshes.at(0).primitives.at(1).material};
}

TEST(MaterialVariants, EachPrimitiveTakesTheMaterialItsVariantMapsItTo) {
  test::TempDir dir;
  const fs::path f = dir.write("variants.gltf", variants_file());
  EXPECT_EQ(materials_of(f, ""), std::make_pair(0, 3)) << "no variant: each primitive's own material";
  EXPECT_EQ(materials_of(f, "Red"), std::make_pair(1, 2));
  EXPECT_EQ(materials_of(f, "Blue"), std::make_pair(2, 3)) << "primitive 1 has no mapping for Blue: its own";
}

TEST(MaterialVariants, AnUnknownNameIsRefusedWithTheFilesVariants) {
  test::TempDir dir;
  const fs::path f = dir.write("variants.gltf", variants_file());
  try {
    materials_of(f, "Green");
    ADD_FAILURE() << "loaded with an unknown variant";
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 2);
    const std::string msg = e.what();
    EXPECT_NE(msg.find("'Green'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'Red', 'Blue'"), std::string::npos) << msg;
  }
  // The program: exit 2, one line.
  const test::RenderRun r = test::render(
      {f.string(), "--variant", "Green", "--res", "8x6", "--spp", "1", "-q", "-o", (dir.path() / "o.exr").string()},
      dir.path());
  ASSERT_TRUE(r.end.exited) << r.err;
  EXPECT_EQ(r.end.code, 2) << r.err;
  EXPECT_EQ(test::line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("its variants: 'Red', 'Blue'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path() / "o.exr"));
}

TEST(MaterialVariants, TheProgramRendersANamedVariant) {
  test::TempDir dir;
  const fs::path f = dir.write("variants.gltf", variants_file());
  const test::RenderRun r = test::render(
      {f.string(), "--variant", "Blue", "--res", "8x6", "--spp", "1", "-q", "-o", (dir.path() / "o.exr").string()},
      dir.path());
  ASSERT_TRUE(r.end.exited) << r.err;
  EXPECT_EQ(r.end.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir.path() / "o.exr"));
}

TEST(MaterialVariants, AMappingToAVariantTheFileLacksIsRefused) {
  test::TempDir dir;
  const fs::path f = dir.write("variants.gltf", variants_file(R"([{"material": 1, "variants": [0, 5]}])"));
  try {
    materials_of(f, "");
    ADD_FAILURE() << "loaded a mapping to variant 5 of 2";
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 2);
    EXPECT_NE(std::string(e.what()).find(
                  "variants.gltf: meshes[0].primitives[0].extensions.KHR_materials_variants.mappings[0].variants[1]"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace svbrdf
