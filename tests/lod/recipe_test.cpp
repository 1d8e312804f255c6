// Scene recipes: the project's own recipes hold what the LOD comparison needs, and bad recipes are
// refused with one message naming the file, the line and the member's JSON path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "base/error.h"
#include "scenes/recipe.h"
#include "tests/common/test_paths.h"

namespace svbrdf {
namespace {

const std::string kSource = SVBRDF_SOURCE_DIR;

std::string error_of(const std::string& text) {
  try {
    parse_recipe(text, "r.json");
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 2);
    return e.what();
  }
  return "";
}

// The showcase shows what the project is for: near and far copies of the same glossy materials.
// Each material hangs at distances spanning 64×, each copy scaled with its distance so that all
// subtend the same angle and face the camera: the farthest copy fills as many pixels as the nearest
// with 64² times as many texels in each, six MIP levels coarser.
TEST(Recipe, ShowcaseHasNearAndFarCopiesOfEachMaterial) {
  const Recipe r = read_recipe(kSource + "/scenes/showcase.json");
  ASSERT_EQ(r.kind, "scene");
  ASSERT_TRUE(r.scene.sun.has_value());
  EXPECT_GT(r.scene.sun->elevation_deg, 0.0);
  ASSERT_TRUE(r.scene.sky.has_value());
  ASSERT_EQ(r.scene.cameras.size(), 1u);
  const glm::dvec3 eye = r.scene.cameras[0].position;
  std::set<std::string> presets;
  for (const NamedMaterial& m : r.scene.materials) {
    presets.insert(m.recipe.preset);
    double nearest = INFINITY, farthest = 0.0;
    std::vector<double> angles;
    for (const SceneObject& o : r.scene.objects) {
      if (o.material != m.name) continue;
      const glm::dvec3 to_eye = eye - o.position;
      const double d = glm::length(to_eye);
      nearest = std::min(nearest, d), farthest = std::max(farthest, d);
      angles.push_back(o.size.x / d);
      // The panel's face (local +Z turned by its yaw about +Y) looks at the camera within 1°.
      const double yaw = glm::radians(o.yaw_deg);
      const glm::dvec3 face(std::sin(yaw), 0.0, std::cos(yaw));
      const glm::dvec3 flat = glm::normalize(glm::dvec3(to_eye.x, 0.0, to_eye.z));
      EXPECT_GT(glm::dot(face, flat), std::cos(glm::radians(1.0))) << o.name;
    }
    SCOPED_TRACE(m.name);
    ASSERT_GE(angles.size(), 3u);
    EXPECT_GE(farthest / nearest, 63.9);
    for (double a : angles) EXPECT_NEAR(a, angles.front(), 1e-3 * angles.front());
  }
  // A glossy material: its far copies are where averaging parameters and averaging BRDFs differ.
  EXPECT_TRUE(presets.count("metal-tray"));
}

TEST(Recipe, LodRecipeHasItsDistancesAndLights) {
  const Recipe r = read_recipe(kSource + "/scenes/lod.json");
  ASSERT_EQ(r.kind, "lod");
  // The comparison's six (1× to 1024×), and two beyond them at which the filters read the coarsest
  // level at 256 and at 4096 samples per pixel (each sample filters 1/√spp of its pixel:
  // scenes/README.md).
  EXPECT_EQ(r.lod.distances, (std::vector<double>{1, 4, 16, 64, 256, 1024, 4096, 16384}));
  std::set<std::string> presets;
  for (const LodFamily& f : r.lod.families) presets.insert(f.recipe.preset);
  EXPECT_EQ(presets, (std::set<std::string>{"sandstone", "painted-wall", "printed-paper", "metal-tray", "granite"}));
  std::vector<double> incidences;
  int environments = 0;
  for (const LodLight& l : r.lod.lights) {
    if (l.environment) ++environments;
    else incidences.push_back(l.incidence_deg);
  }
  EXPECT_EQ(incidences, (std::vector<double>{0, 45, 75}));
  EXPECT_EQ(environments, 1);
  EXPECT_FALSE(r.lod.mirror_light.empty());
  ASSERT_TRUE(r.lod.tile_roof.has_value());
  for (const LodFamily& f : r.lod.families)
    if (f.recipe.preset == "metal-tray") {
      EXPECT_TRUE(f.glossy);
    }
}

TEST(Recipe, BadRecipesNameTheFileLineAndMember) {
  const std::string scene_head = R"({"kind": "scene", "name": "s",
  "materials": {"m": {"preset": "granite"}},
  "cameras": [{"name": "c", "position": [0, 0, 1], "target": [0, 0, 0]}],
)";
  EXPECT_EQ(error_of(scene_head + R"(  "objects": [{"name": "b", "shape": "box", "size": [1, 1, 1], "position": [0, 0, 0], "material": "m", "colour": 1}]})"),
            "r.json:4: objects[0].colour: unknown member (known here: name, shape, size, position, yaw_deg, rim, plate, material)");
  EXPECT_EQ(error_of(scene_head + R"(  "objects": [{"name": "b", "shape": "cone", "size": [1, 1, 1], "position": [0, 0, 0], "material": "m"}]})"),
            "r.json:4: objects[0].shape: unknown shape \"cone\" (known: box, tray, quad)");
  EXPECT_EQ(error_of(scene_head + R"(  "objects": [{"name": "b", "shape": "box", "size": [1, 0, 1], "position": [0, 0, 0], "material": "m"}]})"),
            "r.json:4: objects[0].size: sizes must be positive");
  EXPECT_EQ(error_of(scene_head + R"(  "objects": [{"name": "b", "shape": "box", "size": [1, 1, 1], "position": [0, 0, 0], "material": "x"}]})"),
            "r.json:4: objects[0].material: no material named \"x\"");
  EXPECT_EQ(error_of(scene_head + R"(  "objects": [{"name": "b c", "shape": "box", "size": [1, 1, 1], "position": [0, 0, 0], "material": "m"}]})"),
            "r.json:4: objects[0].name: a name must be 1-64 letters, digits, '-' or '_'");
  EXPECT_EQ(error_of(R"({"kind": "scene", "name": "s", "materials": {"m": {"preset": "marble"}}})"),
            "r.json:1: materials.m.preset: unknown preset \"marble\" (known: sandstone, painted-wall, printed-paper, metal-tray, granite)");
  EXPECT_EQ(error_of(R"({"kind": "scene", "name": "s", "materials": {"m": {"preset": "granite", "variant": "blue"}}})"),
            "r.json:1: materials.m.variant: unknown variant \"blue\" of granite (known: gray, pink, polished)");
  EXPECT_EQ(error_of(R"({"kind": "scene", "name": "s", "materials": {"m": {"preset": "granite", "size": 100}}})"),
            "r.json:1: materials.m.size: must be a power of two, got 100");
  EXPECT_EQ(error_of(R"({"kind": "tree"})"), "r.json:1: kind: unknown kind \"tree\" (known: scene, lod)");
  EXPECT_EQ(error_of(R"([1])"), "r.json:1: a recipe is a JSON object");
  EXPECT_EQ(error_of(R"({"kind": "lod", "name": "l", "families": [], "lights": [{"name": "e", "environment": true}],
  "mirror_light": "e"})"),
            "r.json:2: mirror_light: must name a directional light with incidence ≥ 1°");
  EXPECT_EQ(error_of(R"({"kind": "lod", "name": "l", "families": [], "lights": [{"name": "s", "incidence_deg": 95}]})"),
            "r.json:1: lights[0].incidence_deg: must be in [0, 89], got 95");
  EXPECT_EQ(error_of(R"({"kind": "lod", "name": "l", "families": [], "lights": [{"name": "s", "incidence_deg": 0}],
  "tile_roof": {"texels_per_period": 12}})"),
            "r.json:2: tile_roof: texture_size must be a multiple of texels_per_period, so the normal map tiles");
  EXPECT_EQ(error_of(R"({"kind": "lod", "name": "l", "distances": [4, 1], "families": [], "lights": []})"),
            "r.json:1: distances: distances must be increasing");
}

TEST(Recipe, UnreadableFileIsBadInput) {
  try {
    read_recipe("/nonexistent/recipe.json");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 2);
    EXPECT_NE(std::string(e.what()).find("/nonexistent/recipe.json"), std::string::npos);
  }
}

}  // namespace
}  // namespace svbrdf
