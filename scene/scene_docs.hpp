// The key tables of docs/scenes.md, generated from the scene schema (scene/scene_schema.hpp
// and the methods' [solver] fields): one markdown table per scene table, one [solver] table
// per method. The committed docs hold each table between the marker comments
//   <!-- schema:begin NAME -->
//   ...
//   <!-- schema:end -->
// and the test models.scene_docs fails when they differ from the generated text.
#pragma once

#include "config/schema.hpp"

#include <map>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace nsb::scene {

// One key of a table: its name and kind ("number", "integer", "boolean", "choice", "text",
// "vector3", "numbers").
struct DocKey {
  std::string key;
  std::string kind;
};

// One generated table: its marker name ("solver.moreau", "model.deck", ...), its markdown and
// its keys in their order of declaration.
struct DocTable {
  std::string name;
  std::string markdown;
  std::vector<DocKey> keys;
};

// The rows of a key table from a struct's fields: key, unit, default, allowed values, meaning.
namespace doc_tables {

// Keys whose default is not the member's value: required keys, values derived when absent.
using DefaultNotes = std::map<std::string_view, std::string_view>;

// Text for a markdown cell: a '|' would end the cell.
inline std::string cell(std::string_view text) {
  std::string out;
  for (char ch : text) {
    if (ch == '|') out += '\\';
    out += ch;
  }
  return out;
}

// The allowed values of a field as the docs state them.
template <class S>
std::string allowed(const config::Field<S>& f) {
  switch (f.kind) {
    case config::Kind::kNumber: return f.range.describe() == "any" ? "finite" : f.range.describe();
    case config::Kind::kInteger: return "integer " + f.range.describe();
    case config::Kind::kBoolean: return "true, false";
    case config::Kind::kChoice: {
      std::string list;
      for (const auto& name : f.choices) list += (list.empty() ? "`\"" : ", `\"") + std::string(name) + "\"`";
      return list;
    }
    case config::Kind::kText: return "text";
    case config::Kind::kVector3: return "3 finite numbers";
    case config::Kind::kNumbers:
      return f.range.describe() == "any" ? "finite numbers" : "numbers " + f.range.describe();
  }
  return {};
}

template <class S>
std::string default_text(const config::Field<S>& f, const S& defaults, const DefaultNotes& notes) {
  if (const auto it = notes.find(f.key); it != notes.end()) return std::string(it->second);
  const config::Value v = f.get(defaults);
  if (const auto* s = std::get_if<std::string>(&v); s != nullptr && s->empty()) return "none";
  // Appended piecewise: GCC 12 reports a false -Wrestrict for "`" + std::string once inlined.
  std::string out = "`";
  out += config::format_value(v);
  out += '`';
  return out;
}

inline const std::string kHeader =
    "| key | unit | default | allowed | meaning |\n|---|---|---|---|---|\n";

template <class S>
std::string rows(std::span<const config::Field<S>> fields, const S& defaults,
                 const DefaultNotes& notes = {}) {
  std::string out;
  for (const auto& f : fields) {
    const std::string unit = f.unit.empty() || f.unit == "-" ? "–" : std::string(f.unit);
    out += "| `" + std::string(f.key) + "` | " + unit + " | " +
           cell(default_text(f, defaults, notes)) + " | " + cell(allowed(f)) + " | " +
           cell(f.meaning) + " |\n";
  }
  return out;
}

inline std::string kind_name(config::Kind k) {
  switch (k) {
    case config::Kind::kNumber: return "number";
    case config::Kind::kInteger: return "integer";
    case config::Kind::kBoolean: return "boolean";
    case config::Kind::kChoice: return "choice";
    case config::Kind::kText: return "text";
    case config::Kind::kVector3: return "vector3";
    case config::Kind::kNumbers: return "numbers";
  }
  return {};
}

// The keys of fields, in their order of declaration.
template <class S>
std::vector<DocKey> keys(std::span<const config::Field<S>> fields) {
  std::vector<DocKey> out;
  for (const auto& f : fields) out.push_back({std::string(f.key), kind_name(f.kind)});
  return out;
}

inline std::vector<DocKey> joined(std::vector<DocKey> a, const std::vector<DocKey>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

template <class S>
DocTable table(std::string name, std::span<const config::Field<S>> fields, const S& defaults,
               const DefaultNotes& notes = {}) {
  return {std::move(name), kHeader + rows(fields, defaults, notes), keys(fields)};
}

}  // namespace doc_tables

// Every table of the schema (the part kinds' with their kinds, scene/bridge_part_kinds.hpp).
std::vector<DocTable> scene_doc_tables();

// Where key is declared in a scene, for the hint of an unknown key: the tables other than
// `path` (a key path such as "model.seats") that hold it, as a scene file writes them
// ("[model.abutments]", "[[model.bents]]", "[solver] with method = \"compliance\""); empty
// when none does.
std::vector<std::string> tables_holding(std::string_view key, std::string_view path);

// doc with the text between each pair of markers replaced by the generated table of that
// name. Throws std::invalid_argument naming a marker whose name the schema does not know, an
// unterminated block, or a generated table the document has no block for.
std::string regenerate_scene_docs(const std::string& doc);

}  // namespace nsb::scene
