#include "gltf/scene_reader.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <span>
#include <sstream>
#include <string_view>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "base/error.h"
#include "gltf/document.h"
#include "gltf/accessor.h"
#include "gltf/animation.h"
#include "gltf/animation_reader.h"
#include "gltf/draco_decode.h"
#include "gltf/material_reader.h"
#include "gltf/tangents.h"
#include "base/math.h"

namespace svbrdf {

namespace {

using gltf::AccessorShape;
using gltf::json_index;

using gltf::finite_all;

// The component types a vertex attribute may have: glTF 2.0 §3.7.2.1's and KHR_mesh_quantization's
// tables together; UNSIGNED_INT is in neither.
const std::vector<int> kAttributeComponentTypes = {
    TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
    TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_COMPONENT_TYPE_FLOAT};

class Loader {
 public:
  Loader(const std::filesystem::path& path, const LoadOptions& options) : path_(path), options_(options) {
    scene_.file = path;
  }

  Scene run() {
    read_model();
    check_extensions();
    read_appearance();
    read_variants();
    read_meshes();
    read_lights();
    read_nodes();
    if (degenerate_triangles_ > 0)
      scene_.warnings.push_back(std::to_string(degenerate_triangles_) + " zero-area triangles (first in " +
                                first_degenerate_ + ") render as nothing");
    return std::move(scene_);
  }

 private:
  float checked(double x, double lo, double hi, const std::string& where) const {
    return gltf::in_range(x, lo, hi, path_, where);
  }

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw input_error(path_.string() + (where.empty() ? "" : ": " + where), what);
  }

  void read_model() {
    doc_ = gltf::read_document(path_);
  }

  // Images, textures and materials: the reader the MIP build shares (gltf/material_reader.h). Every
  // image a texture shows is decoded, one at a time (decode_image's note on OpenImageIO); one no
  // texture names is never drawn, and its pixels stay empty.
  void read_appearance() {
    gltf::Materials m = gltf::read_materials(doc_);
    std::vector<char> shown(m.images.size(), 0);
    for (const TextureDesc& t : m.textures)
      if (t.image >= 0) shown[std::size_t(t.image)] = 1;
    std::vector<char> color(m.images.size(), 0);
    for (std::size_t t = 0; t < m.textures.size(); ++t)
      for (const MaterialDesc& d : m.materials)
        if (m.textures[t].image >= 0 && d.shows_as_color(int(t))) color[std::size_t(m.textures[t].image)] = 1;
    for (std::size_t i = 0; i < m.images.size(); ++i) {
      if (!shown[i]) continue;
      const bool is_color = color[i] != 0;
      std::function<bool(ImageDesc&)> found;
      if (options_.find_image) found = [&](ImageDesc& image) { return options_.find_image(i, image, is_color); };
      if (gltf::decode_image(doc_, m, i, found) && options_.take_image) options_.take_image(i, m.images[i], is_color);
    }
    doc_.images.clear();
    scene_.images = std::move(m.images);
    scene_.textures = std::move(m.textures);
    scene_.materials = std::move(m.materials);
    scene_.warnings.insert(scene_.warnings.end(), m.warnings.begin(), m.warnings.end());
  }

