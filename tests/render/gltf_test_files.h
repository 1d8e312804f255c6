#pragma once
// Small glTF files written by the tests themselves: a unit quad (or any triangles) with its buffer
// embedded as a data URI, and knobs to break it in each way a malformed file can.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace svbrdf::test {

inline std::string base64(const std::vector<unsigned char>& in) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const unsigned v = (in[i] << 16) | (in[i + 1] << 8) | in[i + 2];
    out += {k[(v >> 18) & 63], k[(v >> 12) & 63], k[(v >> 6) & 63], k[v & 63]};
  }
  if (i + 1 == in.size()) {
    const unsigned v = in[i] << 16;
    out += {k[(v >> 18) & 63], k[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == in.size()) {
    const unsigned v = (in[i] << 16) | (in[i + 1] << 8);
    out += {k[(v >> 18) & 63], k[(v >> 12) & 63], k[(v >> 6) & 63], '='};
  }
  return out;
}

template <typename T>
void append_bytes(std::vector<unsigned char>& out, const std::vector<T>& v) {
  const auto* p = reinterpret_cast<const unsigned char*>(v.data());
  out.insert(out.end(), p, p + v.size() * sizeof(T));
}

// A triangle mesh in one buffer: positions (float VEC3) then indices (uint16), one node, one scene.
// Every field is plain JSON text so a test can replace any part with something broken.
struct GltfQuad {
  std::vector<float> positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  std::vector<std::uint16_t> indices = {0, 1, 2, 0, 2, 3};
  std::vector<float> texcoords;  // optional VEC2 float, after the indices
  long position_count = -1;      // −1: from positions
  long index_count = -1;         // −1: from indices
  long buffer_length = -1;       // declared byteLength; −1: actual
  std::string buffer_uri;        // empty: data URI of the bytes
  std::string nodes = R"([{"mesh": 0}])";
  std::string scene_nodes = "[0]";
  std::string materials;          // JSON array text, or empty for none
  std::string primitive_extra;    // extra members of the primitive, with a leading comma
  std::string top_extra;          // extra top-level members, with a leading comma
  std::string position_accessor = "0";

  std::vector<unsigned char> bytes() const {
    std::vector<unsigned char> b;
    append_bytes(b, positions);
    append_bytes(b, indices);
    while (b.size() % 4) b.push_back(0);
    append_bytes(b, texcoords);
    return b;
  }

  std::string json() const {
    const std::vector<unsigned char> b = bytes();
    const std::size_t pos_bytes = positions.size() * 4, idx_bytes = indices.size() * 2;
    const std::size_t idx_padded = (pos_bytes + idx_bytes + 3) / 4 * 4 - pos_bytes;
    const std::string uri = buffer_uri.empty() ? "data:application/octet-stream;base64," + base64(b) : buffer_uri;
    const long npos = position_count >= 0 ? position_count : long(positions.size() / 3);
    const long nidx = index_count >= 0 ? index_count : long(indices.size());
    std::string s = R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": )" + scene_nodes + "}]";
    s += R"(, "nodes": )" + nodes;
    std::string attrs = R"("POSITION": )" + position_accessor;
    if (!texcoords.empty()) attrs += R"(, "TEXCOORD_0": 2)";
    s += R"(, "meshes": [{"primitives": [{"attributes": {)" + attrs + R"(}, "indices": 1)" + primitive_extra + "}]}]";
    s += R"(, "buffers": [{"uri": ")" + uri + R"(", "byteLength": )" +
         std::to_string(buffer_length >= 0 ? std::size_t(buffer_length) : b.size()) + "}]";
    s += R"(, "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": )" + std::to_string(pos_bytes) + "}";
    s += R"(, {"buffer": 0, "byteOffset": )" + std::to_string(pos_bytes) + R"(, "byteLength": )" +
         std::to_string(idx_bytes) + "}";
    if (!texcoords.empty())
      s += R"(, {"buffer": 0, "byteOffset": )" + std::to_string(pos_bytes + idx_padded) + R"(, "byteLength": )" +
           std::to_string(texcoords.size() * 4) + "}";
    s += "]";
    s += R"(, "accessors": [{"bufferView": 0, "componentType": 5126, "count": )" + std::to_string(npos) +
         R"(, "type": "VEC3"}, {"bufferView": 1, "componentType": 5123, "count": )" + std::to_string(nidx) +
         R"(, "type": "SCALAR"})";
    if (!texcoords.empty())
      s += R"(, {"bufferView": 2, "componentType": 5126, "count": )" + std::to_string(texcoords.size() / 2) +
           R"(, "type": "VEC2"})";
    s += "]";
    if (!materials.empty()) s += R"(, "materials": )" + materials;
    s += top_extra + "}";
    return s;
  }
};

// A fresh directory under the system temp dir, removed at destruction.
class TempDir {
 public:
  TempDir() {
    static int counter = 0;
    path_ = std::filesystem::temp_directory_path() /
            ("svbrdf-render-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path write(const std::string& name, const std::string& text) const {
    const auto p = path_ / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  std::filesystem::path write_bytes(const std::string& name, const std::vector<unsigned char>& b) const {
    const auto p = path_ / name;
    std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
    return p;
  }

 private:
  std::filesystem::path path_;
};

// A .glb container (glTF 2.0 §4.4) with the given JSON and BIN chunk.
inline std::vector<unsigned char> make_glb(std::string json, std::vector<unsigned char> bin) {
  while (json.size() % 4) json += ' ';
  while (bin.size() % 4) bin.push_back(0);
  std::vector<unsigned char> out;
  auto u32 = [&](std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
  };
  const std::uint32_t total = 12 + 8 + std::uint32_t(json.size()) + (bin.empty() ? 0 : 8 + std::uint32_t(bin.size()));
  u32(0x46546C67), u32(2), u32(total);
  u32(std::uint32_t(json.size())), u32(0x4E4F534A);
  out.insert(out.end(), json.begin(), json.end());
  if (!bin.empty()) {
    u32(std::uint32_t(bin.size())), u32(0x004E4942);
    out.insert(out.end(), bin.begin(), bin.end());
  }
  return out;
}

}  // namespace svbrdf::test
