#pragma once
// Escaping text for XML, SVG and HTML (element content and double-quoted attribute values): the
// four characters that would end or open markup there. One helper for the SVG plots of svbrdf-brdf
// and the HTML/SVG of the LOD report.
#include <string>
#include <string_view>

namespace svbrdf {

inline std::string markup_escape(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace svbrdf