  // KHR_materials_variants README: the root extension's `variants` name the variants; a primitive's
  // `mappings` say which material each variant gives it. The variant --variant names is looked up here;
  // the primitives' mappings are applied as each is read (apply_variant).
  void read_variants() {
    const std::string w = "extensions.KHR_materials_variants";
    const auto it = model_.extensions.find("KHR_materials_variants");
    if (it != model_.extensions.end()) {
      if (!it->second.IsObject() || !it->second.Has("variants") || !it->second.Get("variants").IsArray())
        fail(w, "has no variants array");
      const tinygltf::Value& list = it->second.Get("variants");
      for (std::size_t i = 0; i < list.ArrayLen(); ++i) {
        const tinygltf::Value& v = list.Get(int(i));
        if (!v.IsObject() || !v.Has("name") || !v.Get("name").IsString())
          fail(w + ".variants[" + std::to_string(i) + "]", "has no name");
        variant_names_.push_back(v.Get("name").Get<std::string>());
      }
    }
    if (options_.variant.empty()) return;
    const auto found = std::find(variant_names_.begin(), variant_names_.end(), options_.variant);
    if (found == variant_names_.end()) {
      std::string names;
      for (const std::string& n : variant_names_) names += (names.empty() ? "'" : ", '") + n + "'";
      throw input_error("--variant '" + options_.variant + "'",
                        variant_names_.empty() ? path_.string() + " has no material variants (KHR_materials_variants)"
                                               : "is not a variant of " + path_.string() + "; its variants: " + names);
    }
    variant_ = int(found - variant_names_.begin());
  }

  // The material the selected variant maps primitive `p` to, or its own. Every mapping is checked,
  // whichever variant is selected.
  int apply_variant(const tinygltf::Primitive& p, const std::string& where, int material) const {
    const auto it = p.extensions.find("KHR_materials_variants");
    if (it == p.extensions.end()) return material;
    const std::string w = where + ".extensions.KHR_materials_variants.mappings";
    if (!it->second.IsObject() || !it->second.Has("mappings") || !it->second.Get("mappings").IsArray())
      fail(w, "must be an array");
    const tinygltf::Value& mappings = it->second.Get("mappings");
    int chosen = material;
    for (std::size_t m = 0; m < mappings.ArrayLen(); ++m) {
      const std::string wm = w + "[" + std::to_string(m) + "]";
      const tinygltf::Value& mapping = mappings.Get(int(m));
      const int mat = mapping_material(mapping, wm);
      if (!mapping.Has("variants") || !mapping.Get("variants").IsArray())
        fail(wm + ".variants", "must be an array of variant indices");
      const tinygltf::Value& vs = mapping.Get("variants");
      for (std::size_t k = 0; k < vs.ArrayLen(); ++k) {
        const int v = gltf::whole_index(vs.Get(int(k))).value_or(-1);
        if (v < 0 || static_cast<std::size_t>(v) >= variant_names_.size())
          fail(wm + ".variants[" + std::to_string(k) + "]",
               "must name one of the file's " + std::to_string(variant_names_.size()) + " variants");
        if (v == variant_) chosen = mat;
      }
    }
    return chosen;
  }

  int mapping_material(const tinygltf::Value& mapping, const std::string& wm) const {
    const int mat = mapping.IsObject() && mapping.Has("material") ? gltf::whole_index(mapping.Get("material")).value_or(-1) : -1;
    if (mat < 0 || static_cast<std::size_t>(mat) >= scene_.materials.size())
      fail(wm + ".material", "must name one of the file's " + std::to_string(scene_.materials.size()) + " materials");
    return mat;
  }

  void check_extensions() {
    const auto& ok = gltf::supported_extensions();
    auto supported = [&](const std::string& e) { return std::find(ok.begin(), ok.end(), e) != ok.end(); };
    for (const auto& e : model_.extensionsRequired)
      if (!supported(e)) fail("extensionsRequired", "requires " + e + ", which svbrdf-render does not support");
    // An unsupported extension of a material is warned about once per material, naming it (the
    // material reader); any other once for the file.
    auto on_a_material = [&](const std::string& e) {
      return std::any_of(model_.materials.begin(), model_.materials.end(),
                         [&](const tinygltf::Material& m) { return m.extensions.count(e) != 0; });
    };
    for (const auto& e : model_.extensionsUsed)
      if (!supported(e) && !on_a_material(e))
        scene_.warnings.push_back("optional extension " + e + " is not supported; the file renders without it");
  }

  // --- meshes ------------------------------------------------------------------------------

