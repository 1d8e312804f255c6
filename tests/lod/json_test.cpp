// The JSON layer over nlohmann-json (base/json.h) against RFC 8259: what parses, what is refused
// (with the line and column), duplicate members and deep nesting, the JSON path that typed reads
// name in their errors, and the written text's round trip.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "base/error.h"
#include "base/json.h"

namespace svbrdf {
namespace {

std::string error_of(const std::string& text) {
  try {
    JsonDocument::parse(text, "t.json");
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 2);
    return e.what();
  }
  return "";
}

// The message of the svbrdf::Error `read` throws, or "" when it throws none.
template <class Read>
std::string read_error(Read read) {
  try {
    read();
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 2);
    return e.what();
  }
  return "";
}

TEST(Json, ParsesEveryValueType) {
  const JsonDocument doc =
      JsonDocument::parse(R"({"a": [1, -2.5e3, 0.125], "b": "x\"y\\z\n", "c": true, "d": false, "e": null, "f": {}})", "t");
  const Json& v = doc.value();
  ASSERT_TRUE(v.is_object());
  ASSERT_EQ(v.size(), 6u);
  const Json& a = v["a"];
  ASSERT_EQ(a.size(), 3u);
  EXPECT_EQ(a[0].get<double>(), 1.0);
  EXPECT_EQ(a[1].get<double>(), -2500.0);
  EXPECT_EQ(a[2].get<double>(), 0.125);
  EXPECT_EQ(v["b"].get<std::string>(), "x\"y\\z\n");
  EXPECT_TRUE(v["c"].get<bool>());
  EXPECT_TRUE(v["d"].is_boolean());
  EXPECT_TRUE(v["e"].is_null());
  EXPECT_TRUE(v["f"].is_object());
  // Members keep the order of the text.
  std::string keys;
  for (const auto& [key, value] : v.items()) keys += key;
  EXPECT_EQ(keys, "abcdef");
}

TEST(Json, UnicodeEscapesBecomeUtf8) {
  // U+00E9 (2 bytes), U+20AC (3 bytes), U+1F600 as a surrogate pair (4 bytes).
  const JsonDocument doc = JsonDocument::parse(R"("\u00e9\u20AC\ud83d\ude00")", "t");
  EXPECT_EQ(doc.value().get<std::string>(), "\xC3\xA9\xE2\x82\xAC\xF0\x9F\x98\x80");
}

TEST(Json, RefusesWhatRfc8259Refuses) {
  for (const char* bad : {"", "{", "[1,]", "{\"a\":1,}", "01", "1.", ".5", "+1", "1e", "tru", "\"abc", "\"\\x\"",
                          "{\"a\" 1}", "{a: 1}", "[1 2]", "\"\\ud800\"", "\"\\udc00x\"", "1 2", "nul", "1e999",
                          "\"a\tb\"", "[1] // comment"})
    EXPECT_FALSE(error_of(bad).empty()) << "accepted: " << bad;
}

TEST(Json, ErrorsNameTheLineAndColumn) {
  EXPECT_EQ(error_of("{\n  \"a\": 1,\n  \"b\": ]\n}"),
            "t.json:3:8: syntax error while parsing value - unexpected ']'; expected '[', '{', or a literal");
  EXPECT_EQ(error_of("{\"a\": 1, \"a\": 2}"), "t.json:1:10: duplicate member \"a\"");
  // A key with an escaped quote: the column is still that of its opening quote.
  EXPECT_EQ(error_of("{\"a\\\"\": 1,\n \"a\\\"\": 2}"), "t.json:2:2: duplicate member \"a\"\"");
  // At the end of the text: the column just past its last byte.
  EXPECT_EQ(error_of("[1,\n2").substr(0, 11), "t.json:2:2:");
  EXPECT_EQ(error_of("[1e999]"), "t.json:1:7: number overflow parsing '1e999'");
}

TEST(Json, DeepNestingIsRefusedNotACrash) {
  const std::string open(kMaxJsonNesting + 1, '['), close(kMaxJsonNesting + 1, ']');
  EXPECT_EQ(error_of(open + close), "t.json:1:" + std::to_string(kMaxJsonNesting + 1) + ": nesting deeper than " +
                                        std::to_string(kMaxJsonNesting) + " levels");
  EXPECT_NE(error_of(std::string(100000, '[')).find("nesting deeper"), std::string::npos);
  EXPECT_NE(error_of(std::string(100000, '[') + std::string(100000, ']')).find("nesting deeper"), std::string::npos);
  EXPECT_EQ(error_of(open.substr(1) + close.substr(1)), "");  // exactly the limit
}

