// Running sweeps: rows that do not depend on the number of workers, a numerically failing run
// that stays a row, resume, and the refusal of a changed design. Expected values come from the
// bouncing ball's closed form and from independent single runs, not from the sweep itself.
#include "sweep/runner.hpp"
#include "sweep/test/results_text.hpp"

#include "integrators/run.hpp"
#include "scene/scene.hpp"
#include "sweep/csv.hpp"

#include <doctest/doctest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace fs = std::filesystem;
using namespace nsb::sweep;
using nsb::sweep::test::without_wall_time;

namespace {

const std::string kScenes = NSB_SCENES_DIR;

fs::path scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("nsb_runner_test_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Bouncing ball (e = 0.9, dropped from 1 m, 4 s) with the event-driven method, over gravity.
// g = 1e40 m/s^2 is a real failure: the adaptive step underflows at t = 0 ("step size
// underflow"), so the run stops with status "stalled" there. (A scene number is at most 1e100
// in magnitude: g = 1e308 is bad input.)
fs::path ball_design(const fs::path& dir, const std::string& gravities) {
  const fs::path file = dir / "ball.toml";
  std::ofstream(file) << "scene = \"" << kScenes << "/bouncing-ball.toml\"\n"
                      << "set = [\"solver.method=event_driven\"]\n"
                      << "[[factor]]\nkey = \"model.gravity\"\nvalues = [" << gravities << "]\n";
  return file;
}

std::string cell(const Table& t, std::size_t row, const std::string& column) {
  return t.rows.at(row).at(t.column(column));
}

}  // namespace

TEST_CASE("the impacts of the bouncing ball match the closed form; a failing run is a row") {
  const fs::path dir = scratch("ball");
  SweepOptions o;
  o.out = dir / "out";
  o.jobs = 2;
  o.progress = false;
  const SweepSummary s = run_sweep(ball_design(dir, "9.81, 1e40, 4.905"), o);
  CHECK(s.runs == 3);
  CHECK(s.ran == 3);
  CHECK(s.failed == 1);
  const Table t = read_csv(o.out / "results.csv");
  REQUIRE(t.rows.size() == 3);
  // Impacts before t = 4 s: the first at t1 = sqrt(2h/g), then flights of 2 e^k v1 / g with
  // v1 = sqrt(2 g h). g = 9.81: t1 = 0.4515 s, flights 0.903 * 0.9^k s, the 6th impact at
  // 0.4515 + 0.903 (0.9 + ... + 0.9^5) = 3.87 s, the 7th at 4.35 s: 6 impacts.
  // g = 4.905: t1 = 0.6386 s, flights 1.277 * 0.9^k s; the 4th at 3.75 s, the 5th at 4.59 s: 4.
  CHECK(cell(t, 0, "status") == "completed");
  CHECK(cell(t, 0, "impacts") == "6");
  CHECK(cell(t, 2, "impacts") == "4");
  // The ball starts at rest at 1 m, the highest it ever is: peak |y| = 1 exactly.
  CHECK(cell(t, 0, "peak_y") == "1");
  CHECK(cell(t, 1, "status") == "stalled");
  CHECK(cell(t, 1, "failure_time") == "0");
  CHECK(cell(t, 1, "message").find("step size underflow") != std::string::npos);
  // Each run has its own outputs.
  for (const char* id : {"0000", "0001", "0002"}) {
    CHECK(fs::exists(o.out / "runs" / id / "summary.json"));
    CHECK(fs::exists(o.out / "runs" / id / "history.csv"));
  }
}

TEST_CASE("a row equals an independent single run of the same scene") {
  const fs::path dir = scratch("single");
  const fs::path design = dir / "d.toml";
  std::ofstream(design) << "scene = \"" << kScenes << "/bridge-exc5.toml\"\n"
                        << "set = [\"solver.end_time=3\"]\n"
                        << "[[factor]]\nkey = \"model.excitation.target_pga\"\nvalues = [1.0]\n";
  SweepOptions o;
  o.out = dir / "out";
  o.progress = false;
  (void)run_sweep(design, o);
  const Table t = read_csv(o.out / "results.csv");
  // The same run by hand, as `nsbridge run` does it.
  auto scene = nsb::scene::load_scene(kScenes + "/bridge-exc5.toml",
                                       {"solver.end_time=3", "model.excitation.target_pga=1.0"});
  // Every step recorded: the peaks are over every accepted step (docs/outputs.md).
  nsb::integrators::Recorder recorder(*scene.system, 0.0);
  const auto result = nsb::integrators::integrate(*scene.system, scene.run, recorder);
  double peak = 0.0;
  for (const double v : recorder.series("theta")) peak = std::max(peak, std::abs(v));
  CHECK(std::stod(cell(t, 0, "peak_theta")) == peak);  // bit for bit: same code, same input
  CHECK(std::stod(cell(t, 0, "residual_theta")) == recorder.series("theta").back());
  CHECK(std::stoll(cell(t, 0, "steps")) == result.steps);
  CHECK(std::stod(cell(t, 0, "energy_error")) == result.energy.error);
}

TEST_CASE("cross_check: the other method's peaks beside each row, read back on resume") {
  const fs::path dir = scratch("cross");
  const fs::path design = dir / "d.toml";
  std::ofstream(design) << "scene = \"" << kScenes << "/bridge-exc5.toml\"\n"
                        << "set = [\"solver.end_time=3\"]\ncross_check = \"event_driven\"\n"
                        << "[[factor]]\nkey = \"model.excitation.target_pga\"\nvalues = [1.0]\n";
  SweepOptions o;
  o.out = dir / "out";
  o.progress = false;
  (void)run_sweep(design, o);
  const Table t = read_csv(o.out / "results.csv");
  const std::string first = without_wall_time(o.out / "results.csv");
  // The same scene run under event-driven by hand, as `nsbridge run --method event_driven`.
  auto scene = nsb::scene::load_scene(kScenes + "/bridge-exc5.toml",
                                       {"solver.end_time=3", "model.excitation.target_pga=1.0",
                                        "solver.method=event_driven"});
  nsb::integrators::Recorder recorder(*scene.system, 0.0);
  (void)nsb::integrators::integrate(*scene.system, scene.run, recorder);
  CHECK(std::stod(cell(t, 0, "cross_check_peak_theta")) == recorder.extremes()[2].magnitude);
  CHECK(cell(t, 0, "cross_check_status") == "completed");
  CHECK(cell(t, 0, "cross_check_agrees") == "1");
  CHECK(!cell(t, 0, "cross_check_peak_theta_error").empty());
  // The columns sit before wall_s, and a resumed sweep gives the same table.
  CHECK(t.header.back() == "wall_s");
  fs::remove(o.out / "results.csv");
  CHECK(run_sweep(design, o).already_done == 1);
  CHECK(without_wall_time(o.out / "results.csv") == first);
  // An unknown method is refused at the key.
  std::ofstream(design) << "scene = \"" << kScenes << "/bridge-exc5.toml\"\n"
                        << "cross_check = \"rk4\"\n"
                        << "[[factor]]\nkey = \"model.excitation.target_pga\"\nvalues = [1.0]\n";
  CHECK_THROWS_WITH_AS(run_sweep(design, o), doctest::Contains("cross_check: must be one of"),
                       std::invalid_argument);
}

TEST_CASE("results.csv does not depend on the number of workers") {
  const fs::path dir = scratch("jobs");
  const fs::path design = dir / "d.toml";
  std::ofstream(design)
      << "scene = \"" << kScenes << "/bridge-exc5.toml\"\n"
      << "set = [\"solver.end_time=1.5\"]\n"
      << "[[factor]]\nkey = \"model.excitation.target_pga\"\nvalues = [0.5, 1.0, 2.0]\n"
      << "[[factor]]\nkey = \"model.seats.friction\"\nvalues = [0.0, 0.5]\n";
  SweepOptions one, three;
  one.out = dir / "one";
  one.jobs = 1;
  one.progress = false;
  three = one;
  three.out = dir / "three";
  three.jobs = 3;
  (void)run_sweep(design, one);
  (void)run_sweep(design, three);
  const std::string a = without_wall_time(one.out / "results.csv");
  CHECK(a.size() > 100);
  CHECK(a == without_wall_time(three.out / "results.csv"));
}

TEST_CASE("resume: completed runs are skipped; a changed design is refused unless restarted") {
  const fs::path dir = scratch("resume");
  SweepOptions o;
  o.out = dir / "out";
  o.jobs = 2;
  o.progress = false;
  const fs::path design = ball_design(dir, "9.81, 4.905, 2.0, 1e40");
  (void)run_sweep(design, o);
  const std::string first = without_wall_time(o.out / "results.csv");
  // An interrupted sweep: two runs never finished.
  fs::remove(o.out / "runs" / "0001" / "row.csv");
  fs::remove_all(o.out / "runs" / "0003");
  const SweepSummary again = run_sweep(design, o);
  CHECK(again.already_done == 2);
  CHECK(again.ran == 2);
  CHECK(again.failed == 1);  // the failed run counts whether resumed or not
  CHECK(without_wall_time(o.out / "results.csv") == first);
  // Nothing left to do.
  const SweepSummary done = run_sweep(design, o);
  CHECK(done.already_done == 4);
  CHECK(done.ran == 0);

  const fs::path changed = ball_design(dir, "9.81, 4.0");
  std::string message;
  try {
    (void)run_sweep(changed, o);
  } catch (const std::invalid_argument& e) {
    message = e.what();
  }
  CHECK(message.find("holds the runs of a different design") != std::string::npos);
  CHECK(message.find("--restart") != std::string::npos);
  CHECK(fs::exists(o.out / "runs" / "0003" / "row.csv"));  // refused: nothing touched
  o.restart = true;
  const SweepSummary fresh = run_sweep(changed, o);
  CHECK(fresh.already_done == 0);
  CHECK(fresh.ran == 2);
  CHECK(!fs::exists(o.out / "runs" / "0003"));
}

TEST_CASE("options are checked") {
  SweepOptions o;
  CHECK_THROWS_AS(o.validate(), std::invalid_argument);  // no --out
  o.out = "x";
  o.jobs = -1;
  CHECK_THROWS_AS(o.validate(), std::invalid_argument);
}
