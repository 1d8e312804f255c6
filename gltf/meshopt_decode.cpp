#include "gltf/meshopt_decode.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <set>

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "base/checked_number.h"
#include "base/error.h"
#include "base/resource_limits.h"
#include "gltf/document.h"

namespace svbrdf::gltf {

namespace {

constexpr const char* kExtension = "EXT_meshopt_compression";

// What tinygltf is given in place of a fallback buffer: four zero bytes (it refuses an empty data: URI).
constexpr const char* kPlaceholderUri = "data:application/octet-stream;base64,AAAAAA==";
constexpr std::uint64_t kPlaceholderBytes = 4;

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& where, const std::string& what) {
  throw input_error(file.string() + ": " + where, what);
}

const nlohmann::json* member(const nlohmann::json& o, const char* key) {
  if (!o.is_object()) return nullptr;
  const auto it = o.find(key);
  return it == o.end() ? nullptr : &*it;
}

// The extension object of `o`, or null.
const nlohmann::json* extension_of(const nlohmann::json& o) {
  const nlohmann::json* exts = member(o, "extensions");
  return exts ? member(*exts, kExtension) : nullptr;
}

class Planner {
 public:
  Planner(nlohmann::json& document, bool binary, const std::filesystem::path& file)
      : doc_(document), binary_(binary), file_(file) {}

  MeshoptPlan run() {
    if (!uses_extension()) return {};
    nlohmann::json* buffers = doc_.is_object() && doc_.contains("buffers") ? &doc_["buffers"] : nullptr;
    if (buffers && buffers->is_array()) {
      for (std::size_t i = 0; i < buffers->size(); ++i) {
        nlohmann::json& b = (*buffers)[i];
        lengths_.push_back(b.is_object() && b.contains("byteLength") && b["byteLength"].is_number_unsigned()
                               ? b["byteLength"].get<std::uint64_t>()
                               : 0);
        // EXT_meshopt_compression README, "Fallback buffers": "the referenced buffer can contain no URI";
        // in a .glb, buffer 0 without one is the binary chunk (glTF 2.0 §4.4.3.3).
        if (!b.is_object() || b.contains("uri") || (binary_ && i == 0)) continue;
        plan_.fallback_buffers.emplace_back(int(i), lengths_.back());
        fallback_.insert(int(i));
        b["uri"] = kPlaceholderUri;
        b["byteLength"] = kPlaceholderBytes;
      }
    }
    const nlohmann::json* views = member(doc_, "bufferViews");
    if (views && views->is_array())
      for (std::size_t i = 0; i < views->size(); ++i) read_view((*views)[i], int(i));
    return std::move(plan_);
  }

 private:
  // Only a file that names the extension has its buffers read this way; any other keeps tinygltf's
  // rules (a buffer without uri in a .gltf is an error).
  bool uses_extension() const {
    for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
      const nlohmann::json* names = member(doc_, list);
      if (names && names->is_array())
        for (const auto& n : *names)
          if (n.is_string() && n.get<std::string>() == kExtension) return true;
    }
    return false;
  }

  std::uint64_t whole(const nlohmann::json& ext, const char* key, const std::string& where, bool required,
                      std::uint64_t fallback = 0) const {
    const nlohmann::json* v = member(ext, key);
    if (!v) {
      if (required) fail(file_, where, std::string("has no ") + key);
      return fallback;
    }
    if (!v->is_number_unsigned()) fail(file_, where + "." + key, "must be a non-negative integer");
    return v->get<std::uint64_t>();
  }

