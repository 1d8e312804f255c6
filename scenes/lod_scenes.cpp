#include "scenes/lod_scenes.h"

#include <algorithm>
#include <cmath>

#include "base/error.h"
#include "base/math.h"
#include "scenes/geometry.h"
#include "scenes/gltf_writer.h"
#include "scenes/json.h"
#include "scenes/scene_assembly.h"
#include "scenes/sky.h"
#include "textures/image.h"
#include "textures/normal_map.h"

namespace svbrdf {

namespace fs = std::filesystem;
using json::Value;

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

std::string camera_name(const std::string& prefix, double k) { return prefix + "d" + json::number_text(k); }

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
    Value extras = Value::object();
    Value info = Value::object();
    info.set("lod_multiple", Value::of(c.multiple));
    info.set("one_texel_per_pixel_m", Value::of(d1));
    extras.set("svbrdf", std::move(info));
    const double dist = glm::length(c.position);
    w.add_camera(c.name, yfov, 1.0, 0.01 * dist, 0.0, where, std::move(extras));
  }
}

Value string_array(const std::vector<std::string>& v) {
  Value a = Value::array();
  for (const auto& s : v) a.push(Value::of(s));
  return a;
}

Value view_value(const std::string& name, const std::vector<LodCamera>& cams, const std::string& prefix,
                 const std::vector<std::string>& lights) {
  Value v = Value::object();
  v.set("name", Value::of(name));
  std::vector<std::string> names;
  for (const LodCamera& c : cams)
    if (c.name.rfind(prefix + "d", 0) == 0) names.push_back(c.name);
  v.set("cameras", string_array(names));
  v.set("lights", string_array(lights));
  return v;
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

  Value manifest = Value::object();
  manifest.set("generator", Value::of("svbrdf-bake scene"));
  manifest.set("recipe", Value::of(r.name));
  manifest.set("image_size", Value::of(r.image_size));
  manifest.set("yfov_deg", Value::of(r.yfov_deg));
  manifest.set("distances", Value::numbers(r.distances));
  Value lights = Value::array();
  std::vector<std::string> all_lights;
  const LodLight* mirror = nullptr;
  for (const LodLight& l : r.lights) {
    Value v = Value::object();
    v.set("name", Value::of(l.name));
    v.set("environment", Value::of(l.environment));
    if (l.environment) {
      v.set("sun", Value::of(""));
      v.set("env", Value::of("sky.hdr"));
    } else {
      v.set("incidence_deg", Value::of(l.incidence_deg));
      v.set("sun", Value::of("0," + json::number_text(l.incidence_deg) + "," + json::number_text(l.irradiance)));
      v.set("env", Value::of("0,0,0"));
    }
    lights.push(std::move(v));
    all_lights.push_back(l.name);
    if (l.name == r.mirror_light) mirror = &l;
  }
  manifest.set("lights", std::move(lights));
  Value cases = Value::array();

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

    Value c = Value::object();
    c.set("name", Value::of(fam.name));
    c.set("kind", Value::of("family"));
    c.set("preset", Value::of(m.preset));
    c.set("variant", Value::of(m.variant));
    c.set("glossy", Value::of(fam.glossy));
    c.set("gltf", Value::of(fam.name + "/" + fam.name + ".gltf"));
    c.set("reference", Value::of(fam.name + "/" + fam.name + ".gltf"));
    c.set("max_depth", Value::of(16));
    c.set("texel_m", Value::of(texel));
    c.set("texture_size", Value::of(m.texels.width));
    c.set("one_texel_per_pixel_m", Value::of(d1));
    c.set("texture_repeats", Value::of(repeats));
    Value views = Value::array();
    views.push(view_value("head-on", cams, "", all_lights));
    if (fam.glossy && mirror) views.push(view_value("mirror", cams, "mirror-", {mirror->name}));
    c.set("views", std::move(views));
    cases.push(std::move(c));
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
      Value mat = Value::object();
      mat.set("name", Value::of(name));
      Value pbr = Value::object();
      pbr.set("baseColorFactor", Value::numbers({t.base_color.r, t.base_color.g, t.base_color.b, 1.0}));
      pbr.set("metallicFactor", Value::of(t.metallic));
      pbr.set("roughnessFactor", Value::of(t.roughness));
      mat.set("pbrMetallicRoughness", std::move(pbr));
      return mat;
    };
    Value roof_info = Value::object();
    roof_info.set("period_m", Value::of(t.period_m));
    roof_info.set("amplitude_m", Value::of(t.amplitude_m));
    roof_info.set("max_slope_deg", Value::of(roof.max_slope_deg()));

    // The real geometry.
    {
      GltfWriter w("svbrdf-bake scene");
      w.set_scene_name(t.name);
      const int mat = w.add_material(factors(t.name));
      w.add_mesh_node(t.name, w.add_mesh(t.name, corrugated_roof(roof), mat));
      add_cameras(w, cams, yfov, d1);
      Value extras = Value::object();
      extras.set("svbrdf", Value::object()).set("tile_roof", roof_info);
      w.set_scene_extras(std::move(extras));
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
      Value mat = factors(t.name + "-proxy");
      mat.set("normalTexture", Value::object()).set("index", Value::of(w.add_texture("textures/" + stem)));
      const int mi = w.add_material(std::move(mat));
      const TriangleMesh quad = rectangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, roof.length_m(), roof.length_m(), 1.0 / side);
      w.add_mesh_node(t.name + "-proxy", w.add_mesh(t.name + "-proxy quad", quad, mi));
      add_cameras(w, cams, yfov, d1);
      const fs::path gltf = dir / (t.name + "-proxy.gltf");
      w.write(gltf);
      written.push_back(gltf);
    }
    Value c = Value::object();
    c.set("name", Value::of(t.name));
    c.set("kind", Value::of("tile-roof"));
    c.set("preset", Value::of(""));
    c.set("variant", Value::of(""));
    c.set("glossy", Value::of(false));
    c.set("gltf", Value::of(t.name + "/" + t.name + "-proxy.gltf"));
    c.set("reference", Value::of(t.name + "/" + t.name + ".gltf"));
    c.set("max_depth", Value::of(1));
    c.set("texel_m", Value::of(texel));
    c.set("texture_size", Value::of(t.texture_size));
    c.set("one_texel_per_pixel_m", Value::of(d1));
    c.set("texture_repeats", Value::of(repeats));
    c.set("tile_roof", roof_info);
    Value views = Value::array();
    views.push(view_value("head-on", cams, "", t.lights.empty() ? all_lights : t.lights));
    c.set("views", std::move(views));
    cases.push(std::move(c));
  }

  manifest.set("cases", std::move(cases));
  const fs::path file = out / "manifest.json";
  json::write_file(file, manifest);
  written.insert(written.begin(), file);
  return written;
}