  template <typename V>
  std::vector<V> read_attribute(const tinygltf::Primitive& p, const char* name, const std::vector<int>& types,
                                const std::string& where, std::size_t vertex_count, int* comps_out = nullptr) {
    auto it = p.attributes.find(name);
    if (it == p.attributes.end()) return {};
    const std::string w = where + ".attributes." + name;
    int comps = 0;
    std::vector<float> f;
    const auto decoded = draco_ ? draco_->attributes.find(name) : decltype(draco_->attributes.end()){};
    if (draco_ && decoded != draco_->attributes.end()) {
      // KHR_draco_mesh_compression README, "Conformance": the accessor describes the decoded data; its
      // bufferView, if any, is ignored.
      comps = gltf::accessor_components(model_, it->second, AccessorShape{types, {}}, path_.string() + ": " + w);
      f = std::move(decoded->second.values);
    } else {
      f = gltf::read_floats(model_, it->second, AccessorShape{types, kAttributeComponentTypes}, path_.string() + ": " + w,
                            &comps);
    }
    // glTF 2.0 §3.7.2.1: COLOR_n is a linear multiplier in [0, 1] (normalized integers are so by type).
    if (std::string_view(name) == "COLOR_0")
      for (std::size_t i = 0; i < f.size(); ++i)
        if (!(f[i] >= 0.0f && f[i] <= 1.0f))
          fail(w, "vertex " + std::to_string(i / std::size_t(comps)) + " has a color component of " +
                      std::to_string(f[i]) + ", outside [0, 1]");
    const std::size_t n = f.size() / std::size_t(comps);
    if (vertex_count != 0 && n != vertex_count)
      fail(w, json_index("accessors", it->second) + " has " + std::to_string(n) + " elements, POSITION has " +
                  std::to_string(vertex_count));
    std::vector<V> out(n, V(1.0f));
    constexpr int kDim = V::length();
    for (std::size_t i = 0; i < n; ++i)
      for (int c = 0; c < std::min(comps, kDim); ++c) out[i][c] = f[i * std::size_t(comps) + std::size_t(c)];
    if (comps_out) *comps_out = comps;
    return out;
  }

  void read_meshes() {
    scene_.meshes.resize(model_.meshes.size());
    for (std::size_t mi = 0; mi < model_.meshes.size(); ++mi) {
      const tinygltf::Mesh& mesh = model_.meshes[mi];
      Mesh& out = scene_.meshes[mi];
      out.name = mesh.name;
      for (std::size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
        const std::string where = json_index("meshes", int(mi)) + ".primitives[" + std::to_string(pi) + "]";
        MeshPrimitive prim;
        if (read_primitive(mesh.primitives[pi], where, prim)) out.primitives.push_back(std::move(prim));
      }
    }
  }

