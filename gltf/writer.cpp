#include "gltf/writer.h"

#include <cmath>
#include <limits>
#include <span>

#include "base/atomic_file.h"
#include "base/error.h"
#include "gltf/scene_reader.h"
#include "textures/image.h"

namespace svbrdf {

namespace {

constexpr int kFloat = 5126, kUnsignedShort = 5123, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

template <class T>
std::span<const std::byte> bytes_of(std::span<const T> v) {
  return std::as_bytes(v);
}

// A node's translation and rotation members, each only when it is not the identity.
void place(Json& node, const Placement& p) {
  if (p.translation != glm::dvec3(0.0)) node["translation"] = Json::array({p.translation.x, p.translation.y, p.translation.z});
  const glm::dquat q = glm::normalize(p.rotation);
  if (q != glm::dquat(1.0, 0.0, 0.0, 0.0))
    node["rotation"] = Json::array({double(float(q.x)), double(float(q.y)), double(float(q.z)), double(float(q.w))});
}

void internal(const std::string& what) { throw Error("glTF writer: " + what, Error::Kind::internal); }

// The index the next item appended to `array` will have.
int next_index(const Json& array) { return int(array.size()); }

}  // namespace

void TriangleMesh::append(const TriangleMesh& o) {
  const auto base = static_cast<std::uint32_t>(positions.size());
  positions.insert(positions.end(), o.positions.begin(), o.positions.end());
  normals.insert(normals.end(), o.normals.begin(), o.normals.end());
  tangents.insert(tangents.end(), o.tangents.begin(), o.tangents.end());
  uvs.insert(uvs.end(), o.uvs.begin(), o.uvs.end());
  for (std::uint32_t i : o.indices) indices.push_back(base + i);
}

glm::dquat look_rotation(const glm::dvec3& forward, const glm::dvec3& up) {
  const glm::dvec3 f = glm::normalize(forward);
  glm::dvec3 r = glm::cross(f, up);
  if (glm::length(r) < 1e-9) r = glm::cross(f, std::abs(f.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1));
  r = glm::normalize(r);
  const glm::dvec3 u = glm::cross(r, f);
  // Columns: where local +X, +Y, +Z go; local −Z must go to f.
  return glm::normalize(glm::quat_cast(glm::dmat3(r, u, -f)));
}

GltfWriter::GltfWriter(std::string generator) : generator_(std::move(generator)) {}

int GltfWriter::add_accessor(std::span<const std::byte> bytes, int component_type, int count, const char* type,
                             int target, Json min, Json max) {
  while (bin_.size() % 4) bin_.push_back(std::byte{0});
  const std::size_t offset = bin_.size();
  bin_.insert(bin_.end(), bytes.begin(), bytes.end());
  buffer_views_.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes.size()}, {"target", target}});
  Json accessor = {{"bufferView", next_index(buffer_views_) - 1}, {"componentType", component_type}, {"count", count}, {"type", type}};
  if (!min.is_null()) accessor["min"] = std::move(min);
  if (!max.is_null()) accessor["max"] = std::move(max);
  accessors_.push_back(std::move(accessor));
  return next_index(accessors_) - 1;
}

// Every texture uses sampler 0 (written by document()): repeat, as the families tile.
int GltfWriter::add_texture(const std::string& uri) {
  images_.push_back({{"uri", uri}});
  textures_.push_back({{"sampler", 0}, {"source", next_index(images_) - 1}});
  return next_index(textures_) - 1;
}

int GltfWriter::add_material(Json material) {
  materials_.push_back(std::move(material));
  return next_index(materials_) - 1;
}

int GltfWriter::add_mesh(const std::string& name, const TriangleMesh& m, int material) {
  const std::size_t n = m.positions.size();
  if (n == 0 || m.indices.empty() || m.indices.size() % 3) internal(name + ": empty mesh or indices not in threes");
  if (m.normals.size() != n || (!m.tangents.empty() && m.tangents.size() != n) || (!m.uvs.empty() && m.uvs.size() != n))
    internal(name + ": attribute arrays of different lengths");
  for (std::uint32_t i : m.indices)
    if (i >= n) internal(name + ": index past the vertex count");
  // The validator's tolerance for unit vectors is 5e-4 (ACCESSOR_VECTOR3_NON_UNIT); ours is tighter.
  for (const glm::vec3& v : m.normals)
    if (std::abs(glm::length(v) - 1.0f) > 1e-5f) internal(name + ": a normal is not unit");
  for (const glm::vec4& t : m.tangents)
    if (std::abs(glm::length(glm::vec3(t)) - 1.0f) > 1e-5f || std::abs(std::abs(t.w) - 1.0f) > 0.0f)
      internal(name + ": a tangent is not unit or its w is not ±1");

  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const glm::vec3& p : m.positions) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) internal(name + ": a position is not finite");
    lo = glm::min(lo, p), hi = glm::max(hi, p);
  }
  Json attributes = Json::object();
  attributes["POSITION"] = add_accessor(bytes_of(std::span(m.positions)), kFloat, int(n), "VEC3", kArrayBuffer,
                                        Json::array({lo.x, lo.y, lo.z}), Json::array({hi.x, hi.y, hi.z}));
  attributes["NORMAL"] = add_accessor(bytes_of(std::span(m.normals)), kFloat, int(n), "VEC3", kArrayBuffer);
  if (!m.tangents.empty())
    attributes["TANGENT"] = add_accessor(bytes_of(std::span(m.tangents)), kFloat, int(n), "VEC4", kArrayBuffer);
  if (!m.uvs.empty())
    attributes["TEXCOORD_0"] = add_accessor(bytes_of(std::span(m.uvs)), kFloat, int(n), "VEC2", kArrayBuffer);
  int indices = 0;
  if (n <= 65535) {  // 65535 is primitive restart in some APIs; glTF forbids it as an index value
    std::vector<std::uint16_t> i16(m.indices.begin(), m.indices.end());
    indices = add_accessor(bytes_of(std::span<const std::uint16_t>(i16)), kUnsignedShort, int(i16.size()), "SCALAR",
                           kElementArrayBuffer);
  } else {
    indices = add_accessor(bytes_of(std::span(m.indices)), kUnsignedInt, int(m.indices.size()), "SCALAR", kElementArrayBuffer);
  }
  Json primitive = {{"attributes", std::move(attributes)}, {"indices", indices}};
  if (material >= 0) primitive["material"] = material;
  primitive["mode"] = 4;
  meshes_.push_back({{"name", name}, {"primitives", Json::array({std::move(primitive)})}});
  return next_index(meshes_) - 1;
}

