// The JSON pre-scan that guards tinygltf's recursive parse: it counts only brackets outside strings
// (so text data full of brackets passes), follows escapes, refuses nesting past kMaxJsonDepth and
// bytes JSON cannot hold, and reports unbalanced text.
#include <gtest/gtest.h>

#include <string>

#include "gltf/json_scan.h"

namespace svbrdf::gltf {
namespace {

std::string nested(int depth) { return std::string(std::size_t(depth), '[') + std::string(std::size_t(depth), ']'); }

TEST(JsonScan, CountsOnlyBracketsOutsideStrings) {
  EXPECT_FALSE(scan_json(nested(kMaxJsonDepth)));
  ASSERT_TRUE(scan_json(nested(kMaxJsonDepth + 1)));
  EXPECT_NE(scan_json(nested(kMaxJsonDepth + 1))->find("deeper than"), std::string::npos);
  // 1000 brackets inside a string, an escaped quote before them, an escaped backslash ending one.
  const std::string text = R"({"a": "\")" + std::string(1000, '[') + R"(", "b": ["\\"], "c": {"d": [1, 2.5e3, true, null]}})";
  EXPECT_FALSE(scan_json(text)) << *scan_json(text);
}

TEST(JsonScan, RefusesBytesJsonCannotHoldAndUnbalancedText) {
  EXPECT_TRUE(scan_json(std::string("{\"a\": 1}\0", 9)));           // a NUL outside a string
  EXPECT_TRUE(scan_json(std::string("{\"a\": \"x\ny\"}")));           // a raw newline inside a string
  EXPECT_TRUE(scan_json("{\"a\": [1, 2}"));                            // one bracket left open
  EXPECT_TRUE(scan_json("{\"a\": 1}}"));                               // one closed twice
  EXPECT_TRUE(scan_json("{\"a\": \"open"));                            // ends inside a string
  EXPECT_FALSE(scan_json("{\"\xC3\xA9\": \"\xE2\x82\xAC\"}\r\n\t "));  // UTF-8 inside strings, whitespace
  // Fed in pieces, the scan is the same as whole: a string and an escape split across two pieces.
  JsonScan scan;
  EXPECT_TRUE(scan.feed("{\"a\": \"[\\"));
  EXPECT_TRUE(scan.feed("\"[\", \"b\": [[]]}"));
  EXPECT_FALSE(scan.finish());
  EXPECT_EQ(scan.max_depth_seen(), 3);
}

}  // namespace
}  // namespace svbrdf::gltf
