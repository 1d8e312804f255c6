#include "gltf/json_scan.h"

namespace svbrdf::gltf {

bool JsonScan::feed(std::string_view bytes) {
  if (!error_.empty()) return false;
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    const auto c = static_cast<unsigned char>(bytes[i]);
    const std::uint64_t at = offset_ + i;
    if (in_string_) {
      // RFC 8259 §7: control characters must be escaped inside strings.
      if (c < 0x20) {
        error_ = "JSON text has control byte " + std::to_string(c) + " inside a string at byte " + std::to_string(at);
        return false;
      }
      if (escaped_) escaped_ = false;
      else if (c == '\\') escaped_ = true;
      else if (c == '"') in_string_ = false;
      continue;
    }
    switch (c) {
      case '"': in_string_ = true; break;
      case '[':
      case '{':
        if (++depth_ > kMaxJsonDepth) {
          error_ = "JSON nests deeper than " + std::to_string(kMaxJsonDepth) + " levels (at byte " +
                   std::to_string(at) + ")";
          return false;
        }
        if (depth_ > max_depth_) max_depth_ = depth_;
        break;
      case ']':
      case '}':
        if (--depth_ < 0) {
          error_ = "JSON text closes a bracket it never opened at byte " + std::to_string(at);
          return false;
        }
        break;
      case ' ': case '\t': case '\n': case '\r': break;
      default:
        // RFC 8259 §2: outside strings only whitespace (above) and printable ASCII tokens occur.
        if (c < 0x20 || c >= 0x7f) {
          error_ = "JSON text has byte " + std::to_string(c) + " outside a string at byte " + std::to_string(at);
          return false;
        }
    }
  }
  offset_ += bytes.size();
  return true;
}

std::optional<std::string> JsonScan::finish() const {
  if (!error_.empty()) return error_;
  if (in_string_) return "JSON text ends inside a string";
  if (depth_ != 0) return "JSON text ends with " + std::to_string(depth_) + " brackets open";
  return std::nullopt;
}

std::optional<std::string> scan_json(std::string_view text) {
  JsonScan scan;
  scan.feed(text);
  return scan.finish();
}

}  // namespace svbrdf::gltf