  // False for primitives that are not surfaces (points, lines): skipped with a warning.
  bool read_primitive(const tinygltf::Primitive& p, const std::string& where, MeshPrimitive& prim) {
    draco_.reset();
    if (const auto ext = p.extensions.find("KHR_draco_mesh_compression"); ext != p.extensions.end())
      draco_ = gltf::decode_draco(model_, p, ext->second, path_, where);
    // A Draco mesh decodes to a list of triangles whichever mode the primitive names (decode_draco
    // allows only TRIANGLES and TRIANGLE_STRIP).
    const int mode = draco_ ? TINYGLTF_MODE_TRIANGLES : p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
    if (mode == TINYGLTF_MODE_POINTS || mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_LINE_LOOP ||
        mode == TINYGLTF_MODE_LINE_STRIP) {
      scene_.warnings.push_back(path_.string() + ": " + where + ": points and lines are not surfaces; skipped");
      return false;
    }
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN)
      fail(where + ".mode", "is " + std::to_string(mode) + ", not a glTF primitive mode");
    prim.where = where;
    if (p.material >= 0) {
      if (static_cast<std::size_t>(p.material) >= scene_.materials.size())
        fail(where + ".material", "names " + json_index("materials", p.material) + ", but the file has " +
                                      std::to_string(scene_.materials.size()) + " materials");
      prim.material = p.material;
    }
    prim.material = apply_variant(p, where, prim.material);
    // glTF 2.0 §3.7.2.1: "When positions are not specified, client implementations SHOULD skip
    // primitive's rendering".
    if (!p.attributes.count("POSITION")) {
      scene_.warnings.push_back(path_.string() + ": " + where + ".attributes: has no POSITION; skipped");
      return false;
    }
    prim.positions = read_attribute<glm::vec3>(p, "POSITION", {TINYGLTF_TYPE_VEC3}, where, 0);
    const std::size_t nv = prim.positions.size();
    // read_floats holds every accessor to finite values; a Draco primitive's are decoded elsewhere.
    for (std::size_t i = 0; draco_ && i < nv; ++i) {
      const glm::vec3& v = prim.positions[i];
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        fail(where + ".attributes.POSITION", "vertex " + std::to_string(i) + " is not finite (NaN or infinity)");
    }
    prim.normals = read_attribute<glm::vec3>(p, "NORMAL", {TINYGLTF_TYPE_VEC3}, where, nv);
    prim.tangents = read_attribute<glm::vec4>(p, "TANGENT", {TINYGLTF_TYPE_VEC4}, where, nv);
    prim.texcoords[0] = read_attribute<glm::vec2>(p, "TEXCOORD_0", {TINYGLTF_TYPE_VEC2}, where, nv);
    prim.texcoords[1] = read_attribute<glm::vec2>(p, "TEXCOORD_1", {TINYGLTF_TYPE_VEC2}, where, nv);
    prim.colors = read_attribute<glm::vec4>(p, "COLOR_0", {TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4}, where, nv);

