#include "render/image_file_description.h"

#include <bit>
#include <charconv>
#include <cstdint>
#include <vector>

#include "base/sha256.h"

namespace svbrdf {

namespace {

constexpr std::string_view kHeader = "svbrdf texture tiles 2";
constexpr std::string_view kDigits = "0123456789abcdef";

void append_table(std::string& out, std::string_view name, const CodeTable& table) {
  out += name;
  out += ' ';
  for (const auto& channel : table)
    for (const float v : channel) {
      const auto bits = std::bit_cast<std::uint32_t>(v);
      for (int shift = 28; shift >= 0; shift -= 4) out += kDigits[(bits >> shift) & 15u];
    }
  out += '\n';
}

// `text` as 4 × 256 bit patterns of 8 lowercase hexadecimal digits each, or false.
bool parse_table(std::string_view text, CodeTable& table) {
  if (text.size() != 4 * 256 * 8) return false;
  std::size_t at = 0;
  for (auto& channel : table)
    for (float& v : channel) {
      std::uint32_t bits = 0;
      for (int k = 0; k < 8; ++k, ++at) {
        const std::size_t digit = kDigits.find(text[at]);
        if (digit == std::string_view::npos) return false;
        bits = bits << 4 | std::uint32_t(digit);
      }
      v = std::bit_cast<float>(bits);
    }
  return true;
}

// A positive int written in decimal, the whole of `text`.
bool parse_int(std::string_view text, int& out) {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  return ec == std::errc() && end == text.data() + text.size() && out > 0 && text[0] != '0';
}

}  // namespace

std::string describe(const ImageFileDescription& d) {
  std::string out;
  out += kHeader;
  out += "\nkey " + d.key + "\nimage " + std::to_string(d.width) + "x" + std::to_string(d.height) + "x" +
         std::to_string(d.channels) + "\nform " + (d.codes ? "codes" : "floats") + "\n";
  if (d.codes) {
    append_table(out, "raw", d.raw_table);
    if (d.linear) append_table(out, "linear", d.linear_table);
  }
  out += "sha256 " + to_hex(sha256(out)) + "\n";
  return out;
}

std::optional<ImageFileDescription> parse_image_file_description(std::string_view text, const std::string& key,
                                                                 std::string* why) {
  const auto refuse = [&](const std::string& what) -> std::optional<ImageFileDescription> {
    if (why) *why = what;
    return std::nullopt;
  };
  if (text.empty()) return refuse("its description is missing");
  // The digest line first: whatever the lines before say, they are read only when they are whole.
  if (text.back() != '\n') return refuse("its description does not end in a line break");
  const std::size_t last = text.rfind('\n', text.size() - 2);
  const std::string_view body = last == std::string_view::npos ? std::string_view() : text.substr(0, last + 1);
  const std::string_view sum = text.substr(body.size(), text.size() - body.size() - 1);
  if (sum.substr(0, 7) != "sha256 " || sum.substr(7) != to_hex(sha256(body)))
    return refuse("its description does not match its digest (garbled)");
  std::vector<std::string_view> lines;
  for (std::size_t at = 0; at < body.size();) {
    const std::size_t end = body.find('\n', at);
    lines.push_back(body.substr(at, end - at));
    at = end + 1;
  }
  const auto field = [&](std::size_t i, std::string_view name) -> std::optional<std::string_view> {
    if (i >= lines.size() || lines[i].substr(0, name.size() + 1) != std::string(name) + " ") return std::nullopt;
    return lines[i].substr(name.size() + 1);
  };
  if (lines.empty() || lines[0] != kHeader) return refuse("its description is not one the texture cache writes");
  ImageFileDescription d;
  const auto k = field(1, "key");
  if (!k || *k != key) return refuse("its description does not name its key");
  d.key = key;
  const auto image = field(2, "image");
  const std::size_t x1 = image ? image->find('x') : std::string_view::npos;
  const std::size_t x2 = x1 == std::string_view::npos ? x1 : image->find('x', x1 + 1);
  if (x2 == std::string_view::npos || !parse_int(image->substr(0, x1), d.width) ||
      !parse_int(image->substr(x1 + 1, x2 - x1 - 1), d.height) || !parse_int(image->substr(x2 + 1), d.channels) ||
      d.channels > 4)
    return refuse("its description gives no image size");
  const auto form = field(3, "form");
  if (!form || (*form != "codes" && *form != "floats")) return refuse("its description names no form");
  d.codes = *form == "codes";
  std::size_t expected = 4;
  if (d.codes) {
    const auto raw = field(4, "raw");
    if (!raw || !parse_table(*raw, d.raw_table)) return refuse("its description's code table is not whole");
    const auto linear = field(5, "linear");
    d.linear = linear.has_value();
    if (linear && !parse_table(*linear, d.linear_table))
      return refuse("its description's linear code table is not whole");
    expected = d.linear ? 6 : 5;
  }
  if (lines.size() != expected) return refuse("its description has lines the texture cache does not write");
  return d;
}

}  // namespace svbrdf
