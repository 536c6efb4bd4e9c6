// Overrides of scene values ("section.key=value", docs/scenes.md, "Overrides"), applied to the
// parsed TOML before any value is read, so that an overridden value is checked like any other.
#include "models/scene_reader.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <sstream>

namespace nsb::models {

namespace {

std::string strip(std::string s) {
  const auto b = s.find_first_not_of(" \t");
  const auto e = s.find_last_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

bool is_index(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](unsigned char ch) { return std::isdigit(ch); });
}

}  // namespace

void apply_override(toml::table& root, const std::string& text, Context& ctx) {
  const auto eq = text.find('=');
  if (eq == std::string::npos) {
    throw std::invalid_argument(ctx.file + ": override \"" + text +
                                "\": expected section.key=value");
  }
  const std::string lhs = strip(text.substr(0, eq));
  const std::string rhs = strip(text.substr(eq + 1));
  std::vector<std::string> parts;
  std::stringstream ss(lhs);
  for (std::string p; std::getline(ss, p, '.');) parts.push_back(strip(p));
  if (parts.size() < 2 || std::any_of(parts.begin(), parts.end(), [](const std::string& p) { return p.empty(); })) {
    throw std::invalid_argument(ctx.file + ": override \"" + text +
                                "\": expected section.key=value");
  }
  // The value: a TOML value, or else the raw text as a string.
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + rhs);
  } catch (const toml::parse_error&) {
    parsed = toml::table{};
    parsed.insert("v", rhs);
  }
  toml::node* value = parsed.get("v");

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
        throw std::invalid_argument(ctx.file + ": override \"" + text + "\": " + path + "." +
                                    p + ": index out of range; " + path + " has " +
                                    std::to_string(a->size()) + " elements (0-based)");
      }
      path += "[" + p + "]";
      cur = a->get(k);
    } else {
      throw std::invalid_argument(ctx.file + ": override \"" + text + "\": " + path +
                                  " is not a table");
    }
  }
  const std::string& last = parts.back();
  auto* parent = cur->as_table();
  if (parent == nullptr) {
    throw std::invalid_argument(ctx.file + ": override \"" + text + "\": " + path +
                                " is not a table");
  }
  value->visit([&](auto& v) { parent->insert_or_assign(last, std::move(v)); });
  ctx.overridden.insert(path + "." + last);
}

}  // namespace nsb::models