  void read_view(const nlohmann::json& view, int index) {
    const std::string vw = json_index("bufferViews", index);
    const nlohmann::json* ext = extension_of(view);
    const nlohmann::json* target = member(view, "buffer");
    const bool into_fallback = target && target->is_number_unsigned() && fallback_.count(int(target->get<std::uint64_t>()));
    if (!ext) {
      // "All references to the buffer must come from bufferViews that have a EXT_meshopt_compression
      // extension specified": a fallback buffer's bytes exist only as the decoded views.
      if (into_fallback)
        fail(file_, vw + ".buffer", "names " + json_index("buffers", int(target->get<std::uint64_t>())) +
                                        ", a fallback buffer with no data, but the view is not compressed");
      return;
    }
    const std::string w = vw + ".extensions." + kExtension;
    if (!ext->is_object()) fail(file_, w, "must be an object");
    MeshoptView m;
    m.view = index;
    const std::uint64_t source = whole(*ext, "buffer", w, true);
    if (source >= lengths_.size())
      fail(file_, w + ".buffer", "names " + json_index("buffers", int(std::min<std::uint64_t>(source, INT32_MAX))) +
                                     ", but the file has " + std::to_string(lengths_.size()) + " buffers");
    m.source_buffer = int(source);
    // "No references to the buffer may come from EXT_meshopt_compression extension JSON."
    if (fallback_.count(m.source_buffer))
      fail(file_, w + ".buffer", "names " + json_index("buffers", m.source_buffer) + ", a fallback buffer with no data");
    m.source_offset = whole(*ext, "byteOffset", w, false);
    m.source_length = whole(*ext, "byteLength", w, true);
    m.stride = whole(*ext, "byteStride", w, true);
    m.count = whole(*ext, "count", w, true);
    if (!range_inside(m.source_offset, m.source_length, lengths_[std::size_t(source)]))
      fail(file_, w, "spans bytes [" + std::to_string(m.source_offset) + ", +" + std::to_string(m.source_length) +
                         ") of " + json_index("buffers", m.source_buffer) + ", which has " +
                         std::to_string(lengths_[std::size_t(source)]));
    m.mode = mode(*ext, w);
    m.filter = filter(*ext, w);
    check_rules(view, m, vw, w);
    plan_.views.push_back(m);
  }

  MeshoptView::Mode mode(const nlohmann::json& ext, const std::string& w) const {
    const nlohmann::json* v = member(ext, "mode");
    if (!v) fail(file_, w, "has no mode");
    const std::string s = v->is_string() ? v->get<std::string>() : v->dump();
    if (s == "ATTRIBUTES") return MeshoptView::Mode::attributes;
    if (s == "TRIANGLES") return MeshoptView::Mode::triangles;
    if (s == "INDICES") return MeshoptView::Mode::indices;
    fail(file_, w + ".mode", "is " + s + "; expected ATTRIBUTES, TRIANGLES or INDICES");
  }

  MeshoptView::Filter filter(const nlohmann::json& ext, const std::string& w) const {
    const nlohmann::json* v = member(ext, "filter");
    if (!v) return MeshoptView::Filter::none;
    const std::string s = v->is_string() ? v->get<std::string>() : v->dump();
    if (s == "NONE") return MeshoptView::Filter::none;
    if (s == "OCTAHEDRAL") return MeshoptView::Filter::octahedral;
    if (s == "QUATERNION") return MeshoptView::Filter::quaternion;
    if (s == "EXPONENTIAL") return MeshoptView::Filter::exponential;
    fail(file_, w + ".filter", "is " + s + "; expected NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");
  }

  // EXT_meshopt_compression README, "JSON schema updates": "For the extension object to be valid, the
  // following must hold". Each is also a precondition of meshoptimizer's decoders (their asserts).
  void check_rules(const nlohmann::json& view, const MeshoptView& m, const std::string& vw, const std::string& w) const {
    using Mode = MeshoptView::Mode;
    using Filter = MeshoptView::Filter;
    const std::string stride = std::to_string(m.stride);
    if (const nlohmann::json* s = member(view, "byteStride"); s && !(s->is_number_unsigned() && s->get<std::uint64_t>() == m.stride))
      fail(file_, w + ".byteStride", "is " + stride + ", but " + vw + ".byteStride is " + s->dump());
    const auto bytes = checked_mul(m.stride, m.count);
    const nlohmann::json* length = member(view, "byteLength");
    if (!bytes || !length || !length->is_number_unsigned() || length->get<std::uint64_t>() != *bytes)
      fail(file_, w, "byteStride " + stride + " times count " + std::to_string(m.count) + " must equal " + vw +
                         ".byteLength (" + (length ? length->dump() : "absent") + ")");
    if (m.mode == Mode::attributes && (m.stride == 0 || m.stride % 4 != 0 || m.stride > 256))
      fail(file_, w + ".byteStride", "is " + stride + "; ATTRIBUTES needs a multiple of 4 from 4 to 256");
    if (m.mode == Mode::triangles && m.count % 3 != 0)
      fail(file_, w + ".count", "is " + std::to_string(m.count) + "; TRIANGLES needs a multiple of 3");
    if (m.mode != Mode::attributes && m.stride != 2 && m.stride != 4)
      fail(file_, w + ".byteStride", "is " + stride + "; TRIANGLES and INDICES need 2 or 4");
    if (m.mode != Mode::attributes && m.filter != Filter::none)
      fail(file_, w + ".filter", "must be NONE for TRIANGLES and INDICES");
    if (m.filter == Filter::octahedral && m.stride != 4 && m.stride != 8)
      fail(file_, w + ".byteStride", "is " + stride + "; OCTAHEDRAL needs 4 or 8");
    if (m.filter == Filter::quaternion && m.stride != 8)
      fail(file_, w + ".byteStride", "is " + stride + "; QUATERNION needs 8");
    // EXPONENTIAL: a multiple of 4, which ATTRIBUTES already requires.
  }

