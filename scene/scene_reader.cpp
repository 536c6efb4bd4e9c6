#include "scene/scene_reader.hpp"

#include "io/spelling.hpp"
#include "scene/scene_docs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace nsb::scene {

void Source::fail(const toml::node* n, const std::string& key, const std::string& what) const {
  std::ostringstream s;
  s << file;
  if (overridden.count(key) != 0) {
    s << ": " << key << " (override)";
  } else if (n != nullptr && n->source().begin.line > 0) {
    s << ':' << n->source().begin.line << ':' << n->source().begin.column;
    if (!key.empty()) s << ": " << key;
  } else if (!key.empty()) {
    s << ": " << key;
  }
  // The top-level table has no key: its messages go straight after the file's position.
  s << ": " << what;
  throw std::invalid_argument(s.str());
}

std::string six_digits(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", x);
  return buffer;
}

std::string derived(double x) {
  if (std::isnan(x)) return "undefined";
  if (std::isinf(x)) return "beyond the range of a double";
  return six_digits(x);
}

std::string implausible_number(const config::Value& v) {
  std::vector<double> x;
  if (const auto* d = std::get_if<double>(&v)) x = {*d};
  if (const auto* a = std::get_if<std::vector<double>>(&v)) x = *a;
  const auto subnormal = [](double y) { return std::fpclassify(y) == FP_SUBNORMAL; };
  const auto huge = [](double y) { return std::abs(y) > kMaxMagnitude; };
  if (std::any_of(x.begin(), x.end(), subnormal)) {
    return "is subnormal (" + config::format_value(v) +
           "; below 2.2e-308, the smallest normal double), no physical value: its reciprocal "
           "overflows; give 0 or a normal number";
  }
  if (std::any_of(x.begin(), x.end(), huge)) {
    return "must be at most 1e+100 in magnitude (got " + config::format_value(v) +
           "): the model's quantities are products of up to three values (1/2 m v^2, k x^2), "
           "which must stay below the largest double, 1.8e+308";
  }
  return {};
}

std::string type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a float";
    case toml::node_type::boolean: return "a boolean";
    default: return "a date/time";
  }
}

std::string Section::key_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

void Section::fail(std::string_view key, const std::string& what) const {
  const toml::node* n = t_.get(key);
  c_.fail(n != nullptr ? n : &t_, key_path(key), what);
}

void Section::fail_table(const std::string& what) const { c_.fail(&t_, path_, what); }

namespace {

// The hint of an unknown key: the known key of this table spelled closest to it (at most a
// third of its letters differ), else the other tables that declare it.
std::string unknown_key_hint(std::string_view key, const std::vector<std::string_view>& known,
                             std::string_view path) {
  std::string_view best;
  std::size_t best_distance = std::max<std::size_t>(1, key.size() / 3) + 1;
  for (const auto& k : known) {
    const std::size_t d = io::edit_distance(key, k);
    if (d < best_distance) {
      best = k;
      best_distance = d;
    }
  }
  if (!best.empty()) return "; did you mean `" + std::string(best) + "`?";
  const std::vector<std::string> elsewhere = tables_holding(key, path);
  if (elsewhere.empty()) return {};
  std::string list;
  for (std::size_t i = 0; i < elsewhere.size(); ++i) {
    list += (i == 0 ? "" : i + 1 == elsewhere.size() ? " or " : ", ") + ("`" + elsewhere[i] + "`");
  }
  return "; did you mean " + list + "? (" + std::string(key) + " is a key there)";
}

}  // namespace

void Section::only(const std::vector<std::string_view>& known) {
  known_ = known;
  for (auto&& [k, v] : t_) {
    if (std::find(known.begin(), known.end(), k.str()) != known.end()) continue;
    std::string list;
    for (const auto& u : known) list.append(list.empty() ? "" : ", ").append(u);
    c_.fail(&v, key_path(k.str()),
            "unknown key" + unknown_key_hint(k.str(), known, path_) + "; allowed here: " + list);
  }
}

namespace {

// A TOML number (integer or float) as a double, or nullopt for another type.
std::optional<double> as_number(const toml::node& n) {
  if (n.is_integer()) return static_cast<double>(n.as_integer()->get());
  if (n.is_floating_point()) return n.as_floating_point()->get();
  return std::nullopt;
}

}  // namespace

std::optional<config::Value> Section::value(std::string_view key, config::Kind kind) const {
  const toml::node* n = t_.get(key);
  if (n == nullptr) return std::nullopt;
  const std::string got = ", got " + type_name(*n);
  switch (kind) {
    case config::Kind::kNumber:
      if (const auto d = as_number(*n)) return config::Value(*d);
      fail(key, "expected a number" + got);
    case config::Kind::kInteger:
      if (n->is_integer()) return config::Value(n->as_integer()->get());
      fail(key, "expected an integer" + got);
    case config::Kind::kBoolean:
      if (n->is_boolean()) return config::Value(n->as_boolean()->get());
      fail(key, "expected true or false" + got);
    case config::Kind::kChoice:
    case config::Kind::kText:
      if (n->is_string()) return config::Value(n->as_string()->get());
      fail(key, "expected a string" + got);
    case config::Kind::kVector3: {
      const toml::array* a = n->as_array();
      if (a == nullptr || a->size() != 3) fail(key, "expected an array of 3 numbers");
      std::vector<double> x;
      for (std::size_t i = 0; i < 3; ++i) {
        const auto d = as_number((*a)[i]);
        if (!d) {
          fail(key, "expected an array of 3 numbers, element " + std::to_string(i) + " is " +
                        type_name((*a)[i]));
        }
        x.push_back(*d);
      }
      return config::Value(std::move(x));
    }
    case config::Kind::kNumbers: {
      const toml::array* a = n->as_array();
      if (a == nullptr) fail(key, "expected an array of numbers" + got);
      std::vector<double> x;
      for (std::size_t i = 0; i < a->size(); ++i) {
        const auto d = as_number((*a)[i]);
        if (!d) {
          fail(key, "expected an array of numbers, element " + std::to_string(i) + " is " +
                        type_name((*a)[i]));
        }
        x.push_back(*d);
      }
      return config::Value(std::move(x));
    }
  }
  return std::nullopt;
}

const toml::table* Section::subtable(std::string_view key) const {
  const toml::node* n = t_.get(key);
  if (n == nullptr) return nullptr;
  if (!n->is_table()) fail(key, "expected a table, got " + type_name(*n));
  return n->as_table();
}

const toml::array* Section::array_of_tables(std::string_view key) const {
  const toml::node* n = t_.get(key);
  if (n == nullptr) return nullptr;
  if (!n->is_array_of_tables()) {
    fail(key, "expected an array of tables ([[" + key_path(key) + "]])");
  }
  return n->as_array();
}

void Section::rethrow(const std::invalid_argument& e,
                      const std::map<std::string, std::string>& field_to_key) const {
  const std::string msg = e.what();
  const auto colon = msg.find(": ");
  if (colon != std::string::npos) {
    std::string field = msg.substr(0, colon);
    const std::string what = msg.substr(colon + 2);
    if (const auto it = field_to_key.find(field); it != field_to_key.end()) field = it->second;
    const bool known = std::find(known_.begin(), known_.end(), field) != known_.end();
    if (t_.get(field) != nullptr || known) fail(field, what);
  }
  fail_table(msg);
}

}  // namespace nsb::scene
