// The recipe JSON reader and writer against RFC 8259: what parses, what is refused (with the line
// and column), escapes, and the writer's round trip.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "base/error.h"
#include "scenes/json.h"

namespace svbrdf {
namespace {

using json::Node;
using json::Value;

std::string error_of(const std::string& text) {
  try {
    json::parse(text, "t.json");
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 2);
    return e.what();
  }
  return "";
}

TEST(Json, ParsesEveryValueType) {
  const Value v = json::parse(R"({"a": [1, -2.5e3, 0.125], "b": "x\"y\\z\n", "c": true, "d": false, "e": null, "f": {}})", "t");
  ASSERT_EQ(v.type, Value::Type::object);
  ASSERT_EQ(v.members.size(), 6u);
  const Value& a = *v.find("a");
  ASSERT_EQ(a.items.size(), 3u);
  EXPECT_EQ(a.items[0].number, 1.0);
  EXPECT_EQ(a.items[1].number, -2500.0);
  EXPECT_EQ(a.items[2].number, 0.125);
  EXPECT_EQ(v.find("b")->string, "x\"y\\z\n");
  EXPECT_TRUE(v.find("c")->boolean);
  EXPECT_EQ(v.find("d")->type, Value::Type::boolean);
  EXPECT_EQ(v.find("e")->type, Value::Type::null);
  EXPECT_EQ(v.find("f")->type, Value::Type::object);
}

TEST(Json, UnicodeEscapesBecomeUtf8) {
  // U+00E9 (2 bytes), U+20AC (3 bytes), U+1F600 as a surrogate pair (4 bytes).
  const Value v = json::parse(R"("\u00e9\u20AC\ud83d\ude00")", "t");
  EXPECT_EQ(v.string, "\xC3\xA9\xE2\x82\xAC\xF0\x9F\x98\x80");
}

TEST(Json, RefusesWhatRfc8259Refuses) {
  for (const char* bad : {"", "{", "[1,]", "{\"a\":1,}", "01", "1.", ".5", "+1", "1e", "tru", "\"abc", "\"\\x\"",
                          "{\"a\" 1}", "{a: 1}", "[1 2]", "\"\\ud800\"", "\"\\udc00x\"", "1 2", "nul", "1e999",
                          "\"a\tb\""})
    EXPECT_FALSE(error_of(bad).empty()) << "accepted: " << bad;
}

TEST(Json, ErrorsNameTheLineAndColumn) {
  EXPECT_EQ(error_of("{\n  \"a\": 1,\n  \"b\": ]\n}"), "t.json:3:8: unexpected character ']', expected a value");
  EXPECT_EQ(error_of("{\"a\": 1, \"a\": 2}"), "t.json:1:10: duplicate member \"a\"");
}

TEST(Json, DeepNestingIsRefusedNotACrash) {
  EXPECT_NE(error_of(std::string(100000, '[')).find("nesting deeper"), std::string::npos);
}

TEST(Json, DumpReadsBackToTheSameTree) {
  Value v = Value::object();
  v.set("pi", Value::of(3.141592653589793));
  v.set("tiny", Value::of(1e-300));
  v.set("int", Value::of(1024));
  v.set("neg0", Value::of(-0.0));
  v.set("text", Value::of("tab\there \"quoted\" \x01"));
  v.set("list", Value::numbers({0.1, 0.2, 0.30000000000000004}));
  v.set("nested", Value::array()).push(Value::object()).set("k", Value::of(true));
  const std::string text = json::dump(v);
  const Value back = json::parse(text, "t");
  EXPECT_EQ(json::dump(back), text);
  EXPECT_EQ(back.find("pi")->number, 3.141592653589793);  // shortest round-trip text is exact
  EXPECT_EQ(back.find("tiny")->number, 1e-300);
  EXPECT_EQ(back.find("list")->items[2].number, 0.30000000000000004);
  EXPECT_EQ(back.find("text")->string, "tab\there \"quoted\" \x01");
  EXPECT_NE(text.find("\"int\": 1024,"), std::string::npos) << text;
  EXPECT_THROW(json::dump(Value::of(std::nan(""))), Error);
}

TEST(Json, NodesNameTheirPlaceInErrors) {
  const Value v = json::parse("{\n\"objects\": [\n  {\"size\": \"big\"}\n]}", "r.json");
  const Node root(v, "r.json");
  try {
    root["objects"][0]["size"].number();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "r.json:3: /objects/0/size: expected a number, found a string");
  }
  try {
    root["objects"][0].only({"shape"});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "r.json:3: /objects/0/size: unknown member (known here: shape)");
  }
  EXPECT_THROW(root["missing"], Error);
  EXPECT_THROW(root["objects"][1], Error);
  const Value n = json::parse("{\"k\": 2.5}", "n");
  EXPECT_THROW(Node(n, "n")["k"].integer(0, 10), Error);
  EXPECT_THROW(Node(n, "n")["k"].number(3, 4), Error);
  EXPECT_EQ(Node(n, "n")["k"].number(2, 3), 2.5);
}

}  // namespace
}  // namespace svbrdf
