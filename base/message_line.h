#pragma once
// A message as the one line a program prints on stderr (DESIGN.md, "Errors"): text from outside —
// a parser's excerpt of a corrupt file, a file name — may hold bytes that are not UTF-8 or control
// characters, which garble a terminal and break tools that read the log as text. Well-formed UTF-8
// (the messages' own "→", "σ") is kept; every other byte below 0x20, 0x7F, and every byte of an
// ill-formed UTF-8 sequence (RFC 3629, section 4: no overlong forms, no surrogates, nothing past
// U+10FFFF) is written as \xNN; a line break becomes " | ", so the message stays one line.
#include <cstdio>
#include <string>
#include <string_view>

namespace svbrdf {

// The length of the well-formed UTF-8 sequence starting at s[i], or 0 when it is not one.
inline std::size_t utf8_sequence_length(std::string_view s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b0 = byte(i);
  std::size_t n;
  unsigned char lo = 0x80, hi = 0xBF;  // the second byte's range (RFC 3629's table)
  if (b0 < 0x80) return 1;
  if (b0 >= 0xC2 && b0 <= 0xDF) n = 2;
  else if (b0 >= 0xE0 && b0 <= 0xEF) {
    n = 3;
    if (b0 == 0xE0) lo = 0xA0;  // no overlong forms
    if (b0 == 0xED) hi = 0x9F;  // no surrogates
  } else if (b0 >= 0xF0 && b0 <= 0xF4) {
    n = 4;
    if (b0 == 0xF0) lo = 0x90;  // no overlong forms
    if (b0 == 0xF4) hi = 0x8F;  // nothing past U+10FFFF
  } else {
    return 0;
  }
  if (i + n > s.size()) return 0;
  if (byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k)
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  return n;
}

// The length of the character at s[i] that message_line writes as it is, or 0 for a byte it
// escapes: ill-formed UTF-8, a control character other than tab (line breaks included), DEL. Tests
// read a program's stderr with it.
inline std::size_t kept_length(std::string_view s, std::size_t i) {
  const std::size_t n = utf8_sequence_length(s, i);
  const unsigned char c = static_cast<unsigned char>(s[i]);
  return n == 1 && (c < 0x20 || c == 0x7F) && c != '\t' ? 0 : n;
}

inline std::string message_line(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c == '\n' || c == '\r') {
      // A CR LF pair is one break.
      out += " | ";
      i += (c == '\r' && i + 1 < s.size() && s[i + 1] == '\n') ? 2 : 1;
      continue;
    }
    const std::size_t n = kept_length(s, i);
    if (n == 0) {
      char hex[5];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      out += hex;
      ++i;
      continue;
    }
    out.append(s.substr(i, n));
    i += n;
  }
  return out;
}

}  // namespace svbrdf
