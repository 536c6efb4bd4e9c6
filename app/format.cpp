#include "app/format.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace nsb::app {

std::string shortest(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

std::string json_number(double x) { return std::isfinite(x) ? shortest(x) : "null"; }

std::string json_string(const std::string& text) {
  std::string s = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') {
      s += '\\';
      s += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
      s += buf;
    } else {
      s += c;
    }
  }
  return s + "\"";
}

}  // namespace nsb::app
