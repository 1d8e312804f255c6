#include "gltf/tinygltf_stand_ins.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "gltf/document.h"

namespace svbrdf::gltf {

namespace {

// Four zero bytes (with a byteLength of 4): tinygltf refuses an empty data: URI.
constexpr const char* kPlaceholderUri = "data:application/octet-stream;base64,AAAAAA==";
constexpr const char* kOctetStream = "data:application/octet-stream;base64,";

// The data: URI headers tinygltf 2.7 decodes (its IsDataURI).
bool tinygltf_decodes(const std::string& uri) {
  for (const char* h : {"data:application/octet-stream;base64,", "data:image/jpeg;base64,", "data:image/png;base64,",
                        "data:image/bmp;base64,", "data:image/gif;base64,", "data:text/plain;base64,",
                        "data:application/gltf-buffer;base64,"})
    if (uri.rfind(h, 0) == 0) return true;
  return false;
}

// RFC 4648 §4 base64 of `bytes`.
std::string base64(const std::string& bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t v = 0;
    for (std::size_t k2 = 0; k2 < 3; ++k2) v = (v << 8) | (k2 < n ? static_cast<unsigned char>(bytes[i + k2]) : 0u);
    for (std::size_t c = 0; c < 4; ++c) out += c <= n ? k[(v >> (18 - 6 * c)) & 63] : '=';
  }
  return out;
}

// A data: URI tinygltf does not decode, as one it does; anything else unchanged.
std::string decodable(const std::string& uri) {
  if (uri.rfind("data:", 0) != 0 || tinygltf_decodes(uri)) return uri;
  const std::size_t comma = uri.find(',');
  if (comma == std::string::npos) return uri;  // not a data: URI at all; tinygltf says so
  const std::string header = uri.substr(0, comma), data = uri.substr(comma + 1);
  const bool is_base64 = header.size() >= 7 && header.compare(header.size() - 7, 7, ";base64") == 0;
  return kOctetStream + (is_base64 ? data : base64(uri_decode(data)));
}

// A URI with a scheme (RFC 3986 §3.1: a letter, then letters, digits, '+', '-', '.', then ':') other
// than data: names no file beside the glTF.
bool names_remote_resource(const std::string& uri) {
  const std::size_t colon = uri.find(':');
  if (colon == std::string::npos || colon < 2 || !std::isalpha(static_cast<unsigned char>(uri[0]))) return false;
  const bool scheme = std::all_of(uri.begin(), uri.begin() + std::ptrdiff_t(colon), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '-' || c == '.';
  });
  return scheme && uri.rfind("data:", 0) != 0;
}

bool known_type(const nlohmann::json& t) {
  if (!t.is_string()) return true;  // tinygltf reports a type that is not a string itself
  const std::string s = t.get<std::string>();
  return s == "SCALAR" || s == "VEC2" || s == "VEC3" || s == "VEC4" || s == "MAT2" || s == "MAT3" || s == "MAT4";
}

// The members glTF 2.0's schema types as integers (indices, counts, enums), and those whose arrays
// or objects hold integers.
bool integer_member(const std::string& key) {
  static const char* const k[] = {"buffer", "byteLength", "byteOffset", "byteStride", "count", "componentType",
                                  "bufferView", "index", "texCoord", "source", "sampler", "mesh", "camera", "skin",
                                  "node", "scene", "material", "indices", "mode", "target", "magFilter", "minFilter",
                                  "wrapS", "wrapT", "input", "output", "skeleton", "inverseBindMatrices", "children",
                                  "nodes", "joints", "attributes", "targets"};
  return std::find(std::begin(k), std::end(k), key) != std::end(k);
}

// Rewrites, under the integer members of the core schema (not inside extras or extensions), each
// number written as a float with no fraction as the integer. Whether any was.
bool whole_floats_as_integers(nlohmann::json& v, const std::string& key) {
  bool changed = false;
  if (v.is_object()) {
    for (auto& [k, child] : v.items())
      if (k != "extras" && k != "extensions") changed |= whole_floats_as_integers(child, integer_member(key) ? key : k);
  } else if (v.is_array()) {
    for (auto& child : v) changed |= whole_floats_as_integers(child, key);
  } else if (v.is_number_float() && integer_member(key)) {
    const double x = v.get<double>();
    if (x >= 0 && x < 9.007199254740992e15 && x == std::floor(x)) {
      v = static_cast<std::uint64_t>(x);
      changed = true;
    }
  }
  return changed;
}

}  // namespace