const LodLightSpec& LodManifest::light(const std::string& name) const {
  for (const LodLightSpec& l : lights)
    if (l.name == name) return l;
  throw input_error((dir / "manifest.json").string(), "no light named \"" + name + "\"");
}

LodManifest read_lod_manifest(const fs::path& file) {
  const json::Value v = json::parse_file(file.string());
  const json::Node root(v, file.string());
  LodManifest m;
  m.dir = fs::absolute(file).parent_path();
  m.image_size = root["image_size"].integer(1, 1 << 15);
  m.yfov_deg = root["yfov_deg"].number(1e-3, 179.0);
  for (const json::Node& d : root["distances"].items()) m.distances.push_back(d.number(1e-9, 1e9));
  for (const json::Node& l : root["lights"].items()) {
    LodLightSpec s;
    s.name = l["name"].string();
    s.environment = l["environment"].boolean();
    s.sun = l["sun"].string();
    s.env = l["env"].string();
    if (s.environment) s.env = (m.dir / s.env).string();
    else s.incidence_deg = l["incidence_deg"].number(0.0, 90.0);
    m.lights.push_back(std::move(s));
  }
  for (const json::Node& c : root["cases"].items()) {
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
    for (const json::Node& vw : c["views"].items()) {
      LodView view;
      view.name = vw["name"].string();
      for (const json::Node& n : vw["cameras"].items()) view.cameras.push_back(n.string());
      for (const json::Node& n : vw["lights"].items()) {
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
