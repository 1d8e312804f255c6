#pragma once
// The distance-LOD scenes and their manifest.
//
// Each material family lies on a square quad in the XY plane facing +Z, its texture repeating, seen
// by perspective cameras on the +Z axis looking at the quad's centre from k × d₁ for every k of the
// recipe's distances, where d₁ is the distance at which one texel covers one pixel:
//
//     d₁ = s · H / (2 · tan(φ/2))        s: texel side (mm_per_texel / 1000 m), H: image height in
//                                         pixels, φ: the camera's vertical field of view
//
// (a pixel at the image centre spans 2·tan(φ/2)/H radians, so on a plane facing the camera at
// distance d it covers d·2·tan(φ/2)/H metres). At k × d₁ a pixel covers k × k texels, i.e. MIP
// level log₂ k. The field of view is narrow (10° by default) so that every pixel sees the same
// direction and footprint to within a percent, and the quad is large enough (a whole number of
// texture repeats) that it fills the image from every camera: every pixel is an object pixel, no
// pixel mixes the object with the background, and the metrics average over H² equivalent pixels.
// Glossy families also get the mirror configuration: cameras at the same distances on the other
// side of the normal from the recipe's mirror light, at the same angle.
//
// Lights are not in the glTF files (one file per family serves every light); the manifest gives
// each as svbrdf-render's --sun ("elevation,azimuth,irradiance": elevation 0 and azimuth θ puts the
// light at incidence θ in the x–z plane) and --env (black "0,0,0" for directional lights, the sky
// image for the environment light).
//
// The tile roof (Exercise 27.11(c)): DIR/tile-roof/tile-roof.gltf is the corrugated geometry
// (geometry.h), DIR/tile-roof/tile-roof-proxy.gltf a flat quad of the same size whose normal map is
// the roof's shading normals sampled at the centres of the proxy's texels (texels_per_period per
// period, repeating), with the roof's material factors. The MIP module's BRDF pyramid of the proxy
// therefore averages the roof's normals: its coarse levels hold the roof's normal distribution.
// The roof cases are rendered with one scattering event (max_depth 1): what a normal distribution
// can stand for is the single-scattering response; interreflections between tiles are another
// effect. Lights steeper than the roof's steepest slope cast no shadows on it (a height field lit
// at incidence θ shadows itself only where its slope exceeds 90° − θ).
//
// Files: DIR/manifest.json, DIR/sky.hdr, DIR/FAMILY/FAMILY.gltf + textures/, DIR/tile-roof/...
#include <filesystem>
#include <string>
#include <vector>

#include "scenes/recipe.h"
#include "textures/color.h"
#include "textures/material_family.h"

namespace svbrdf {

std::vector<std::filesystem::path> bake_lod_scenes(const LodRecipe& recipe, const std::filesystem::path& out_dir,
                                                   const ColorConfig& color = ColorConfig::builtin(),
                                                   const ProgressFn& progress = {});

// d₁ above.
double one_texel_per_pixel_distance(double texel_m, int image_height, double yfov_rad);

// The manifest as the comparison reads it (paths absolute).
struct LodLightSpec {
  std::string name;
  std::string sun;  // svbrdf-render --sun, empty for none
  std::string env;  // svbrdf-render --env: "0,0,0" or an image path
  bool environment = false;
  double incidence_deg = 0.0;
};

struct LodView {
  std::string name;                  // "head-on" or "mirror"
  std::vector<std::string> cameras;  // one per distance, in the order of LodManifest::distances
  std::vector<std::string> lights;   // the lights this view is rendered under
};

struct LodCase {
  std::string name;                 // "metal-tray", "tile-roof"
  std::string kind;                 // "family" or "tile-roof"
  std::string preset, variant;      // families
  bool glossy = false;
  std::filesystem::path gltf;       // what the filters render
  std::filesystem::path reference;  // what the ground truth renders (the roof's geometry; else gltf)
  int max_depth = 16;
  double texel_m = 0.0;             // texel side in metres
  int texture_size = 0;
  double one_texel_per_pixel_m = 0.0;
  std::vector<LodView> views;
};

struct LodManifest {
  std::filesystem::path dir;
  int image_size = 0;
  double yfov_deg = 0.0;
  std::vector<double> distances;
  std::vector<LodLightSpec> lights;
  std::vector<LodCase> cases;

  const LodLightSpec& light(const std::string& name) const;
};

// Throws svbrdf::Error naming the file for a missing or malformed manifest.
LodManifest read_lod_manifest(const std::filesystem::path& file);

}  // namespace svbrdf