int GltfWriter::add_mesh_node(const std::string& name, int mesh, const Placement& where) {
  Json node = {{"name", name}, {"mesh", mesh}};
  place(node, where);
  nodes_.push_back(std::move(node));
  return next_index(nodes_) - 1;
}

int GltfWriter::add_camera(const std::string& name, double yfov, double aspect, double znear, double zfar,
                           const Placement& where, Json extras) {
  Json perspective = {{"aspectRatio", aspect}, {"yfov", yfov}, {"znear", znear}};
  if (zfar > 0.0) perspective["zfar"] = zfar;
  Json camera = {{"name", name}, {"type", "perspective"}, {"perspective", std::move(perspective)}};
  if (!extras.is_null()) camera["extras"] = std::move(extras);
  cameras_.push_back(std::move(camera));
  Json node = {{"name", name}, {"camera", next_index(cameras_) - 1}};
  place(node, where);
  nodes_.push_back(std::move(node));
  return next_index(cameras_) - 1;
}

int GltfWriter::add_directional_light(const std::string& name, const glm::dvec3& color, double irradiance,
                                      const glm::dvec3& direction) {
  lights_.push_back({{"name", name}, {"type", "directional"}, {"color", Json::array({color.r, color.g, color.b})},
                     {"intensity", irradiance * kLumensPerWatt}});  // lux, as KHR_lights_punctual defines it
  Json node = {{"name", name}};
  Placement p;
  p.rotation = look_rotation(direction, std::abs(glm::normalize(direction).y) > 0.99 ? glm::dvec3(0, 0, -1) : glm::dvec3(0, 1, 0));
  place(node, p);
  node["extensions"] = {{"KHR_lights_punctual", {{"light", next_index(lights_) - 1}}}};
  nodes_.push_back(std::move(node));
  return next_index(lights_) - 1;
}

Json GltfWriter::document(const std::string& buffer_uri) const {
  Json doc = {{"asset", {{"version", "2.0"}, {"generator", generator_}}}};
  if (!lights_.empty()) doc["extensionsUsed"] = Json::array({"KHR_lights_punctual"});
  doc["scene"] = 0;
  Json roots = Json::array();
  for (int i = 0; i < next_index(nodes_); ++i) roots.push_back(i);
  Json scene = {{"name", scene_name_}, {"nodes", std::move(roots)}};
  if (!scene_extras_.is_null()) scene["extras"] = scene_extras_;
  doc["scenes"] = Json::array({std::move(scene)});
  doc["nodes"] = nodes_;
  if (!cameras_.empty()) doc["cameras"] = cameras_;
  doc["meshes"] = meshes_;
  if (!materials_.empty()) doc["materials"] = materials_;
  if (!textures_.empty()) {
    doc["textures"] = textures_;
    doc["images"] = images_;
    doc["samplers"] = Json::array({{{"magFilter", 9729},     // LINEAR
                                    {"minFilter", 9987},     // LINEAR_MIPMAP_LINEAR
                                    {"wrapS", 10497},        // REPEAT
                                    {"wrapT", 10497}}});
  }
  doc["buffers"] = Json::array({{{"byteLength", bin_.size()}, {"uri", buffer_uri}}});
  doc["bufferViews"] = buffer_views_;
  doc["accessors"] = accessors_;
  if (!lights_.empty()) doc["extensions"] = {{"KHR_lights_punctual", {{"lights", lights_}}}};
  return doc;
}

void GltfWriter::write(const std::filesystem::path& path, std::size_t embed_limit) const {
  std::string uri;
  if (bin_.size() <= embed_limit) {
    uri = "data:application/octet-stream;base64," + encode_base64(bin_);
  } else {
    const std::filesystem::path bin = std::filesystem::path(path).replace_extension(".bin");
    write_bytes_atomically(bin, bin_);
    uri = bin.filename().string();
  }
  write_json_file(path, document(uri));
}

}  // namespace svbrdf