TEST(Json, WrittenTextReadsBackToTheSameTree) {
  const Json v = {{"pi", 3.141592653589793},
                  {"tiny", 1e-300},
                  {"int", 1024},
                  {"neg0", -0.0},
                  {"text", "tab\there \"quoted\" \x01"},
                  {"list", {0.1, 0.2, 0.30000000000000004}},
                  {"nested", Json::array({{{"k", true}}})}};
  const std::string text = json_text(v);
  const JsonDocument back = JsonDocument::parse(text, "t");
  EXPECT_EQ(json_text(back.value()), text);
  EXPECT_EQ(back.value(), v);
  EXPECT_EQ(back.value()["pi"].get<double>(), 3.141592653589793);  // shortest round-trip text is exact
  EXPECT_EQ(back.value()["tiny"].get<double>(), 1e-300);
  EXPECT_EQ(back.value()["list"][2].get<double>(), 0.30000000000000004);
  EXPECT_EQ(back.value()["text"].get<std::string>(), "tab\there \"quoted\" \x01");
  EXPECT_NE(text.find("\"int\": 1024,"), std::string::npos) << text;
  EXPECT_EQ(text.back(), '\n');
  // Members stay in the order they were set.
  EXPECT_LT(text.find("\"pi\""), text.find("\"tiny\""));
  EXPECT_LT(text.find("\"list\""), text.find("\"nested\""));
  EXPECT_THROW(json_text(Json(std::nan(""))), Error);
  EXPECT_THROW(json_text(Json{{"x", {1.0, INFINITY}}}), Error);
  // Bytes that are not UTF-8 (a file name, say) are replaced, not a failure.
  EXPECT_EQ(json_text(Json("a\xff")), "\"a\xEF\xBF\xBD\"\n");
}

TEST(Json, NodesNameTheirPlaceInErrors) {
  const JsonDocument doc = JsonDocument::parse("{\n\"objects\": [\n  {\"size\": \"big\"}\n]}", "r.json");
  const JsonNode root = doc.root();
  EXPECT_EQ(read_error([&] { root["objects"][0]["size"].number(); }),
            "r.json:3: objects[0].size: expected a number, found a string");
  EXPECT_EQ(read_error([&] { root["objects"][0].only({"shape"}); }),
            "r.json:3: objects[0].size: unknown member (known here: shape)");
  EXPECT_EQ(read_error([&] { root["missing"]; }), "r.json:1: missing member \"missing\"");
  EXPECT_EQ(read_error([&] { root["objects"][1]; }), "r.json:2: objects: index 1 out of range");
  EXPECT_EQ(read_error([&] { root["objects"][0]["size"]["x"]; }),
            "r.json:3: objects[0].size: expected an object, found a string");

  const JsonDocument n = JsonDocument::parse("{\"k\": 2.5,\n \"materials\": {\"m\": {\"roughness\": 1.5}}, \"i\": 16}", "n");
  EXPECT_THROW(n.root()["k"].integer(0, 10), Error);
  EXPECT_THROW(n.root()["k"].number(3, 4), Error);
  EXPECT_EQ(n.root()["k"].number(2, 3), 2.5);
  EXPECT_EQ(n.root()["i"].integer(0, 16), 16);
  EXPECT_EQ(n.root()["i"].unsigned_integer(), 16u);
  EXPECT_EQ(n.root().number_or("absent", 0.5, 0, 1), 0.5);
  EXPECT_EQ(read_error([&] { n.root()["materials"]["m"].number_or("roughness", 0.5, 0, 1); }),
            "n:2: materials.m.roughness: must be in [0, 1], got 1.5");
}

TEST(Json, ANumberAtTheEndOfALineIsOnThatLine) {
  // nlohmann knows a number has ended only once it reads the byte after it, here a newline.
  const JsonDocument doc = JsonDocument::parse("{\n\"a\": 1\n,\"b\": [2,\n3]}", "t");
  EXPECT_EQ(doc.line_of("a"), 2);
  EXPECT_EQ(doc.line_of("b"), 3);
  EXPECT_EQ(doc.line_of("b[0]"), 3);
  EXPECT_EQ(doc.line_of("b[1]"), 4);
  EXPECT_EQ(doc.line_of("c"), 0);
}

TEST(Json, NumberTextIsTheShortestThatReadsBack) {
  EXPECT_EQ(number_text(16.0), "16");
  EXPECT_EQ(number_text(-0.0), "0");
  EXPECT_EQ(number_text(0.1), "0.1");
  EXPECT_EQ(number_text(1e-300), "1e-300");
  EXPECT_THROW(number_text(INFINITY), Error);
}

}  // namespace
}  // namespace svbrdf
