#include "gltf/draco_mesh.h"

#include <draco/compression/decode.h>

namespace svbrdf::gltf {

namespace {

// The values of `a` for every point, or why not: the point → value map must cover every point and
// stay inside the values decoded (ConvertValue checks only the byte address).
std::string read_values(const draco::PointAttribute& a, std::size_t points, int components, std::vector<float>& out) {
  if (a.num_components() != components)
    return "decodes to " + std::to_string(a.num_components()) + " components per point, but its accessor has " +
           std::to_string(components);
  const std::size_t mapped = a.is_mapping_identity() ? a.size() : a.indices_map_size();
  if (mapped < points)
    return "maps only " + std::to_string(mapped) + " of the mesh's " + std::to_string(points) + " points";
  out.resize(points * std::size_t(components));
  for (std::size_t i = 0; i < points; ++i) {
    const draco::AttributeValueIndex v = a.mapped_index(draco::PointIndex(static_cast<std::uint32_t>(i)));
    if (v.value() >= a.size() ||
        !a.ConvertValue<float>(v, static_cast<std::int8_t>(components), out.data() + i * std::size_t(components)))
      return "point " + std::to_string(i) + " maps to value " + std::to_string(v.value()) + ", past the " +
             std::to_string(a.size()) + " values decoded";
  }
  return {};
}

}  // namespace

DracoOutcome decode_draco_mesh(const unsigned char* data, std::size_t size, const std::vector<DracoRequest>& requests,
                               DracoMesh& out) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(data), size);
  const auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
  if (!type.ok()) return {std::string("is not Draco data: ") + type.status().error_msg()};
  if (type.value() != draco::TRIANGULAR_MESH) return {"holds a Draco point cloud, not a triangle mesh"};
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) return {std::string("the Draco data does not decode: ") + decoded.status().error_msg()};
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  if (!mesh) return {"the Draco data decodes to no mesh"};

  out.points = mesh->num_points();
  out.values.assign(requests.size(), {});
  for (std::size_t r = 0; r < requests.size(); ++r) {
    const draco::PointAttribute* a = mesh->GetAttributeByUniqueId(requests[r].unique_id);
    if (!a)
      return {"names Draco attribute " + std::to_string(requests[r].unique_id) +
                  ", which the compressed mesh does not have",
              int(r)};
    if (std::string why = read_values(*a, out.points, requests[r].components, out.values[r]); !why.empty())
      return {why, int(r)};
  }
  const std::size_t faces = mesh->num_faces();
  out.indices.reserve(3 * faces);
  for (std::size_t f = 0; f < faces; ++f) {
    const auto& face = mesh->face(draco::FaceIndex(static_cast<std::uint32_t>(f)));
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = face[k].value();
      if (i >= out.points)
        return {"triangle " + std::to_string(f) + " names point " + std::to_string(i) + ", past the " +
                std::to_string(out.points) + " points decoded"};
      out.indices.push_back(i);
    }
  }
  return {};
}

}  // namespace svbrdf::gltf
