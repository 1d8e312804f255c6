#include "scenes/gltf_writer.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <span>

#include "base/atomic_file.h"
#include "base/error.h"
#include "textures/image.h"

namespace svbrdf {

namespace {

using json::Value;

constexpr int kFloat = 5126, kUnsignedShort = 5123, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

template <class T>
std::span<const std::byte> bytes_of(std::span<const T> v) {
  return std::as_bytes(v);
}

void write_bytes(const std::filesystem::path& path, std::span<const std::byte> data) { write_bytes_atomically(path, data); }

Value translation_rotation(const Placement& p) {
  Value node = Value::object();
  if (p.translation != glm::dvec3(0.0)) node.set("translation", Value::numbers({p.translation.x, p.translation.y, p.translation.z}));
  const glm::dquat q = glm::normalize(p.rotation);
  if (q != glm::dquat(1.0, 0.0, 0.0, 0.0))
    node.set("rotation", Value::numbers({double(float(q.x)), double(float(q.y)), double(float(q.z)), double(float(q.w))}));
  return node;
}

void internal(const std::string& what) { throw Error("glTF writer: " + what, Error::Kind::internal); }

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
                             int target, Value min, Value max) {
  while (bin_.size() % 4) bin_.push_back(std::byte{0});
  const std::size_t offset = bin_.size();
  bin_.insert(bin_.end(), bytes.begin(), bytes.end());
  Value view = Value::object();
  view.set("buffer", Value::of(0));
  view.set("byteOffset", Value::of(double(offset)));
  view.set("byteLength", Value::of(double(bytes.size())));
  view.set("target", Value::of(target));
  buffer_views_.push(std::move(view));
  Value acc = Value::object();
  acc.set("bufferView", Value::of(int(buffer_views_.items.size()) - 1));
  acc.set("componentType", Value::of(component_type));
  acc.set("count", Value::of(count));
  acc.set("type", Value::of(type));
  if (min.type != Value::Type::null) acc.set("min", std::move(min));
  if (max.type != Value::Type::null) acc.set("max", std::move(max));
  accessors_.push(std::move(acc));
  return int(accessors_.items.size()) - 1;
}

// Every texture uses sampler 0 (written by document()): repeat, as the families tile.
int GltfWriter::add_texture(const std::string& uri) {
  Value image = Value::object();
  image.set("uri", Value::of(uri));
  images_.push(std::move(image));
  Value texture = Value::object();
  texture.set("sampler", Value::of(0));
  texture.set("source", Value::of(int(images_.items.size()) - 1));
  textures_.push(std::move(texture));
  return int(textures_.items.size()) - 1;
}

int GltfWriter::add_material(Value material) {
  materials_.push(std::move(material));
  return int(materials_.items.size()) - 1;
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
  Value attributes = Value::object();
  attributes.set("POSITION", Value::of(add_accessor(bytes_of(std::span(m.positions)), kFloat, int(n), "VEC3", kArrayBuffer,
                                                    Value::numbers({lo.x, lo.y, lo.z}), Value::numbers({hi.x, hi.y, hi.z}))));
  attributes.set("NORMAL", Value::of(add_accessor(bytes_of(std::span(m.normals)), kFloat, int(n), "VEC3", kArrayBuffer)));
  if (!m.tangents.empty())
    attributes.set("TANGENT", Value::of(add_accessor(bytes_of(std::span(m.tangents)), kFloat, int(n), "VEC4", kArrayBuffer)));
  if (!m.uvs.empty())
    attributes.set("TEXCOORD_0", Value::of(add_accessor(bytes_of(std::span(m.uvs)), kFloat, int(n), "VEC2", kArrayBuffer)));
  int indices = 0;
  if (n <= 65535) {  // 65535 is primitive restart in some APIs; glTF forbids it as an index value
    std::vector<std::uint16_t> i16(m.indices.begin(), m.indices.end());
    indices = add_accessor(bytes_of(std::span<const std::uint16_t>(i16)), kUnsignedShort, int(i16.size()), "SCALAR",
                           kElementArrayBuffer);
  } else {
    indices = add_accessor(bytes_of(std::span(m.indices)), kUnsignedInt, int(m.indices.size()), "SCALAR", kElementArrayBuffer);
  }
  Value primitive = Value::object();
  primitive.set("attributes", std::move(attributes));
  primitive.set("indices", Value::of(indices));
  if (material >= 0) primitive.set("material", Value::of(material));
  primitive.set("mode", Value::of(4));
  Value mesh = Value::object();
  mesh.set("name", Value::of(name));
  mesh.set("primitives", Value::array()).push(std::move(primitive));
  meshes_.push(std::move(mesh));
  return int(meshes_.items.size()) - 1;
}

int GltfWriter::add_mesh_node(const std::string& name, int mesh, const Placement& where) {
  Value node = Value::object();
  node.set("name", Value::of(name));
  node.set("mesh", Value::of(mesh));
  for (auto& [k, v] : translation_rotation(where).members) node.set(k, std::move(v));
  nodes_.push(std::move(node));
  return int(nodes_.items.size()) - 1;
}

int GltfWriter::add_camera(const std::string& name, double yfov, double aspect, double znear, double zfar,
                           const Placement& where, Value extras) {
  Value perspective = Value::object();
  perspective.set("aspectRatio", Value::of(aspect));
  perspective.set("yfov", Value::of(yfov));
  perspective.set("znear", Value::of(znear));
  if (zfar > 0.0) perspective.set("zfar", Value::of(zfar));
  Value camera = Value::object();
  camera.set("name", Value::of(name));
  camera.set("type", Value::of("perspective"));
  camera.set("perspective", std::move(perspective));
  if (extras.type != Value::Type::null) camera.set("extras", std::move(extras));
  cameras_.push(std::move(camera));
  Value node = Value::object();
  node.set("name", Value::of(name));
  node.set("camera", Value::of(int(cameras_.items.size()) - 1));
  for (auto& [k, v] : translation_rotation(where).members) node.set(k, std::move(v));
  nodes_.push(std::move(node));
  return int(cameras_.items.size()) - 1;
}

int GltfWriter::add_directional_light(const std::string& name, const glm::dvec3& color, double irradiance,
                                      const glm::dvec3& direction) {
  Value light = Value::object();
  light.set("name", Value::of(name));
  light.set("type", Value::of("directional"));
  light.set("color", Value::numbers({color.r, color.g, color.b}));
  light.set("intensity", Value::of(irradiance));
  lights_.push(std::move(light));
  Value node = Value::object();
  node.set("name", Value::of(name));
  Placement p;
  p.rotation = look_rotation(direction, std::abs(glm::normalize(direction).y) > 0.99 ? glm::dvec3(0, 0, -1) : glm::dvec3(0, 1, 0));
  for (auto& [k, v] : translation_rotation(p).members) node.set(k, std::move(v));
  Value ext = Value::object();
  ext.set("KHR_lights_punctual", Value::object()).set("light", Value::of(int(lights_.items.size()) - 1));
  node.set("extensions", std::move(ext));
  nodes_.push(std::move(node));
  return int(lights_.items.size()) - 1;
}

Value GltfWriter::document(const std::string& buffer_uri) const {
  Value doc = Value::object();
  Value asset = Value::object();
  asset.set("version", Value::of("2.0"));
  asset.set("generator", Value::of(generator_));
  doc.set("asset", std::move(asset));
  if (!lights_.items.empty()) doc.set("extensionsUsed", Value::array()).push(Value::of("KHR_lights_punctual"));
  doc.set("scene", Value::of(0));
  Value scene = Value::object();
  scene.set("name", Value::of(scene_name_));
  Value roots = Value::array();
  for (std::size_t i = 0; i < nodes_.items.size(); ++i) roots.push(Value::of(int(i)));
  scene.set("nodes", std::move(roots));
  if (scene_extras_.type != Value::Type::null) scene.set("extras", scene_extras_);
  doc.set("scenes", Value::array()).push(std::move(scene));
  doc.set("nodes", nodes_);
  if (!cameras_.items.empty()) doc.set("cameras", cameras_);
  doc.set("meshes", meshes_);
  if (!materials_.items.empty()) doc.set("materials", materials_);
  if (!textures_.items.empty()) {
    doc.set("textures", textures_);
    doc.set("images", images_);
    Value sampler = Value::object();
    sampler.set("magFilter", Value::of(9729));   // LINEAR
    sampler.set("minFilter", Value::of(9987));   // LINEAR_MIPMAP_LINEAR
    sampler.set("wrapS", Value::of(10497));      // REPEAT
    sampler.set("wrapT", Value::of(10497));
    doc.set("samplers", Value::array()).push(std::move(sampler));
  }
  Value buffer = Value::object();
  buffer.set("byteLength", Value::of(double(bin_.size())));
  buffer.set("uri", Value::of(buffer_uri));
  doc.set("buffers", Value::array()).push(std::move(buffer));
  doc.set("bufferViews", buffer_views_);
  doc.set("accessors", accessors_);
  if (!lights_.items.empty()) {
    Value ext = Value::object();
    ext.set("KHR_lights_punctual", Value::object()).set("lights", lights_);
    doc.set("extensions", std::move(ext));
  }
  return doc;
}

void GltfWriter::write(const std::filesystem::path& path, std::size_t embed_limit) const {
  std::string uri;
  if (bin_.size() <= embed_limit) {
    uri = "data:application/octet-stream;base64," + encode_base64(bin_);
  } else {
    const std::filesystem::path bin = std::filesystem::path(path).replace_extension(".bin");
    write_bytes(bin, bin_);
    uri = bin.filename().string();
  }
  const std::string text = json::dump(document(uri));
  write_bytes(path, std::as_bytes(std::span(text.data(), text.size())));
}

}  // namespace svbrdf
