// Reading JSON text (RFC 8259) whole into a value: what nsbridge's own readers of its output
// files use (`nsbridge plot` reading summary.json, the figures' check reading claims.json).
#pragma once

#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace nsb::io {

// A JSON value. An object keeps its members in the order of the text.
struct JsonValue {
  enum class Type { kNull, kBool, kNumber, kString, kArray, kObject };
  Type type = Type::kNull;
  bool boolean = false;                                   // a bool's value
  double number = std::numeric_limits<double>::quiet_NaN();  // a number's value; NaN otherwise
                                                          // (nsbridge writes a non-finite
                                                          // number as null)
  std::string text;                                       // a string's value
  std::vector<JsonValue> items;                           // an array's elements
  std::vector<std::string> keys;    // an object's keys, in order, and their values (a vector
  std::vector<JsonValue> values;    //   of pairs would hold JsonValue while it is incomplete)

  // The first member named key; nullptr when there is none or this is not an object.
  const JsonValue* find(std::string_view key) const;
  // The member named key, or a null value when there is none.
  const JsonValue& at(std::string_view key) const;
  // The member named key when it is a string; empty otherwise.
  std::string string_member(std::string_view key) const;
};

// Malformed JSON text: what is wrong (reason) and where (position, the 0-based byte offset).
// what() reads "<reason> at byte <position + 1>".
class JsonError : public std::invalid_argument {
 public:
  JsonError(std::string reason, std::size_t position);
  const std::string& reason() const { return reason_; }
  std::size_t position() const { return position_; }

 private:
  std::string reason_;
  std::size_t position_;
};

// The one JSON value of text, surrounded by white space only. Strings are unescaped (\uXXXX of
// the basic plane as UTF-8); numbers are read by strtod. Throws JsonError for anything else,
// and beyond 64 levels of nesting.
JsonValue parse_json(std::string_view text);

}  // namespace nsb::io