  nlohmann::json& doc_;
  bool binary_;
  const std::filesystem::path& file_;
  MeshoptPlan plan_;
  std::vector<std::uint64_t> lengths_;  // every buffer's byteLength as the file states it
  std::set<int> fallback_;
};

}  // namespace

MeshoptPlan plan_meshopt(nlohmann::json& document, bool binary, const std::filesystem::path& file) {
  return Planner(document, binary, file).run();
}

void decode_meshopt(const MeshoptPlan& plan, tinygltf::Model& model, const std::filesystem::path& file) {
  for (const auto& [buffer, length] : plan.fallback_buffers) {
    // The byteLength was held to the memory budget when the document was first read (check_declared_ranges).
    auto& data = model.buffers.at(static_cast<std::size_t>(buffer)).data;
    data.assign(length, 0);
  }
  std::vector<unsigned char> decoded;
  for (const MeshoptView& m : plan.views) {
    const std::string w = json_index("bufferViews", m.view) + ".extensions." + kExtension;
    const tinygltf::BufferView& view = model.bufferViews.at(static_cast<std::size_t>(m.view));
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
      fail(file, json_index("bufferViews", m.view) + ".buffer", "names a buffer the file lacks");
    std::vector<unsigned char>& target = model.buffers[static_cast<std::size_t>(view.buffer)].data;
    const std::vector<unsigned char>& source = model.buffers.at(static_cast<std::size_t>(m.source_buffer)).data;
    // The file's own lengths were checked from the JSON; checked again against the bytes tinygltf holds.
    if (!range_inside(m.source_offset, m.source_length, source.size()))
      fail(file, w, "spans bytes past the end of " + json_index("buffers", m.source_buffer) + " (" +
                        std::to_string(source.size()) + " bytes)");
    const std::uint64_t bytes = m.stride * m.count;  // checked not to overflow by plan_meshopt
    if (!range_inside(view.byteOffset, bytes, target.size()) || bytes != view.byteLength)
      fail(file, json_index("bufferViews", m.view), "does not fit the " + std::to_string(bytes) + " bytes it decodes to");
    check_allocation(m.count, m.stride, file.string() + ": " + w, "decoded bytes");
    // Decoded apart from the buffer: the filters read 16-bit and 32-bit values, which must be aligned.
    decoded.assign(bytes, 0);
    const unsigned char* in = source.data() + m.source_offset;
    int status = 0;
    switch (m.mode) {
      case MeshoptView::Mode::attributes:
        status = meshopt_decodeVertexBuffer(decoded.data(), m.count, m.stride, in, m.source_length);
        break;
      case MeshoptView::Mode::triangles:
        status = meshopt_decodeIndexBuffer(decoded.data(), m.count, m.stride, in, m.source_length);
        break;
      case MeshoptView::Mode::indices:
        status = meshopt_decodeIndexSequence(decoded.data(), m.count, m.stride, in, m.source_length);
        break;
    }
    if (status != 0)
      fail(file, w, "the compressed data does not decode (meshoptimizer error " + std::to_string(status) + ")");
    switch (m.filter) {
      case MeshoptView::Filter::none: break;
      case MeshoptView::Filter::octahedral: meshopt_decodeFilterOct(decoded.data(), m.count, m.stride); break;
      case MeshoptView::Filter::quaternion: meshopt_decodeFilterQuat(decoded.data(), m.count, m.stride); break;
      case MeshoptView::Filter::exponential: meshopt_decodeFilterExp(decoded.data(), m.count, m.stride); break;
    }
    if (bytes > 0) std::memcpy(target.data() + view.byteOffset, decoded.data(), bytes);
  }
}

}  // namespace svbrdf::gltf
