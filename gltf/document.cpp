#include "gltf/document.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
#include <nlohmann/json.hpp>

#include "base/atomic_file.h"
#include "base/checked_number.h"
#include "base/error.h"
#include "base/resource_limits.h"
#include "gltf/draco_decode.h"
#include "gltf/json_scan.h"
#include "gltf/meshopt_decode.h"
#include "gltf/tinygltf_stand_ins.h"

namespace svbrdf::gltf {

namespace fs = std::filesystem;

std::string json_index(const char* array, int i) { return std::string(array) + "[" + std::to_string(i) + "]"; }

std::optional<int> whole_index(const tinygltf::Value& v) {
  if (!v.IsNumber()) return std::nullopt;
  if (v.IsInt()) return v.Get<int>() >= 0 ? std::optional<int>(v.Get<int>()) : std::nullopt;
  return whole_int(v.Get<double>(), 0);
}

bool finite_all(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

double number_or(const tinygltf::Value& object, const char* key, double fallback) {
  if (!object.IsObject() || !object.Has(key)) return fallback;
  const tinygltf::Value& x = object.Get(key);
  return x.IsNumber() ? x.GetNumberAsDouble() : std::nan("");
}

float in_range(double x, double lo, double hi, const std::filesystem::path& file, const std::string& where) {
  if (!std::isfinite(x) || x < lo || x > hi) {
    std::ostringstream s;
    s << "is " << x << ", outside [" << lo << ", " << hi << "]";
    throw input_error(file.string() + ": " + where, s.str());
  }
  return static_cast<float>(x);
}

std::string uri_decode(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    auto hex = [](char c) { return std::isxdigit(static_cast<unsigned char>(c)) != 0; };
    if (s[i] == '%' && i + 2 < s.size() && hex(s[i + 1]) && hex(s[i + 2])) {
      out += static_cast<char>(std::stoi(s.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

namespace {

// What the document says of the files beside it, read before tinygltf opens any of them.
struct FileRules {
  std::map<fs::path, std::uint64_t> buffer_bytes;  // a buffer's file → its byteLength
  // The image file read_whole_file last checked and left unread: tinygltf hands the image loader
  // (keep_image_bytes) the bytes of the file it just read, one image at a time.
  fs::path unread_image;
  std::string error;                               // the first file refused, for the message
  std::map<fs::path, std::string> refused;         // every file refused → why
};

fs::path normal(const fs::path& p) {
  std::error_code ec;
  const fs::path abs = fs::absolute(p, ec);
  return (ec ? p : abs).lexically_normal();
}

// Reads the regular file `path` whole into `out`, or says why not. `size_refusal` sees the file's size
// before a byte is read and returns why it is refused (empty: accepted); `feed` sees each piece as it
// is read (1 MiB at a time) and may refuse it the same way. Opened non-blocking, so a FIFO or a device
// is refused rather than waited on.
template <typename Bytes>
std::string read_regular_file(const std::string& path, Bytes& out,
                              const std::function<std::string(std::uint64_t)>& size_refusal,
                              const std::function<std::string(std::string_view, std::uint64_t)>& feed) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) return errno == ENOENT ? "does not exist" : "cannot be opened: " + errno_text(errno);
  struct stat st {};
  std::string why;
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) why = "is not a regular file";
  const auto size = static_cast<std::uint64_t>(st.st_size);
  if (why.empty()) why = size_refusal(size);
  if (why.empty()) {
    out.resize(size);
    for (std::uint64_t got = 0; got < size && why.empty();) {
      const ssize_t n = ::read(fd, out.data() + got, std::min<std::uint64_t>(size - got, 1 << 20));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        why = n < 0 ? "cannot be read: " + errno_text(errno) : "ended while being read";
        break;
      }
      if (feed) why = feed(std::string_view(reinterpret_cast<const char*>(out.data()) + got, std::size_t(n)), got);
      got += std::uint64_t(n);
    }
  }
  ::close(fd);
  return why;
}

// Why an image file of `size` bytes is refused, or empty.
std::string image_size_refusal(std::uint64_t size) {
  if (size > image_file_limit() || size > resource_limits().memory_bytes)
    return "is " + byte_size_text(size) + ", more than an image of at most " + std::to_string(resource_limits().max_texels) +
           " texels can be (--max-texels)";
  return {};
}

// tinygltf's file reader, replaced: only regular files (a FIFO or a device would hang or never end),
// and no more bytes than the document allows the file — a buffer exactly its byteLength, an image
// at most image_file_limit() — checked from the file's size before reading. An image file is only
// checked: tinygltf gets one placeholder byte, and take_image_bytes reads the file when its image is
// decoded.
bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  auto* rules = static_cast<FileRules*>(user);
  auto refuse = [&](const std::string& why) {
    const std::string line = "'" + path + "' " + why;
    if (rules->error.empty()) rules->error = line;
    rules->refused[normal(path)] = line;
    if (err) *err += line + "\n";
    return false;
  };
  const auto it = rules->buffer_bytes.find(normal(path));
  const bool buffer = it != rules->buffer_bytes.end();
  std::uint64_t image_size = 0;
  // The image's size is checked, then its reading stopped before a byte is read.
  static const std::string kUnread = "unread";
  std::string why = read_regular_file(
      path, *out,
      [&](std::uint64_t size) -> std::string {
        if (buffer && size != it->second)
          return "is " + std::to_string(size) + " bytes; its buffer's byteLength says " + std::to_string(it->second);
        if (buffer) return {};
        image_size = size;
        const std::string refusal = image_size_refusal(size);
        return refusal.empty() ? kUnread : refusal;
      },
      nullptr);
  if (why == kUnread) {
    why.clear();
    // An empty file stays empty: tinygltf then reports the image as unreadable, as it would.
    out->assign(image_size > 0 ? 1 : 0, 0);
    rules->unread_image = path;
  }
  return why.empty() ? true : refuse(why);
}

bool file_exists(const std::string& path, void*) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0;
}

std::string no_expansion(const std::string& path, void*) { return path; }

// A non-negative integer member, or nothing when absent or of another type (tinygltf reports those).
std::optional<std::uint64_t> unsigned_member(const nlohmann::json& o, const char* key) {
  if (!o.is_object()) return std::nullopt;
  const auto it = o.find(key);
  if (it == o.end() || !it->is_number_unsigned()) return std::nullopt;
  return it->get<std::uint64_t>();
}

class Reader {
 public:
  explicit Reader(const fs::path& path) : path_(path) { doc_.path = path; }

