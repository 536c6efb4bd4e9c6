// results.csv's limit-state columns (sweep/limit_columns.hpp, docs/sweep.md "Limit-state
// columns"): the union over the runs in order of first appearance, before wall_s, empty cells
// where a run has no such limit state, and no columns when no run watches any.
#include "sweep/limit_columns.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace fs = std::filesystem;

TEST_CASE("limit columns: union in first-appearance order, empty cells, before wall_s") {
  const fs::path dir = fs::temp_directory_path() / ("nsb-limit-columns-" + std::to_string(::getpid()));
  fs::create_directories(dir / "a");
  fs::create_directories(dir / "b");
  fs::create_directories(dir / "c");
  std::ofstream(dir / "a" / "limit_states.csv") << "name,exceeded,margin\nclosure_left,1,-0.001\n";
  std::ofstream(dir / "b" / "limit_states.csv")
      << "name,exceeded,margin\nunseating_left,0,0.25\nclosure_left,0,0.01\n";
  std::string header = "run,status,message,wall_s";
  std::vector<std::optional<std::string>> rows = {"a,completed,,1.5", "b,unseated,\"x, y\",2",
                                                  "c,rejected,bad,0.1", std::nullopt};
  nsb::sweep::add_limit_columns(header, rows, {dir / "a", dir / "b", dir / "c", dir / "d"});
  CHECK(header == "run,status,message,closure_left_exceeded,closure_left_margin,"
                  "unseating_left_exceeded,unseating_left_margin,wall_s");
  CHECK(*rows[0] == "a,completed,,1,-0.001,,,1.5");
  CHECK(*rows[1] == "b,unseated,\"x, y\",0,0.01,0,0.25,2");
  CHECK(*rows[2] == "c,rejected,bad,,,,,0.1");
  CHECK(!rows[3]);
  std::string plain = "run,status,wall_s";
  std::vector<std::optional<std::string>> one = {"c,completed,1"};
  nsb::sweep::add_limit_columns(plain, one, {dir / "c"});
  CHECK(plain == "run,status,wall_s");
  CHECK(*one[0] == "c,completed,1");
  fs::remove_all(dir);
}
