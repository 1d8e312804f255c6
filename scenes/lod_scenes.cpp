#include "scenes/lod_scenes.h"

#include <algorithm>
#include <cmath>

#include "base/error.h"
#include "base/json.h"
#include "base/math.h"
#include "gltf/writer.h"
#include "scenes/geometry.h"
#include "scenes/scene_assembly.h"
#include "scenes/sky.h"
#include "textures/image.h"
#include "textures/normal_map.h"

namespace svbrdf {

namespace fs = std::filesystem;

double one_texel_per_pixel_distance(double texel_m, int image_height, double yfov_rad) {
  return texel_m * image_height / (2.0 * std::tan(yfov_rad / 2.0));
}

namespace {

constexpr double kDeg = kPiD / 180.0;

struct LodCamera {
  std::string name;
  double multiple = 1.0;
  glm::dvec3 position{0.0};
};

std::string camera_name(const std::string& prefix, double k) { return prefix + "d" + number_text(k); }

// The cameras of a case: head-on at every distance, and mirror ones when asked.
std::vector<LodCamera> cameras(const LodRecipe& r, double d1, const LodLight* mirror) {
  std::vector<LodCamera> out;
  for (double k : r.distances) out.push_back({camera_name("", k), k, {0.0, 0.0, k * d1}});
  if (mirror) {
    const double t = mirror->incidence_deg * kDeg;
    // The light comes from +x at incidence t (toward it: (sin t, 0, cos t)); the mirror direction
    // is (−sin t, 0, cos t).
    for (double k : r.distances) out.push_back({camera_name("mirror-", k), k, k * d1 * glm::dvec3(-std::sin(t), 0.0, std::cos(t))});
  }
  return out;
}

// The largest |x| and |y| at which the camera's image corners meet the plane z = 0 (the camera
// looks at the origin); the quad must reach past them.
double visible_half_extent(const LodCamera& c, double yfov) {
  const glm::dvec3 f = glm::normalize(-c.position);
  glm::dvec3 right = glm::cross(f, glm::dvec3(0, 1, 0));
  right = glm::normalize(right);
  const glm::dvec3 up = glm::cross(right, f);
  const double t = std::tan(yfov / 2);
  double extent = 0.0;
  for (double sx : {-1.0, 1.0})
    for (double sy : {-1.0, 1.0}) {
      const glm::dvec3 d = f + right * (sx * t) + up * (sy * t);  // square images
      if (d.z >= 0.0) throw Error("LOD camera: an image corner misses the quad", Error::Kind::internal);
      const glm::dvec3 p = c.position + d * (-c.position.z / d.z);
      extent = std::max({extent, std::abs(p.x), std::abs(p.y)});
    }
  return extent;
}

void add_cameras(GltfWriter& w, const std::vector<LodCamera>& cams, double yfov, double d1) {
  for (const LodCamera& c : cams) {
    Placement where;
    where.translation = c.position;
    where.rotation = look_rotation(-c.position);
    const Json extras = {{"svbrdf", {{"lod_multiple", c.multiple}, {"one_texel_per_pixel_m", d1}}}};
    const double dist = glm::length(c.position);
    w.add_camera(c.name, yfov, 1.0, 0.01 * dist, 0.0, where, extras);
  }
}

Json view_value(const std::string& name, const std::vector<LodCamera>& cams, const std::string& prefix,
                const std::vector<std::string>& lights) {
  std::vector<std::string> names;
  for (const LodCamera& c : cams)
    if (c.name.rfind(prefix + "d", 0) == 0) names.push_back(c.name);
  return {{"name", name}, {"cameras", names}, {"lights", lights}};
}

}  // namespace

std::vector<fs::path> bake_lod_scenes(const LodRecipe& r, const fs::path& out, const ColorConfig& color,
                                      const ProgressFn& progress) {
  make_output_dir(out);
  std::vector<fs::path> written;
  const auto stage = [&](const std::string& s) {
    if (progress) progress(s);
  };
  const double yfov = r.yfov_deg * kDeg;

  stage("sky");
  write_image(out / "sky.hdr", sky_image(r.sky.model, r.sky.width, r.sky.height), PixelFormat::float32);
  written.push_back(out / "sky.hdr");

  Json manifest = {{"generator", "svbrdf-bake scene"}, {"recipe", r.name}, {"image_size", r.image_size},
                   {"yfov_deg", r.yfov_deg}, {"distances", r.distances}};
  Json lights = Json::array();
  std::vector<std::string> all_lights;
  const LodLight* mirror = nullptr;
  for (const LodLight& l : r.lights) {
    Json v = {{"name", l.name}, {"environment", l.environment}};
    if (l.environment) {
      v["sun"] = "";
      v["env"] = "sky.hdr";
    } else {
      v["incidence_deg"] = l.incidence_deg;
      v["sun"] = "0," + number_text(l.incidence_deg) + "," + number_text(l.irradiance);
      v["env"] = "0,0,0";
    }
    lights.push_back(std::move(v));
    all_lights.push_back(l.name);
    if (l.name == r.mirror_light) mirror = &l;
  }
  manifest["lights"] = std::move(lights);
  Json cases = Json::array();

  for (const LodFamily& fam : r.families) {
    stage(fam.name);
    const ProceduralMaterial m = generate_material(fam.recipe, color);
    const double texel = m.mm_per_texel / 1000.0;
    const double d1 = one_texel_per_pixel_distance(texel, r.image_size, yfov);
    const auto cams = cameras(r, d1, fam.glossy ? mirror : nullptr);
    double half = 0.0;
    for (const LodCamera& c : cams) half = std::max(half, visible_half_extent(c, yfov));
    // A whole, even number of texture repeats, 10 % beyond what any camera sees.
    const double side = m.side_mm() / 1000.0;
    const double repeats = 2.0 * std::ceil(1.1 * half / side);
    const fs::path dir = out / fam.name;
    make_output_dir(dir);
    GltfWriter w("svbrdf-bake scene");
    w.set_scene_name(fam.name);
    const int mat = write_material(w, m, fam.name, dir, written);
    const TriangleMesh quad = rectangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, repeats * side, repeats * side, 1.0 / side);
    w.add_mesh_node(fam.name, w.add_mesh(fam.name + " quad", quad, mat));
    add_cameras(w, cams, yfov, d1);
    const fs::path gltf = dir / (fam.name + ".gltf");
    w.write(gltf);
    written.push_back(gltf);

    Json views = Json::array({view_value("head-on", cams, "", all_lights)});
    if (fam.glossy && mirror) views.push_back(view_value("mirror", cams, "mirror-", {mirror->name}));
    cases.push_back({{"name", fam.name},
                     {"kind", "family"},
                     {"preset", m.preset},
                     {"variant", m.variant},
                     {"glossy", fam.glossy},
                     {"gltf", fam.name + "/" + fam.name + ".gltf"},
                     {"reference", fam.name + "/" + fam.name + ".gltf"},
                     {"max_depth", 16},
                     {"texel_m", texel},
                     {"texture_size", m.texels.width},
                     {"one_texel_per_pixel_m", d1},
                     {"texture_repeats", repeats},
                     {"views", std::move(views)}});
  }

