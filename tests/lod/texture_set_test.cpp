// Baked texture sets: byte-identical per seed, read back as the generator's texels, a quad of the
// preset's physical size, and valid glTF by the Khronos validator.
#include "scenes/texture_set.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <iterator>

#include "base/error.h"
#include "base/json.h"
#include "tests/common/temp_dir.h"
#include "textures/material_loader.h"
#include "tests/common/test_paths.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

TEST(TextureSet, BakesAreByteIdenticalForASeed) {
  const TempDir dir;
  for (const MaterialPreset& p : material_presets()) {
    SCOPED_TRACE(std::string(p.name));
    const MaterialRecipe recipe{std::string(p.name), "", 64, 5, 0.0};
    const TextureSetFiles a = bake_material(recipe, dir / "a");
    const TextureSetFiles b = bake_material(recipe, dir / "b");
    for (const auto& [fa, fb] : {std::pair{a.gltf, b.gltf}, {a.base_color, b.base_color},
                                 {a.metallic_roughness, b.metallic_roughness}, {a.normal, b.normal}}) {
      ASSERT_TRUE(fs::exists(fa)) << fa;
      EXPECT_EQ(slurp(fa), slurp(fb)) << fa.filename();
    }
    const TextureSetFiles c = bake_material(MaterialRecipe{std::string(p.name), "", 64, 6, 0.0}, dir / "c");
    EXPECT_NE(slurp(a.base_color), slurp(c.base_color));
  }
  // No temporary files are left behind.
  for (const auto& e : fs::recursive_directory_iterator(dir.path()))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

// Reading the baked files with the loader gives the generator's texels: a MIP build from memory
// and one from the files see the same level 0.
TEST(TextureSet, BakedFilesLoadAsTheGeneratedTexels) {
  const TempDir dir;
  for (const MaterialPreset& p : material_presets()) {
    SCOPED_TRACE(std::string(p.name));
    const ProceduralMaterial m = generate_material(MaterialRecipe{std::string(p.name), "", 32, 3, 0.0});
    const TextureSetFiles files = write_texture_set(m, dir / std::string(p.name));
    MaterialFiles in;
    in.base_color = files.base_color;
    in.metallic_roughness = files.metallic_roughness;
    in.normal = files.normal;
    const MaterialTexels t = load_material_texels(in);
    ASSERT_EQ(t.size(), m.texels.size());
    for (std::size_t k = 0; k < t.size(); ++k) {
      for (int c = 0; c < 3; ++c) {
        ASSERT_NEAR(t.base_color[k][c], m.texels.base_color[k][c], 1e-6) << k;
        ASSERT_NEAR(t.normal[k][c], m.texels.normal[k][c], 1e-6) << k;
      }
      ASSERT_NEAR(t.roughness[k], m.texels.roughness[k], 1e-6) << k;
      ASSERT_NEAR(t.metallic[k], m.texels.metallic[k], 1e-6) << k;
    }
  }
}

TEST(TextureSet, QuadHasThePresetsPhysicalSize) {
  const ProceduralMaterial m = generate_material(MaterialRecipe{"metal-tray", "silver", 64, 1, 0.0});
  const Json doc = material_quad_gltf(m, TextureSetFiles{"t.gltf", "b.png", "mr.png", "n.png"}).document("t.bin");
  // 64 texels × 0.08 mm = 5.12 mm: corners at ±2.56 mm = ±0.00256 m.
  const int position = doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<int>();
  const Json& accessor = doc["accessors"][std::size_t(position)];
  for (int c = 0; c < 2; ++c) {
    EXPECT_NEAR(accessor["max"][std::size_t(c)].get<double>(), 0.00256, 1e-9) << doc.dump();
    EXPECT_NEAR(accessor["min"][std::size_t(c)].get<double>(), -0.00256, 1e-9);
  }
  EXPECT_EQ(accessor["max"][2].get<double>(), 0.0);
  EXPECT_EQ(doc["images"][0]["uri"], "b.png");
  const Json& extras = doc["materials"][0]["extras"]["svbrdf"];
  EXPECT_NEAR(extras["side_mm"].get<double>(), 5.12, 1e-12);
  EXPECT_EQ(extras["variant"], "silver");
}

TEST(TextureSet, BadInputWritesNothing) {
  const TempDir dir;
  EXPECT_THROW(bake_material(MaterialRecipe{"granite", "blue", 16, 1, 0.0}, dir / "out"), Error);
  EXPECT_THROW(bake_material(MaterialRecipe{"granite", "", 12, 1, 0.0}, dir / "out"), Error);
  EXPECT_FALSE(fs::exists(dir / "out"));
  std::ofstream(dir / "file") << "x";
  try {
    bake_material(MaterialRecipe{"granite", "", 16, 1, 0.0}, dir / "file");
    ADD_FAILURE() << "no error for an output path that is a file";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("file"), std::string::npos) << e.what();
    EXPECT_EQ(e.exit_code(), 2);
  }
  EXPECT_EQ(slurp(dir / "file"), "x");
}

// The Khronos glTF validator (npm gltf-validator, installed by tools/install-deps into
// tools/node_modules) must report no error and no warning for every preset's bake.
TEST(TextureSet, GltfValidatorReportsNoErrorsOrWarnings) {
  const fs::path validator = fs::path(SVBRDF_SOURCE_DIR) / "tools/node_modules/gltf-validator";
  const fs::path script = fs::path(SVBRDF_SOURCE_DIR) / "tests/textures/validate_gltf.cjs";
  if (std::system("node --version >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "node is not installed: cannot run the Khronos glTF validator (tools/install-deps installs it with npm)";
  if (!fs::exists(validator / "package.json"))
    GTEST_SKIP() << "gltf-validator is not in " << validator << ": run tools/install-deps (needs npm)";
  const TempDir dir;
  std::vector<fs::path> gltfs;
  std::string command = "node '" + script.string() + "' '" + validator.string() + "'";
  for (const MaterialPreset& p : material_presets())
    for (std::string_view variant : p.variants) {
      const std::string name = std::string(p.name) + "_" + std::string(variant);
      gltfs.push_back(bake_material(MaterialRecipe{std::string(p.name), std::string(variant), 32, 1, 0.0}, dir / name).gltf);
      command += " '" + gltfs.back().string() + "'";
    }
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::vector<std::string> lines;
  std::string line;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), int(buf.size()), pipe)) {
    line += buf.data();
    if (!line.empty() && line.back() == '\n') lines.push_back(std::move(line)), line.clear();
  }
  EXPECT_EQ(::pclose(pipe), 0);
  ASSERT_EQ(lines.size(), gltfs.size()) << (lines.empty() ? line : lines.front());
  for (std::size_t k = 0; k < gltfs.size(); ++k) {
    EXPECT_NE(lines[k].find(gltfs[k].string()), std::string::npos) << lines[k];
    EXPECT_NE(lines[k].find("\"errors\":0,\"warnings\":0,"), std::string::npos) << lines[k];
  }
}

}  // namespace
}  // namespace svbrdf
