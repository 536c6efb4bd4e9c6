#include "config/schema.hpp"

#include <charconv>
#include <cstdio>

namespace nsb::config {

namespace {

// The shortest text that reads back as v (std::to_chars): 10, 0.5, 1e-08, 2.747e+07.
std::string shortest(double v) {
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
  return std::string(buffer, end);
}

// v with at most 6 significant digits, as messages quote a value: 0.3, 1e+308.
std::string six_digits(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

std::string with_unit(std::string text, std::string_view unit) {
  if (!unit.empty() && unit != "-") text += " [" + std::string(unit) + "]";
  return text;
}

}  // namespace

bool Range::contains(double v) const {
  if (std::isnan(v)) return false;
  const bool above = lo_open ? v > lo : v >= lo;
  const bool below = hi_open ? v < hi : v <= hi;
  return above && below;
}

std::string Range::describe() const {
  const bool lo_inf = std::isinf(lo);
  const bool hi_inf = std::isinf(hi);
  if (lo_inf && hi_inf) return "any";
  if (hi_inf) return (lo_open ? "> " : ">= ") + shortest(lo);
  if (lo_inf) return (hi_open ? "< " : "<= ") + shortest(hi);
  return std::string("in ") + (lo_open ? "(" : "[") + shortest(lo) + ", " + shortest(hi) +
         (hi_open ? ")" : "]");
}

Range any() { return {}; }
Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
Range non_negative() { return {0.0, std::numeric_limits<double>::infinity(), false, false}; }
Range closed(double lo, double hi) { return {lo, hi, false, false}; }
Range open(double lo, double hi) { return {lo, hi, true, true}; }
Range closed_open(double lo, double hi) { return {lo, hi, false, true}; }
Range open_closed(double lo, double hi) { return {lo, hi, true, false}; }

std::string format_value(const Value& v) {
  struct Visitor {
    std::string operator()(double d) const { return shortest(d); }
    std::string operator()(std::int64_t i) const { return std::to_string(i); }
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(const std::string& s) const { return "\"" + s + "\""; }
    std::string operator()(const std::vector<double>& x) const {
      std::string out = "[";
      for (std::size_t i = 0; i < x.size(); ++i) out += (i ? ", " : "") + shortest(x[i]);
      return out + "]";
    }
  };
  return std::visit(Visitor{}, v);
}

std::string describe_kind(Kind kind, std::string_view unit, const Range& range,
                          const std::vector<std::string_view>& choices) {
  switch (kind) {
    case Kind::kNumber:
      return range.describe() == "any" ? with_unit("a finite number", unit)
                                       : with_unit("must be " + range.describe(), unit);
    case Kind::kInteger:
      return range.describe() == "any" ? std::string("an integer")
                                       : "must be an integer " + range.describe();
    case Kind::kBoolean: return "true or false";
    case Kind::kChoice: {
      std::string list;
      for (const auto& c : choices) {
        if (!list.empty()) list.append(", ");
        list.append("\"").append(c).append("\"");
      }
      return "must be one of " + list;
    }
    case Kind::kText: return "a string";
    case Kind::kVector3: return with_unit("an array of 3 finite numbers", unit);
    case Kind::kNumbers:
      return range.describe() == "any"
                 ? with_unit("an array of finite numbers", unit)
                 : with_unit("an array of numbers, each " + range.describe(), unit);
  }
  return {};
}

std::string misfit_value(Kind kind, std::string_view unit, const Range& range,
                         const std::vector<std::string_view>& choices, const Value& v) {
  const std::string rule = describe_kind(kind, unit, range, choices);
  switch (kind) {
    case Kind::kNumber: {
      if (!std::holds_alternative<double>(v)) return "expected a number";
      const double d = std::get<double>(v);
      if (!std::isfinite(d)) return "must be finite";
      if (!range.contains(d)) return rule + " (got " + six_digits(d) + ")";
      return {};
    }
    case Kind::kInteger: {
      if (!std::holds_alternative<std::int64_t>(v)) return "expected an integer";
      const auto i = std::get<std::int64_t>(v);
      if (!range.contains(static_cast<double>(i))) return rule + " (got " + std::to_string(i) + ")";
      return {};
    }
    case Kind::kBoolean:
      return std::holds_alternative<bool>(v) ? std::string() : std::string("expected true or false");
    case Kind::kChoice: {
      if (!std::holds_alternative<std::string>(v)) return "expected a string; " + rule;
      const auto& s = std::get<std::string>(v);
      for (const auto& c : choices) {
        if (c == s) return {};
      }
      return rule + " (got \"" + s + "\")";
    }
    case Kind::kText:
      return std::holds_alternative<std::string>(v) ? std::string() : std::string("expected a string");
    case Kind::kVector3: {
      if (!std::holds_alternative<std::vector<double>>(v)) return "expected an array of 3 numbers";
      const auto& x = std::get<std::vector<double>>(v);
      if (x.size() != 3) return "expected an array of 3 numbers";
      for (double d : x) {
        if (!std::isfinite(d)) return "must be finite";
      }
      return {};
    }
    case Kind::kNumbers: {
      if (!std::holds_alternative<std::vector<double>>(v)) return "expected an array of numbers";
      for (double d : std::get<std::vector<double>>(v)) {
        if (!std::isfinite(d)) return "must be finite";
        if (!range.contains(d)) return rule + " (got " + six_digits(d) + ")";
      }
      return {};
    }
  }
  return {};
}

}  // namespace nsb::config
