#include "gltf/draco_decode.h"

#include <nlohmann/json.hpp>

#include "base/checked_number.h"
#include "base/error.h"
#include "gltf/accessor.h"
#include "gltf/document.h"
#include "gltf/draco_mesh.h"

namespace svbrdf::gltf {

namespace {

constexpr const char* kExtension = "KHR_draco_mesh_compression";

class DracoReader {
 public:
  DracoReader(const tinygltf::Model& model, const tinygltf::Primitive& p, const tinygltf::Value& extension,
              const std::filesystem::path& file, const std::string& where)
      : model_(model), p_(p), ext_(extension), file_(file), where_(where),
        ext_where_(where + ".extensions." + kExtension) {}

  DracoPrimitive run() {
    if (!ext_.IsObject()) fail(ext_where_, "must be an object");
    // KHR_draco_mesh_compression README, "Restrictions on geometry type": TRIANGLES or TRIANGLE_STRIP.
    // A Draco mesh is a set of triangles whichever of the two the primitive names.
    const int mode = p_.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p_.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP)
      fail(where_ + ".mode", "is " + std::to_string(mode) + "; " + kExtension + " allows TRIANGLES (4) or TRIANGLE_STRIP (5)");
    DracoPrimitive out;
    read(compressed_bytes(), out);
    return out;
  }

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw input_error(file_.string() + ": " + where, what);
  }

  // The extension's bufferView, checked to lie inside its buffer's data.
  std::pair<const unsigned char*, std::size_t> compressed_bytes() const {
    const std::string w = ext_where_ + ".bufferView";
    if (!ext_.Has("bufferView")) fail(ext_where_, "has no bufferView");
    const auto bv = whole_index(ext_.Get("bufferView"));
    if (!bv || static_cast<std::size_t>(*bv) >= model_.bufferViews.size())
      fail(w, "must name one of the file's " + std::to_string(model_.bufferViews.size()) + " buffer views");
    const tinygltf::BufferView& view = model_.bufferViews[static_cast<std::size_t>(*bv)];
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model_.buffers.size())
      fail(w, json_index("bufferViews", *bv) + " names " + json_index("buffers", view.buffer) + ", which the file lacks");
    const std::vector<unsigned char>& data = model_.buffers[static_cast<std::size_t>(view.buffer)].data;
    if (!range_inside(view.byteOffset, view.byteLength, data.size()))
      fail(w, json_index("bufferViews", *bv) + " spans bytes [" + std::to_string(view.byteOffset) + ", +" +
                  std::to_string(view.byteLength) + ") of " + json_index("buffers", view.buffer) + ", which has " +
                  std::to_string(data.size()));
    return {data.data() + view.byteOffset, view.byteLength};
  }

  // KHR_draco_mesh_compression README, "attributes": each names the unique id of a Draco attribute and
  // must be one of the primitive's own attributes, whose accessor "must match the decompressed data":
  // as many elements as the mesh has points, as many components as the Draco attribute.
  void read(std::pair<const unsigned char*, std::size_t> bytes, DracoPrimitive& out) const {
    const std::string aw = ext_where_ + ".attributes";
    if (!ext_.Has("attributes") || !ext_.Get("attributes").IsObject()) fail(ext_where_, "has no attributes object");
    const tinygltf::Value& attrs = ext_.Get("attributes");
    const std::vector<std::string> names = attrs.Keys();
    std::vector<DracoRequest> requests;
    std::vector<int> accessors;
    for (const std::string& name : names) {
      const std::string w = aw + "." + name;
      const auto id = whole_index(attrs.Get(name));
      if (!id) fail(w, "must be a Draco attribute id (a whole number)");
      const auto own = p_.attributes.find(name);
      if (own == p_.attributes.end())
        fail(w, "names " + name + ", which the primitive's attributes lack (the extension's must be a subset)");
      // Any glTF type here: the reader checks each attribute's shape where it reads it.
      const int comps = accessor_components(
          model_, own->second,
          AccessorShape{{TINYGLTF_TYPE_SCALAR, TINYGLTF_TYPE_VEC2, TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4}, {}},
          file_.string() + ": " + where_ + ".attributes." + name);
      requests.push_back({static_cast<std::uint32_t>(*id), comps});
      accessors.push_back(own->second);
    }
    DracoMesh mesh;
    const DracoOutcome outcome = decode_draco_mesh(bytes.first, bytes.second, requests, mesh);
    if (!outcome.error.empty())
      fail(outcome.request < 0 ? ext_where_ + ".bufferView" : aw + "." + names[std::size_t(outcome.request)],
           outcome.error);
    out.points = mesh.points;
    for (std::size_t r = 0; r < names.size(); ++r) {
      const std::size_t count =
          element_count(model_, accessors[r], file_.string() + ": " + where_ + ".attributes." + names[r]);
      if (count != mesh.points)
        fail(aw + "." + names[r], "decodes to " + std::to_string(mesh.points) + " points, but " +
                                      json_index("accessors", accessors[r]) + " says " + std::to_string(count));
      out.attributes[names[r]] = DecodedAttribute{std::move(mesh.values[r]), requests[r].components};
    }
    const std::size_t faces = mesh.indices.size() / 3;
    const int mode = p_.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p_.mode;
    if (p_.indices >= 0 && mode == TINYGLTF_MODE_TRIANGLES) {
      const std::size_t count = element_count(model_, p_.indices, file_.string() + ": " + where_ + ".indices");
      if (count != mesh.indices.size())
        fail(ext_where_ + ".bufferView", "decodes to " + std::to_string(faces) + " triangles (" +
                                             std::to_string(mesh.indices.size()) + " indices), but the primitive's " +
                                             json_index("accessors", p_.indices) + " says " + std::to_string(count));
    }
    out.indices = std::move(mesh.indices);
  }

  const tinygltf::Model& model_;
  const tinygltf::Primitive& p_;
  const tinygltf::Value& ext_;
  const std::filesystem::path& file_;
  std::string where_, ext_where_;
};

}  // namespace

