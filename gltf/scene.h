#pragma once
// A glTF scene as the renderer holds it (DESIGN.md, "Data through the house", step 1): triangle
// meshes with their vertex attributes already decoded and checked, instances of them with their
// world transforms, materials, textures and their images, cameras and punctual lights, all in world
// space. Built by load_gltf (gltf/scene_reader.h); nothing in it refers back to tinygltf.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "base/sha256.h"
#include "gltf/material_desc.h"
#include "textures/image.h"
#include "textures/sampler.h"

namespace svbrdf {

// One glTF primitive as triangles. Attributes are per vertex; indices three per triangle.
struct MeshPrimitive {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;   // always present (generated flat when the file has none)
  std::vector<glm::vec4> tangents;  // xyz + bitangent sign w; empty when neither given nor needed
  std::vector<glm::vec2> texcoords[2];  // TEXCOORD_0/1; empty when absent
  std::vector<glm::vec4> colors;        // COLOR_0 as RGBA (linear); empty = white
  std::vector<std::uint32_t> indices;
  int material = -1;  // −1: the glTF default material
  std::string where;  // "meshes[2].primitives[0]"

  std::size_t triangle_count() const { return indices.size() / 3; }
};

struct Mesh {
  std::string name;
  std::vector<MeshPrimitive> primitives;
};

// A node that references a mesh: the mesh placed in the world.
struct Instance {
  int mesh = -1;
  int node = -1;
  glm::dmat4 to_world{1.0};
};

struct TextureDesc {
  int image = -1;  // index into Scene::images
  Sampler sampler;  // the glTF sampler's wrap modes and filter (textures/sampler.h)
  std::string where;  // "textures[4]"
};

// An image as decoded from the file: values as stored (no color conversion), rows from the top.
struct ImageDesc {
  std::string name;
  std::string uri;        // empty for images in a buffer view or a data URI
  std::string mime_type;  // from the file, or guessed from the uri's extension
  std::string where;      // "images[3]"
  Image pixels;
  // SHA-256 of the encoded bytes the pixels were decoded from (the file, data: URI or buffer view):
  // what the MIP cache's key hashes instead of the decoded floats, 4 to 16 times fewer bytes. Absent
  // for an image made in memory.
  std::optional<Sha256Digest> encoded_digest;
};

struct CameraMotion;  // gltf/animation.h

struct CameraDesc {
  enum class Type { perspective, orthographic };
  std::string name;  // the camera's name, else its node's
  Type type = Type::perspective;
  float yfov = 0.7f;          // radians (perspective)
  float aspect_ratio = 0.0f;  // 0 when the file gives none
  float xmag = 1.0f, ymag = 1.0f;  // half extents (orthographic)
  float znear = 0.0f, zfar = 0.0f;
  glm::dmat4 to_world{1.0};  // the camera looks along its local −Z with +Y up; the static pose
  int node = -1;
  // What the file's animations do to the node and its ancestors (LoadOptions::camera_animation); null
  // when they were not read or no animation moves the camera.
  std::shared_ptr<const CameraMotion> motion;
};

// KHR_lights_punctual, in world space, in the renderer's radiometric units: a directional light's
// `intensity` is the irradiance (W/m²) it delivers to a surface facing it, a point or spot light's its
// radiant intensity (W/sr). The file's photometric values (lux, candela) are converted on reading
// (gltf/scene_reader.h).
struct LightDesc {
  enum class Type { directional, point, spot };
  std::string name;
  Type type = Type::point;
  Rgb color{1.0f};
  float intensity = 1.0f;
  float range = 0.0f;  // 0: infinite
  float inner_cone = 0.0f, outer_cone = 0.7853982f;  // radians (spot)
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // the direction light travels (local −Z)
  int node = -1;
};

struct Scene {
  std::filesystem::path file;
  std::vector<Mesh> meshes;
  std::vector<Instance> instances;
  std::vector<MaterialDesc> materials;
  std::vector<TextureDesc> textures;
  std::vector<ImageDesc> images;
  std::vector<CameraDesc> cameras;
  std::vector<LightDesc> lights;
  // Messages worth one line each (an optional extension we ignore, degenerate triangles skipped).
  std::vector<std::string> warnings;

  // The material a primitive uses: its own, or glTF's default material.
  const MaterialDesc& material_of(const MeshPrimitive& p) const {
    return p.material >= 0 ? materials[static_cast<std::size_t>(p.material)] : default_material;
  }
  MaterialDesc default_material = [] {
    MaterialDesc m;
    m.name = "default";
    m.where = "the default material";
    return m;
  }();
};

}  // namespace svbrdf
