// Tests of the output files of a run record: their columns and keys (the contract of
// docs/outputs.md), exact round trip of numbers, no partial file on failure.
#include "runs/files.hpp"
#include "testsupport/systems.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

namespace nsb::runs {
namespace {

using integrators::EventKind;
using integrators::Recorder;
using integrators::RunResult;
using integrators::Vector;

// Three DOF, two contacts: enough to name every kind of column.
using TwoCorners = nsb::testsupport::TwoCornerBody;

std::string read(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::filesystem::path fresh_dir(const std::string& name) {
  auto d = std::filesystem::temp_directory_path() /
           ("nsb-output-test-" + std::to_string(::getpid()) + "-" + name);
  std::filesystem::remove_all(d);
  return d;
}

Recorder filled_recorder(TwoCorners& s) {
  Recorder rec(s, 0.0);
  auto c = s.make_contact_buffer();
  c[0].gap_normal = 0.1;
  c[1].gap_normal = -1.0 / 3.0;
  Vector q(3), u(3), ln(2), lt(2);
  q << 1.0 / 3.0, 0.0, -2e-7;
  u << 0.5, 0.0, 1e300;
  ln << 144.0, 0.0;
  lt << -72.0, 0.0;
  rec.step(0.0, q, u, c, ln, lt, 1e-9);
  q[0] = -2.0;
  u[2] = NAN;
  rec.step(0.25, q, u, c, ln, lt, 2e-9);
  rec.event(0.125, 1, EventKind::kImpact);
  rec.event(0.25, 2, EventKind::kSlip);
  rec.event(0.25, 0, EventKind::kWarning, "note, with \"quotes\"");
  return rec;
}

// A record as runs::run makes it, from a recorder and a result.
RunRecord record_of(const std::string& scene, const Recorder& rec, const RunResult& stats) {
  return RunRecord{scene, "test", stats, rec, make_digest(rec, stats)};
}

}  // namespace

TEST_CASE("history.csv has the documented columns and round-trips numbers exactly") {
  TwoCorners s({});
  const Recorder rec = filled_recorder(s);
  const std::string csv = history_csv(rec);
  std::istringstream in(csv);
  std::string header;
  std::getline(in, header);
  CHECK(header ==
        "t,x,y,theta,vx,vy,omega,gN1,lambdaN1,lambdaT1,gN2,lambdaN2,lambdaT2,energy_error");
  std::string row;
  std::getline(in, row);
  // Shortest round-trip form: 1/3 reads back bit for bit.
  CHECK(row.rfind("0,0.3333333333333333,0,-2e-07,0.5,0,1e+300,0.1,144,-72,", 0) == 0);
  CHECK(std::stod(row.substr(2, row.find(',', 2) - 2)) == 1.0 / 3.0);
  std::getline(in, row);
  // A non-finite value is an empty field, never "nan".
  CHECK(row.find("nan") == std::string::npos);
  CHECK(row.rfind("0.25,-2,0,-2e-07,0.5,0,,", 0) == 0);
  CHECK(!std::getline(in, row));
}

TEST_CASE("events.csv lists t, contact, kind and a quoted note") {
  TwoCorners s({});
  const Recorder rec = filled_recorder(s);
  CHECK(events_csv(rec) ==
        "t,contact,kind,note\n0.125,1,impact,\n0.25,2,slip,\n"
        "0.25,0,warning,\"note, with \"\"quotes\"\"\"\n");
}

TEST_CASE("summary.json holds the documented keys") {
  TwoCorners s({});
  const Recorder rec = filled_recorder(s);
  RunResult stats;
  stats.method = "moreau";
  stats.completed = true;
  stats.steps = 7;
  stats.lcp_solves = 3;
  stats.lcp_status["solved"] = 3;
  stats.energy.error = 1e-9;
  stats.warnings = {"a \"warning\""};
  const std::string j = summary_json(record_of("bridge-exc7", rec, stats));
  for (const char* key :
       {"\"scene\": \"bridge-exc7\"", "\"method\": \"moreau\"", "\"completed\": true",
        "\"message\"", "\"end_time\"", "\"steps\": 7", "\"rejected_steps\": 0",
        "\"steps_with_lcp\"", "\"lcp_solves\": 3", "\"lcp_fallbacks\"",
        "\"lcp_status\": {\"solved\": 3}", "\"factorizations\"", "\"wall_time\"",
        "\"samples\": 2", "\"energy\"", "\"error\": 1e-09", "\"events\": {\"impact\": 1",
        "\"contact_events\": [{\"contact\": 1, \"impact\": 1", "\"peaks\"",
        "\"x\": {\"max\": 0.3333333333333333, \"t_max\": 0, \"min\": -2, \"t_min\": 0.25, "
        "\"abs_max\": 2, \"t_abs_max\": 0.25, \"error\": null}",
        "\"warnings\": [\"a \\\"warning\\\"\"]",
        "\"error_estimate\": {\"enabled\": false, \"computed\": false",
        "\"cost\": {\"run_cpu_seconds\": 0", "\"accuracy\": {\"target\": 0, \"met\": null"}) {
    INFO(key);
    CHECK(j.find(key) != std::string::npos);
  }
  CHECK(j.find("nan") == std::string::npos);
}

TEST_CASE("write_record writes the three files and leaves no temporary behind") {
  TwoCorners s({});
  const Recorder rec = filled_recorder(s);
  RunResult stats;
  const auto dir = fresh_dir("ok") / "nested";
  write_record(dir, record_of("scene", rec, stats));
  CHECK(read(dir / "history.csv") == history_csv(rec));
  CHECK(read(dir / "events.csv") == events_csv(rec));
  CHECK(read(dir / "summary.json") == summary_json(record_of("scene", rec, stats)));
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
  CHECK(files == 3);
  std::filesystem::remove_all(dir.parent_path());
}

TEST_CASE("a failed write throws naming the path and leaves no half file") {
  TwoCorners s({});
  const Recorder rec = filled_recorder(s);
  const auto base = fresh_dir("fail");
  std::filesystem::create_directories(base);
  SUBCASE("the directory is a file") {
    std::ofstream(base / "file") << "x";
    CHECK_THROWS_WITH_AS(write_record(base / "file", record_of("s", rec, {})),
                         doctest::Contains("file"), std::runtime_error);
  }
  SUBCASE("a target name is taken by a directory: nothing is renamed into place") {
    std::filesystem::create_directories(base / "out" / "summary.json" / "x");
    CHECK_THROWS_AS(write_record(base / "out", record_of("s", rec, {})), std::runtime_error);
    for (const auto& e : std::filesystem::directory_iterator(base / "out")) {
      INFO(e.path().string());
      CHECK(e.path().filename().string().find(".tmp") == std::string::npos);
    }
  }
  std::filesystem::remove_all(base);
}

TEST_CASE("write_record replaces an older set as a whole and keeps the user's own files") {
  TwoCorners s({});
  const Recorder rec = filled_recorder(s);
  RunResult stats;
  const auto base = fresh_dir("swap");
  const auto dir = base / "out";
  std::filesystem::create_directories(dir);
  for (const char* f : {"history.csv", "events.csv", "summary.json"})
    std::ofstream(dir / f) << "old";
  write_record(dir, record_of("scene", rec, stats));
  CHECK(read(dir / "history.csv") == history_csv(rec));
  CHECK(read(dir / "summary.json") == summary_json(record_of("scene", rec, stats)));
  // Nothing but the output directory is left in its parent (no staging or old directory).
  int entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(base)) ++entries;
  CHECK(entries == 1);
  // A directory holding the user's own file keeps it, and receives the new set.
  std::ofstream(dir / "notes.txt") << "mine";
  std::ofstream(dir / "events.csv") << "old";
  write_record(dir, record_of("scene", rec, stats));
  CHECK(read(dir / "notes.txt") == "mine");
  CHECK(read(dir / "events.csv") == events_csv(rec));
  std::filesystem::remove_all(base);
}

TEST_CASE("a failed write leaves the previous set as it was: never a mix of old and new") {
  TwoCorners s({});
  const Recorder rec = filled_recorder(s);
  const auto base = fresh_dir("mixed");
  const auto dir = base / "out";
  std::filesystem::create_directories(dir / "summary.json" / "x");  // cannot be replaced
  std::ofstream(dir / "history.csv") << "old";
  std::ofstream(dir / "events.csv") << "old";
  CHECK_THROWS_AS(write_record(dir, record_of("s", rec, {})), std::runtime_error);
  CHECK(read(dir / "history.csv") == "old");
  CHECK(read(dir / "events.csv") == "old");
  int entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(base)) ++entries;
  CHECK(entries == 1);
  std::filesystem::remove_all(base);
}

}  // namespace nsb::runs
