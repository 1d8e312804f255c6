// base/message_line.h: what programs print as their one error line.
#include <gtest/gtest.h>

#include "base/message_line.h"

namespace svbrdf {
namespace {

TEST(MessageLine, KeepsWellFormedUtf8) {
  const std::string s = "granite.gltf: \xCF\x83 \xE2\x86\x92 \xF0\x9F\x98\x80 ok";  // σ → 😀
  EXPECT_EQ(message_line(s), s);
  EXPECT_EQ(message_line("tab\tstays"), "tab\tstays");
}

TEST(MessageLine, EscapesIllFormedBytesAndControls) {
  // A lone continuation byte, a truncated sequence at the end, an overlong '/', a surrogate
  // (U+D800), a code point past U+10FFFF, 0xFF (RFC 3629, section 4); a control character and DEL.
  EXPECT_EQ(message_line("a\x80z"), "a\\x80z");
  EXPECT_EQ(message_line("end\xE2\x86"), "end\\xE2\\x86");
  EXPECT_EQ(message_line("\xC0\xAF"), "\\xC0\\xAF");
  EXPECT_EQ(message_line("\xED\xA0\x80"), "\\xED\\xA0\\x80");
  EXPECT_EQ(message_line("\xF4\x90\x80\x80"), "\\xF4\\x90\\x80\\x80");
  EXPECT_EQ(message_line("\xFF"), "\\xFF");
  EXPECT_EQ(message_line("bell\x07" "del\x7F"), "bell\\x07del\\x7F");
}

TEST(MessageLine, IsOneLine) {
  EXPECT_EQ(message_line("first\nsecond\r\nthird\rfourth"), "first | second | third | fourth");
}

}  // namespace
}  // namespace svbrdf
