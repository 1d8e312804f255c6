#include "scenes/texture_set.h"

#include <array>

#include <tbb/parallel_invoke.h>

#include "base/error.h"

namespace svbrdf {

GltfWriter material_quad_gltf(const ProceduralMaterial& m, const TextureSetFiles& files) {
  const float half = float(m.side_mm() / 2000.0);  // mm → m
  // Vertices counter-clockwise seen from +Z: bottom-left, bottom-right, top-right, top-left.
  // uv (0, 0) is the image's top-left, so v runs down the quad (−Y); the tangent is +X (+u) with
  // w = +1, which makes the bitangent cross(N, T)·w = +Y, the normal map's +Y ("up").
  TriangleMesh quad;
  quad.positions = {glm::vec3(-half, -half, 0), {half, -half, 0}, {half, half, 0}, {-half, half, 0}};
  quad.normals.assign(4, glm::vec3(0, 0, 1));
  quad.tangents.assign(4, glm::vec4(1, 0, 0, 1));
  quad.uvs = {glm::vec2(0, 1), {1, 1}, {1, 0}, {0, 0}};
  quad.indices = {0, 1, 2, 0, 2, 3};

  const std::string name = m.variant.empty() ? m.preset : m.preset + "-" + m.variant;
  GltfWriter w("svbrdf-bake material");
  w.set_scene_name(name);
  // The writer's textures repeat, as the families tile.
  const int base_color = w.add_texture(files.base_color.filename().string());
  const int metallic_roughness = w.add_texture(files.metallic_roughness.filename().string());
  const int normal = w.add_texture(files.normal.filename().string());
  const int material = w.add_material(
      {{"name", name},
       {"pbrMetallicRoughness",
        {{"baseColorTexture", {{"index", base_color}}}, {"metallicRoughnessTexture", {{"index", metallic_roughness}}}}},
       {"normalTexture", {{"index", normal}, {"scale", 1}}},
       {"extras",
        {{"svbrdf",
          {{"preset", m.preset}, {"variant", m.variant}, {"seed", m.seed}, {"size", m.texels.width},
           {"mm_per_texel", m.mm_per_texel}, {"side_mm", m.side_mm()}}}}}});
  w.add_mesh_node(name, w.add_mesh(name + " quad", quad, material));
  return w;
}

TextureSetFiles write_texture_set(const ProceduralMaterial& m, const std::filesystem::path& dir, const ProgressFn& progress) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw input_error(dir.string(), "exists and is not a directory");
  fs::create_directories(dir, ec);
  if (ec) throw input_error(dir.string(), "cannot create the output directory: " + ec.message());
  TextureSetFiles files{dir / (m.preset + ".gltf"), dir / (m.preset + "_base_color.png"),
                        dir / (m.preset + "_metallic_roughness.png"), dir / (m.preset + "_normal.png")};
  const auto stage = [&](std::string_view s) {
    if (progress) progress(s);
  };
  // PNG compression is single-threaded: write the three images at once.
  stage("writing images");
  tbb::parallel_invoke([&] { write_image(files.base_color, m.base_color, m.base_color_format); },
                       [&] { write_image(files.metallic_roughness, m.metallic_roughness, m.metallic_roughness_format); },
                       [&] { write_image(files.normal, m.normal, m.normal_format); });
  stage("writing glTF");
  material_quad_gltf(m, files).write(files.gltf);
  return files;
}

TextureSetFiles bake_material(const MaterialRecipe& recipe, const std::filesystem::path& dir, const ColorConfig& color,
                              const ProgressFn& progress) {
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec))
    throw input_error(dir.string(), "exists and is not a directory");
  return write_texture_set(generate_material(recipe, color, progress), dir, progress);
}

}  // namespace svbrdf
