#include "base/json.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <set>
#include <span>
#include <sstream>

#include "base/atomic_file.h"
#include "base/error.h"

namespace svbrdf {

namespace {

// nlohmann's parser tells its callback what it read but not where. This iterator, over which it
// reads the text, records the furthest byte it has taken, so the callback can give each value its
// line and a duplicate member its column.
class ReadHead {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  ReadHead(const char* at, const char** furthest) : at_(at), furthest_(furthest) {}
  reference operator*() const { return *at_; }
  ReadHead& operator++() {
    *furthest_ = ++at_;
    return *this;
  }
  ReadHead operator++(int) {
    ReadHead before = *this;
    ++*this;
    return before;
  }
  bool operator==(const ReadHead& other) const { return at_ == other.at_; }

 private:
  const char* at_ = nullptr;
  const char** furthest_ = nullptr;
};

// Line and column (1-based) of byte `at`; queries mostly move forward, so counting resumes where
// the last one stopped.
class LineCounter {
 public:
  explicit LineCounter(std::string_view text) : text_(text) {}

  std::pair<int, std::size_t> at(std::size_t at) {
    if (at < pos_) pos_ = 0, line_ = 1, line_start_ = 0;
    for (; pos_ < at && pos_ < text_.size(); ++pos_)
      if (text_[pos_] == '\n') ++line_, line_start_ = pos_ + 1;
    return {line_, at - line_start_ + 1};
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0, line_start_ = 0;
  int line_ = 1;
};

// What nlohmann says after its "[json.exception.parse_error.101] parse error at line 3, column 8: ".
std::string reason(const std::exception& e) {
  std::string_view s = e.what();
  if (const auto tag = s.find("] "); tag != std::string_view::npos) s.remove_prefix(tag + 2);
  if (s.rfind("parse error", 0) == 0)
    if (const auto colon = s.find(": "); colon != std::string_view::npos) s.remove_prefix(colon + 2);
  return std::string(s);
}

// JSON paths as the glTF reader writes them: "objects[0].size".
std::string member_path(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}
std::string item_path(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

bool number_byte(char c) { return (c >= '0' && c <= '9') || c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-'; }

// One parse: the callback follows the parser through the document, keeping the path of the value
// it is in, the members each open object has, and where each value begins.
class Parse {
 public:
  Parse(std::string_view text, const std::string& name) : text_(text), name_(name), lines_(text) {}

  Json run(std::unordered_map<std::string, int>& lines) {
    furthest_ = text_.data();
    const ReadHead begin(text_.data(), &furthest_), end(text_.data() + text_.size(), &furthest_);
    try {
      Json v = Json::parse(begin, end, [&](int, Json::parse_event_t event, Json& parsed) { return on(event, parsed); });
      lines = std::move(value_lines_);
      return v;
    } catch (const Json::parse_error& e) {
      // e.byte counts the byte it stopped at from 1 (the text's size + 1 at its end).
      fail(e.byte > 0 ? e.byte - 1 : 0, reason(e));
    } catch (const Json::exception& e) {  // a number too large for a double, found at the read head
      fail(read() > 0 ? read() - 1 : 0, reason(e));
    }
  }

 private:
  struct Open {
    bool object = false;
    std::string path;
    std::size_t index = 0;       // arrays: the next item's
    std::string key;             // objects: the member being read
    std::set<std::string> keys;  // objects: the members so far
  };

  std::size_t read() const { return std::size_t(furthest_ - text_.data()); }

  [[noreturn]] void fail(std::size_t at, const std::string& what) {
    const auto [line, column] = lines_.at(at);
    throw input_error(name_ + ":" + std::to_string(line) + ":" + std::to_string(column), what);
  }

  std::string next_path() const {
    if (open_.empty()) return "";
    const Open& o = open_.back();
    return o.object ? member_path(o.path, o.key) : item_path(o.path, o.index);
  }

  void done_with_value() {
    if (!open_.empty() && !open_.back().object) ++open_.back().index;
  }

  bool on(Json::parse_event_t event, const Json& parsed) {
    using E = Json::parse_event_t;
    switch (event) {
      case E::object_start:
      case E::array_start: {
        const std::size_t bracket = read() - 1;
        if (open_.size() >= std::size_t(kMaxJsonNesting))
          fail(bracket, "nesting deeper than " + std::to_string(kMaxJsonNesting) + " levels");
        std::string path = next_path();
        value_lines_[path] = lines_.at(bracket).first;
        open_.push_back({event == E::object_start, std::move(path), 0, "", {}});
        break;
      }
      case E::key: {
        Open& o = open_.back();
        o.key = parsed.get<std::string>();
        if (!o.keys.insert(o.key).second) fail(opening_quote(read() - 1), "duplicate member \"" + o.key + "\"");
        break;
      }
      case E::value: {
        // A number is known only once the byte after it is read; strings and literals end on their
        // last byte.
        std::size_t last = read() - 1;
        if (parsed.is_number() && last > 0 && !number_byte(text_[last])) --last;
        value_lines_[next_path()] = lines_.at(last).first;
        done_with_value();
        break;
      }
      case E::object_end:
      case E::array_end:
        open_.pop_back();
        done_with_value();
        break;
    }
    return true;
  }

  // The quote that opens the string whose closing quote is at `close`: the first one before it
  // that no backslash escapes.
  std::size_t opening_quote(std::size_t close) const {
    for (std::size_t i = close; i-- > 0;) {
      if (text_[i] != '"') continue;
      std::size_t slashes = 0;
      while (slashes < i && text_[i - 1 - slashes] == '\\') ++slashes;
      if (slashes % 2 == 0) return i;
    }
    return close;
  }

  std::string_view text_;
  const std::string& name_;
  LineCounter lines_;
  const char* furthest_ = nullptr;
  std::vector<Open> open_;
  std::unordered_map<std::string, int> value_lines_;
};

const char* type_name(const Json& v) {
  switch (v.type()) {
    case Json::value_t::null: return "null";
    case Json::value_t::boolean: return "a boolean";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
    case Json::value_t::number_float: return "a number";
    case Json::value_t::string: return "a string";
    case Json::value_t::array: return "an array";
    case Json::value_t::object: return "an object";
    default: return "not a JSON value";
  }
}

void check_finite(const Json& v) {
  if (v.is_number_float() && !std::isfinite(v.get<double>()))
    throw Error("JSON cannot hold the number " + std::to_string(v.get<double>()), Error::Kind::internal);
  if (v.is_structured())
    for (const Json& item : v) check_finite(item);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Documents

JsonDocument JsonDocument::parse(std::string_view text, std::string name) {
  JsonDocument doc;
  doc.name_ = std::move(name);
  doc.value_ = Parse(text, doc.name_).run(doc.lines_);
  return doc;
}

JsonDocument JsonDocument::read(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::ifstream f(file, std::ios::binary);
  if (!f) throw input_error(name, "cannot open the file");
  std::stringstream ss;
  ss << f.rdbuf();
  if (f.bad()) throw input_error(name, "cannot read the file");
  return parse(ss.str(), name);
}

JsonNode JsonDocument::root() const { return {*this, value_, ""}; }

int JsonDocument::line_of(const std::string& path) const {
  const auto it = lines_.find(path);
  return it == lines_.end() ? 0 : it->second;
}

// ---------------------------------------------------------------------------------------------
// Nodes

std::string JsonNode::where() const {
  std::string w = doc_->name();
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict, PR 105651) on ":" + std::string.
  if (const int line = doc_->line_of(path_); line > 0) {
    w += ':';
    w += std::to_string(line);
  }
  if (!path_.empty()) {
    w += ": ";
    w += path_;
  }
  return w;
}

void JsonNode::fail(const std::string& what) const { throw input_error(where(), what); }

bool JsonNode::has(std::string_view key) const { return is_object() && v_->contains(key); }

JsonNode JsonNode::operator[](std::string_view key) const {
  if (!is_object()) fail(std::string("expected an object, found ") + type_name(*v_));
  const auto it = v_->find(key);
  if (it == v_->end()) fail("missing member \"" + std::string(key) + "\"");
  return child(*it, member_path(path_, key));
}

std::size_t JsonNode::size() const {
  if (!v_->is_array()) fail(std::string("expected an array, found ") + type_name(*v_));
  return v_->size();
}

JsonNode JsonNode::operator[](std::size_t i) const {
  if (i >= size()) fail("index " + std::to_string(i) + " out of range");
  return child((*v_)[i], item_path(path_, i));
}

std::vector<JsonNode> JsonNode::items() const {
  std::vector<JsonNode> out;
  for (std::size_t i = 0; i < size(); ++i) out.push_back((*this)[i]);
  return out;
}

std::vector<std::pair<std::string, JsonNode>> JsonNode::members() const {
  if (!is_object()) fail(std::string("expected an object, found ") + type_name(*v_));
  std::vector<std::pair<std::string, JsonNode>> out;
  for (const auto& [key, value] : v_->items()) out.emplace_back(key, child(value, member_path(path_, key)));
  return out;
}

void JsonNode::only(std::initializer_list<std::string_view> known) const {
  for (const auto& [key, node] : members()) {
    bool ok = false;
    for (std::string_view name : known) ok = ok || name == key;
    if (!ok) {
      std::string list;
      for (std::string_view name : known) list += (list.empty() ? "" : ", ") + std::string(name);
      node.fail("unknown member (known here: " + list + ")");
    }
  }
}

double JsonNode::number() const {
  if (!v_->is_number()) fail(std::string("expected a number, found ") + type_name(*v_));
  return v_->get<double>();
}

double JsonNode::number(double lo, double hi) const {
  const double x = number();
  if (!(x >= lo && x <= hi)) fail("must be in [" + number_text(lo) + ", " + number_text(hi) + "], got " + number_text(x));
  return x;
}

int JsonNode::integer(int lo, int hi) const {
  const double x = number(lo, hi);
  if (x != std::floor(x)) fail("expected an integer, got " + number_text(x));
  return int(x);
}

std::uint64_t JsonNode::unsigned_integer() const {
  const double x = number(0.0, 9007199254740992.0);  // 2^53: every integer up to it is exact
  if (x != std::floor(x)) fail("expected a non-negative integer, got " + number_text(x));
  return std::uint64_t(x);
}

bool JsonNode::boolean() const {
  if (!v_->is_boolean()) fail(std::string("expected true or false, found ") + type_name(*v_));
  return v_->get<bool>();
}

const std::string& JsonNode::string() const {
  if (!v_->is_string()) fail(std::string("expected a string, found ") + type_name(*v_));
  return v_->get_ref<const std::string&>();
}

std::vector<double> JsonNode::numbers(std::size_t n) const {
  if (!v_->is_array() || v_->size() != n) fail("expected an array of " + std::to_string(n) + " numbers");
  std::vector<double> out;
  for (std::size_t i = 0; i < n; ++i) out.push_back((*this)[i].number());
  return out;
}

double JsonNode::number_or(std::string_view key, double fallback, double lo, double hi) const {
  return has(key) ? (*this)[key].number(lo, hi) : fallback;
}
int JsonNode::integer_or(std::string_view key, int fallback, int lo, int hi) const {
  return has(key) ? (*this)[key].integer(lo, hi) : fallback;
}
bool JsonNode::boolean_or(std::string_view key, bool fallback) const {
  return has(key) ? (*this)[key].boolean() : fallback;
}
std::string JsonNode::string_or(std::string_view key, const std::string& fallback) const {
  return has(key) ? (*this)[key].string() : fallback;
}

// ---------------------------------------------------------------------------------------------
// Writing

std::string json_text(const Json& value) {
  check_finite(value);
  return value.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

void write_json_file(const std::filesystem::path& path, const Json& value) {
  const std::string text = json_text(value);
  write_bytes_atomically(path, std::as_bytes(std::span(text)));
}

std::string number_text(double x) {
  if (!std::isfinite(x)) throw Error("no decimal for the number " + std::to_string(x), Error::Kind::internal);
  if (x == 0.0) return "0";  // also −0
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

}  // namespace svbrdf