  if (r.tile_roof) {
    const TileRoofRecipe& t = *r.tile_roof;
    stage(t.name);
    const double texel = t.period_m / t.texels_per_period;
    const double d1 = one_texel_per_pixel_distance(texel, r.image_size, yfov);
    const auto cams = cameras(r, d1, nullptr);
    double half = 0.0;
    for (const LodCamera& c : cams) half = std::max(half, visible_half_extent(c, yfov));
    // The roof spans a whole, even number of proxy textures (so periods are whole and even too).
    const int periods_per_texture = t.texture_size / t.texels_per_period;
    const double side = t.texture_size * texel;
    const double repeats = 2.0 * std::ceil(1.1 * half / side);
    CorrugatedRoof roof;
    roof.period_m = t.period_m;
    roof.amplitude_m = t.amplitude_m;
    roof.segments = t.segments;
    roof.periods = int(repeats) * periods_per_texture;
    roof.width_m = roof.length_m();
    const fs::path dir = out / t.name;
    make_output_dir(dir / "textures");

    const auto factors = [&](const std::string& name) {
      return Json{{"name", name},
                  {"pbrMetallicRoughness",
                   {{"baseColorFactor", Json::array({t.base_color.r, t.base_color.g, t.base_color.b, 1.0})},
                    {"metallicFactor", t.metallic},
                    {"roughnessFactor", t.roughness}}}};
    };
    const Json roof_info = {{"period_m", t.period_m}, {"amplitude_m", t.amplitude_m}, {"max_slope_deg", roof.max_slope_deg()}};

    // The real geometry.
    {
      GltfWriter w("svbrdf-bake scene");
      w.set_scene_name(t.name);
      const int mat = w.add_material(factors(t.name));
      w.add_mesh_node(t.name, w.add_mesh(t.name, corrugated_roof(roof), mat));
      add_cameras(w, cams, yfov, d1);
      w.set_scene_extras({{"svbrdf", {{"tile_roof", roof_info}}}});
      const fs::path gltf = dir / (t.name + ".gltf");
      w.write(gltf);
      written.push_back(gltf);
    }
    // The flat proxy: the roof's shading normals at the proxy's texel centres, as its normal map.
    {
      Image normal(t.texture_size, t.texture_size, 3);
      for (int i = 0; i < t.texture_size; ++i) {
        const glm::vec3 n = glm::vec3(roof_mesh_normal(roof, (i + 0.5) * texel));
        const glm::vec3 e = encode_normal(glm::normalize(n));
        for (int j = 0; j < t.texture_size; ++j)
          for (int ch = 0; ch < 3; ++ch) normal.at(i, j, ch) = e[ch];
      }
      const std::string stem = t.name + "-proxy_normal.png";
      write_image(dir / "textures" / stem, normal, PixelFormat::uint16);
      written.push_back(dir / "textures" / stem);
      GltfWriter w("svbrdf-bake scene");
      w.set_scene_name(t.name + "-proxy");
      Json mat = factors(t.name + "-proxy");
      mat["normalTexture"] = {{"index", w.add_texture("textures/" + stem)}};
      const int mi = w.add_material(std::move(mat));
      const TriangleMesh quad = rectangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, roof.length_m(), roof.length_m(), 1.0 / side);
      w.add_mesh_node(t.name + "-proxy", w.add_mesh(t.name + "-proxy quad", quad, mi));
      add_cameras(w, cams, yfov, d1);
      const fs::path gltf = dir / (t.name + "-proxy.gltf");
      w.write(gltf);
      written.push_back(gltf);
    }
    cases.push_back({{"name", t.name},
                     {"kind", "tile-roof"},
                     {"preset", ""},
                     {"variant", ""},
                     {"glossy", false},
                     {"gltf", t.name + "/" + t.name + "-proxy.gltf"},
                     {"reference", t.name + "/" + t.name + ".gltf"},
                     {"max_depth", 1},
                     {"texel_m", texel},
                     {"texture_size", t.texture_size},
                     {"one_texel_per_pixel_m", d1},
                     {"texture_repeats", repeats},
                     {"tile_roof", roof_info},
                     {"views", Json::array({view_value("head-on", cams, "", t.lights.empty() ? all_lights : t.lights)})}});
  }

  manifest["cases"] = std::move(cases);
  const fs::path file = out / "manifest.json";
  write_json_file(file, manifest);
  written.insert(written.begin(), file);
  return written;
}

