#include "scenes/scene_assembly.h"

#include <cmath>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "base/error.h"
#include "base/math.h"
#include "scenes/geometry.h"
#include "scenes/lod_scenes.h"
#include "scenes/sky.h"
#include "textures/image.h"

namespace svbrdf {

namespace fs = std::filesystem;

void make_output_dir(const fs::path& dir) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw input_error(dir.string(), "exists and is not a directory");
  fs::create_directories(dir, ec);
  if (ec) throw input_error(dir.string(), "cannot create the output directory: " + ec.message());
}

double uv_per_metre(const ProceduralMaterial& m) { return 1000.0 / m.side_mm(); }

int write_material(GltfWriter& writer, const ProceduralMaterial& m, const std::string& name, const fs::path& dir,
                   std::vector<fs::path>& written) {
  make_output_dir(dir / "textures");
  const std::string stems[3] = {name + "_base_color.png", name + "_metallic_roughness.png", name + "_normal.png"};
  // PNG compression is single-threaded: write the three maps at once.
  tbb::parallel_invoke([&] { write_image(dir / "textures" / stems[0], m.base_color, m.base_color_format); },
                       [&] { write_image(dir / "textures" / stems[1], m.metallic_roughness, m.metallic_roughness_format); },
                       [&] { write_image(dir / "textures" / stems[2], m.normal, m.normal_format); });
  int tex[3];
  for (int k = 0; k < 3; ++k) {
    written.push_back(dir / "textures" / stems[k]);
    tex[k] = writer.add_texture("textures/" + stems[k]);
  }
  return writer.add_material(
      {{"name", name},
       {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", tex[0]}}}, {"metallicRoughnessTexture", {{"index", tex[1]}}}}},
       {"normalTexture", {{"index", tex[2]}}},
       {"extras",
        {{"svbrdf",
          {{"preset", m.preset},
           {"variant", m.variant},
           {"seed", m.seed},
           {"size", m.texels.width},
           {"mm_per_texel", m.mm_per_texel}}}}}});
}

namespace {

glm::dquat yaw(double deg) { return glm::angleAxis(deg * kPiD / 180, glm::dvec3(0, 1, 0)); }

std::vector<fs::path> bake_composed(const SceneRecipe& r, const fs::path& out, const ColorConfig& color,
                                    const ProgressFn& progress) {
  make_output_dir(out);
  std::vector<fs::path> written;
  const auto stage = [&](const std::string& s) {
    if (progress) progress(s);
  };

  // The materials, generated in parallel (each family also parallelizes over rows).
  std::vector<ProceduralMaterial> materials(r.materials.size());
  stage("materials");
  tbb::parallel_for(std::size_t(0), r.materials.size(),
                    [&](std::size_t i) { materials[i] = generate_material(r.materials[i].recipe, color); });

  GltfWriter w("svbrdf-bake scene");
  w.set_scene_name(r.name);
  std::vector<int> material_index(r.materials.size());
  stage("textures");
  for (std::size_t i = 0; i < r.materials.size(); ++i)
    material_index[i] = write_material(w, materials[i], r.materials[i].name, out, written);

  for (const SceneObject& o : r.objects) {
    std::size_t mi = 0;
    while (r.materials[mi].name != o.material) ++mi;
    const double k = uv_per_metre(materials[mi]);
    TriangleMesh mesh;
    Placement where;
    where.translation = o.position;
    where.rotation = yaw(o.yaw_deg);
    switch (o.shape) {
      case SceneObject::Shape::box: mesh = box(o.size, k); break;
      case SceneObject::Shape::tray: mesh = tray(o.size, o.rim, o.plate, k); break;
      case SceneObject::Shape::quad:
        // Horizontal, facing +Y: right = +X, up (texture −v) = −Z.
        mesh = rectangle({0, 0, 0}, {1, 0, 0}, {0, 0, -1}, o.size.x, o.size.z, k);
        break;
    }
    w.add_mesh_node(o.name, w.add_mesh(o.name, mesh, material_index[mi]), where);
  }

  for (const CameraRecipe& c : r.cameras) {
    Placement where;
    where.translation = c.position;
    where.rotation = look_rotation(c.target - c.position);
    w.add_camera(c.name, c.yfov_deg * kPiD / 180, c.aspect, 0.01, 0.0, where);
  }
  if (r.sun) w.add_directional_light("sun", r.sun->color, r.sun->irradiance, -r.sun->toward());
  if (r.sky) {
    stage("sky");
    const fs::path sky = out / "sky.hdr";
    write_image(sky, sky_image(r.sky->model, r.sky->width, r.sky->height), PixelFormat::float32);
    written.push_back(sky);
    w.set_scene_extras({{"svbrdf", {{"environment", "sky.hdr"}}}});
  }
  stage("glTF");
  const fs::path gltf = out / (r.name + ".gltf");
  w.write(gltf);
  written.insert(written.begin(), gltf);
  return written;
}

}  // namespace

std::vector<fs::path> bake_scene(const Recipe& recipe, const fs::path& out_dir, const ColorConfig& color,
                                 const ProgressFn& progress) {
  if (recipe.kind == "scene") return bake_composed(recipe.scene, out_dir, color, progress);
  return bake_lod_scenes(recipe.lod, out_dir, color, progress);
}

}  // namespace svbrdf