  Document run() {
    const std::string bytes = read_file();
    const bool binary = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
    std::string_view json = binary ? glb_json_chunk(bytes) : std::string_view(bytes);
    if (!binary && json.size() >= 3 && json.compare(0, 3, "\xEF\xBB\xBF") == 0) json.remove_prefix(3);
    // A text file was scanned as it was read; a .glb's JSON chunk is scanned here.
    if (binary)
      if (auto why = scan_json(json)) fail("", "not a glTF file: " + *why);
    nlohmann::json document = check_declared_ranges(json);
    // Two kinds of compressed geometry are written in ways tinygltf 2.7 refuses: EXT_meshopt_compression's
    // fallback buffers with no bytes (gltf/meshopt_decode.h) and KHR_draco_mesh_compression's index
    // accessors with no bufferView (gltf/draco_decode.h). tinygltf is then given a copy of the JSON with
    // placeholders, taken back after.
    const MeshoptPlan meshopt = plan_meshopt(document, binary, path_);
    const std::vector<int> lent = lend_draco_index_views(document);
    const StandIns stand_ins = lend_stand_ins(document, binary);
    if (meshopt.fallback_buffers.empty() && lent.empty() && !stand_ins.rewritten) {
      parse(bytes, binary, binary ? glb_length_ : bytes.size());
    } else {
      const std::string rewritten = binary ? glb_with_json(bytes, document.dump()) : document.dump();
      parse(rewritten, binary, rewritten.size());
    }
    check_every_primitive_read(document);
    doc_.animation_channels = kept_channels(document);
    return_draco_index_views(lent, doc_.model);
    return_stand_ins(stand_ins, doc_.model);
    decode_meshopt(meshopt, doc_.model, path_);
    doc_.images.resize(doc_.model.images.size());
    // An image file refused by read_whole_file: say why rather than only that it is missing.
    const fs::path base = path_.has_parent_path() ? path_.parent_path() : fs::path(".");
    for (std::size_t i = 0; i < doc_.images.size(); ++i) {
      const std::string& uri = doc_.model.images[i].uri;
      if (doc_.images[i].loaded || uri.empty() || uri.rfind("data:", 0) == 0) continue;
      const auto it = rules_.refused.find(normal(base / uri_decode(uri)));
      if (it != rules_.refused.end()) doc_.images[i].error = it->second;
    }
    return std::move(doc_);
  }

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw input_error(path_.string() + (where.empty() ? "" : ": " + where), what);
  }

