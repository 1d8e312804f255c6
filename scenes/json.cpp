#include "scenes/json.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <span>
#include <sstream>

#include "base/atomic_file.h"
#include "base/error.h"

namespace svbrdf::json {

// ---------------------------------------------------------------------------------------------
// Values

Value Value::of(bool b) {
  Value v;
  v.type = Type::boolean;
  v.boolean = b;
  return v;
}
Value Value::of(double x) {
  Value v;
  v.type = Type::number;
  v.number = x;
  return v;
}
Value Value::of(std::string_view s) {
  Value v;
  v.type = Type::string;
  v.string = std::string(s);
  return v;
}
Value Value::array(std::vector<Value> items) {
  Value v;
  v.type = Type::array;
  v.items = std::move(items);
  return v;
}
Value Value::numbers(std::initializer_list<double> xs) { return numbers(std::vector<double>(xs)); }
Value Value::numbers(const std::vector<double>& xs) {
  Value v = array();
  for (double x : xs) v.items.push_back(of(x));
  return v;
}
Value Value::object() {
  Value v;
  v.type = Type::object;
  return v;
}
Value& Value::set(std::string key, Value v) {
  members.emplace_back(std::move(key), std::move(v));
  return members.back().second;
}
Value& Value::push(Value v) {
  items.push_back(std::move(v));
  return items.back();
}
const Value* Value::find(std::string_view key) const {
  for (const auto& [k, v] : members)
    if (k == key) return &v;
  return nullptr;
}
Value* Value::find(std::string_view key) {
  for (auto& [k, v] : members)
    if (k == key) return &v;
  return nullptr;
}

// ---------------------------------------------------------------------------------------------
// Parsing (recursive descent over RFC 8259's grammar)

namespace {

constexpr int kMaxDepth = 200;  // deeper documents are refused rather than risking the stack

class Parser {
 public:
  Parser(std::string_view text, const std::string& name) : s_(text), name_(name) {}

  Value document() {
    skip_space();
    Value v = value(0);
    skip_space();
    if (pos_ != s_.size()) fail("unexpected text after the JSON value");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    // Line and column of pos_, counted from 1.
    int line = 1, column = 1;
    for (std::size_t i = 0; i < pos_ && i < s_.size(); ++i) {
      if (s_[i] == '\n') ++line, column = 1;
      else ++column;
    }
    throw input_error(name_ + ":" + std::to_string(line) + ":" + std::to_string(column), what);
  }

  // Values are visited in text order, so lines are counted incrementally.
  int line_here() {
    for (; line_pos_ < pos_; ++line_pos_)
      if (s_[line_pos_] == '\n') ++line_count_;
    return line_count_;
  }

  void skip_space() {
    while (pos_ < s_.size() && (s_[pos_] == ' ' || s_[pos_] == '\t' || s_[pos_] == '\n' || s_[pos_] == '\r')) ++pos_;
  }

  bool literal(std::string_view word) {
    if (s_.substr(pos_, word.size()) != word) return false;
    pos_ += word.size();
    return true;
  }

  Value value(int depth) {
    if (depth > kMaxDepth) fail("nesting deeper than " + std::to_string(kMaxDepth) + " levels");
    if (pos_ >= s_.size()) fail("unexpected end of the text, expected a value");
    const int line = line_here();
    Value v;
    const char c = s_[pos_];
    if (c == '{') v = object(depth);
    else if (c == '[') v = array(depth);
    else if (c == '"') v = Value::of(std::string_view(string()));
    else if (c == '-' || (c >= '0' && c <= '9')) v = Value::of(number());
    else if (literal("true")) v = Value::of(true);
    else if (literal("false")) v = Value::of(false);
    else if (literal("null")) v = Value{};
    else fail(std::string("unexpected character '") + c + "', expected a value");
    v.line = line;
    return v;
  }

