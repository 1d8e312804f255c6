// Scene recipes: the project's own recipes hold what the LOD comparison needs, and bad recipes are
// refused with one message naming the file, the line and the member's JSON path.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>

#include "base/error.h"
#include "scenes/recipe.h"

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

TEST(Recipe, ShowcaseHasItsMaterialsSunSkyAndCamera) {
  const Recipe r = read_recipe(kSource + "/scenes/showcase.json");
  ASSERT_EQ(r.kind, "scene");
  std::set<std::string> looks;
  for (const NamedMaterial& m : r.scene.materials) looks.insert(m.recipe.preset + "/" + m.recipe.variant);
  for (const char* want : {"sandstone/red", "sandstone/ochre", "sandstone/buff", "granite/", "metal-tray/", "printed-paper/"}) {
    const bool found = std::any_of(looks.begin(), looks.end(), [&](const std::string& s) { return s.rfind(want, 0) == 0; });
    EXPECT_TRUE(found) << "no " << want << " material";
  }
  EXPECT_TRUE(std::any_of(looks.begin(), looks.end(), [](const std::string& s) { return s.rfind("painted-wall/", 0) == 0; }));
  ASSERT_TRUE(r.scene.sun.has_value());
  EXPECT_GT(r.scene.sun->elevation_deg, 0.0);
  ASSERT_TRUE(r.scene.sky.has_value());
  ASSERT_EQ(r.scene.cameras.size(), 1u);
  // The page lies on the tray: inside its outline and just above its plate.
  const auto obj = [&](const std::string& name) {
    for (const SceneObject& o : r.scene.objects)
      if (o.name == name) return o;
    ADD_FAILURE() << "no object " << name;
    return SceneObject{};
  };
  const SceneObject tray = obj("metal-tray"), page = obj("printed-page");
  EXPECT_EQ(tray.shape, SceneObject::Shape::tray);
  EXPECT_GT(page.position.y, tray.position.y + tray.plate);
  EXPECT_LT(page.position.y, tray.position.y + tray.plate + 0.002);
  EXPECT_LT(std::abs(page.position.x - tray.position.x), tray.size.x / 2);
  EXPECT_LT(std::abs(page.position.z - tray.position.z), tray.size.z / 2);
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