StandIns lend_stand_ins(nlohmann::json& document, bool binary) {
  StandIns lent;
  if (!document.is_object()) return lent;
  if (auto buffers = document.find("buffers"); buffers != document.end() && buffers->is_array()) {
    for (std::size_t i = 0; i < buffers->size(); ++i) {
      nlohmann::json& b = (*buffers)[i];
      if (!b.is_object()) continue;
      const auto uri = b.find("uri");
      const bool binary_chunk = binary && i == 0;
      if ((uri == b.end() && !binary_chunk) ||
          (uri != b.end() && uri->is_string() && names_remote_resource(uri->get<std::string>()))) {
        lent.empty_buffers.emplace_back(int(i), uri == b.end() || !uri->is_string() ? "" : uri->get<std::string>());
        b["uri"] = kPlaceholderUri;
        b["byteLength"] = 4;  // tinygltf holds a data: URI to its byteLength
      } else if (uri != b.end() && uri->is_string()) {
        const std::string d = decodable(uri->get<std::string>());
        if (d != uri->get<std::string>()) *uri = d, lent.rewritten = true;
      }
    }
  }
  if (auto images = document.find("images"); images != document.end() && images->is_array())
    for (nlohmann::json& im : *images) {
      const auto uri = im.is_object() ? im.find("uri") : im.end();
      if (uri == im.end() || !uri->is_string()) continue;
      const std::string d = decodable(uri->get<std::string>());
      if (d != uri->get<std::string>()) *uri = d, lent.rewritten = true;
    }
  auto accessors = document.find("accessors");
  const bool have_accessors = accessors != document.end() && accessors->is_array();
  if (have_accessors)
    for (std::size_t i = 0; i < accessors->size(); ++i) {
      nlohmann::json& a = (*accessors)[i];
      if (a.is_object() && a.contains("type") && !known_type(a["type"])) {
        a["type"] = "SCALAR";
        lent.unknown_types.push_back(int(i));
      }
    }
  if (auto meshes = document.find("meshes"); have_accessors && meshes != document.end() && meshes->is_array())
    for (std::size_t m = 0; m < meshes->size(); ++m) {
      nlohmann::json& mesh = (*meshes)[m];
      const auto prims = mesh.is_object() ? mesh.find("primitives") : mesh.end();
      if (prims == mesh.end() || !prims->is_array()) continue;
      for (std::size_t p = 0; p < prims->size(); ++p) {
        nlohmann::json& prim = (*prims)[p];
        const auto indices = prim.is_object() ? prim.find("indices") : prim.end();
        if (indices == prim.end() || !indices->is_number_unsigned() || indices->get<std::uint64_t>() >= accessors->size())
          continue;
        const auto a = indices->get<std::uint64_t>();
        const nlohmann::json& accessor = (*accessors)[a];
        // KHR_draco_mesh_compression's index accessors are lent a view by their module.
        const auto exts = prim.find("extensions");
        if (exts != prim.end() && exts->is_object() && exts->contains("KHR_draco_mesh_compression")) continue;
        if (!accessor.is_object() || accessor.contains("bufferView")) continue;
        prim.erase("indices");
        lent.removed_indices.push_back({int(m), int(p), int(a)});
      }
    }
  lent.rewritten = whole_floats_as_integers(document, "") || lent.rewritten || !lent.empty_buffers.empty() || !lent.removed_indices.empty() ||
                   !lent.unknown_types.empty();
  return lent;
}

void return_stand_ins(const StandIns& lent, tinygltf::Model& model) {
  for (const auto& [b, uri] : lent.empty_buffers) {
    tinygltf::Buffer& buffer = model.buffers.at(std::size_t(b));
    std::vector<unsigned char>().swap(buffer.data);
    buffer.uri = uri;
  }
  for (const auto& [m, p, a] : lent.removed_indices)
    model.meshes.at(std::size_t(m)).primitives.at(std::size_t(p)).indices = a;
  for (const int a : lent.unknown_types) model.accessors.at(std::size_t(a)).type = -1;
}

}  // namespace svbrdf::gltf