  Value object(int depth) {
    Value v = Value::object();
    ++pos_;  // {
    skip_space();
    if (pos_ < s_.size() && s_[pos_] == '}') return ++pos_, v;
    for (;;) {
      skip_space();
      if (pos_ >= s_.size() || s_[pos_] != '"') fail("expected a member name in double quotes");
      const std::size_t key_at = pos_;
      std::string key = string();
      if (v.find(key)) pos_ = key_at, fail("duplicate member \"" + key + "\"");
      skip_space();
      if (pos_ >= s_.size() || s_[pos_] != ':') fail("expected ':' after a member name");
      ++pos_;
      skip_space();
      Value item = value(depth + 1);
      v.members.emplace_back(std::move(key), std::move(item));
      skip_space();
      if (pos_ < s_.size() && s_[pos_] == ',') {
        ++pos_;
        continue;
      }
      if (pos_ < s_.size() && s_[pos_] == '}') return ++pos_, v;
      fail("expected ',' or '}' in an object");
    }
  }

  Value array(int depth) {
    Value v = Value::array();
    ++pos_;  // [
    skip_space();
    if (pos_ < s_.size() && s_[pos_] == ']') return ++pos_, v;
    for (;;) {
      skip_space();
      v.items.push_back(value(depth + 1));
      skip_space();
      if (pos_ < s_.size() && s_[pos_] == ',') {
        ++pos_;
        continue;
      }
      if (pos_ < s_.size() && s_[pos_] == ']') return ++pos_, v;
      fail("expected ',' or ']' in an array");
    }
  }

  unsigned hex4() {
    if (pos_ + 4 > s_.size()) fail("truncated \\u escape");
    unsigned u = 0;
    for (int k = 0; k < 4; ++k) {
      const char c = s_[pos_++];
      u <<= 4;
      if (c >= '0' && c <= '9') u |= unsigned(c - '0');
      else if (c >= 'a' && c <= 'f') u |= unsigned(c - 'a' + 10);
      else if (c >= 'A' && c <= 'F') u |= unsigned(c - 'A' + 10);
      else fail("bad hexadecimal digit in a \\u escape");
    }
    return u;
  }

  static void append_utf8(std::string& out, unsigned cp) {
    if (cp < 0x80) {
      out += char(cp);
    } else if (cp < 0x800) {
      out += char(0xc0 | (cp >> 6));
      out += char(0x80 | (cp & 0x3f));
    } else if (cp < 0x10000) {
      out += char(0xe0 | (cp >> 12));
      out += char(0x80 | ((cp >> 6) & 0x3f));
      out += char(0x80 | (cp & 0x3f));
    } else {
      out += char(0xf0 | (cp >> 18));
      out += char(0x80 | ((cp >> 12) & 0x3f));
      out += char(0x80 | ((cp >> 6) & 0x3f));
      out += char(0x80 | (cp & 0x3f));
    }
  }

  std::string string() {
    ++pos_;  // opening quote
    std::string out;
    for (;;) {
      if (pos_ >= s_.size()) fail("unterminated string");
      const char c = s_[pos_++];
      if (c == '"') return out;
      if (static_cast<unsigned char>(c) < 0x20) --pos_, fail("control character in a string");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (pos_ >= s_.size()) fail("unterminated string");
      const char e = s_[pos_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          unsigned cp = hex4();
          if (cp >= 0xd800 && cp < 0xdc00) {  // a high surrogate must be followed by a low one
            if (!literal("\\u")) fail("unpaired UTF-16 surrogate in a \\u escape");
            const unsigned lo = hex4();
            if (lo < 0xdc00 || lo >= 0xe000) fail("unpaired UTF-16 surrogate in a \\u escape");
            cp = 0x10000 + ((cp - 0xd800) << 10) + (lo - 0xdc00);
          } else if (cp >= 0xdc00 && cp < 0xe000) {
            fail("unpaired UTF-16 surrogate in a \\u escape");
          }
          append_utf8(out, cp);
          break;
        }
        default: --pos_, fail(std::string("unknown escape '\\") + e + "'");
      }
    }
  }

