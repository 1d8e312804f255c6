#include "gltf/tangents.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>

#include "appearance/frame.h"

namespace svbrdf {

namespace {

struct CornerKey {
  std::uint32_t vertex;
  std::uint32_t bits[4];
  bool operator==(const CornerKey& o) const { return vertex == o.vertex && std::memcmp(bits, o.bits, sizeof bits) == 0; }
};
struct CornerKeyHash {
  std::size_t operator()(const CornerKey& k) const {
    std::size_t h = k.vertex * 0x9E3779B97F4A7C15ULL;
    for (auto b : k.bits) h = (h ^ b) * 0x100000001B3ULL;
    return h;
  }
};

// Exact attribute identity, as MikkTSpace welds vertices before grouping.
struct WeldKey {
  float v[8];
  bool operator==(const WeldKey& o) const { return std::memcmp(v, o.v, sizeof v) == 0; }
};
struct WeldKeyHash {
  std::size_t operator()(const WeldKey& k) const {
    std::size_t h = 1469598103934665603ULL;
    for (float f : k.v) {
      std::uint32_t b;
      std::memcpy(&b, &f, 4);
      h = (h ^ b) * 1099511628211ULL;
    }
    return h;
  }
};

glm::vec3 safe_normalize(const glm::vec3& v) {
  const float l = glm::length(v);
  return l > 0.0f ? v / l : glm::vec3(0.0f);
}

}  // namespace

void make_flat_normals(MeshPrimitive& prim) {
  const std::size_t tris = prim.triangle_count();
  MeshPrimitive out;
  out.material = prim.material;
  out.where = std::move(prim.where);
  const bool has_tangents = !prim.tangents.empty(), has_colors = !prim.colors.empty();
  out.positions.reserve(tris * 3);
  out.normals.reserve(tris * 3);
  for (std::size_t t = 0; t < tris; ++t) {
    const std::uint32_t i[3] = {prim.indices[3 * t], prim.indices[3 * t + 1], prim.indices[3 * t + 2]};
    const glm::vec3 n =
        glm::cross(prim.positions[i[1]] - prim.positions[i[0]], prim.positions[i[2]] - prim.positions[i[0]]);
    const float len = glm::length(n);
    const glm::vec3 nn = len > 0.0f && std::isfinite(len) ? n / len : glm::vec3(0, 0, 1);
    for (int c = 0; c < 3; ++c) {
      out.positions.push_back(prim.positions[i[c]]);
      out.normals.push_back(nn);
      for (int s = 0; s < 2; ++s)
        if (!prim.texcoords[s].empty()) out.texcoords[s].push_back(prim.texcoords[s][i[c]]);
      if (has_tangents) out.tangents.push_back(prim.tangents[i[c]]);
      if (has_colors) out.colors.push_back(prim.colors[i[c]]);
      out.indices.push_back(static_cast<std::uint32_t>(3 * t + c));
    }
  }
  prim = std::move(out);
}

void generate_tangents(MeshPrimitive& prim, int tex_coord) {
  const auto& uvs = prim.texcoords[tex_coord];
  const std::size_t tris = prim.triangle_count();
  const std::size_t nv = prim.positions.size();
  // MikkTSpace's uv has v up.
  auto uv = [&](std::uint32_t i) { return glm::vec2(uvs[i].x, 1.0f - uvs[i].y); };

  // Weld identical vertices (position, normal, uv).
  std::vector<std::uint32_t> weld(nv);
  {
    std::unordered_map<WeldKey, std::uint32_t, WeldKeyHash> ids;
    ids.reserve(nv);
    for (std::size_t i = 0; i < nv; ++i) {
      const glm::vec3 p = prim.positions[i], n = prim.normals[i];
      const glm::vec2 t = uvs[i];
      const WeldKey k{{p.x, p.y, p.z, n.x, n.y, n.z, t.x, t.y}};
      weld[i] = ids.emplace(k, static_cast<std::uint32_t>(ids.size())).first->second;
    }
  }

  // Per triangle: the unit ∂p/∂u and the uv orientation (1, −1, or 0 for degenerate uv/geometry).
  std::vector<glm::vec3> tri_tangent(tris);
  std::vector<int> tri_orient(tris, 0);
  for (std::size_t t = 0; t < tris; ++t) {
    const std::uint32_t i0 = prim.indices[3 * t], i1 = prim.indices[3 * t + 1], i2 = prim.indices[3 * t + 2];
    const glm::vec3 d1 = prim.positions[i1] - prim.positions[i0], d2 = prim.positions[i2] - prim.positions[i0];
    const glm::vec2 t1 = uv(i1) - uv(i0), t2 = uv(i2) - uv(i0);
    const float area = t1.x * t2.y - t1.y * t2.x;  // twice the signed uv area
    // Solving d = Δu·T + Δv·B for T gives T = (t2.y·d1 − t1.y·d2) / area.
    const glm::vec3 os = t2.y * d1 - t1.y * d2;
    const float len = glm::length(os);
    if (area != 0.0f && len > 0.0f && std::isfinite(len)) {
      const float sign = area > 0.0f ? 1.0f : -1.0f;
      tri_tangent[t] = os * (sign / len);
      tri_orient[t] = area > 0.0f ? 1 : -1;
    }
  }

  // Accumulate angle-weighted projected tangents per (welded vertex, orientation) group.
  struct Group {
    glm::vec3 sum{0.0f};
    float weight = 0.0f;
  };
  std::vector<Group> groups(std::size_t(weld.empty() ? 0 : *std::max_element(weld.begin(), weld.end()) + 1) * 2);
  auto group_of = [&](std::uint32_t v, int orient) -> Group& { return groups[std::size_t(weld[v]) * 2 + (orient > 0 ? 1 : 0)]; };
  for (std::size_t t = 0; t < tris; ++t) {
    if (tri_orient[t] == 0) continue;
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t v = prim.indices[3 * t + c];
      const std::uint32_t a = prim.indices[3 * t + (c + 1) % 3], b = prim.indices[3 * t + (c + 2) % 3];
      const glm::vec3 n = safe_normalize(prim.normals[v]);
      const glm::vec3 proj = safe_normalize(tri_tangent[t] - n * glm::dot(n, tri_tangent[t]));
      glm::vec3 e1 = prim.positions[a] - prim.positions[v], e2 = prim.positions[b] - prim.positions[v];
      e1 = safe_normalize(e1 - n * glm::dot(n, e1));
      e2 = safe_normalize(e2 - n * glm::dot(n, e2));
      const float angle = std::acos(glm::clamp(glm::dot(e1, e2), -1.0f, 1.0f));
      Group& g = group_of(v, tri_orient[t]);
      g.sum += proj * angle;
      g.weight += angle;
    }
  }

