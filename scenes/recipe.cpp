#include "scenes/recipe.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "base/error.h"
#include "base/json.h"
#include "base/math.h"

namespace svbrdf {

namespace {

using Node = JsonNode;

glm::dvec3 vec3(const Node& n) {
  const auto v = n.numbers(3);
  return {v[0], v[1], v[2]};
}

glm::dvec3 color(const Node& n) {
  const glm::dvec3 c = vec3(n);
  if (c.x < 0 || c.y < 0 || c.z < 0) n.fail("a color cannot be negative");
  return c;
}

glm::dvec3 positive_size(const Node& n) {
  const glm::dvec3 s = vec3(n);
  if (!(s.x > 0 && s.y > 0 && s.z > 0)) n.fail("sizes must be positive");
  return s;
}

// Names end up in file names and glTF names: keep them plain.
std::string plain_name(const Node& n) {
  const std::string& s = n.string();
  const bool ok = !s.empty() && s.size() <= 64 && std::all_of(s.begin(), s.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
  });
  if (!ok) n.fail("a name must be 1-64 letters, digits, '-' or '_'");
  return s;
}

int power_of_two(const Node& n) {
  const int v = n.integer(1, kMaxMaterialSize);
  if (v & (v - 1)) n.fail("must be a power of two, got " + std::to_string(v));
  return v;
}

// A material recipe: preset, variant, size, seed, mm_per_texel. Checked against the presets here
// so a typo fails before anything is baked.
MaterialRecipe material(const Node& n, int default_size) {
  n.only({"preset", "variant", "size", "seed", "mm_per_texel"});
  MaterialRecipe r;
  r.preset = n["preset"].string();
  const MaterialPreset* preset = nullptr;
  std::string known;
  for (const MaterialPreset& p : material_presets()) {
    if (p.name == r.preset) preset = &p;
    known += (known.empty() ? "" : ", ") + std::string(p.name);
  }
  if (!preset) n["preset"].fail("unknown preset \"" + r.preset + "\" (known: " + known + ")");
  r.variant = n.string_or("variant", "");
  if (!r.variant.empty() && std::find(preset->variants.begin(), preset->variants.end(), r.variant) == preset->variants.end()) {
    known.clear();
    for (auto v : preset->variants) known += (known.empty() ? "" : ", ") + std::string(v);
    n["variant"].fail("unknown variant \"" + r.variant + "\" of " + r.preset + " (known: " + known + ")");
  }
  r.size = n.has("size") ? power_of_two(n["size"]) : default_size;
  r.seed = n.has("seed") ? n["seed"].unsigned_integer() : 1;
  r.mm_per_texel = n.number_or("mm_per_texel", 0.0, 1e-4, 1000.0);
  return r;
}

SkyRecipe sky(const Node& n) {
  n.only({"zenith", "horizon", "ground", "disc", "disc_direction", "disc_radius_deg", "size"});
  SkyRecipe s;
  if (n.has("zenith")) s.model.zenith = color(n["zenith"]);
  if (n.has("horizon")) s.model.horizon = color(n["horizon"]);
  if (n.has("ground")) s.model.ground = color(n["ground"]);
  if (n.has("disc")) s.model.disc = color(n["disc"]);
  if (n.has("disc_direction")) {
    s.model.disc_direction = vec3(n["disc_direction"]);
    if (glm::length(s.model.disc_direction) < 1e-9) n["disc_direction"].fail("must not be zero");
  }
  s.model.disc_radius_deg = n.number_or("disc_radius_deg", s.model.disc_radius_deg, 0.1, 90.0);
  if (n.has("size")) {
    const Node sz = n["size"];
    if (sz.size() != 2) sz.fail("expected [width, height]");
    s.width = sz[0].integer(4, 8192);
    s.height = sz[1].integer(2, 4096);
  }
  return s;
}

SceneRecipe scene(const Node& root) {
  root.only({"kind", "name", "materials", "objects", "sun", "sky", "cameras"});
  SceneRecipe r;
  r.name = plain_name(root["name"]);
  std::set<std::string> material_names;
  for (const auto& [key, node] : root["materials"].members()) {
    NamedMaterial m{key, material(node, 512)};
    if (!material_names.insert(key).second) node.fail("duplicate material name");
    r.materials.push_back(std::move(m));
  }
  if (r.materials.empty()) root["materials"].fail("a scene needs at least one material");
  for (const Node& o : root["objects"].items()) {
    o.only({"name", "shape", "size", "position", "yaw_deg", "rim", "plate", "material"});
    SceneObject obj;
    obj.name = plain_name(o["name"]);
    const std::string& shape = o["shape"].string();
    if (shape == "box") obj.shape = SceneObject::Shape::box;
    else if (shape == "tray") obj.shape = SceneObject::Shape::tray;
    else if (shape == "quad") obj.shape = SceneObject::Shape::quad;
    else o["shape"].fail("unknown shape \"" + shape + "\" (known: box, tray, quad)");
    if (obj.shape == SceneObject::Shape::quad) {
      const auto v = o["size"].numbers(2);
      if (!(v[0] > 0 && v[1] > 0)) o["size"].fail("sizes must be positive");
      obj.size = {v[0], 0.0, v[1]};
    } else {
      obj.size = positive_size(o["size"]);
    }
    obj.position = vec3(o["position"]);
    obj.yaw_deg = o.number_or("yaw_deg", 0.0, -360.0, 360.0);
    obj.rim = o.number_or("rim", obj.rim, 1e-4, 1.0);
    obj.plate = o.number_or("plate", obj.plate, 1e-4, 1.0);
    if (obj.shape == SceneObject::Shape::tray && (2 * obj.rim >= std::min(obj.size.x, obj.size.z) || obj.plate >= obj.size.y))
      o.fail("a tray's rim must be narrower than half its sides and its plate thinner than its height");
    obj.material = o["material"].string();
    if (!material_names.count(obj.material)) o["material"].fail("no material named \"" + obj.material + "\"");
    r.objects.push_back(std::move(obj));
  }
  if (r.objects.empty()) root["objects"].fail("a scene needs at least one object");
  if (root.has("sun")) {
    const Node s = root["sun"];
    s.only({"elevation_deg", "azimuth_deg", "irradiance", "color"});
    SunRecipe sun;
    sun.elevation_deg = s["elevation_deg"].number(-90.0, 90.0);
    sun.azimuth_deg = s["azimuth_deg"].number(-360.0, 360.0);
    sun.irradiance = s["irradiance"].number(0.0, 1e6);
    if (s.has("color")) sun.color = color(s["color"]);
    r.sun = sun;
  }
  if (root.has("sky")) r.sky = sky(root["sky"]);
  std::set<std::string> camera_names;
  for (const Node& c : root["cameras"].items()) {
    c.only({"name", "position", "target", "yfov_deg", "aspect"});
    CameraRecipe cam;
    cam.name = plain_name(c["name"]);
    if (!camera_names.insert(cam.name).second) c["name"].fail("duplicate camera name");
    cam.position = vec3(c["position"]);
    cam.target = vec3(c["target"]);
    if (glm::length(cam.target - cam.position) < 1e-9) c["target"].fail("the target is where the camera stands");
    cam.yfov_deg = c.number_or("yfov_deg", cam.yfov_deg, 1e-3, 179.0);
    cam.aspect = c.number_or("aspect", cam.aspect, 1e-3, 1e3);
    r.cameras.push_back(cam);
  }
  if (r.cameras.empty()) root["cameras"].fail("a scene needs at least one camera");
  return r;
}

LodRecipe lod(const Node& root) {
  root.only({"kind", "name", "image_size", "yfov_deg", "distances", "texture_size", "families", "lights", "mirror_light",
             "sky", "tile_roof"});
  LodRecipe r;
  r.name = plain_name(root["name"]);
  r.image_size = root.integer_or("image_size", r.image_size, 4, 4096);
  r.yfov_deg = root.number_or("yfov_deg", r.yfov_deg, 0.01, 120.0);
  if (root.has("distances")) {
    r.distances.clear();
    for (const Node& d : root["distances"].items()) r.distances.push_back(d.number(1e-3, 1e6));
    if (r.distances.empty()) root["distances"].fail("expected at least one distance");
    if (!std::is_sorted(r.distances.begin(), r.distances.end())) root["distances"].fail("distances must be increasing");
  }
  if (root.has("texture_size")) r.texture_size = power_of_two(root["texture_size"]);
  std::set<std::string> names;
  for (const Node& f : root["families"].items()) {
    f.only({"name", "material", "glossy"});
    LodFamily fam;
    fam.recipe = material(f["material"], r.texture_size);
    fam.name = f.has("name") ? plain_name(f["name"]) : fam.recipe.preset + (fam.recipe.variant.empty() ? "" : "-" + fam.recipe.variant);
    fam.glossy = f.boolean_or("glossy", false);
    if (!names.insert(fam.name).second) f.fail("duplicate family name \"" + fam.name + "\"");
    r.families.push_back(std::move(fam));
  }
  std::set<std::string> light_names;
  for (const Node& l : root["lights"].items()) {
    l.only({"name", "incidence_deg", "irradiance", "environment"});
    LodLight light;
    light.name = plain_name(l["name"]);
    if (!light_names.insert(light.name).second) l["name"].fail("duplicate light name");
    light.environment = l.boolean_or("environment", false);
    if (light.environment) {
      if (l.has("incidence_deg") || l.has("irradiance")) l.fail("an environment light takes no incidence or irradiance");
    } else {
      light.incidence_deg = l["incidence_deg"].number(0.0, 89.0);
      light.irradiance = l.number_or("irradiance", 1.0, 1e-6, 1e6);
    }
    r.lights.push_back(light);
  }
  if (r.lights.empty()) root["lights"].fail("expected at least one light");
  if (root.has("mirror_light")) {
    r.mirror_light = root["mirror_light"].string();
    const auto it = std::find_if(r.lights.begin(), r.lights.end(), [&](const LodLight& l) { return l.name == r.mirror_light; });
    if (it == r.lights.end() || it->environment || it->incidence_deg < 1.0)
      root["mirror_light"].fail("must name a directional light with incidence ≥ 1°");
  }
  if (root.has("sky")) r.sky = sky(root["sky"]);
  if (root.has("tile_roof")) {
    const Node t = root["tile_roof"];
    t.only({"name", "period_m", "amplitude_m", "segments", "texels_per_period", "texture_size", "base_color", "roughness",
            "metallic", "lights"});
    TileRoofRecipe roof;
    if (t.has("name")) roof.name = plain_name(t["name"]);
    if (names.count(roof.name)) t["name"].fail("the tile roof's name is taken by a family");
    roof.period_m = t.number_or("period_m", roof.period_m, 1e-4, 100.0);
    roof.amplitude_m = t.number_or("amplitude_m", roof.amplitude_m, 0.0, 100.0);
    roof.segments = t.integer_or("segments", roof.segments, 2, 1024);
    roof.texels_per_period = t.integer_or("texels_per_period", roof.texels_per_period, 2, 4096);
    roof.texture_size = t.has("texture_size") ? power_of_two(t["texture_size"]) : r.texture_size;
    if (roof.texture_size % roof.texels_per_period)
      t.fail("texture_size must be a multiple of texels_per_period, so the normal map tiles");
    if (t.has("base_color")) roof.base_color = color(t["base_color"]);
    roof.roughness = t.number_or("roughness", roof.roughness, 0.0, 1.0);
    roof.metallic = t.number_or("metallic", roof.metallic, 0.0, 1.0);
    if (t.has("lights"))
      for (const Node& l : t["lights"].items()) {
        if (!light_names.count(l.string())) l.fail("no light named \"" + l.string() + "\"");
        roof.lights.push_back(l.string());
      }
    r.tile_roof = roof;
  }
  if (r.families.empty() && !r.tile_roof) root["families"].fail("expected at least one family or a tile_roof");
  return r;
}

Recipe from_document(const JsonDocument& doc) {
  const Node root = doc.root();
  if (!root.is_object()) root.fail("a recipe is a JSON object");
  Recipe r;
  r.file = doc.name();
  r.kind = root["kind"].string();
  if (r.kind == "scene") r.scene = scene(root);
  else if (r.kind == "lod") r.lod = lod(root);
  else root["kind"].fail("unknown kind \"" + r.kind + "\" (known: scene, lod)");
  return r;
}

}  // namespace

glm::dvec3 SunRecipe::toward() const {
  const double e = elevation_deg * kPiD / 180, a = azimuth_deg * kPiD / 180;
  return {std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a)};
}

Recipe read_recipe(const std::string& path) { return from_document(JsonDocument::read(path)); }
Recipe parse_recipe(const std::string& text, const std::string& name) { return from_document(JsonDocument::parse(text, name)); }

}  // namespace svbrdf
