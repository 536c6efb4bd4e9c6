// A sequence of records ([[model.excitation.sequence]], docs/ground-motions.md, "Sequences") is
// one run of one system whose ground motion is the records in turn: the bridge meets the second
// record in the state the first left it in. On the benchmark bridge (excitation 7's model) with
// two short synthetic records, A (1.5 s, then a rest of 1 s) and B (1.5 s, then 0.5 s):
//  - Moreau–Jean: the sequence equals, bit for bit, record A alone run to the end of its rest
//    t_b = 2.5 s and then restarted from the state saved there (integrators::MoreauJeanCheckpoint
//    and a copy of the models::Assembly: the bents' Takeda branches, the seats' contacts, the
//    limit watch) under the sequence's motion from t_b on, which is record B's own
//    (models/test/ground_motion_test.cpp: after B's start the sequence's motion is B's, bit for
//    bit). h = 2^-13 s puts t_b on the step grid exactly, so that the run of A alone ends where
//    the sequence's step does.
//  - event-driven and compliance cannot restart from a saved state (their step control and
//    event history are not saved; docs/ground-motions.md, "Sequences"): their sequence runs
//    equal record A alone up to t_b and their state is continuous across the switch; after it
//    event-driven follows the Moreau–Jean sequence within the methods' agreement.
#include "integrators/moreau_jean.hpp"
#include "integrators/run.hpp"
#include "models/assembly.hpp"
#include "scene/scene.hpp"

#include <doctest/doctest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
namespace ni = nsb::integrators;
namespace nm = nsb::models;

constexpr double kSwitch = 2.5;  // [s]: the end of A (1.5 s) and of its rest (1 s)
constexpr double kEnd = 4.5;     // [s]: B ends at 4 s, then 0.5 s of rest
constexpr const char* kStep = "solver.step=1.220703125e-4";  // 2^-13 s
// Event-driven and compliance against record A alone before t_b: the same steps, as long as
// the end time does not shorten one, so the same numbers; measured 0 (round-off margin).
constexpr double kSameSteps = 1e-12;
// Across the switch a state is continuous: the change between the last row at or before t_b
// and the first after it is at most the largest speed times the interval between them, with
// 10 % margin for the acceleration over that interval.
constexpr double kContinuityMargin = 1.1;
// After the switch, event-driven (tolerance 1e-8) against Moreau–Jean at h = 2^-13 s, relative
// to each coordinate's peak: measured 1.4e-3 (1.3e-3 before the switch); twice that as the
// tolerance. A run that lost the state at the switch (B meeting the bridge at rest) differs by
// 0.27 of the peak. Compliance is not compared so: its Hertz contacts give this pounding
// another response, 0.26 of the peak from Moreau–Jean's already before the switch (and 0.17
// to 0.45 with the contact stiffness 10 or 100 times the default), as large as a lost state.
constexpr double kEventAgreement = 3e-3;

// A scratch folder of this process, removed at exit.
const fs::path& scratch() {
  struct Dir {
    fs::path dir = fs::temp_directory_path() / ("nsb-sequence-" + std::to_string(::getpid()));
    Dir() { fs::create_directories(dir); }
    ~Dir() {
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
  };
  static const Dir d;
  return d.dir;
}

// A two-column record "t a" [s, m/s^2]: amplitude A, period T, 0 to `duration` at 0.005 s,
// the times written exactly ("%.3f" of multiples of 0.005 read back as those decimals).
std::string write_record(const std::string& name, double A, double T, double duration) {
  std::ofstream out(scratch() / name);
  const int n = static_cast<int>(std::lround(duration / 0.005));
  for (int i = 0; i <= n; ++i) {
    char line[64];
    const double t = i * 0.005;
    std::snprintf(line, sizeof line, "%.3f %.17g\n", t,
                  A * std::sin(2.0 * std::numbers::pi * t / T));
    out << line;
  }
  return (scratch() / name).string();
}

// The benchmark bridge (scenes/bridge-exc7.toml's model) under `excitation`.
std::string bridge_scene(const std::string& excitation) {
  return R"(kind = "bridge"
[model.deck]
mass = 140.5
inertia = 13090.0
length = 33.53
width = 2.44
[model.gaps]
left = 0.0127
right = 0.0127
[model.damping]
ratio_i = 0.08
ratio_j = 0.08
mode_i = 1
mode_j = 3
[[model.bents]]
position = -8.3825
height = 1.83
column_diameter = 0.305
columns = 2
[[model.bents]]
position = 0.0
height = 2.44
column_diameter = 0.305
columns = 2
[[model.bents]]
position = 8.3825
height = 1.52
column_diameter = 0.305
columns = 2
[model.seats]
restitution = 0.0
friction = 0.5
)" + excitation;
}

struct Records {
  std::string ax, ay, bx, by;  // A and B, longitudinal and transverse
};

