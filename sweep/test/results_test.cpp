// The typed rows of a sweep and their text (sweep/results.hpp): the limit-state columns are
// the union over the runs in order of first appearance, before wall_s, with empty cells where
// a run has no such limit state; a row's resume files read back to the same row; a results.csv
// read back gives the same text; each column's type is the one its field has.
#include "sweep/results.hpp"

#include <doctest/doctest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using namespace nsb::sweep;

namespace {

const std::string kScenes = NSB_SCENES_DIR;

// A one-at-a-time design of the bouncing ball (coordinate "y"): the base run (both labels
// empty), gravity 9.81 and 4.905 (TOML floats), and a named level "a, b" (a comma, quoted).
Design ball_design() {
  const fs::path dir =
      fs::temp_directory_path() / ("nsb_results_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / "ball.toml";
  std::ofstream(file) << "scene = \"" << kScenes << "/bouncing-ball.toml\"\nmode = \"oat\"\n"
                      << "[[factor]]\nkey = \"model.gravity\"\nvalues = [9.81, 4.905]\n"
                      << "[[factor]]\nkey = \"name\"\n"
                      << "levels = [{name = \"a, b\", set = [\"model.gravity=9.81\"]}]\n";
  Design d = load_design(file);
  fs::remove_all(dir);
  return d;
}

Row row(const Design& d, std::size_t index, std::string status, std::vector<LimitCell> limits) {
  Row r;
  r.run = d.runs.at(index).id;
  r.labels = d.runs[index].labels;
  r.status = std::move(status);
  r.peaks = {1.0};
  r.peak_errors = {0.002};
  r.residual = -0.25;
  r.impacts = 3;
  r.max_penetration = 0.0;
  r.energy_error = 1e-05;
  r.end_time = 4.0;
  r.steps = 120;
  r.lcp_solves = 0;
  r.lcp_fallbacks = 0;
  r.lcp_unsolved = 0;
  r.limit_states = std::move(limits);
  r.wall_s = 1.5;
  return r;
}

}  // namespace

TEST_CASE("results.csv from typed rows: limit columns are the union, before wall_s") {
  const Design d = ball_design();
  REQUIRE(d.runs.size() == 4);  // base, gravity 9.81, gravity 4.905, name "a, b"
  std::vector<std::optional<Row>> rows = {
      row(d, 0, "completed", {{"closure_left", true, -0.001}}),
      row(d, 1, "unseated", {{"unseating_left", false, 0.25}, {"closure_left", false, 0.01}}),
      rejected_row(d, 2, "bad \"step\", too large", 0.1),
      std::nullopt};
  rows[1]->message = "x, y";
  const Results r = results_of(d, rows);
  const std::string expected =
      "run,model.gravity,name,status,peak_y,peak_y_error,residual_y,impacts,max_penetration,"
      "energy_error,end_time,steps,lcp_solves,lcp_fallbacks,lcp_unsolved,failure_time,message,"
      "closure_left_exceeded,closure_left_margin,unseating_left_exceeded,unseating_left_margin,"
      "wall_s\n"
      "0000,,,completed,1,0.002,-0.25,3,0,1e-05,4,120,0,0,0,,,1,-0.001,,,1.5\n"
      "0001,9.81,,unseated,1,0.002,-0.25,3,0,1e-05,4,120,0,0,0,,\"x, y\",0,0.01,0,0.25,1.5\n"
      "0002,4.905,,rejected,,,,,,,,,,,,,\"bad \"\"step\"\", too large\",,,,,0.1\n";
  CHECK(r.csv() == expected);
  // The same text read back gives the same table.
  const fs::path file = fs::temp_directory_path() / ("nsb_results_" + std::to_string(::getpid()));
  std::ofstream(file) << expected;
  CHECK(results_of(read_csv(file)).csv() == expected);
  fs::remove(file);
  // Numbers: an absent limit state and a rejected run's counts are none.
  const std::size_t impacts = r.column("impacts"), margin = r.column("unseating_left_margin");
  CHECK(r.number(r.rows[0], impacts) == 3.0);
  CHECK_FALSE(r.number(r.rows[2], impacts).has_value());
  CHECK_FALSE(r.number(r.rows[0], margin).has_value());
  CHECK(r.number(r.rows[1], margin) == 0.25);
}

TEST_CASE("without limit states there are no limit columns") {
  const Design d = ball_design();
  const Results r = results_of(d, {row(d, 3, "completed", {})});
  CHECK(r.csv() ==
        "run,model.gravity,name,status,peak_y,peak_y_error,residual_y,impacts,max_penetration,"
        "energy_error,end_time,steps,lcp_solves,lcp_fallbacks,lcp_unsolved,failure_time,message,"
        "wall_s\n"
        "0003,,\"a, b\",completed,1,0.002,-0.25,3,0,1e-05,4,120,0,0,0,,,1.5\n");
}

TEST_CASE("a row's resume files read back to the same row") {
  const Design d = ball_design();
  Row r = row(d, 3, "diverged", {{"closure_left", true, -0.001}, {"u", false, kNotANumber}});
  r.failure_time = 0.125;
  r.message = "non-finite state, at \"t\"\nsecond line";
  r.peaks = {kNotANumber};
  r.peak_errors = {kNotANumber};
  const std::string line = row_line(d, r);
  CHECK(line ==
        "0003,,\"a, b\",diverged,,,-0.25,3,0,1e-05,4,120,0,0,0,0.125,"
        "\"non-finite state, at \"\"t\"\"\nsecond line\",1.5");
  const std::string limits = limit_states_csv(r.limit_states);
  CHECK(limits == "name,exceeded,margin\nclosure_left,1,-0.001\nu,0,\n");
  const auto back = parse_row(d, 3, line, limits);
  REQUIRE(back.has_value());
  CHECK(results_of(d, {back}).csv() == results_of(d, {r}).csv());
  CHECK(back->labels == d.runs[3].labels);
  CHECK(std::isnan(back->peaks[0]));
  CHECK_FALSE(parse_row(d, 2, line, limits).has_value());  // another run's line
  CHECK_FALSE(parse_row(d, 3, "0003,,x,completed", limits).has_value());  // too few fields
  CHECK(is_result(row(d, 0, "unseated", {})));
  CHECK_FALSE(is_result(rejected_row(d, 0, "no", 0.0)));
}

TEST_CASE("column types: from the fields, and a factor's from its levels") {
  const Design d = ball_design();
  const Results r = results_of(d, {row(d, 0, "completed", {{"closure_left", true, 0.0}})});
  const auto kind = [&r](const std::string& c) { return r.columns[r.column(c)].kind; };
  CHECK(kind("run") == ValueKind::kText);
  CHECK(kind("model.gravity") == ValueKind::kReal);
  CHECK(kind("name") == ValueKind::kText);
  CHECK(kind("status") == ValueKind::kText);
  CHECK(kind("peak_y") == ValueKind::kReal);
  CHECK(kind("impacts") == ValueKind::kInteger);
  CHECK(kind("steps") == ValueKind::kInteger);
  CHECK(kind("closure_left_exceeded") == ValueKind::kBoolean);
  CHECK(kind("closure_left_margin") == ValueKind::kReal);
  CHECK(kind("wall_s") == ValueKind::kReal);
  // A TOML float written without a fraction stays real; an integer, integer; names by their
  // text as a TOML value; a mix of integers and reals is real, any other mix text.
  Factor f;
  f.levels = {{"2", {}, ValueKind::kReal}, {"", {}}};
  CHECK(factor_kind(f) == ValueKind::kReal);
  f.levels = {{"2", {}, ValueKind::kInteger}, {"3", {}, ValueKind::kInteger}};
  CHECK(factor_kind(f) == ValueKind::kInteger);
  f.levels = {{"0.17", {}}, {"1", {}}};
  CHECK(factor_kind(f) == ValueKind::kReal);
  f.levels = {{"true", {}}, {"false", {}}};
  CHECK(factor_kind(f) == ValueKind::kBoolean);
  f.levels = {{"yes", {}}, {"1", {}}};
  CHECK(factor_kind(f) == ValueKind::kText);
  f.levels = {{"3", {}, ValueKind::kText}};  // a TOML string "3"
  CHECK(factor_kind(f) == ValueKind::kText);
}
