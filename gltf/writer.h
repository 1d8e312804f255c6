#pragma once
// Writing glTF 2.0 scenes (the scene assembler's output): meshes with positions, normals, tangents
// and uvs, metallic-roughness materials, perspective cameras, KHR_lights_punctual directional
// lights, and nodes placing them. The geometry goes into one binary buffer, embedded as a data: URI
// when small and written beside the .gltf as NAME.bin otherwise. What it writes passes the Khronos
// glTF validator with no error and no warning (tests/lod checks every scene the recipes make):
// each accessor has its own 4-byte-aligned buffer view, POSITION carries min/max, normals and
// tangents are unit, indices are 16-bit when they fit.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "base/json.h"

namespace svbrdf {

// A triangle mesh as the writer takes it: per-vertex attributes, three indices per triangle,
// counter-clockwise seen from the front. Tangents are glTF's (xyz unit along +u, w = ±1 with the
// bitangent cross(normal, tangent)·w pointing toward −v, the normal map's +Y).
struct TriangleMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec4> tangents;
  std::vector<glm::vec2> uvs;
  std::vector<std::uint32_t> indices;

  // Appends another mesh's vertices and triangles.
  void append(const TriangleMesh& other);
};

// A node's placement: translation, then rotation (unit quaternion), then uniform scale 1.
struct Placement {
  glm::dvec3 translation{0.0};
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};  // (w, x, y, z)
};

// The rotation that turns a camera's or light's local −Z toward `forward` with local +Y as close
// to `up` as possible (glTF cameras and lights look and shine along local −Z).
glm::dquat look_rotation(const glm::dvec3& forward, const glm::dvec3& up = {0.0, 1.0, 0.0});

class GltfWriter {
 public:
  explicit GltfWriter(std::string generator);

  // An image file next to the .gltf (uri relative to it) and a texture sampling it with repeat
  // wrapping and trilinear filtering; returns the texture index.
  int add_texture(const std::string& uri);
  // A material (a glTF material object, built by the caller); returns its index.
  int add_material(Json material);
  // A mesh of one primitive; returns the mesh index. Throws svbrdf::Error (internal) when the
  // attribute arrays disagree in length, an index is out of range or a normal is not unit.
  int add_mesh(const std::string& name, const TriangleMesh& mesh, int material);
  // A node holding a mesh; returns the node index. Nodes are roots of the scene.
  int add_mesh_node(const std::string& name, int mesh, const Placement& where = {});
  // A perspective camera (yfov radians, aspect width/height) and its node; returns the camera index.
  // `extras` (an object, or null for none) becomes the camera's extras.
  int add_camera(const std::string& name, double yfov, double aspect, double znear, double zfar, const Placement& where,
                 Json extras = nullptr);
  // A KHR_lights_punctual directional light of `irradiance` W/m² on a surface facing it (the
  // renderer's units; written in lux, irradiance × kLumensPerWatt, as the extension defines it)
  // shining along `direction` (the way the light travels).
  int add_directional_light(const std::string& name, const glm::dvec3& color, double irradiance,
                            const glm::dvec3& direction);
  // The scene's extras (e.g. the sky the renderer should use).
  void set_scene_extras(Json extras) { scene_extras_ = std::move(extras); }
  void set_scene_name(std::string name) { scene_name_ = std::move(name); }

  // Writes path (.gltf) and, when the buffer is larger than `embed_limit` bytes, path's stem + .bin
  // beside it (first, so the .gltf never names a missing file); both atomically.
  void write(const std::filesystem::path& path, std::size_t embed_limit = 1 << 16) const;
  // The document alone, with the buffer under `buffer_uri` (for tests; write() calls it).
  Json document(const std::string& buffer_uri) const;
  std::span<const std::byte> buffer() const { return bin_; }

 private:
  int add_accessor(std::span<const std::byte> bytes, int component_type, int count, const char* type, int target,
                   Json min = nullptr, Json max = nullptr);

  std::string generator_;
  std::string scene_name_ = "scene";
  std::vector<std::byte> bin_;
  Json buffer_views_ = Json::array(), accessors_ = Json::array();
  Json images_ = Json::array(), textures_ = Json::array();
  Json materials_ = Json::array(), meshes_ = Json::array();
  Json nodes_ = Json::array(), cameras_ = Json::array(), lights_ = Json::array();
  Json scene_extras_;
};

}  // namespace svbrdf
