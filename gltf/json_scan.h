#pragma once
// A byte-level pass over JSON text before any parser builds a tree from it. tinygltf 2.7 turns
// `extras` and `extensions` into its own Value by recursion, one stack frame per level of nesting, so
// 20,000 nested arrays overflow the stack; a pass that only counts brackets outside strings refuses
// such text in linear time, with no allocation and no recursion, before tinygltf sees it. It also
// refuses bytes that JSON never contains outside strings (a NUL, a control character), so a file of
// zeros stops at its first byte instead of being read whole.
//
// Why a scan and not a depth-limited nlohmann-json parse handed to tinygltf: tinygltf 2.7 parses the
// text itself and takes no parsed document, so a checked document could not be handed on; the scan
// costs one pass and no memory.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace svbrdf::gltf {

// The deepest nesting of arrays and objects accepted. A glTF document's own structure is at most 7
// levels deep (root, meshes, primitive, attributes, extensions, an extension, its textureInfo); the
// rest is room for `extras` and extensions that nest application data.
inline constexpr int kMaxJsonDepth = 128;

class JsonScan {
 public:
  // Feeds the next bytes of the text; false once the text is refused (then error() says why).
  bool feed(std::string_view bytes);
  // After the last byte: whether the brackets closed. Returns the reason when not (or refused earlier).
  std::optional<std::string> finish() const;
  const std::string& error() const { return error_; }
  int max_depth_seen() const { return max_depth_; }

 private:
  std::string error_;
  std::uint64_t offset_ = 0;  // bytes fed so far
  int depth_ = 0, max_depth_ = 0;
  bool in_string_ = false, escaped_ = false;
};

// Scans a whole text; the reason it is refused, or nothing.
std::optional<std::string> scan_json(std::string_view text);

}  // namespace svbrdf::gltf
