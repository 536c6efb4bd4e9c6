// The key tables of docs/scenes.md, generated from the scene schema (scene/scene_schema.hpp
// and the methods' [solver] fields): one markdown table per scene table, one [solver] table
// per method. The committed docs hold each table between the marker comments
//   <!-- schema:begin NAME -->
//   ...
//   <!-- schema:end -->
// and the test models.scene_docs fails when they differ from the generated text.
#pragma once

#include <string>
#include <vector>

namespace nsb::scene {

// One generated table: its marker name ("solver.moreau", "model.deck", ...) and its markdown.
struct DocTable {
  std::string name;
  std::string markdown;
};

// Every table of the schema, in the order of docs/scenes.md.
std::vector<DocTable> scene_doc_tables();

// doc with the text between each pair of markers replaced by the generated table of that
// name. Throws std::invalid_argument naming a marker whose name the schema does not know, an
// unterminated block, or a generated table the document has no block for.
std::string regenerate_scene_docs(const std::string& doc);

}  // namespace nsb::scene