DracoPrimitive decode_draco(const tinygltf::Model& model, const tinygltf::Primitive& p,
                            const tinygltf::Value& extension, const std::filesystem::path& file,
                            const std::string& where) {
  return DracoReader(model, p, extension, file, where).run();
}

std::vector<int> lend_draco_index_views(nlohmann::json& document) {
  std::vector<int> lent;
  if (!document.is_object() || !document.contains("accessors") || !document["accessors"].is_array()) return lent;
  nlohmann::json& accessors = document["accessors"];
  const auto views = document.find("bufferViews");
  const std::size_t view_count = views != document.end() && views->is_array() ? views->size() : 0;
  const auto meshes = document.find("meshes");
  if (view_count == 0 || meshes == document.end() || !meshes->is_array()) return lent;
  for (const auto& mesh : *meshes) {
    const auto prims = mesh.is_object() ? mesh.find("primitives") : mesh.end();
    if (prims == mesh.end() || !prims->is_array()) continue;
    for (const auto& p : *prims) {
      const auto exts = p.is_object() ? p.find("extensions") : p.end();
      const auto indices = p.is_object() ? p.find("indices") : p.end();
      if (exts == p.end() || !exts->is_object() || !exts->contains(kExtension) || indices == p.end() ||
          !indices->is_number_unsigned() || indices->get<std::uint64_t>() >= accessors.size())
        continue;
      const int a = static_cast<int>(indices->get<std::uint64_t>());
      nlohmann::json& accessor = accessors[std::size_t(a)];
      if (!accessor.is_object() || accessor.contains("bufferView")) continue;
      // The extension's own view where it names one, else the first: never read (decode_draco reads
      // the compressed data; the accessor's bufferView is ignored), only there for tinygltf.
      const nlohmann::json& ext = (*exts)[kExtension];
      const auto bv = ext.is_object() ? ext.find("bufferView") : ext.end();
      accessor["bufferView"] =
          bv != ext.end() && bv->is_number_unsigned() && bv->get<std::uint64_t>() < view_count ? bv->get<std::uint64_t>() : 0;
      lent.push_back(a);
    }
  }
  return lent;
}

void return_draco_index_views(const std::vector<int>& accessors, tinygltf::Model& model) {
  for (int a : accessors) model.accessors.at(static_cast<std::size_t>(a)).bufferView = -1;
}

}  // namespace svbrdf::gltf