const LodLightSpec& LodManifest::light(const std::string& name) const {
  for (const LodLightSpec& l : lights)
    if (l.name == name) return l;
  throw input_error((dir / "manifest.json").string(), "no light named \"" + name + "\"");
}

LodManifest read_lod_manifest(const fs::path& file) {
  const JsonDocument doc = JsonDocument::read(file);
  const JsonNode root = doc.root();
  LodManifest m;
  m.dir = fs::absolute(file).parent_path();
  m.image_size = root["image_size"].integer(1, 1 << 15);
  m.yfov_deg = root["yfov_deg"].number(1e-3, 179.0);
  for (const JsonNode& d : root["distances"].items()) m.distances.push_back(d.number(1e-9, 1e9));
  for (const JsonNode& l : root["lights"].items()) {
    LodLightSpec s;
    s.name = l["name"].string();
    s.environment = l["environment"].boolean();
    s.sun = l["sun"].string();
    s.env = l["env"].string();
    if (s.environment) s.env = (m.dir / s.env).string();
    else s.incidence_deg = l["incidence_deg"].number(0.0, 90.0);
    m.lights.push_back(std::move(s));
  }
  for (const JsonNode& c : root["cases"].items()) {
    LodCase k;
    k.name = c["name"].string();
    k.kind = c["kind"].string();
    k.preset = c["preset"].string();
    k.variant = c["variant"].string();
    k.glossy = c["glossy"].boolean();
    k.gltf = m.dir / c["gltf"].string();
    k.reference = m.dir / c["reference"].string();
    k.max_depth = c["max_depth"].integer(0, 1024);
    k.texel_m = c["texel_m"].number(1e-12, 1e3);
    k.texture_size = c["texture_size"].integer(1, 1 << 15);
    k.one_texel_per_pixel_m = c["one_texel_per_pixel_m"].number(1e-12, 1e9);
    for (const JsonNode& vw : c["views"].items()) {
      LodView view;
      view.name = vw["name"].string();
      for (const JsonNode& n : vw["cameras"].items()) view.cameras.push_back(n.string());
      for (const JsonNode& n : vw["lights"].items()) {
        view.lights.push_back(n.string());
        (void)m.light(n.string());  // must exist
      }
      if (view.cameras.size() != m.distances.size()) vw["cameras"].fail("expected one camera per distance");
      k.views.push_back(std::move(view));
    }
    m.cases.push_back(std::move(k));
  }
  return m;
}

}  // namespace svbrdf
