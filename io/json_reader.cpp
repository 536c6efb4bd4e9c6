#include "io/json_reader.hpp"

#include <cstdlib>
#include <utility>

namespace nsb::io {

const JsonValue* JsonValue::find(std::string_view key) const {
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (keys[i] == key) return &values[i];
  }
  return nullptr;
}

const JsonValue& JsonValue::at(std::string_view key) const {
  static const JsonValue kMissing;
  const JsonValue* v = find(key);
  return v != nullptr ? *v : kMissing;
}

std::string JsonValue::string_member(std::string_view key) const {
  const JsonValue* v = find(key);
  return v != nullptr && v->type == Type::kString ? v->text : std::string();
}

JsonError::JsonError(std::string reason, std::size_t position)
    : std::invalid_argument(reason + " at byte " + std::to_string(position + 1)),
      reason_(std::move(reason)),
      position_(position) {}

namespace {

// A recursive-descent reader of RFC 8259's grammar, one byte of look-ahead.
class Reader {
 public:
  explicit Reader(std::string_view text) : s_(text) {}

  JsonValue document() {
    JsonValue v = value(0);
    space();
    if (i_ != s_.size()) fail("text after the JSON value");
    return v;
  }

 private:
  // The deepest nesting read; nsbridge's files nest at most 5 deep.
  static constexpr int kMaxDepth = 64;

  [[noreturn]] void fail(const std::string& what) const { throw JsonError(what, i_); }
  // RFC 8259, section 2: white space is space, tab, line feed and carriage return.
  void space() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\n' || s_[i_] == '\r' || s_[i_] == '\t'))
      ++i_;
  }
  bool eat(char c) {
    space();
    if (i_ < s_.size() && s_[i_] == c) {
      ++i_;
      return true;
    }
    return false;
  }
  void expect(char c) {
    if (!eat(c)) fail(std::string("expected '") + c + "'");
  }
  JsonValue value(int depth) {
    if (depth > kMaxDepth) fail("nested too deep");
    space();
    if (i_ >= s_.size()) fail("unexpected end");
    JsonValue v;
    const char c = s_[i_];
    if (c == '{') {
      ++i_;
      v.type = JsonValue::Type::kObject;
      if (eat('}')) return v;
      do {
        space();
        std::string key = string();
        expect(':');
        v.values.push_back(value(depth + 1));
        v.keys.push_back(std::move(key));
      } while (eat(','));
      expect('}');
    } else if (c == '[') {
      ++i_;
      v.type = JsonValue::Type::kArray;
      if (eat(']')) return v;
      do {
        v.items.push_back(value(depth + 1));
      } while (eat(','));
      expect(']');
    } else if (c == '"') {
      v.type = JsonValue::Type::kString;
      v.text = string();
    } else if (literal("null")) {
      v.type = JsonValue::Type::kNull;
    } else if (literal("true")) {
      v.type = JsonValue::Type::kBool;
      v.boolean = true;
    } else if (literal("false")) {
      v.type = JsonValue::Type::kBool;
    } else {
      v.type = JsonValue::Type::kNumber;
      v.number = number();
    }
    return v;
  }
  bool literal(std::string_view word) {
    if (s_.substr(i_, word.size()) != word) return false;
    i_ += word.size();
    return true;
  }
  double number() {
    const std::size_t start = i_;
    constexpr std::string_view kNumberBytes = "+-0123456789.eE";
    while (i_ < s_.size() && kNumberBytes.find(s_[i_]) != std::string_view::npos) ++i_;
    if (i_ == start) fail("expected a value");
    const std::string text(s_.substr(start, i_ - start));
    char* end = nullptr;
    const double x = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size()) fail("bad number '" + text + "'");
    return x;
  }
  std::string string() {
    if (i_ >= s_.size() || s_[i_] != '"') fail("expected a string");
    ++i_;
    std::string out;
    while (true) {
      if (i_ >= s_.size()) fail("unterminated string");
      const char c = s_[i_++];
      if (c == '"') return out;
      if (c != '\\') {
        out += c;
        continue;
      }
      if (i_ >= s_.size()) fail("unterminated string");
      const char e = s_[i_++];
      switch (e) {
        case '"': case '\\': case '/': out += e; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': append_utf8(out, hex4()); break;
        default: fail("bad escape");
      }
    }
  }
  unsigned hex4() {
    if (i_ + 4 > s_.size()) fail("bad \\u escape");
    unsigned u = 0;
    for (int k = 0; k < 4; ++k) {
      const char h = s_[i_++];
      u *= 16;
      if (h >= '0' && h <= '9') u += static_cast<unsigned>(h - '0');
      else if (h >= 'a' && h <= 'f') u += static_cast<unsigned>(h - 'a' + 10);
      else if (h >= 'A' && h <= 'F') u += static_cast<unsigned>(h - 'A' + 10);
      else fail("bad \\u escape");
    }
    return u;
  }
  // A code point of the basic plane as UTF-8 (nsbridge's writer escapes only control
  // characters).
  static void append_utf8(std::string& out, unsigned u) {
    if (u < 0x80) {
      out += static_cast<char>(u);
    } else if (u < 0x800) {
      out += static_cast<char>(0xC0 | (u >> 6));
      out += static_cast<char>(0x80 | (u & 0x3F));
    } else {
      out += static_cast<char>(0xE0 | (u >> 12));
      out += static_cast<char>(0x80 | ((u >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (u & 0x3F));
    }
  }

  std::string_view s_;
  std::size_t i_ = 0;
};

}  // namespace

JsonValue parse_json(std::string_view text) { return Reader(text).document(); }

}  // namespace nsb::io