  double number() {
    // RFC 8259: -? (0 | [1-9][0-9]*) (. [0-9]+)? ([eE] [+-]? [0-9]+)?
    const std::size_t start = pos_;
    const auto digits = [&] {
      const std::size_t d = pos_;
      while (pos_ < s_.size() && s_[pos_] >= '0' && s_[pos_] <= '9') ++pos_;
      return pos_ > d;
    };
    if (s_[pos_] == '-') ++pos_;
    if (pos_ < s_.size() && s_[pos_] == '0') ++pos_;
    else if (!digits()) fail("bad number");
    if (pos_ < s_.size() && s_[pos_] == '.') {
      ++pos_;
      if (!digits()) fail("bad number: digits must follow '.'");
    }
    if (pos_ < s_.size() && (s_[pos_] == 'e' || s_[pos_] == 'E')) {
      ++pos_;
      if (pos_ < s_.size() && (s_[pos_] == '+' || s_[pos_] == '-')) ++pos_;
      if (!digits()) fail("bad number: digits must follow the exponent");
    }
    double x = 0.0;
    const auto r = std::from_chars(s_.data() + start, s_.data() + pos_, x);
    if (r.ec != std::errc() || !std::isfinite(x)) pos_ = start, fail("number out of range");
    return x;
  }

  std::string_view s_;
  std::string name_;
  std::size_t pos_ = 0;
  std::size_t line_pos_ = 0;
  int line_count_ = 1;
};

}  // namespace

Value parse(std::string_view text, const std::string& name) { return Parser(text, name).document(); }

Value parse_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw input_error(path, "cannot open the file");
  std::stringstream ss;
  ss << f.rdbuf();
  if (f.bad()) throw input_error(path, "cannot read the file");
  return parse(ss.str(), path);
}

// ---------------------------------------------------------------------------------------------
// Writing

std::string number_text(double x) {
  if (!std::isfinite(x)) throw Error("JSON cannot hold the number " + std::to_string(x), Error::Kind::internal);
  if (x == 0.0) return "0";  // also −0
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

namespace {

void quote(std::string& out, std::string_view s) {
  out += '"';
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          static const char* hex = "0123456789abcdef";
          out += "\\u00";
          out += hex[(c >> 4) & 0xf];
          out += hex[c & 0xf];
        } else {
          out += c;
        }
    }
  }
  out += '"';
}

bool flat(const Value& v) {
  if (v.type != Value::Type::array) return false;
  for (const Value& i : v.items)
    if (i.type == Value::Type::array || i.type == Value::Type::object) return false;
  return true;
}

void write(std::string& out, const Value& v, int indent) {
  const auto newline = [&](int n) {
    out += '\n';
    out.append(std::size_t(n) * 2, ' ');
  };
  switch (v.type) {
    case Value::Type::null: out += "null"; break;
    case Value::Type::boolean: out += v.boolean ? "true" : "false"; break;
    case Value::Type::number: out += number_text(v.number); break;
    case Value::Type::string: quote(out, v.string); break;
    case Value::Type::array:
      if (v.items.empty()) {
        out += "[]";
      } else if (flat(v)) {
        out += '[';
        for (std::size_t i = 0; i < v.items.size(); ++i) {
          if (i) out += ", ";
          write(out, v.items[i], indent);
        }
        out += ']';
      } else {
        out += '[';
        for (std::size_t i = 0; i < v.items.size(); ++i) {
          if (i) out += ',';
          newline(indent + 1);
          write(out, v.items[i], indent + 1);
        }
        newline(indent);
        out += ']';
      }
      break;
    case Value::Type::object:
      if (v.members.empty()) {
        out += "{}";
        break;
      }
      out += '{';
      for (std::size_t i = 0; i < v.members.size(); ++i) {
        if (i) out += ',';
        newline(indent + 1);
        quote(out, v.members[i].first);
        out += ": ";
        write(out, v.members[i].second, indent + 1);
      }
      newline(indent);
      out += '}';
      break;
  }
}

const char* type_name(Value::Type t) {
  switch (t) {
    case Value::Type::null: return "null";
    case Value::Type::boolean: return "a boolean";
    case Value::Type::number: return "a number";
    case Value::Type::string: return "a string";
    case Value::Type::array: return "an array";
    case Value::Type::object: return "an object";
  }
  return "?";
}

}  // namespace

std::string dump(const Value& v) {
  std::string out;
  write(out, v, 0);
  out += '\n';
  return out;
}

void write_file(const std::filesystem::path& path, const Value& v) {
  const std::string text = dump(v);
  write_bytes_atomically(path, std::as_bytes(std::span(text)));
}

// ---------------------------------------------------------------------------------------------
// Nodes

std::string Node::where() const {
  std::string w = file_;
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict, PR 105651) on ":" + std::string.
  if (v_->line > 0) {
    w += ':';
    w += std::to_string(v_->line);
  }
  w += ": ";
  w += pointer_.empty() ? "/" : pointer_;
  return w;
}

