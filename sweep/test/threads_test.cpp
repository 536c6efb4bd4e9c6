// Sweeps on threads share nothing: event-driven runs of the bridge on two worker threads give
// the rows one thread gives, bit for bit. This is also the test the ThreadSanitizer build runs
// (scripts/run-tests.sh, build-tsan/): a data race between the runs (state shared by every run
// of a process, such as a library's global error handler switched per run) fails it there.
#include "sweep/csv.hpp"
#include "sweep/runner.hpp"
#include "sweep/test/results_text.hpp"

#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using namespace nsb::sweep;
using nsb::sweep::test::without_wall_time;

namespace {

// Four event-driven runs of the benchmark bridge under excitation 5, 8 s each (25 to 30 impacts), at four
// transverse PGAs: each run locates events with the root finder and solves impact problems.
fs::path bridge_design(const fs::path& dir) {
  const fs::path file = dir / "bridge-ed.toml";
  std::ofstream(file) << "scene = \"" << NSB_SCENES_DIR << "/bridge-exc5.toml\"\n"
                      << "set = [\"solver.method=event_driven\", \"solver.end_time=8.0\"]\n"
                      << "[[factor]]\nkey = \"model.excitation.target_pga\"\n"
                      << "values = [0.6, 0.7, 0.8, 1.0]\n";
  return file;
}

}  // namespace

TEST_CASE("event-driven bridge runs on two threads give the rows of one thread") {
  const fs::path dir = fs::temp_directory_path() / ("nsb_threads_test_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path design = bridge_design(dir);

  SweepOptions one;
  one.out = dir / "one";
  one.jobs = 1;
  one.progress = false;
  SweepOptions two = one;
  two.out = dir / "two";
  two.jobs = 2;

  const SweepSummary a = run_sweep(design, one);
  const SweepSummary b = run_sweep(design, two);
  CHECK(a.runs == 4);
  CHECK(a.failed == 0);
  CHECK(b.failed == 0);
  CHECK(without_wall_time(a.results) == without_wall_time(b.results));
  // Every run met impacts: the root finder and the impact problems ran on both threads.
  const Table t = read_csv(b.results);
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    CHECK(std::stoi(t.rows[r].at(t.column("impacts"))) > 0);
  }
  fs::remove_all(dir);
}