const Records& records() {
  static const Records r{write_record("a-x.txt", 9.0, 0.30, 1.5),
                         write_record("a-y.txt", 8.0, 0.35, 1.5),
                         write_record("b-x.txt", 5.0, 0.40, 1.5),
                         write_record("b-y.txt", 6.0, 0.33, 1.5)};
  return r;
}

std::string write_scene(const std::string& name, const std::string& excitation) {
  const fs::path p = scratch() / name;
  std::ofstream(p) << "[model]\n" << bridge_scene(excitation);
  return p.string();
}

// The sequence A, 1 s of rest, B, 0.5 s of rest.
std::string sequence_scene() {
  const Records& r = records();
  return write_scene("sequence.toml", "[model.excitation]\nbaseline_correction = true\n"
                                      "[[model.excitation.sequence]]\nlongitudinal_record = \"" +
                                          r.ax + "\"\ntransverse_record = \"" + r.ay +
                                          "\"\nrest = 1.0\n[[model.excitation.sequence]]\n"
                                          "longitudinal_record = \"" + r.bx +
                                          "\"\ntransverse_record = \"" + r.by + "\"\nrest = 0.5\n");
}

// Record A alone (the single-record form).
std::string first_scene() {
  const Records& r = records();
  return write_scene("first.toml", "[model.excitation]\nlongitudinal_record = \"" + r.ax +
                                       "\"\ntransverse_record = \"" + r.ay + "\"\n");
}

nsb::scene::Scene load(const std::string& file, const std::string& method, double end) {
  return nsb::scene::load_scene(file, {"solver.method=" + method, kStep,
                                       "solver.end_time=" + std::to_string(end)});
}

ni::Recorder run(const std::string& file, const std::string& method, double end) {
  nsb::scene::Scene s = load(file, method, end);
  ni::Recorder rec(*s.system, 0.0);
  const ni::RunResult r = ni::integrate(*s.system, s.run, rec);
  REQUIRE(ni::succeeded(r.status));
  return rec;
}

// The rows of `rec` by time.
std::map<double, std::size_t> rows_by_time(const ni::Recorder& rec) {
  std::map<double, std::size_t> out;
  for (std::size_t r = 0; r < rec.rows(); ++r) out[rec.at(r, 0)] = r;
  return out;
}

// Each coordinate column's (x, y, theta) peak |value| over rec.
std::vector<double> peaks(const ni::Recorder& rec) {
  std::vector<double> p(3, 1e-300);
  for (std::size_t r = 0; r < rec.rows(); ++r) {
    for (std::size_t c = 0; c < 3; ++c) p[c] = std::max(p[c], std::abs(rec.at(r, 1 + c)));
  }
  return p;
}

// The largest difference of the coordinates (columns 1-3: x, y, theta) of a and b at the times
// of b's rows in (from, until), a linearly interpolated, relative to a's peaks.
double coordinate_difference(const ni::Recorder& a, const ni::Recorder& b, double from,
                             double until) {
  const std::vector<double> peak = peaks(a);
  double worst = 0.0;
  std::size_t k = 1;
  for (std::size_t r = 0; r < b.rows(); ++r) {
    const double t = b.at(r, 0);
    if (!(t > from && t < until)) continue;
    while (k + 1 < a.rows() && a.at(k, 0) < t) ++k;
    const double t0 = a.at(k - 1, 0), t1 = a.at(k, 0);
    const double w = t1 > t0 ? (t - t0) / (t1 - t0) : 0.0;
    for (std::size_t c = 0; c < 3; ++c) {
      const double ref = (1 - w) * a.at(k - 1, 1 + c) + w * a.at(k, 1 + c);
      worst = std::max(worst, std::abs(ref - b.at(r, 1 + c)) / peak[c]);
    }
  }
  return worst;
}

}  // namespace

