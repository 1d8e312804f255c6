#include "textures/texture_set.h"

#include <array>
#include <bit>
#include <charconv>
#include <cstdint>
#include <span>
#include <vector>

#include <tbb/parallel_invoke.h>

#include "base/atomic_file.h"
#include "base/error.h"
#include "textures/sampler.h"

namespace svbrdf {

namespace {

// Shortest decimal that reads back as the same float (std::to_chars): deterministic, and the
// accessor min/max match the buffer's values exactly, as the validator checks.
std::string num(float v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}
std::string num(double v) {
  char buf[40];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// Only our own ASCII names go into the JSON; escape anyway so no name can break it.
std::string json_string(std::string_view s) {
  std::string out(1, '"');
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) continue;
    out += c;
  }
  out += '"';
  return out;
}

void put_u32(std::vector<std::byte>& b, std::uint32_t v) {
  for (int s = 0; s < 32; s += 8) b.push_back(std::byte((v >> s) & 0xffu));
}
void put_f32(std::vector<std::byte>& b, float v) { put_u32(b, std::bit_cast<std::uint32_t>(v)); }
void put_u16(std::vector<std::byte>& b, std::uint16_t v) {
  b.push_back(std::byte(v & 0xffu));
  b.push_back(std::byte(v >> 8));
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  write_bytes_atomically(path, std::as_bytes(std::span(text)));
}

}  // namespace

std::string material_quad_gltf(const ProceduralMaterial& m, const TextureSetFiles& files) {
  const float half = float(m.side_mm() / 2000.0);  // mm → m
  // Vertices counter-clockwise seen from +Z: bottom-left, bottom-right, top-right, top-left.
  // uv (0, 0) is the image's top-left, so v runs down the quad (−Y); the tangent is +X (+u) with
  // w = +1, which makes the bitangent cross(N, T)·w = +Y, the normal map's +Y ("up").
  const std::array<glm::vec3, 4> pos = {glm::vec3(-half, -half, 0), {half, -half, 0}, {half, half, 0}, {-half, half, 0}};
  const std::array<glm::vec2, 4> uv = {glm::vec2(0, 1), {1, 1}, {1, 0}, {0, 0}};
  std::vector<std::byte> bin;
  for (const auto& p : pos)
    for (int c = 0; c < 3; ++c) put_f32(bin, p[c]);
  for (int v = 0; v < 4; ++v) {
    put_f32(bin, 0.0f), put_f32(bin, 0.0f), put_f32(bin, 1.0f);
  }
  for (int v = 0; v < 4; ++v) {
    put_f32(bin, 1.0f), put_f32(bin, 0.0f), put_f32(bin, 0.0f), put_f32(bin, 1.0f);
  }
  for (const auto& t : uv) put_f32(bin, t.x), put_f32(bin, t.y);
  for (std::uint16_t i : {0, 1, 2, 0, 2, 3}) put_u16(bin, i);
  // Pad to a multiple of 4 (glTF: buffer byte lengths need not be aligned, but views are).
  while (bin.size() % 4) bin.push_back(std::byte(0));

  // Appended piece by piece (GCC 12 warns falsely, -Wrestrict PR 105651, on "literal" + std::string).
  std::string j;
  const auto add = [&j](const auto&... parts) { (j.append(parts), ...); };
  const std::string name = m.variant.empty() ? m.preset : m.preset + "-" + m.variant;
  const std::string wrap = std::to_string(gltf_code(WrapMode::repeat));  // the families tile
  add("{\n");
  add("  \"asset\": {\"version\": \"2.0\", \"generator\": \"svbrdf-bake material\"},\n");
  add("  \"scene\": 0,\n");
  add("  \"scenes\": [{\"name\": ", json_string(name), ", \"nodes\": [0]}],\n");
  add("  \"nodes\": [{\"name\": ", json_string(name), ", \"mesh\": 0}],\n");
  add("  \"meshes\": [{\"name\": ", json_string(name + " quad"),
      ", \"primitives\": [{\"attributes\": {\"POSITION\": 0, \"NORMAL\": 1, \"TANGENT\": 2, \"TEXCOORD_0\": 3}, "
      "\"indices\": 4, \"material\": 0, \"mode\": 4}]}],\n");
  add("  \"materials\": [{\n");
  add("    \"name\": ", json_string(name), ",\n");
  add("    \"pbrMetallicRoughness\": {\"baseColorTexture\": {\"index\": 0}, \"metallicRoughnessTexture\": {\"index\": 1}},\n");
  add("    \"normalTexture\": {\"index\": 2, \"scale\": 1},\n");
  add("    \"extras\": {\"svbrdf\": {\"preset\": ", json_string(m.preset), ", \"variant\": ", json_string(m.variant),
      ", \"seed\": ", std::to_string(m.seed), ", \"size\": ", std::to_string(m.texels.width),
      ", \"mm_per_texel\": ", num(m.mm_per_texel), ", \"side_mm\": ", num(m.side_mm()), "}}\n");
  add("  }],\n");
  add("  \"textures\": [{\"sampler\": 0, \"source\": 0}, {\"sampler\": 0, \"source\": 1}, {\"sampler\": 0, \"source\": 2}],\n");
  add("  \"samplers\": [{\"magFilter\": 9729, \"minFilter\": 9987, \"wrapS\": ", wrap, ", \"wrapT\": ", wrap, "}],\n");
  add("  \"images\": [{\"uri\": ", json_string(files.base_color.filename().string()), "}, {\"uri\": ",
      json_string(files.metallic_roughness.filename().string()), "}, {\"uri\": ", json_string(files.normal.filename().string()),
      "}],\n");
  add("  \"buffers\": [{\"byteLength\": ", std::to_string(bin.size()), ", \"uri\": \"data:application/octet-stream;base64,",
      encode_base64(bin), "\"}],\n");
  add("  \"bufferViews\": [\n");
  add("    {\"buffer\": 0, \"byteOffset\": 0, \"byteLength\": 48, \"target\": 34962},\n");
  add("    {\"buffer\": 0, \"byteOffset\": 48, \"byteLength\": 48, \"target\": 34962},\n");
  add("    {\"buffer\": 0, \"byteOffset\": 96, \"byteLength\": 64, \"target\": 34962},\n");
  add("    {\"buffer\": 0, \"byteOffset\": 160, \"byteLength\": 32, \"target\": 34962},\n");
  add("    {\"buffer\": 0, \"byteOffset\": 192, \"byteLength\": 12, \"target\": 34963}\n");
  add("  ],\n");
  add("  \"accessors\": [\n");
  add("    {\"bufferView\": 0, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\", \"min\": [", num(-half), ",",
      num(-half), ",0], \"max\": [", num(half), ",", num(half), ",0]},\n");
  add("    {\"bufferView\": 1, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\"},\n");
  add("    {\"bufferView\": 2, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC4\"},\n");
  add("    {\"bufferView\": 3, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC2\"},\n");
  add("    {\"bufferView\": 4, \"componentType\": 5123, \"count\": 6, \"type\": \"SCALAR\"}\n");
  add("  ]\n");
  add("}\n");
  return j;
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
  write_text(files.gltf, material_quad_gltf(m, files));
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