void Node::fail(const std::string& what) const { throw input_error(where(), what); }

bool Node::has(std::string_view key) const { return is_object() && v_->find(key) != nullptr; }

Node Node::operator[](std::string_view key) const {
  if (!is_object()) fail(std::string("expected an object, found ") + type_name(v_->type));
  const Value* m = v_->find(key);
  if (!m) fail("missing member \"" + std::string(key) + "\"");
  return Node(*m, file_, pointer_ + "/" + std::string(key));
}

std::size_t Node::size() const {
  if (!is_array()) fail(std::string("expected an array, found ") + type_name(v_->type));
  return v_->items.size();
}

Node Node::operator[](std::size_t i) const {
  if (i >= size()) fail("index " + std::to_string(i) + " out of range");
  return Node(v_->items[i], file_, pointer_ + "/" + std::to_string(i));
}

std::vector<Node> Node::items() const {
  std::vector<Node> out;
  for (std::size_t i = 0; i < size(); ++i) out.push_back((*this)[i]);
  return out;
}

std::vector<std::pair<std::string, Node>> Node::members() const {
  if (!is_object()) fail(std::string("expected an object, found ") + type_name(v_->type));
  std::vector<std::pair<std::string, Node>> out;
  for (const auto& [k, v] : v_->members) out.emplace_back(k, Node(v, file_, pointer_ + "/" + k));
  return out;
}

void Node::only(std::initializer_list<std::string_view> known) const {
  if (!is_object()) fail(std::string("expected an object, found ") + type_name(v_->type));
  for (const auto& [k, v] : v_->members) {
    bool ok = false;
    for (std::string_view name : known) ok = ok || name == k;
    if (!ok) {
      std::string list;
      for (std::string_view name : known) list += (list.empty() ? "" : ", ") + std::string(name);
      Node(v, file_, pointer_ + "/" + k).fail("unknown member (known here: " + list + ")");
    }
  }
}

double Node::number() const {
  if (!is_number()) fail(std::string("expected a number, found ") + type_name(v_->type));
  return v_->number;
}

double Node::number(double lo, double hi) const {
  const double x = number();
  if (!(x >= lo && x <= hi)) fail("must be in [" + number_text(lo) + ", " + number_text(hi) + "], got " + number_text(x));
  return x;
}

int Node::integer(int lo, int hi) const {
  const double x = number(lo, hi);
  if (x != std::floor(x)) fail("expected an integer, got " + number_text(x));
  return int(x);
}

std::uint64_t Node::unsigned_integer() const {
  const double x = number(0.0, 9007199254740992.0);  // 2^53: every integer up to it is exact
  if (x != std::floor(x)) fail("expected a non-negative integer, got " + number_text(x));
  return std::uint64_t(x);
}

bool Node::boolean() const {
  if (v_->type != Value::Type::boolean) fail(std::string("expected true or false, found ") + type_name(v_->type));
  return v_->boolean;
}

const std::string& Node::string() const {
  if (!is_string()) fail(std::string("expected a string, found ") + type_name(v_->type));
  return v_->string;
}

std::vector<double> Node::numbers(std::size_t n) const {
  if (!is_array() || v_->items.size() != n) fail("expected an array of " + std::to_string(n) + " numbers");
  std::vector<double> out;
  for (std::size_t i = 0; i < n; ++i) out.push_back((*this)[i].number());
  return out;
}

double Node::number_or(std::string_view key, double fallback) const {
  return has(key) ? (*this)[key].number() : fallback;
}
double Node::number_or(std::string_view key, double fallback, double lo, double hi) const {
  return has(key) ? (*this)[key].number(lo, hi) : fallback;
}
int Node::integer_or(std::string_view key, int fallback, int lo, int hi) const {
  return has(key) ? (*this)[key].integer(lo, hi) : fallback;
}
bool Node::boolean_or(std::string_view key, bool fallback) const { return has(key) ? (*this)[key].boolean() : fallback; }
std::string Node::string_or(std::string_view key, const std::string& fallback) const {
  return has(key) ? (*this)[key].string() : fallback;
}

}  // namespace svbrdf::json