  // Each corner's tangent; a corner of a degenerate triangle takes its vertex's heavier group.
  std::vector<glm::vec4> corner(tris * 3);
  for (std::size_t t = 0; t < tris; ++t) {
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t v = prim.indices[3 * t + c];
      int orient = tri_orient[t];
      if (orient == 0) orient = group_of(v, 1).weight >= group_of(v, -1).weight ? 1 : -1;
      const glm::vec3 n = safe_normalize(prim.normals[v]);
      glm::vec3 tan = safe_normalize(group_of(v, orient).sum);
      if (tan == glm::vec3(0.0f)) tan = Frame::from_normal(n == glm::vec3(0.0f) ? glm::vec3(0, 0, 1) : n).s;
      corner[3 * t + c] = glm::vec4(tan, orient > 0 ? 1.0f : -1.0f);
    }
  }

  // Write back per vertex, splitting vertices whose corners disagree.
  std::unordered_map<CornerKey, std::uint32_t, CornerKeyHash> remap;
  remap.reserve(nv);
  std::vector<std::uint32_t> source;  // new vertex → old vertex
  std::vector<glm::vec4> tangents;
  source.reserve(nv);
  for (std::size_t k = 0; k < corner.size(); ++k) {
    CornerKey key{prim.indices[k], {}};
    std::memcpy(key.bits, &corner[k], sizeof key.bits);
    auto [it, inserted] = remap.emplace(key, static_cast<std::uint32_t>(source.size()));
    if (inserted) {
      source.push_back(prim.indices[k]);
      tangents.push_back(corner[k]);
    }
    prim.indices[k] = it->second;
  }
  auto gather = [&](auto& attr) {
    if (attr.empty()) return;
    std::remove_reference_t<decltype(attr)> out(source.size());
    for (std::size_t i = 0; i < source.size(); ++i) out[i] = attr[source[i]];
    attr = std::move(out);
  };
  gather(prim.positions);
  gather(prim.normals);
  gather(prim.texcoords[0]);
  gather(prim.texcoords[1]);
  gather(prim.colors);
  prim.tangents = std::move(tangents);
}

}  // namespace svbrdf
