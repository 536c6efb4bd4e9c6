// The key tables of docs/scenes.md, generated from the scene schema (scene/scene_schema.hpp
// and the methods' [solver] fields): one markdown table per scene table, one [solver] table
// per method. The committed docs hold each table between the marker comments
//   <!-- schema:begin NAME -->
//   ...
//   <!-- schema:end -->
// and the test models.scene_docs fails when they differ from the generated text.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace nsb::scene {

// One key of a table: its name and kind ("number", "integer", "boolean", "choice", "text",
// "vector3").
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

// Every table of the schema, in the order of docs/scenes.md.
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
