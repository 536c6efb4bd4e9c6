// scene_docs: the key tables of docs/scenes.md, generated from the scene schema
// (scene/scene_docs.hpp).
//   scene_docs                 prints every table between its markers
//   scene_docs --write FILE    replaces the tables of FILE with the generated ones
//   scene_docs --check FILE    exits 1 when FILE's tables differ from the generated ones
//   scene_docs --keys          prints every key as "<table> <key> <kind>", one a line (the
//                              fault-injection tests enumerate the schema's keys with it)
#include "scene/scene_docs.hpp"

#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument(path + ": cannot open");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

int run(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (argc == 1) {
    for (const auto& t : nsb::scene::scene_doc_tables()) {
      std::cout << "<!-- schema:begin " << t.name << " -->\n" << t.markdown
                << "<!-- schema:end -->\n\n";
    }
    return 0;
  }
  if (argc == 2 && mode == "--keys") {
    for (const auto& t : nsb::scene::scene_doc_tables()) {
      for (const auto& k : t.keys) std::cout << t.name << ' ' << k.key << ' ' << k.kind << '\n';
    }
    return 0;
  }
  if (argc != 3 || (mode != "--write" && mode != "--check")) {
    std::cerr << "usage: scene_docs [--write FILE | --check FILE | --keys]\n";
    return 2;
  }
  const std::string path = argv[2];
  const std::string doc = read_file(path);
  const std::string generated = nsb::scene::regenerate_scene_docs(doc);
  if (mode == "--write") {
    if (generated != doc) std::ofstream(path) << generated;
    return 0;
  }
  if (generated == doc) return 0;
  std::cerr << path << ": the key tables differ from the scene schema "
            << "(the models' fields in models/, scene/scene_schema.cpp, integrators/options.cpp); "
            << "regenerate them with\n"
            << "  cmake --build build --target scene_docs && build/scene/scene_docs --write "
            << path << "\n";
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "scene_docs: " << e.what() << "\n";
    return 2;
  }
}
