#pragma once
// The project's JSON: nlohmann-json's ordered_json, and what the readers of hand-written JSON (the
// scene recipes, the LOD manifest) need on top of it. ordered_json rather than json: members stay
// in the order they were written or set, so a recipe's materials keep their order (and with it
// their glTF indices), an error names the first bad member in the text, and written files list
// members in the order the code sets them.
//
// Reading: JsonDocument::parse()/read() refuse what nlohmann refuses, plus duplicate members and
// nesting deeper than kMaxJsonNesting, with one line "file:line:column: what". A JsonNode is a view
// of one value with its JSON path ("objects[0].size"); its typed reads throw svbrdf::Error (bad
// input) "file:line: path: what" on a missing member, a wrong type or a value out of range.
// Writing: json_text() / write_json_file(), two-space indentation.
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace svbrdf {

using Json = nlohmann::ordered_json;

// Deeper documents are refused before anything walks them: nlohmann parses without recursion, but
// copying, comparing and dumping a value recurse once per level.
inline constexpr int kMaxJsonNesting = 200;

class JsonNode;

// A parsed JSON text with its name and the line where each value begins, for messages.
class JsonDocument {
 public:
  // Throws svbrdf::Error (bad input) "name:line:column: what" for text that is not one JSON value,
  // an object with a member twice, or nesting deeper than kMaxJsonNesting.
  static JsonDocument parse(std::string_view text, std::string name);
  // Reads and parses a file; throws svbrdf::Error naming it when it cannot be read.
  static JsonDocument read(const std::filesystem::path& file);

  const Json& value() const { return value_; }
  const std::string& name() const { return name_; }
  // The whole document; the view points into this object, which must outlive it and not move.
  JsonNode root() const;
  // The line where the value at `path` begins (1-based), or 0 for a path the text does not have.
  int line_of(const std::string& path) const;

 private:
  Json value_;
  std::string name_;
  std::unordered_map<std::string, int> lines_;
};

// A read-only view of one value of a document and its JSON path (empty for the root).
class JsonNode {
 public:
  JsonNode(const JsonDocument& doc, const Json& value, std::string path)
      : doc_(&doc), v_(&value), path_(std::move(path)) {}

  const Json& value() const { return *v_; }
  const std::string& path() const { return path_; }
  // "file:line: path" — the prefix of every message about this value.
  std::string where() const;
  // An svbrdf::Error (bad input) about this value.
  [[noreturn]] void fail(const std::string& what) const;

  bool is_object() const { return v_->is_object(); }

  // Members: a required one throws when missing; has() asks.
  bool has(std::string_view key) const;
  JsonNode operator[](std::string_view key) const;
  // Array items.
  std::size_t size() const;
  JsonNode operator[](std::size_t i) const;
  std::vector<JsonNode> items() const;
  // Object members in order (key, node).
  std::vector<std::pair<std::string, JsonNode>> members() const;
  // Throws naming the first member whose key is not in `known` (catches typos in recipes).
  void only(std::initializer_list<std::string_view> known) const;

  // Typed reads; the ranged ones throw when outside [lo, hi]. Integers are numbers with no
  // fraction, whatever their spelling (16, 16.0, 1.6e1).
  double number() const;
  double number(double lo, double hi) const;
  int integer(int lo, int hi) const;
  std::uint64_t unsigned_integer() const;
  bool boolean() const;
  const std::string& string() const;
  // An array of exactly n numbers.
  std::vector<double> numbers(std::size_t n) const;

  // Optional members with defaults.
  double number_or(std::string_view key, double fallback, double lo, double hi) const;
  int integer_or(std::string_view key, int fallback, int lo, int hi) const;
  bool boolean_or(std::string_view key, bool fallback) const;
  std::string string_or(std::string_view key, const std::string& fallback) const;

 private:
  JsonNode child(const Json& value, std::string path) const { return {*doc_, value, std::move(path)}; }

  const JsonDocument* doc_;
  const Json* v_;
  std::string path_;
};

// The text of a value: two-space indentation and a final newline; bytes that are not UTF-8 in
// strings become U+FFFD. Throws svbrdf::Error (internal) for a NaN or an infinity, which JSON cannot
// hold (nlohmann would write null silently).
std::string json_text(const Json& value);
// json_text() written to a file atomically; throws svbrdf::Error naming it when it cannot be written.
void write_json_file(const std::filesystem::path& path, const Json& value);

// The shortest decimal that reads back as `x` (std::to_chars), whole numbers without a fraction
// ("16", not "16.0"): for names and messages made of numbers (the LOD camera "d16", "[0, 89]").
std::string number_text(double x);

}  // namespace svbrdf