  // tinygltf 2.7 leaves out, without an error, a primitive it cannot read: one whose attributes
  // (required, glTF 2.0 mesh.primitive) are missing or not an object of accessor indices. Every
  // primitive the file lists must have been read, or the file is refused naming the first such one.
  void check_every_primitive_read(const nlohmann::json& document) const {
    const auto meshes = document.find("meshes");
    if (meshes == document.end() || !meshes->is_array()) return;
    for (std::size_t m = 0; m < meshes->size() && m < doc_.model.meshes.size(); ++m) {
      const nlohmann::json& mesh = (*meshes)[m];
      const auto prims = mesh.is_object() ? mesh.find("primitives") : mesh.end();
      if (prims == mesh.end() || !prims->is_array() || doc_.model.meshes[m].primitives.size() == prims->size()) continue;
      std::size_t p = 0;
      const auto readable = [](const nlohmann::json& prim) {
        const auto a = prim.is_object() ? prim.find("attributes") : prim.end();
        if (a == prim.end() || !a->is_object()) return false;
        for (const auto& v : *a)
          if (!v.is_number_integer()) return false;
        return true;
      };
      while (p + 1 < prims->size() && readable((*prims)[p])) ++p;
      fail("meshes[" + std::to_string(m) + "].primitives[" + std::to_string(p) + "]",
           "a primitive that cannot be read: its attributes, required, must be an object of accessor indices");
    }
  }

  // Which channels of each animation tinygltf 2.7 kept (Document::animation_channels): its rule, an
  // integer `sampler` and, where `target` is an object, an integer `node` and a string `path` in it.
  // Where the count is not tinygltf's, each channel is taken to be the file's own.
  std::vector<std::vector<int>> kept_channels(const nlohmann::json& document) const {
    std::vector<std::vector<int>> out(doc_.model.animations.size());
    const auto animations = document.find("animations");
    for (std::size_t a = 0; a < out.size(); ++a) {
      const std::size_t kept = doc_.model.animations[a].channels.size();
      if (animations != document.end() && animations->is_array() && a < animations->size()) {
        const nlohmann::json& anim = (*animations)[a];
        const auto channels = anim.is_object() ? anim.find("channels") : anim.end();
        if (channels != anim.end() && channels->is_array())
          for (std::size_t c = 0; c < channels->size(); ++c) {
            const nlohmann::json& ch = (*channels)[c];
            if (!ch.is_object() || !ch.contains("sampler") || !ch["sampler"].is_number_integer()) continue;
            const auto target = ch.find("target");
            if (target != ch.end() && target->is_object() &&
                (!target->contains("node") || !(*target)["node"].is_number_integer() || !target->contains("path") ||
                 !(*target)["path"].is_string()))
              continue;
            out[a].push_back(int(c));
          }
      }
      if (out[a].size() != kept) {
        out[a].resize(kept);
        for (std::size_t c = 0; c < kept; ++c) out[a][c] = int(c);
      }
    }
    return out;
  }

  // The whole file, refused before reading when it is not a regular file or larger than the memory
  // budget allows. A text file is scanned as it is read, so a file that is not JSON (zeros, a binary)
  // is refused at its first bad byte rather than after reading all of it.
  std::string read_file() const {
    std::string bytes;
    JsonScan scan;
    bool text = false;
    const std::string why = read_regular_file(
        path_.string(), bytes,
        [&](std::uint64_t size) -> std::string {
          if (size <= resource_limits().memory_bytes) return {};
          return "is " + byte_size_text(size) + ", over the memory budget of " +
                 byte_size_text(resource_limits().memory_bytes);
        },
        [&](std::string_view piece, std::uint64_t from) -> std::string {
          if (from == 0) {
            text = piece.compare(0, 4, "glTF") != 0;  // a .glb starts with its magic; trust bytes over names
            if (piece.compare(0, 3, "\xEF\xBB\xBF") == 0) piece.remove_prefix(3);
          }
          return !text || scan.feed(piece) ? std::string() : "not a glTF file: " + scan.error();
        });
    if (why == "does not exist") fail("", "no such glTF file");
    if (!why.empty()) fail("", why);
    return bytes;
  }

