// svbrdf-bake mip | eval | compare end to end: the file it builds, compare's table against the
// library's numbers, eval against texel_eval and the exact reference, and bad input (one line naming
// the file or argument, exit 2, no output file left behind).
#include <gtest/gtest.h>

#include <fstream>

#include <cstdio>
#include <sstream>
#include <string>

#include "apps/compare_report.h"
#include "base/json.h"
#include "mip/mip_file.h"
#include "tests/mip/synthetic_materials.h"
#include "tests/common/run_command.h"
#include "textures/image.h"
#include "textures/material_loader.h"
#include "scenes/texture_set.h"
#include "textures/normal_map.h"
#include "tests/common/test_paths.h"

namespace svbrdf {
namespace {

using BakeRun = testing::CommandResult;

// Runs `svbrdf-bake ARGS` through the shell with `input` on stdin.
BakeRun bake(const testing::TempDir& dir, const std::string& args, const std::string& input = "") {
  return testing::run_command(std::string("'") + SVBRDF_BAKE + "' " + args, dir.path(), input);
}

int lines(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }

// A small texture set on disk: the tray's parameters as glTF images.
struct TextureSet {
  std::filesystem::path base_color, metallic_roughness, normal;
};
TextureSet write_set(const testing::TempDir& dir, int size) {
  const MaterialTexels m = synthetic::painted_wall(size);
  const MaterialTexels t = synthetic::tray(size);
  Image bc(size, size, 3), mr(size, size, 3), n(size, size, 3);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const std::size_t k = m.index(i, j);
      for (int c = 0; c < 3; ++c) bc.at(i, j, c) = 0.3f + 0.4f * t.roughness[k] * float(c + 1) / 3;  // sRGB-encoded
      mr.at(i, j, 0) = 1.0f;
      mr.at(i, j, 1) = t.roughness[k];
      mr.at(i, j, 2) = (i + j) % 3 == 0 ? 1.0f : 0.0f;
      const glm::vec3 e = encode_normal(m.normal[k]);
      for (int c = 0; c < 3; ++c) n.at(i, j, c) = e[c];
    }
  TextureSet s{dir / "bc.png", dir / "mr.png", dir / "n.png"};
  write_image(s.base_color, bc, PixelFormat::uint8);
  write_image(s.metallic_roughness, mr, PixelFormat::uint8);
  write_image(s.normal, n, PixelFormat::uint16);
  return s;
}

std::string q(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

TEST(BakeCli, MipBuildsWhatTheLibraryBuilds) {
  testing::TempDir dir;
  const TextureSet s = write_set(dir, 16);
  const auto out = dir / "wall.exr";
  const BakeRun r = bake(dir, "mip --base-color " + q(s.base_color) + " --metallic-roughness " + q(s.metallic_roughness) +
                              " --normal " + q(s.normal) + " --normal-scale 0.8 --lobes 3 --out " + q(out));
  ASSERT_EQ(r.status, 0) << r.err;
  const MipData file = read_mip_file(out);
  MaterialFiles f;
  f.base_color = s.base_color;
  f.metallic_roughness = s.metallic_roughness;
  f.normal = s.normal;
  f.normal_scale = 0.8f;
  BrdfBuildOptions o;
  o.reduction.max_lobes = 3;
  const MipData lib = build_mip(load_material_texels(f), o);
  ASSERT_EQ(file.levels(), lib.levels());
  for (int l = 1; l < lib.levels(); ++l) {
    const std::vector<Lobe> a = file.brdf.level(l).all_lobes(), b = lib.brdf.level(l).all_lobes();
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k) {
      EXPECT_EQ(a[k].weight, b[k].weight);
      EXPECT_EQ(a[k].alpha2, b[k].alpha2);
    }
  }
}

// `mip SCENE.gltf --material INDEX` reads the material's textures and factors from the glTF file: the
// same pyramid as from the images named on the command line (the textures module's quad of a preset).
TEST(BakeCli, MipFromAGltfMaterialEqualsMipFromItsImages) {
  testing::TempDir dir;
  MaterialRecipe r;
  r.preset = "metal-tray";
  r.size = 16;
  const TextureSetFiles files = write_texture_set(generate_material(r), dir.path());
  const BakeRun a = bake(dir, "mip " + q(files.gltf) + " --material 0 --out " + q(dir / "a.exr"));
  ASSERT_EQ(a.status, 0) << a.err;
  const BakeRun b = bake(dir, "mip --base-color " + q(files.base_color) + " --metallic-roughness " + q(files.metallic_roughness) +
                                  " --normal " + q(files.normal) + " --out " + q(dir / "b.exr"));
  ASSERT_EQ(b.status, 0) << b.err;
  const MipData ma = read_mip_file(dir / "a.exr"), mb = read_mip_file(dir / "b.exr");
  ASSERT_EQ(ma.levels(), mb.levels());
  EXPECT_EQ(ma.level0.roughness, mb.level0.roughness);
  EXPECT_EQ(ma.level0.base_color, mb.level0.base_color);
  for (int l = 1; l < ma.levels(); ++l) EXPECT_EQ(ma.brdf.level(l).counts, mb.brdf.level(l).counts);
  const BakeRun c = bake(dir, "mip " + q(files.gltf) + " --material 7 --out " + q(dir / "c.exr"));
  EXPECT_EQ(c.status, 2);
  EXPECT_NE(c.err.find("--material"), std::string::npos) << c.err;
}

// compare prints the library's numbers (compare_levels, formatted %.4f); eval prints texel_eval, or
// the exact reference for `--mode exact` (%.9g).
TEST(BakeCli, CompareAndEvalPrintTheLibrarysNumbers) {
  testing::TempDir dir;
  const auto file = dir / "tray.exr";
  write_mip_file(file, build_mip(synthetic::tray(32)));
  const BakeRun r = bake(dir, "compare " + q(file) + " --levels 2..5");
  ASSERT_EQ(r.status, 0) << r.err;
  CompareOptions o;
  o.first_level = 2;
  o.last_level = 5;
  const auto rows = compare_levels(read_mip_file(file), o);
  std::istringstream in(r.out);
  std::string line;
  std::getline(in, line);  // header
  int checked = 0;
  for (const LevelComparison& l : rows)
    for (const ModeLevelStats& m : l.modes) {
      ASSERT_TRUE(std::getline(in, line));
      int level = 0, bytes = 0;
      char size[32], mode[32];
      double erel = 0, erel_max = 0, elog = 0, emean = 0;
      // "level size texels(two words) mode ..."
      char t1[32], t2[32];
      ASSERT_EQ(std::sscanf(line.c_str(), "%d %31s %31s %31s %31s %lf %lf %lf %lf %d", &level, size, t1, t2, mode, &erel, &erel_max,
                            &elog, &emean, &bytes),
                10)
          << line;
      EXPECT_EQ(level, l.level);
      EXPECT_EQ(std::string(mode), std::string(filter_name(m.mode)));
      EXPECT_NEAR(erel, m.erel_mean, 5.1e-5);
      EXPECT_NEAR(erel_max, m.erel_max, 5.1e-5);
      EXPECT_NEAR(elog, m.elog_mean, 5.1e-5);
      EXPECT_NEAR(emean, m.emean, 5.1e-5);
      EXPECT_EQ(bytes, m.bytes_per_texel);
      ++checked;
    }
  EXPECT_EQ(checked, 16);
  const BakeRun j = bake(dir, "compare " + q(file) + " --levels 4 --json");
  ASSERT_EQ(j.status, 0) << j.err;
  EXPECT_TRUE(Json::parse(j.out).at("levels").at(0).at("modes").at("brdf").contains("e_rel_mean")) << j.out;

  const MipData mip = read_mip_file(file);
  const std::string pairs =
      "# a comment, then a blank line\n\n0 0 1 0 0 1\n0.5 0 0.8660254 -0.5 0 0.8660254\n0.6 0.0 0.8 0.0 -0.6 0.8\n";
  const ExactReference exact(mip.level0);
  for (const std::string mode : {"exact", "param", "toksvig", "vmf", "brdf"}) {
    const BakeRun e = bake(dir, "eval " + q(file) + " --level 3 --texel 1 2 --mode " + mode, pairs);
    ASSERT_EQ(e.status, 0) << e.err;
    std::istringstream ein(e.out);
    for (const auto& [wi, wo] : {std::pair{glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1)},
                                 std::pair{glm::dvec3(0.5, 0, 0.8660254), glm::dvec3(-0.5, 0, 0.8660254)},
                                 std::pair{glm::dvec3(0.6, 0, 0.8), glm::dvec3(0, -0.6, 0.8)}}) {
      // eval renormalizes its input directions (in float), as svbrdf-brdf does.
      const glm::dvec3 nwi(glm::normalize(glm::vec3(wi))), nwo(glm::normalize(glm::vec3(wo)));
      const glm::dvec3 want =
          mode == "exact" ? exact.eval(3, 1, 2, nwi, nwo) : texel_eval(mip, *parse_filter(mode), 3, 1, 2, nwi, nwo);
      double r0, g0, b0;
      ASSERT_TRUE(ein >> r0 >> g0 >> b0) << e.out;
      EXPECT_NEAR(r0, want.r, 1e-8 * want.r + 1e-12);
      EXPECT_NEAR(b0, want.b, 1e-8 * want.b + 1e-12);
    }
  }
}

