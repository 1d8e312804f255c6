#pragma once
// Scene recipes: the small JSON files in scenes/ from which `svbrdf-bake scene RECIPE --out DIR`
// makes glTF scenes at build time (scenes/README.md documents every member). Two kinds:
//   "scene" — a composed scene: procedural materials, boxes, trays and quads placed in the world, a
//             sun (KHR_lights_punctual directional light), a sky (an equirectangular image the
//             renderer uses as its environment) and cameras. The showcase is one.
//   "lod"   — the distance-LOD scenes: each material family on a quad, cameras at
//             multiples of the one-texel-per-pixel distance, one scene per light, and the tile
//             roof of Exercise 27.11(c) with its flat proxy; plus a manifest for the comparison.
// Parsing checks everything (unknown members included, to catch typos) and throws svbrdf::Error
// naming the file, line and JSON path before anything is written.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scenes/sky.h"
#include "textures/material_family.h"

namespace svbrdf {

// A procedural material under a name the objects refer to.
struct NamedMaterial {
  std::string name;
  MaterialRecipe recipe;
};

struct SceneObject {
  std::string name;
  enum class Shape { box, tray, quad } shape = Shape::box;
  glm::dvec3 size{1.0};       // box, tray: x, y, z; quad: x, 0, z (horizontal, facing +Y)
  glm::dvec3 position{0.0};   // box, quad: centre; tray: centre of its bottom
  double yaw_deg = 0.0;       // rotation about +Y
  double rim = 0.01, plate = 0.004;  // tray
  std::string material;
};

struct SunRecipe {
  double elevation_deg = 40.0;  // above the horizon (+Y up)
  double azimuth_deg = 30.0;    // from +Z toward +X (svbrdf-render's --sun convention)
  double irradiance = 3.0;      // W/m² on a surface facing it
  glm::dvec3 color{1.0};
  // The unit direction toward the sun.
  glm::dvec3 toward() const;
};

struct SkyRecipe {
  SkyModel model;
  int width = 128, height = 64;
};

struct CameraRecipe {
  std::string name;
  glm::dvec3 position{0.0, 1.0, 3.0};
  glm::dvec3 target{0.0};
  double yfov_deg = 45.0;
  double aspect = 16.0 / 9.0;
};

struct SceneRecipe {
  std::string name;
  std::vector<NamedMaterial> materials;
  std::vector<SceneObject> objects;
  std::optional<SunRecipe> sun;
  std::optional<SkyRecipe> sky;
  std::vector<CameraRecipe> cameras;
};

// The LOD scenes.
struct LodFamily {
  std::string name;       // the folder and case names; default "PRESET" or "PRESET-VARIANT"
  MaterialRecipe recipe;  // size = the recipe's texture_size unless given
  bool glossy = false;    // adds the mirror-configuration view
};

struct LodLight {
  std::string name;
  bool environment = false;      // lit by the sky image alone (no punctual light)
  double incidence_deg = 0.0;    // directional: angle from the quad's normal, in the x–z plane
  double irradiance = 1.0;       // W/m² on a surface facing the light
};

struct TileRoofRecipe {
  std::string name = "tile-roof";
  double period_m = 0.2;              // one channel + cover tile
  double amplitude_m = 0.014;         // crest to mean
  int segments = 16;                  // mesh strips per period
  int texels_per_period = 16;         // the proxy's normal map resolution
  int texture_size = 256;             // proxy texture side (a multiple of texels_per_period)
  glm::dvec3 base_color{0.45, 0.16, 0.08};  // linear (glazed terracotta)
  double roughness = 0.35;
  double metallic = 0.0;
  std::vector<std::string> lights;    // names from LodRecipe::lights; empty: all
};

struct LodRecipe {
  std::string name = "lod";
  int image_size = 48;                // square images, pixels per side
  double yfov_deg = 10.0;
  std::vector<double> distances{1, 4, 16, 64, 256, 1024};  // multiples of the 1:1 distance
  int texture_size = 256;
  std::vector<LodFamily> families;
  std::vector<LodLight> lights;
  std::string mirror_light;           // the light whose mirror view glossy families get
  SkyRecipe sky;
  std::optional<TileRoofRecipe> tile_roof;
};

struct Recipe {
  std::string kind;  // "scene" or "lod"
  std::string file;
  SceneRecipe scene;
  LodRecipe lod;
};

// Throws svbrdf::Error (bad input) naming the file, line and member.
Recipe read_recipe(const std::string& path);
Recipe parse_recipe(const std::string& text, const std::string& name);

}  // namespace svbrdf
