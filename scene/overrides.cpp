// Overrides of scene values ("section.key=value", docs/scenes.md, "Overrides"), applied to the
// parsed TOML before any value is read, so that an overridden value is checked like any other.
#include "scene/scene.hpp"
#include "scene/scene_reader.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <sstream>
#include <type_traits>

namespace nsb::scene {

namespace {

std::string strip(std::string s) {
  const auto b = s.find_first_not_of(" \t");
  const auto e = s.find_last_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

bool is_index(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](unsigned char ch) { return std::isdigit(ch); });
}

// "section.key" split at its dots; empty when a part is empty or there is only one.
std::vector<std::string> key_parts(const std::string& key) {
  std::vector<std::string> parts;
  std::stringstream ss(key);
  for (std::string p; std::getline(ss, p, '.');) parts.push_back(strip(p));
  if (parts.size() < 2 || std::any_of(parts.begin(), parts.end(), [](const std::string& p) { return p.empty(); })) {
    return {};
  }
  return parts;
}

// The value of an override text: a TOML value, or else the raw text as a string.
toml::table parse_value(const std::string& rhs) {
  try {
    return toml::parse("v = " + rhs);
  } catch (const toml::parse_error&) {
    toml::table parsed;
    parsed.insert("v", rhs);
    return parsed;
  }
}

// Sets the key path `parts` of root to value; `text` names the override in messages. Tables
// on the way are created, arrays indexed. Records the key path in `overridden`.
void set_value(toml::table& root, const std::vector<std::string>& parts, toml::node& value,
               const std::string& text, const std::string& file,
               std::set<std::string>& overridden) {
  // Walk to the parent of the last component; tables are created, arrays indexed.
  std::string path;
  toml::node* cur = &root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    const std::string& p = parts[i];
    if (auto* t = cur->as_table()) {
      path += (path.empty() ? "" : ".") + p;
      toml::node* next = t->get(p);
      if (next == nullptr) {
        t->insert(p, toml::table{});
        next = t->get(p);
      }
      cur = next;
    } else if (auto* a = cur->as_array(); a != nullptr && is_index(p)) {
      // Any run of digits is an index; one too large for size_t is out of range like any
      // other index past the end.
      std::size_t k = 0;
      const auto [end, ec] = std::from_chars(p.data(), p.data() + p.size(), k);
      if (ec != std::errc() || end != p.data() + p.size() || k >= a->size()) {
        throw std::invalid_argument(file + ": override \"" + text + "\": " + path + "." +
                                    p + ": index out of range; " + path + " has " +
                                    std::to_string(a->size()) + " elements (0-based)");
      }
      path += "[" + p + "]";
      cur = a->get(k);
    } else {
      throw std::invalid_argument(file + ": override \"" + text + "\": " + path +
                                  " is not a table");
    }
  }
  const std::string& last = parts.back();
  auto* parent = cur->as_table();
  if (parent == nullptr) {
    throw std::invalid_argument(file + ": override \"" + text + "\": " + path +
                                " is not a table");
  }
  value.visit([&](auto& v) { parent->insert_or_assign(last, std::move(v)); });
  overridden.insert(path + "." + last);
}

// The TOML node of a typed value, in a table under "v".
toml::table value_table(const OverrideValue& value) {
  toml::table t;
  std::visit(
      [&t](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::vector<double>>) {
          toml::array a;
          for (const double x : v) a.push_back(x);
          t.insert("v", std::move(a));
        } else {
          t.insert("v", v);
        }
      },
      value);
  return t;
}

[[noreturn]] void malformed(const std::string& file, std::string_view text) {
  throw std::invalid_argument((file.empty() ? std::string() : file + ": ") + "override \"" +
                              std::string(text) + "\": expected section.key=value");
}

}  // namespace

Override parse_override(std::string_view text) {
  const auto eq = text.find('=');
  if (eq == std::string_view::npos) malformed("", text);
  Override o;
  o.key = strip(std::string(text.substr(0, eq)));
  if (key_parts(o.key).empty()) malformed("", text);
  const toml::table parsed = parse_value(strip(std::string(text.substr(eq + 1))));
  const toml::node& v = *parsed.get("v");
  if (v.is_boolean()) {
    o.value = v.as_boolean()->get();
  } else if (v.is_integer()) {
    o.value = v.as_integer()->get();
  } else if (v.is_floating_point()) {
    o.value = v.as_floating_point()->get();
  } else if (v.is_string()) {
    o.value = v.as_string()->get();
  } else if (const toml::array* a = v.as_array();
             a != nullptr && std::all_of(a->begin(), a->end(), [](const toml::node& x) { return x.is_number(); })) {
    std::vector<double> x;
    for (const auto& e : *a) x.push_back(*e.value<double>());
    o.value = std::move(x);
  } else {
    throw std::invalid_argument("override \"" + std::string(text) + "\": expected a boolean, " +
                                "an integer, a number, a string or an array of numbers, got " +
                                type_name(v));
  }
  return o;
}

std::string to_string(const Override& o) {
  const toml::table t = value_table(o.value);
  std::ostringstream s;
  s << o.key << '=';
  s << toml::toml_formatter(*t.get("v"));
  return s.str();
}

void apply_overrides(SceneTable& scene, const std::vector<Override>& overrides) {
  for (const auto& o : overrides) {
    const std::vector<std::string> parts = key_parts(o.key);
    const std::string text = to_string(o);
    if (parts.empty()) malformed(scene.origin.name, text);
    toml::table value = value_table(o.value);
    set_value(scene.table, parts, *value.get("v"), text, scene.origin.name, scene.overridden);
  }
}

void apply_overrides(SceneTable& scene, const std::vector<std::string>& overrides) {
  for (const auto& text : overrides) {
    const auto eq = text.find('=');
    if (eq == std::string::npos) malformed(scene.origin.name, text);
    const std::vector<std::string> parts = key_parts(strip(text.substr(0, eq)));
    if (parts.empty()) malformed(scene.origin.name, text);
    toml::table value = parse_value(strip(text.substr(eq + 1)));
    set_value(scene.table, parts, *value.get("v"), text, scene.origin.name, scene.overridden);
  }
}

}  // namespace nsb::scene