    std::vector<std::uint32_t> idxs;
    if (draco_ || p.indices >= 0) {
      const std::string wi = where + (draco_ ? ".extensions.KHR_draco_mesh_compression" : ".indices");
      idxs = draco_ ? std::move(draco_->indices) : gltf::read_indices(model_, p.indices, path_.string() + ": " + wi);
      if (idxs.empty()) fail(wi, "decodes to no triangles");
      for (std::size_t k = 0; k < idxs.size(); ++k)
        if (idxs[k] >= nv)
          fail(wi, "index " + std::to_string(idxs[k]) + " (element " + std::to_string(k) + ") is past the " +
                       std::to_string(nv) + " vertices of POSITION");
    } else {
      idxs.resize(nv);
      for (std::size_t k = 0; k < nv; ++k) idxs[k] = static_cast<std::uint32_t>(k);
    }
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      // glTF 2.0 §3.7.2.1 makes triangle i of vertices 3i, 3i+1, 3i+2: vertices past the last whole
      // triangle belong to none (the validator warns, MESH_PRIMITIVE_INCOMPATIBLE_MODE), as on a GPU.
      if (const std::size_t rest = idxs.size() % 3; rest != 0) {
        scene_.warnings.push_back(path_.string() + ": " + where + ": " + std::to_string(idxs.size()) +
                                  " vertices do not make whole triangles; the last " + std::to_string(rest) +
                                  " belong to none");
        idxs.resize(idxs.size() - rest);
      }
      prim.indices = std::move(idxs);
    } else {
      // Strips and fans as lists, keeping each triangle's winding (glTF §3.7.2.1).
      for (std::size_t k = 2; k < idxs.size(); ++k) {
        std::uint32_t a, b, c;
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
          a = idxs[k - 2], b = idxs[k - 1], c = idxs[k];
          if (k % 2 == 1) std::swap(a, b);
        } else {
          a = idxs[0], b = idxs[k - 1], c = idxs[k];
        }
        prim.indices.insert(prim.indices.end(), {a, b, c});
      }
    }
    for (std::size_t t = 0; t < prim.triangle_count(); ++t) {
      const glm::vec3 a = prim.positions[prim.indices[3 * t]], b = prim.positions[prim.indices[3 * t + 1]],
                      c = prim.positions[prim.indices[3 * t + 2]];
      if (glm::cross(b - a, c - a) == glm::vec3(0.0f) && degenerate_triangles_++ == 0) first_degenerate_ = where;
    }

    const MaterialDesc& mat = scene_.material_of(prim);
    for (const auto& [slot, ref] : mat.texture_slots()) {
      if (!ref->present() || ref == &mat.occlusion_texture) continue;  // occlusion is never read
      const int set = ref->uv_set();
      if (prim.texcoords[set].empty())
        fail(where + ".attributes", mat.where + "." + slot + " samples TEXCOORD_" + std::to_string(set) +
                                        ", which this primitive does not have");
    }
    if (prim.normals.empty()) {
      make_flat_normals(prim);
    }
    if (prim.tangents.empty() && mat.needs_tangents() && !prim.texcoords[mat.tangent_uv_set()].empty())
      generate_tangents(prim, mat.tangent_uv_set());
    return true;
  }

  // --- lights, nodes, cameras ----------------------------------------------------------------

  void read_lights() {
    for (std::size_t i = 0; i < model_.lights.size(); ++i) {
      const tinygltf::Light& l = model_.lights[i];
      const std::string w = "extensions.KHR_lights_punctual.lights[" + std::to_string(i) + "]";
      LightDesc d;
      d.name = l.name.empty() ? w : l.name;
      if (l.type == "directional") d.type = LightDesc::Type::directional;
      else if (l.type == "point") d.type = LightDesc::Type::point;
      else if (l.type == "spot") d.type = LightDesc::Type::spot;
      else {
        // KHR_lights_punctual defines these three; a light of another type (a later extension's)
        // is not drawn, and nodes that place it place nothing.
        scene_.warnings.push_back(path_.string() + ": " + w + ".type: is '" + l.type +
                                  "', not directional, point or spot; the light is not drawn");
        light_templates_.push_back(std::nullopt);
        continue;
      }
      if (!l.color.empty()) {
        if (l.color.size() != 3) fail(w + ".color", "must be three numbers");
        for (int c = 0; c < 3; ++c) d.color[c] = checked(l.color[std::size_t(c)], 0, 1e30, w + ".color");
      }
      const double intensity = checked(l.intensity, 0, 1e30, w + ".intensity");
      d.intensity = float(options_.light_units == LightUnits::photometric ? intensity / kLumensPerWatt : intensity);
      d.range = checked(l.range, 0, 1e30, w + ".range");
      if (d.type == LightDesc::Type::spot) {
        d.outer_cone = checked(l.spot.outerConeAngle, 1e-6, 0.5 * kPiD, w + ".spot.outerConeAngle");
        d.inner_cone = checked(l.spot.innerConeAngle, 0, d.outer_cone, w + ".spot.innerConeAngle");
      }
      light_templates_.push_back(d);
    }
  }

  glm::dmat4 local_transform(const tinygltf::Node& n, const std::string& w) const {
    if (!n.matrix.empty()) {
      if (n.matrix.size() != 16 || !finite_all(n.matrix)) fail(w + ".matrix", "must be 16 finite numbers");
      return glm::make_mat4(n.matrix.data());  // column-major, as glTF stores it
    }
    glm::dmat4 m(1.0);
    if (!n.translation.empty()) {
      if (n.translation.size() != 3 || !finite_all(n.translation)) fail(w + ".translation", "must be 3 finite numbers");
      m = glm::translate(m, glm::dvec3(n.translation[0], n.translation[1], n.translation[2]));
    }
    if (!n.rotation.empty()) {
      if (n.rotation.size() != 4 || !finite_all(n.rotation)) fail(w + ".rotation", "must be 4 finite numbers");
      glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);  // glTF stores x, y, z, w
      const double len = glm::length(q);
      if (len < 1e-12) fail(w + ".rotation", "is a zero quaternion");
      m = m * glm::mat4_cast(q / len);
    }
    if (!n.scale.empty()) {
      if (n.scale.size() != 3 || !finite_all(n.scale)) fail(w + ".scale", "must be 3 finite numbers");
      m = glm::scale(m, glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
    }
    return m;
  }

  void visit_node(int node, const glm::dmat4& world) {
    const tinygltf::Node& n = model_.nodes[static_cast<std::size_t>(node)];
    const std::string w = json_index("nodes", node);
    if (n.mesh >= 0) {
      if (static_cast<std::size_t>(n.mesh) >= model_.meshes.size())
        fail(w + ".mesh", "names " + json_index("meshes", n.mesh) + ", but the file has " +
                              std::to_string(model_.meshes.size()) + " meshes");
      scene_.instances.push_back(Instance{n.mesh, node, world});
      if (n.skin >= 0 && !warned_skin_) {
        warned_skin_ = true;
        scene_.warnings.push_back("skins are not animated; skinned meshes are drawn in their bind pose");
      }
    }
    if (n.camera >= 0) {
      if (static_cast<std::size_t>(n.camera) >= model_.cameras.size())
        fail(w + ".camera", "names " + json_index("cameras", n.camera) + ", but the file has " +
                                std::to_string(model_.cameras.size()) + " cameras");
      scene_.cameras.push_back(camera(n.camera, node, world));
      if (options_.camera_animation) {
        // The node and its ancestors, the root first: what an animation may move the camera by.
        std::vector<int> chain;
        for (int k = node; k >= 0; k = parent_[std::size_t(k)]) chain.insert(chain.begin(), k);
        CameraMotion motion = gltf::read_camera_motion(doc_, chain, &scene_.warnings);
        if (motion.animated()) scene_.cameras.back().motion = std::make_shared<const CameraMotion>(std::move(motion));
      }
    }
    auto it = n.extensions.find("KHR_lights_punctual");
    if (it != n.extensions.end()) {
      const std::string wl = w + ".extensions.KHR_lights_punctual.light";
      const double li = gltf::number_or(it->second, "light", -1);
      if (!(li >= 0) || li >= double(light_templates_.size()))
        fail(wl, "names light " + std::to_string(li) + ", but the file has " +
                     std::to_string(light_templates_.size()) + " lights");
      if (!light_templates_[std::size_t(li)]) return;
      LightDesc d = *light_templates_[std::size_t(li)];
      d.node = node;
      d.position = glm::vec3(world * glm::dvec4(0, 0, 0, 1));
      const glm::dvec3 dir = glm::dmat3(world) * glm::dvec3(0, 0, -1);
      if (glm::length(dir) < 1e-300) fail(w, "has a singular transform; the light has no direction");
      d.direction = glm::vec3(glm::normalize(dir));
      scene_.lights.push_back(d);
    }
  }

  CameraDesc camera(int ci, int node, const glm::dmat4& world) const {
    const tinygltf::Camera& c = model_.cameras[static_cast<std::size_t>(ci)];
    const std::string w = json_index("cameras", ci);
    // A camera's node must place it (camera_transform_fault).
    const std::string wn = json_index("nodes", node);
    if (const char* fault = camera_transform_fault(world)) fail(wn, "places " + w + " " + fault);
    CameraDesc d;
    d.name = !c.name.empty() ? c.name : !model_.nodes[std::size_t(node)].name.empty() ? model_.nodes[std::size_t(node)].name : w;
    d.node = node;
    d.to_world = world;
    if (c.type == "perspective") {
      d.type = CameraDesc::Type::perspective;
      // Strictly below π, so that tan(yfov / 2) stays finite.
      d.yfov = checked(c.perspective.yfov, 1e-6, kPiD * (1 - 1e-6), w + ".perspective.yfov");
      d.aspect_ratio = checked(c.perspective.aspectRatio, 0, 1e6, w + ".perspective.aspectRatio");
      d.znear = checked(c.perspective.znear, 0, 1e30, w + ".perspective.znear");
      d.zfar = checked(c.perspective.zfar, 0, 1e30, w + ".perspective.zfar");
    } else if (c.type == "orthographic") {
      d.type = CameraDesc::Type::orthographic;
      // Nonzero (glTF 2.0 §5.14) and, so that the film's extent stays finite in float arithmetic
      // after the aspect ratio (up to 1e6) multiplies it, within [1e-18, 1e18].
      auto mag = [&](double v, const char* key) {
        if (!std::isfinite(v) || std::abs(v) < 1e-18 || std::abs(v) > 1e18)
          fail(w + ".orthographic." + key, "must be a nonzero number of magnitude within [1e-18, 1e18]");
      };
      mag(c.orthographic.xmag, "xmag");
      mag(c.orthographic.ymag, "ymag");
      d.xmag = float(std::abs(c.orthographic.xmag));
      d.ymag = float(std::abs(c.orthographic.ymag));
      d.znear = checked(c.orthographic.znear, 0, 1e30, w + ".orthographic.znear");
      d.zfar = checked(c.orthographic.zfar, 0, 1e30, w + ".orthographic.zfar");
    } else {
      fail(w + ".type", "is '" + c.type + "'; expected perspective or orthographic");
    }
    return d;
  }

  // Each node's parent (−1 for a root), after checking the whole node graph, not only the part the
  // scene reaches, is a forest (glTF 2.0 §3.5.3: "node hierarchy MUST be a set of disjoint strict
  // trees"): no node is the child of two, and no chain of parents returns to where it began.
  std::vector<int> node_parents() const {
    const std::size_t nn = model_.nodes.size();
    std::vector<int> parent(nn, -1);
    for (std::size_t i = 0; i < nn; ++i)
      for (const int c : model_.nodes[i].children) {
        const std::string wc = json_index("nodes", int(i)) + ".children";
        if (std::size_t(c) == i) fail(wc, "names the node itself: the node graph has a cycle");
        if (parent[std::size_t(c)] >= 0)
          fail(wc, "names " + json_index("nodes", c) + ", which " + json_index("nodes", parent[std::size_t(c)]) +
                       " lists too: glTF nodes form a tree");
        parent[std::size_t(c)] = int(i);
      }
    // With one parent each, a cycle is a chain of parents that meets itself: walk each chain once,
    // marking its nodes with the walk's number.
    std::vector<std::size_t> walk(nn, 0);
    for (std::size_t i = 0; i < nn; ++i) {
      std::size_t n = i;
      while (walk[n] == 0) {
        walk[n] = i + 1;
        if (parent[n] < 0) break;
        n = std::size_t(parent[n]);
      }
      if (walk[n] == i + 1 && parent[n] >= 0)
        fail(json_index("nodes", int(n)), "is its own ancestor: the node graph has a cycle");
    }
    return parent;
  }

  void read_nodes() {
    const std::size_t nn = model_.nodes.size();
    auto check_node = [&](int n, const std::string& where) {
      if (n < 0 || static_cast<std::size_t>(n) >= nn)
        fail(where, "names " + json_index("nodes", n) + ", but the file has " + std::to_string(nn) + " nodes");
    };
    for (std::size_t i = 0; i < nn; ++i)
      for (std::size_t c = 0; c < model_.nodes[i].children.size(); ++c)
        check_node(model_.nodes[i].children[c], json_index("nodes", int(i)) + ".children[" + std::to_string(c) + "]");

    parent_ = node_parents();
    const std::vector<int>& parent = parent_;

    std::vector<int> roots;
    std::string roots_where;
    if (model_.scenes.empty() && model_.defaultScene >= 0)
      fail("scene", "names " + json_index("scenes", model_.defaultScene) + ", but the file has no scenes");
    if (model_.scenes.empty()) {
      // No scene: glTF leaves what to show to the application; show every parentless node.
      std::vector<char> child(nn, 0);
      for (const auto& n : model_.nodes)
        for (int c : n.children) child[static_cast<std::size_t>(c)] = 1;
      for (std::size_t i = 0; i < nn; ++i)
        if (!child[i]) roots.push_back(int(i));
      roots_where = "nodes";
    } else {
      int s = model_.defaultScene;
      if (s < 0) s = 0;
      if (static_cast<std::size_t>(s) >= model_.scenes.size())
        fail("scene", "names " + json_index("scenes", s) + ", but the file has " + std::to_string(model_.scenes.size()) +
                          " scenes");
      roots = model_.scenes[static_cast<std::size_t>(s)].nodes;
      roots_where = json_index("scenes", s) + ".nodes";
      for (std::size_t r = 0; r < roots.size(); ++r) {
        const std::string wr = roots_where + "[" + std::to_string(r) + "]";
        check_node(roots[r], wr);
        // glTF 2.0 §5.28 (scene.nodes): "the indices of each root node"; a child listed too is drawn twice.
        if (const int p = parent[std::size_t(roots[r])]; p >= 0)
          fail(wr, "names " + json_index("nodes", roots[r]) + ", a child of " + json_index("nodes", p) +
                       "; a scene lists root nodes only");
      }
    }

    // Depth-first with an explicit stack, so a deep or cyclic graph can neither overflow nor hang.
    // 1 = on the current path, 2 = finished; meeting a node on the path is a cycle, meeting a finished
    // one means it has two parents (glTF requires a forest).
    std::vector<char> state(nn, 0);
    struct Frame {
      int node;
      glm::dmat4 world;
      std::size_t next_child;
    };
    std::vector<Frame> stack;
    for (int root : roots) {
      if (state[static_cast<std::size_t>(root)] != 0)
        fail(roots_where, json_index("nodes", root) + " is reached twice: glTF nodes form a tree");
      const glm::dmat4 w = local_transform(model_.nodes[std::size_t(root)], json_index("nodes", root));
      state[static_cast<std::size_t>(root)] = 1;
      visit_node(root, w);
      stack.push_back({root, w, 0});
      while (!stack.empty()) {
        Frame& f = stack.back();
        const auto& children = model_.nodes[static_cast<std::size_t>(f.node)].children;
        if (f.next_child == children.size()) {
          state[static_cast<std::size_t>(f.node)] = 2;
          stack.pop_back();
          continue;
        }
        const int c = children[f.next_child++];
        const std::string wc = json_index("nodes", f.node) + ".children";
        if (state[static_cast<std::size_t>(c)] == 1)
          fail(wc, "names " + json_index("nodes", c) + ", its own ancestor: the node graph has a cycle");
        if (state[static_cast<std::size_t>(c)] == 2)
          fail(wc, "names " + json_index("nodes", c) + ", which already has another parent: glTF nodes form a tree");
        const glm::dmat4 w = f.world * local_transform(model_.nodes[static_cast<std::size_t>(c)], json_index("nodes", c));
        state[static_cast<std::size_t>(c)] = 1;
        visit_node(c, w);
        stack.push_back({c, w, 0});
      }
    }
  }

  std::filesystem::path path_;
  LoadOptions options_;
  gltf::Document doc_;
  tinygltf::Model& model_ = doc_.model;  // the document's, read by every step
  Scene scene_;
  std::vector<int> parent_;  // each node's parent, −1 for a root (node_parents)
  std::vector<std::optional<LightDesc>> light_templates_;  // none: a light of a type not drawn
  std::vector<std::string> variant_names_;  // KHR_materials_variants, in the file's order
  int variant_ = -1;                         // the one --variant selects; −1: none
  std::optional<gltf::DracoPrimitive> draco_;  // the primitive being read, when Draco-compressed
  std::size_t degenerate_triangles_ = 0;
  std::string first_degenerate_;
  bool warned_skin_ = false;
};

}  // namespace

Scene load_gltf(const std::filesystem::path& path, const LoadOptions& options) { return Loader(path, options).run(); }

}  // namespace svbrdf
