#pragma once
// A small JSON reader and writer for the scene recipes, the LOD manifest and the glTF files the
// scene assembler writes (RFC 8259). No JSON library is among the project's Debian dependencies
// (tinygltf keeps its nlohmann copy private), and recipes need error messages that name the file,
// the line and the JSON pointer, which is what this one gives.
//
// Reading: parse() builds a tree of Values that remember their line; a Node is a view of one value
// with its JSON pointer, and its accessors throw svbrdf::Error "file:line: /a/0/b: expected ..." on
// a wrong type or a missing member. Writing: Values are built with the make_* helpers and dump()
// writes them with object members in insertion order and numbers as the shortest text that reads
// back to the same double, so the output is byte-identical for the same input.
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace svbrdf::json {

struct Value {
  enum class Type { null, boolean, number, string, array, object };
  Type type = Type::null;
  bool boolean = false;
  double number = 0.0;
  std::string string;
  std::vector<Value> items;                            // array
  std::vector<std::pair<std::string, Value>> members;  // object, in order
  int line = 0;                                        // where it began in the parsed text (1-based)

  // Builders for writing.
  static Value null_value() { return {}; }
  static Value of(bool b);
  static Value of(double x);
  static Value of(int x) { return of(double(x)); }
  static Value of(std::uint64_t x) { return of(double(x)); }
  static Value of(std::string_view s);
  static Value of(const char* s) { return of(std::string_view(s)); }
  static Value array(std::vector<Value> items = {});
  static Value numbers(std::initializer_list<double> xs);
  static Value numbers(const std::vector<double>& xs);
  static Value object();

  // Object: appends a member (keys stay unique by construction of the writer; not checked).
  Value& set(std::string key, Value v);
  // Array: appends an item, returns it.
  Value& push(Value v);
  // Object member or nullptr.
  const Value* find(std::string_view key) const;
  Value* find(std::string_view key);
};

// Parses a whole document; throws svbrdf::Error "name:line:column: what" on a syntax error,
// duplicate keys or trailing text.
Value parse(std::string_view text, const std::string& name);
// Reads and parses a file; throws svbrdf::Error naming it when it cannot be read.
Value parse_file(const std::string& path);

// Text for a value: pretty-printed with two-space indentation, except that arrays of numbers stay
// on one line. Throws svbrdf::Error (internal) for a non-finite number, which JSON cannot hold.
std::string dump(const Value& v);
// dump() written to a file atomically; throws svbrdf::Error naming it when it cannot be written.
void write_file(const std::filesystem::path& path, const Value& v);
// The shortest decimal that reads back as `x` (std::to_chars); integers without a fraction.
std::string number_text(double x);

// A read-only view of a parsed value with its place in the document, for error messages.
class Node {
 public:
  Node(const Value& v, std::string file, std::string pointer = "") : v_(&v), file_(std::move(file)), pointer_(std::move(pointer)) {}

  const Value& value() const { return *v_; }
  const std::string& pointer() const { return pointer_; }
  // "file:line: /pointer" — the prefix of every message about this value.
  std::string where() const;
  // An svbrdf::Error (bad input) about this value.
  [[noreturn]] void fail(const std::string& what) const;

  bool is_object() const { return v_->type == Value::Type::object; }
  bool is_array() const { return v_->type == Value::Type::array; }
  bool is_string() const { return v_->type == Value::Type::string; }
  bool is_number() const { return v_->type == Value::Type::number; }

  // Members: a required one throws when missing; has() asks.
  bool has(std::string_view key) const;
  Node operator[](std::string_view key) const;
  // Array items.
  std::size_t size() const;
  Node operator[](std::size_t i) const;
  std::vector<Node> items() const;
  // Object members in order (key, node).
  std::vector<std::pair<std::string, Node>> members() const;
  // Throws naming the first member whose key is not in `known` (catches typos in recipes).
  void only(std::initializer_list<std::string_view> known) const;

  // Typed reads; the ranged ones throw when outside [lo, hi].
  double number() const;
  double number(double lo, double hi) const;
  int integer(int lo, int hi) const;
  std::uint64_t unsigned_integer() const;
  bool boolean() const;
  const std::string& string() const;
  // An array of exactly n numbers.
  std::vector<double> numbers(std::size_t n) const;

  // Optional members with defaults.
  double number_or(std::string_view key, double fallback) const;
  double number_or(std::string_view key, double fallback, double lo, double hi) const;
  int integer_or(std::string_view key, int fallback, int lo, int hi) const;
  bool boolean_or(std::string_view key, bool fallback) const;
  std::string string_or(std::string_view key, const std::string& fallback) const;

 private:
  const Value* v_;
  std::string file_;
  std::string pointer_;
};

}  // namespace svbrdf::json