TEST_CASE("a sequence under Moreau-Jean is record A, then a restart under record B, bit for bit") {
  const std::string seq_file = sequence_scene(), first_file = first_scene();
  const ni::Recorder sequence = run(seq_file, "moreau", kEnd);

  // Record A alone to t_b, saved there.
  nsb::scene::Scene first = load(first_file, "moreau", kSwitch);
  ni::MoreauJeanCheckpoint saved;
  ni::RunHooks save;
  save.checkpoint = &saved;
  ni::Recorder before(*first.system, 0.0);
  REQUIRE(ni::succeeded(ni::integrate(*first.system, first.run, before, {}, save).status));
  REQUIRE(saved.time == kSwitch);
  const auto* assembly = dynamic_cast<const nm::Assembly*>(first.system.get());
  REQUIRE(assembly != nullptr);
  // The state A leaves: yielded bents and a deck still moving.
  CHECK(saved.energy.hysteretic > 0.0);
  CHECK(saved.velocity.norm() > 1e-3);

  // Restarted from that state under the sequence's motion (B from t_b on).
  nm::Assembly restarted(*assembly);
  nsb::scene::Scene motions = load(seq_file, "moreau", kEnd);
  restarted.use_motions_of(dynamic_cast<const nm::Assembly&>(*motions.system));
  ni::RunHooks resume;
  resume.resume = &saved;
  ni::Recorder after(restarted, 0.0);
  REQUIRE(ni::succeeded(ni::integrate(restarted, motions.run, after, {}, resume).status));

  // Before and at t_b: the sequence is record A alone, row for row.
  REQUIRE(sequence.rows() == before.rows() + after.rows() - 1);
  REQUIRE(sequence.columns() == before.columns());
  std::size_t differing = 0;
  for (std::size_t r = 0; r < before.rows(); ++r) {
    for (std::size_t c = 0; c < before.columns().size(); ++c) {
      if (!(sequence.at(r, c) == before.at(r, c))) ++differing;
    }
  }
  CHECK(differing == 0);
  // After t_b: the restart, row for row (its row at t_b itself has no step's forces yet).
  const std::size_t offset = before.rows() - 1;
  differing = 0;
  for (std::size_t r = 1; r < after.rows(); ++r) {
    for (std::size_t c = 0; c < after.columns().size(); ++c) {
      if (!(sequence.at(offset + r, c) == after.at(r, c))) ++differing;
    }
  }
  CHECK(differing == 0);
  CHECK(after.at(after.rows() - 1, 0) == doctest::Approx(kEnd));

  // The state A leaves matters: the same sequence with A scaled to zero (B meeting the bridge
  // at rest and undamaged) gives another response after t_b.
  nsb::scene::Scene fresh = nsb::scene::load_scene(
      seq_file, {"solver.method=moreau", kStep, "solver.end_time=" + std::to_string(kEnd),
                 "model.excitation.sequence.0.scale=0"});
  ni::Recorder from_rest(*fresh.system, 0.0);
  REQUIRE(ni::succeeded(ni::integrate(*fresh.system, fresh.run, from_rest).status));
  const double lost = coordinate_difference(sequence, from_rest, kSwitch, kEnd);
  MESSAGE("B from rest against the sequence: ", lost, " of the peak");
  CHECK(lost > 0.1);
}

TEST_CASE("a sequence under event-driven and compliance carries the state across the switch") {
  const std::string seq_file = sequence_scene(), first_file = first_scene();
  const ni::Recorder moreau = run(seq_file, "moreau", kEnd);
  for (const char* method : {"event_driven", "compliance"}) {
    INFO("method ", std::string(method));
    const ni::Recorder sequence = run(seq_file, method, kEnd);
    const ni::Recorder before = run(first_file, method, kSwitch);
    // Up to t_b the runs take the same steps (the last of `before`, shortened to t_b, aside).
    const std::map<double, std::size_t> seq_rows = rows_by_time(sequence);
    const std::vector<double> peak = peaks(sequence);
    std::size_t common = 0;
    double worst = 0.0;
    for (std::size_t r = 0; r + 1 < before.rows(); ++r) {
      const auto it = seq_rows.find(before.at(r, 0));
      if (it == seq_rows.end()) continue;
      ++common;
      for (std::size_t c = 0; c < 3; ++c) {
        worst = std::max(worst, std::abs(sequence.at(it->second, 1 + c) - before.at(r, 1 + c)) /
                                    peak[c]);
      }
    }
    CHECK(common + 2 >= before.rows());
    CHECK(worst <= kSameSteps);
    // Continuity across the switch: from the last row at or before t_b to the first after.
    std::size_t k = 0;
    while (k + 1 < sequence.rows() && sequence.at(k + 1, 0) <= kSwitch) ++k;
    REQUIRE(k + 1 < sequence.rows());
    const double dt = sequence.at(k + 1, 0) - sequence.at(k, 0);
    for (std::size_t c = 0; c < 3; ++c) {
      const double speed =
          std::max(std::abs(sequence.at(k, 4 + c)), std::abs(sequence.at(k + 1, 4 + c)));
      CHECK(std::abs(sequence.at(k + 1, 1 + c) - sequence.at(k, 1 + c)) <=
            kContinuityMargin * speed * dt + 1e-15);
    }
    // After the switch, event-driven follows Moreau-Jean's sequence within the methods'
    // agreement (see kEventAgreement for compliance).
    const double agreement = coordinate_difference(moreau, sequence, kSwitch, kEnd);
    const double agreement_before = coordinate_difference(moreau, sequence, 0.0, kSwitch);
    MESSAGE(std::string(method), " against Moreau-Jean after the switch: ", agreement,
            " of the peak; before it: ", agreement_before);
    if (std::string(method) == "event_driven") CHECK(agreement <= kEventAgreement);
  }
}
