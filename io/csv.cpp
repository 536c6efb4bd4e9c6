#include "io/csv.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace nsb::io {

void append_csv_number(std::string& out, double v) {
  if (!std::isfinite(v)) return;
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof(buf), v);
  out.append(buf, r.ptr);
}

std::string csv_number(double v) {
  std::string out;
  append_csv_number(out, v);
  return out;
}

std::string shortest(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  return csv_number(x);
}

std::string three_digits(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", x);
  return buffer;
}

std::string csv_quote(std::string_view s) {
  if (s.find_first_of(",\"\n\r") == std::string_view::npos) return std::string(s);
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
  return out;
}

std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> out(1);
  std::vector<bool> was_quoted(1, false);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char ch = line[i];
    if (quoted) {
      if (ch == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        out.back() += '"';
        ++i;
      } else if (ch == '"') {
        quoted = false;
      } else {
        out.back() += ch;
      }
    } else if (ch == '"') {
      quoted = true;
      was_quoted.back() = true;
    } else if (ch == ',') {
      out.emplace_back();
      was_quoted.push_back(false);
    } else if (ch != '\r') {
      out.back() += ch;
    }
  }
  for (std::size_t k = 0; k < out.size(); ++k) {
    if (was_quoted[k]) continue;
    auto& f = out[k];
    const auto b = f.find_first_not_of(" \t");
    const auto e = f.find_last_not_of(" \t");
    f = b == std::string::npos ? std::string() : f.substr(b, e - b + 1);
  }
  return out;
}

}  // namespace nsb::io