// Bad input: one line on stderr naming the file or argument, exit 2, and no output file.
TEST(BakeCli, BadInputIsOneLineAndExitTwo) {
  testing::TempDir dir;
  const TextureSet s = write_set(dir, 8);
  Image wide(16, 8, 3), gray(8, 8, 1);
  write_image(dir / "wide.png", wide, PixelFormat::uint8);
  write_image(dir / "gray.png", gray, PixelFormat::uint8);
  const auto out = dir / "bad.exr";
  const auto file = dir / "ok.exr";
  write_mip_file(file, build_mip(synthetic::paper(8)));
  std::vector<std::pair<std::string, std::string>> cases = {
      {"mip --base-color " + q(dir / "nope.png") + " --out " + q(out), "nope.png"},
      {"mip --base-color " + q(s.base_color) + " --normal " + q(dir / "wide.png") + " --out " + q(out), "wide.png"},
      {"mip --base-color " + q(s.base_color) + " --normal " + q(dir / "gray.png") + " --out " + q(out), "gray.png"},
      {"mip --base-color " + q(s.base_color) + " --lobes 9 --out " + q(out), "--lobes"},
      {"mip --out " + q(out), "--base-color"},
      {"mip --base-color-factor 0.5,0.5 --out " + q(out), "--base-color-factor"},
      {"mip " + q(dir / "scene.gltf") + " --material 0 --out " + q(out), "scene.gltf"},
      {"eval " + q(file) + " --level 9 --texel 0 0 --mode brdf", "--level"},
      {"eval " + q(file) + " --level 1 --texel 4 0 --mode brdf", "--texel"},
      {"eval " + q(file) + " --level 1 --texel 0 0 --mode shiny", "--mode"},
      {"eval " + q(file) + " --level 1 --texel 0 0 --mode level0", "--mode"},  // stores no coarse texel
      {"eval " + q(dir / "nope.exr") + " --level 1 --texel 0 0 --mode brdf", "nope.exr"},
      {"compare " + q(file) + " --levels 2..9", "--levels"},
      {"compare " + q(s.base_color), "bc.png"},
  };
  // The glTF reader is the renderer's: deep nesting is refused before tinygltf's recursive parse.
  std::ofstream(dir / "deep.gltf") << R"({"asset": {"version": "2.0"}, "extras": )" << std::string(20000, '[')
                                   << std::string(20000, ']') << "}";
  cases.push_back({"mip " + q(dir / "deep.gltf") + " --material 0 --out " + q(out), "nests deeper"});
  for (const auto& [args, names] : cases) {
    const BakeRun r = bake(dir, args, "0 0 1 0 0 1\n");
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
    EXPECT_EQ(lines(r.err), 1) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(names), std::string::npos) << args << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
  }
  // A malformed direction line names its line number.
  const BakeRun r = bake(dir, "eval " + q(file) + " --level 1 --texel 0 0 --mode brdf", "0 0 1 0 0 1\n0 0 1 oops\n");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("line 2"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace svbrdf