  // The JSON chunk of a binary glTF (glTF 2.0 §4.4), every length checked against the bytes present.
  std::string_view glb_json_chunk(const std::string& b) {
    auto u32 = [&](std::size_t at) {
      std::uint32_t v;
      std::memcpy(&v, b.data() + at, 4);
      return v;  // little-endian, as the format and every machine this builds for
    };
    if (b.size() < 20) fail("", "a binary glTF shorter than its 12-byte header and first chunk header");
    if (u32(4) != 2) fail("", "binary glTF version " + std::to_string(u32(4)) + "; only version 2 is read");
    const std::uint64_t length = u32(8);
    glb_length_ = length;
    if (length > b.size())
      fail("", "binary glTF header says " + std::to_string(length) + " bytes, the file has " + std::to_string(b.size()));
    const std::uint64_t json_length = u32(12);
    if (u32(16) != 0x4E4F534Au) fail("", "the first chunk of a binary glTF is not JSON");
    if (!range_inside(20, json_length, length))
      fail("", "the JSON chunk's length " + std::to_string(json_length) + " runs past the file's " +
                   std::to_string(length) + " bytes");
    glb_json_end_ = 20 + json_length;
    return std::string_view(b.data() + 20, json_length);
  }

  // The .glb `b` with its JSON chunk replaced by `json` and every later chunk kept as it was.
  std::string glb_with_json(const std::string& b, std::string json) const {
    while (json.size() % 4 != 0) json += ' ';  // glTF 2.0 §4.4.3.2: the JSON chunk is padded with spaces
    const std::string_view rest(b.data() + glb_json_end_, glb_length_ - glb_json_end_);
    const std::uint64_t total = 20 + json.size() + rest.size();
    if (total > std::numeric_limits<std::uint32_t>::max()) fail("", "a binary glTF of 4 GiB or more");
    std::string out;
    auto u32 = [&](std::uint64_t v) {
      for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xFF);
    };
    out += "glTF";
    u32(2), u32(total), u32(json.size());
    out += "JSON";
    out += json;
    out += rest;
    return out;
  }

  // Buffer views against the byteLength of their buffers, and each buffer's file against the size it
  // must have, from the JSON itself: tinygltf 2.7 forms &buffer.data[view.byteOffset] for an image
  // before any check, and reads a buffer's file whole before comparing its size. Returns the JSON.
  nlohmann::json check_declared_ranges(std::string_view text) {
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(text.begin(), text.end());
    } catch (const nlohmann::json::exception& e) {
      fail("", std::string("not a readable glTF file: ") + e.what());
    }
    if (!j.is_object()) fail("", "not a glTF file: the JSON is not an object");
    check_integers(j, "");
    check_asset_and_collections(j);
    std::vector<std::optional<std::uint64_t>> buffer_length;
    const fs::path base = path_.has_parent_path() ? path_.parent_path() : fs::path(".");
    if (const auto it = j.find("buffers"); it != j.end() && it->is_array()) {
      for (std::size_t i = 0; i < it->size(); ++i) {
        const auto& b = (*it)[i];
        const auto length = unsigned_member(b, "byteLength");
        buffer_length.push_back(length);
        // The schema's minimum (glTF 2.0, buffer.schema.json); tinygltf 2.7 copies a .glb's BIN chunk
        // into an empty buffer through data.at(0), which throws std::out_of_range.
        if (length && *length == 0) fail(json_index("buffers", int(i)) + ".byteLength", "is 0; a buffer has at least 1 byte");
        if (length && *length > resource_limits().memory_bytes)
          fail(json_index("buffers", int(i)) + ".byteLength",
               "is " + byte_size_text(*length) + ", over the memory budget of " +
                   byte_size_text(resource_limits().memory_bytes));
        const auto uri = b.is_object() ? b.find("uri") : b.end();
        if (length && uri != b.end() && uri->is_string() && uri->get<std::string>().rfind("data:", 0) != 0)
          rules_.buffer_bytes[normal(base / uri_decode(uri->get<std::string>()))] = *length;
      }
    }
    if (const auto it = j.find("bufferViews"); it != j.end() && it->is_array()) {
      for (std::size_t i = 0; i < it->size(); ++i) {
        const auto& v = (*it)[i];
        const auto buffer = unsigned_member(v, "buffer");
        const auto length = unsigned_member(v, "byteLength");
        const std::uint64_t offset = unsigned_member(v, "byteOffset").value_or(0);
        if (!buffer || !length) continue;  // tinygltf reports a missing required member
        const std::string w = json_index("bufferViews", int(i));
        // glTF 2.0 §5.11 (bufferView.byteStride): within [4, 252], a multiple of 4.
        if (const auto stride = unsigned_member(v, "byteStride"); stride && (*stride < 4 || *stride > 252 || *stride % 4))
          fail(w + ".byteStride", "is " + std::to_string(*stride) + "; glTF allows multiples of 4 from 4 to 252");
        if (*buffer >= buffer_length.size())
          fail(w + ".buffer", "names buffers[" + std::to_string(*buffer) + "], but the file has " +
                                  std::to_string(buffer_length.size()) + " buffers");
        const auto have = buffer_length[*buffer];
        if (have && !range_inside(offset, *length, *have))
          fail(w, "spans bytes [" + std::to_string(offset) + ", +" + std::to_string(*length) + ") of buffers[" +
                      std::to_string(*buffer) + "], which has " + std::to_string(*have) + " bytes");
      }
    }
    return j;
  }

  // glTF 2.0 §3.3 and §5.3: every top-level collection is an array (tinygltf 2.7 skips one that is
  // not, and the file would render without it), and the asset names the version it targets as
  // MAJOR.MINOR; a reader of glTF 2.0 reads major version 2 only, and no file whose minVersion asks
  // for a later minor version ("a minimum version that a client implementation must support").
  void check_asset_and_collections(const nlohmann::json& j) const {
    for (const char* key : {"accessors", "animations", "buffers", "bufferViews", "cameras", "images", "materials",
                            "meshes", "nodes", "samplers", "scenes", "skins", "textures", "extensionsUsed",
                            "extensionsRequired"})
      if (const auto it = j.find(key); it != j.end() && !it->is_array())
        fail(key, "is " + std::string(it->type_name()) + ", not an array");
    const auto asset = j.find("asset");
    if (asset == j.end() || !asset->is_object()) return;  // tinygltf reports a missing asset
    auto version = [&](const char* key) -> std::optional<std::pair<unsigned long, unsigned long>> {
      const auto v = asset->find(key);
      if (v == asset->end()) return std::nullopt;
      const std::string text = v->is_string() ? v->get<std::string>() : v->dump();
      const std::size_t dot = text.find('.');
      const auto digits = [](const std::string& s) {
        return !s.empty() && s.size() < 10 && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
      };
      if (!v->is_string() || dot == std::string::npos || !digits(text.substr(0, dot)) || !digits(text.substr(dot + 1)))
        fail(std::string("asset.") + key, "is '" + text + "', not a glTF version MAJOR.MINOR");
      return std::pair(std::stoul(text.substr(0, dot)), std::stoul(text.substr(dot + 1)));
    };
    const auto v = version("version");
    if (v && v->first != 2)
      fail("asset.version", "is " + std::to_string(v->first) + "." + std::to_string(v->second) +
                                "; this reader reads glTF 2.x");
    const auto min = version("minVersion");
    if (min && (min->first != 2 || min->second > 0))
      fail("asset.minVersion", "is " + std::to_string(min->first) + "." + std::to_string(min->second) +
                                   ": the file needs a glTF reader of that version; this one reads glTF 2.0");
  }

  // tinygltf 2.7 stores indices (bufferView, material, texture, node, ...) and every integer inside
  // an extension as a 32-bit int, truncating larger ones: an index of 2^33 would silently become 0.
  // Every integer of the document outside `extras` (application data tinygltf never interprets) must
  // fit an int, but the four byte and element counts tinygltf keeps in 64 bits.
  void check_integers(const nlohmann::json& v, const std::string& where) const {
    if (v.is_object()) {
      for (const auto& [key, child] : v.items()) {
        if (key == "extras") continue;
        const std::string w = where.empty() ? key : where + "." + key;
        const bool wide = key == "byteOffset" || key == "byteLength" || key == "count" || key == "byteStride";
        if (!(wide && child.is_number_unsigned())) check_integers(child, w);
      }
    } else if (v.is_array()) {
      for (std::size_t i = 0; i < v.size(); ++i) check_integers(v[i], where + "[" + std::to_string(i) + "]");
    } else if (v.is_number_integer()) {
      const bool fits = v.is_number_unsigned() ? v.get<std::uint64_t>() <= std::uint64_t(std::numeric_limits<int>::max())
                                               : v.get<std::int64_t>() >= std::numeric_limits<int>::min();
      if (!fits) fail(where, "is " + v.dump() + ", beyond the range of a 32-bit integer");
    }
  }

  void parse(const std::string& bytes, bool binary, std::uint64_t length) {
    // tinygltf 2.7 takes the length as unsigned int; a .glb's is one by format.
    if (length > std::numeric_limits<unsigned int>::max()) fail("", "a glTF JSON text of 4 GiB or more");
    tinygltf::TinyGLTF reader;
    tinygltf::FsCallbacks fs{&file_exists, &no_expansion, &read_whole_file, nullptr, &rules_};
    reader.SetFsCallbacks(fs);
    reader.SetImageLoader(&Reader::keep_image_bytes, this);
    reader.SetPreserveImageChannels(true);
    std::string err, warn;
    const std::string base = path_.has_parent_path() ? path_.parent_path().string() : ".";
    const bool ok =
        binary ? reader.LoadBinaryFromMemory(&doc_.model, &err, &warn,
                                             reinterpret_cast<const unsigned char*>(bytes.data()),
                                             static_cast<unsigned int>(length), base)
               : reader.LoadASCIIFromString(&doc_.model, &err, &warn, bytes.data(),
                                            static_cast<unsigned int>(length), base);
    if (!ok) {
      if (!rules_.error.empty()) fail("", rules_.error);
      fail("", "not a readable glTF file: " + first_line(err.empty() ? warn : err));
    }
  }

  // tinygltf's message, made one line and short (it can quote a whole data: URI).
  static std::string first_line(const std::string& s) {
    std::string line = s.substr(0, s.find('\n'));
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    constexpr std::size_t kMax = 200;
    if (line.size() > kMax) line = line.substr(0, kMax) + "...";
    return line;
  }

  static bool keep_image_bytes(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
                               const unsigned char* bytes, int size, void* user) {
    auto* self = static_cast<Reader*>(user);
    if (index < 0) return false;
    auto& images = self->doc_.images;
    if (static_cast<std::size_t>(index) >= images.size()) images.resize(std::size_t(index) + 1);
    ImageBytes& ib = images[static_cast<std::size_t>(index)];
    if (image->bufferView >= 0) {
      // The view was checked against its buffer's byteLength (check_declared_ranges), and tinygltf
      // makes every buffer's data exactly that long; checked again here against the data itself.
      const auto& m = self->doc_.model;
      const auto& view = m.bufferViews[static_cast<std::size_t>(image->bufferView)];
      const auto& buffer = m.buffers[static_cast<std::size_t>(view.buffer)];
      if (!range_inside(view.byteOffset, view.byteLength, buffer.data.size()) ||
          view.byteLength > std::uint64_t(std::numeric_limits<int>::max())) {
        ib.error = json_index("bufferViews", image->bufferView) + " spans bytes past the end of " +
                   json_index("buffers", view.buffer) + " (" + std::to_string(buffer.data.size()) + " bytes)";
        return true;
      }
    }
    const bool external = image->bufferView < 0 && !image->uri.empty() && image->uri.rfind("data:", 0) != 0;
    if (external && !self->rules_.unread_image.empty()) {
      ib.file = self->rules_.unread_image;
      self->rules_.unread_image.clear();
    } else if (size > 0 && bytes) {
      ib.bytes.assign(bytes, bytes + size);
    }
    ib.loaded = true;
    return true;
  }

  fs::path path_;
  std::uint64_t glb_length_ = 0;
  std::uint64_t glb_json_end_ = 0;  // where a .glb's JSON chunk ends: the next chunk's header
  Document doc_;
  FileRules rules_;
};

}  // namespace

Document read_document(const fs::path& path) { return Reader(path).run(); }

std::vector<unsigned char> take_image_bytes(Document& doc, std::size_t i) {
  ImageBytes& ib = doc.images.at(i);
  std::vector<unsigned char> out;
  if (ib.file.empty()) {
    out.swap(ib.bytes);
    return out;
  }
  const std::string why = read_regular_file(ib.file.string(), out, image_size_refusal, nullptr);
  if (!why.empty())
    throw input_error(doc.path.string() + ": " + json_index("images", int(i)), "'" + ib.file.string() + "' " + why);
  ib.file.clear();
  return out;
}

}  // namespace svbrdf::gltf
