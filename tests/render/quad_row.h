#pragma once
// GlTF scenes of textured quads for the out-of-core tests (texture_cache_test.cpp, mip_tiles_test.cpp,
// texture_cache_warm_test.cpp).
#include <filesystem>
#include <string>

#include "base/json.h"
#include "gltf/writer.h"
#include "scenes/texture_set.h"
#include "textures/image.h"

namespace svbrdf::testing {

// `count` quads side by side, eight a row, each with its own base colour texture of side² texels
// (8-bit RGBA PNG, smooth so that the files are small: the encoded bytes the reader holds stay out of
// the measure), or none (`textured` false: the baseline); unlit (the texture read as it is) or lit (a
// material the MIP filters take part in).
inline std::filesystem::path quads(const std::filesystem::path& dir, int count, int side, bool textured,
                                   bool unlit = true) {
  GltfWriter w("svbrdf texture cache test");
  TriangleMesh quad;
  quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  quad.normals.assign(4, glm::vec3(0, 0, 1));
  quad.uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  for (int k = 0; k < count; ++k) {
    Json material = unlit ? Json{{"extensions", {{"KHR_materials_unlit", Json::object()}}}} : Json::object();
    if (textured) {
      Image im(side, side, 4);
      for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
          im.at(i, j, 0) = float((i + k) % 256) / 255.0f;
          im.at(i, j, 1) = float((j + 3 * k) % 256) / 255.0f;
          im.at(i, j, 2) = float((i + j) % 256) / 255.0f;
          im.at(i, j, 3) = 1.0f;
        }
      // Appended piece by piece: GCC 12 warns falsely (-Wrestrict, PR 105651) on "t" + std::string.
      std::string name = "t";
      name += std::to_string(k);
      name += ".png";
      write_image(dir / name, im, PixelFormat::uint8);
      material["pbrMetallicRoughness"] = {{"baseColorTexture", {{"index", w.add_texture(name)}}}};
    }
    const int mesh = w.add_mesh("quad" + std::to_string(k), quad, w.add_material(material));
    Placement at;
    at.translation = {double(k % 8), double(k / 8), 0.0};
    w.add_mesh_node("quad" + std::to_string(k), mesh, at);
  }
  const std::filesystem::path path = dir / (textured ? "textured.gltf" : "plain.gltf");
  w.write(path);
  return path;
}

// A baked material on a quad, 64² texels, seed 3: metal-tray's textures are 16-bit (the cache's float
// files), sandstone's base colour 8-bit (its codes and their tables).
inline std::filesystem::path baked_quad(const std::filesystem::path& dir, const std::string& preset) {
  MaterialRecipe r;
  r.preset = preset;
  r.size = 64;
  r.seed = 3;
  return bake_material(r, dir / preset).gltf;
}

}  // namespace svbrdf::testing
