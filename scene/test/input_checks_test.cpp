// The checks of a scene's values beyond each key's range (scene/scene_reader.hpp,
// scene/scene_builders.hpp): the hint of an unknown key, subnormal numbers, the work a run
// may take, values off by a unit factor and values derived from several keys, each refused
// at the key responsible with the inputs that conflict.
#include "scene/scene.hpp"
#include "scene/test/scene_files.hpp"

#include <doctest/doctest.h>

#include <sys/stat.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using nsb::scene::test_files::error_of;
using nsb::scene::test_files::scratch_dir;

namespace {

bool contains(const std::string& s, const std::string& part) {
  const bool ok = s.find(part) != std::string::npos;
  if (!ok) MESSAGE("'" << s << "' does not contain '" << part << "'");
  return ok;
}

// The error of loading the shipped scene `name` with overrides ("" when it loads).
std::string shipped_error(const std::string& name, const std::vector<std::string>& overrides) {
  try {
    nsb::scene::load_scene(fs::path(NSB_SCENES_DIR) / name, overrides);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

const std::string kBall = R"([model]
kind = "bouncing_ball"
mass = 1.0
height = 1.0
restitution = 0.9
)";

const std::string kDeck = R"([model]
kind = "rigid_deck"
mass = 140.5
inertia = 13090.0
length = 33.35
width = 2.44
)";

}  // namespace

TEST_CASE("an unknown key gets the closest spelling, or the tables that declare it") {
  CHECK(contains(error_of("typo.toml", kBall + "[solver]\nstepp = 1e-5\n"),
                 "typo.toml:7:9: solver.stepp: unknown key; did you mean `step`?"));
  CHECK(contains(error_of("mas.toml", kDeck + "mas = 1.0\n"),
                 "model.mas: unknown key; did you mean `mass`?"));
  // pile_stiffness is a key of [model.abutments], not of [model.seats].
  const std::string e = shipped_error("bridge-exc7.toml", {"model.seats.pile_stiffness=1"});
  CHECK(contains(e, "model.seats.pile_stiffness (override): unknown key; did you mean "
                    "`[model.abutments]`? (pile_stiffness is a key there)"));
  // seat_length in [model.seats] is refused with the tables that hold it.
  const std::string s = shipped_error("bridge-exc7.toml", {"model.seats.seat_length=0.3"});
  CHECK(contains(s, "model.seats.seat_length (override): the abutments' seat length is a key "
                    "of [model.abutments] (seat_length), a hinge's of its [[model.hinges]] "
                    "element"));
  // A key no table declares gets no hint.
  CHECK(contains(error_of("none.toml", kBall + "zzzzzz = 1\n"),
                 "model.zzzzzz: unknown key; allowed here"));
}

TEST_CASE("a subnormal number is refused at its key although it lies in the range") {
  CHECK(contains(error_of("sub.toml", kDeck, {"model.mass=4.9e-324"}),
                 "sub.toml: model.mass (override): is subnormal (5e-324;"));
  CHECK(contains(error_of("sub2.toml", kBall + "[output]\nsample_dt = 1e-310\n"),
                 "sub2.toml:7:13: output.sample_dt: is subnormal"));
  // 0 and the smallest normal double are numbers.
  CHECK(error_of("norm.toml", kBall + "[solver]\nend_time = 0.01\n[output]\nsample_dt = 0.0\n")
            .empty());
}

TEST_CASE("the work of a run is bounded before it starts, at the key that makes it too large") {
  // Moreau–Jean: 1 s in steps of 1e-9 s is 1e9 steps > kMaxSteps = 1e8.
  CHECK(contains(error_of("steps.toml", kBall + "[solver]\nend_time = 1.0\nstep = 1e-9\n"),
                 "steps.toml:8:8: solver.step: end_time 1 s with step 1e-09 s takes at least "
                 "1e+09 steps, more than the 1e+08 a run may take"));
  // Rows: 1 s sampled every 1e-8 s is 1e8 + 1 rows > kMaxRows = 1e7.
  CHECK(contains(error_of("rows.toml",
                          kBall + "[solver]\nmethod = \"event_driven\"\n[output]\nsample_dt = 1e-8\n"),
                 "rows.toml:9:13: output.sample_dt: end_time 1 s with output.sample_dt 1e-08 s "
                 "gives 1e+08 history rows"));
  // An end_time beyond any run (1e6 s) names end_time, whatever the step; beyond 1e100 it is
  // refused as a number.
  CHECK(contains(error_of("end.toml", kBall + "[solver]\nmethod = \"event_driven\"\n"
                                              "end_time = 1e99\n[output]\nsample_dt = 0.01\n"),
                 "end.toml:8:12: solver.end_time: end_time 1e+99 s with output.sample_dt 0.01 s "
                 "gives 1e+101 history rows"));
  CHECK(contains(error_of("cend.toml", kBall + "[solver]\nmethod = \"compliance\"\n"
                                               "end_time = 1e99\n"),
                 "cend.toml:8:12: solver.end_time: end_time 1e+99 s with max_step 0.001 s takes "
                 "at least 1e+102 steps"));
  CHECK(contains(error_of("huge.toml", kBall + "[solver]\nend_time = 1e308\n"),
                 "huge.toml:7:12: solver.end_time: must be at most 1e+100 in magnitude"));
  // Every step a row: Moreau–Jean with sample_dt = 0 and 2e7 steps.
  CHECK(contains(error_of("row2.toml", kBall + "[solver]\nend_time = 2.0\nstep = 1e-7\n"),
                 "solver.step: end_time 2 s with step 1e-07 s and output.sample_dt = 0 (a row per "
                 "step) gives 2e+07 history rows"));
}

TEST_CASE("a deck mass or inertia off by a unit factor is refused with the likely unit") {
  // 140.5 t typed in kg: 140500 / (33.35 x 2.44 = 81.374) = 1726.60 t/m^2 > 100 t/m^2.
  CHECK(contains(error_of("kg.toml", kDeck, {"model.mass=140500"}),
                 "model.mass (override): mass 140500 t over a plan of 33.35 m x 2.44 m is 1726.6 "
                 "t/m^2; expected 1e-06 to 100 t/m^2 (a concrete deck weighs 1 to 2 t/m^2); a "
                 "mass in kg? 140500 kg is 140.5 t"));
  // 13090 t m^2 in kg m^2: 1.309e7 / (140.5 (33.35^2 + 2.44^2) / 12 = 13092.0) = 999.85.
  CHECK(contains(error_of("kgm2.toml", kDeck, {"model.inertia=1.309e7"}),
                 "model.inertia (override): inertia 1.309e+07 t m^2 is 999.849 times that of the "
                 "mass 140.5 t"));
  CHECK(contains(error_of("kgm2.toml", kDeck, {"model.inertia=1.309e7"}),
                 "an inertia in kg m^2? 1.309e+07 kg m^2 is 13090 t m^2"));
  // The one-deck bridge's [model.deck] and a bridge segment are checked alike.
  CHECK(contains(shipped_error("bridge-exc7.toml", {"model.deck.mass=1e-300"}),
                 "model.deck.mass (override): mass 1e-300 t over a plan"));
  CHECK(contains(shipped_error("bridge-two-frame.toml", {"model.segments.1.mass=70250"}),
                 "model.segments[1].mass (override)"));
}

TEST_CASE("a bent whose derived spring is not finite is refused at the design key") {
  // k = 12 n E I_eff / H^3 = 1.5e5 / H^3 kN/m (n = 2, E = 3e7 kPa, I_eff = 0.5 pi d^4 / 64,
  // d = 0.305 m) is 1.5e305 for H = 1e-100 m, beyond the 1e100 of a scene number; with
  // d = 1e99 m, d^4 = 1e396 overflows.
  const std::string h = shipped_error("bridge-exc7.toml", {"model.bents.0.height=1e-100"});
  CHECK(contains(h, "model.bents[0].height (override): the column design (height = 1e-100 m"));
  CHECK(contains(h, "longitudinal stiffness k = 1.5"));
  CHECK(contains(h, "e+305 kN/m"));
  CHECK(h.find("takeda::") == std::string::npos);
  const std::string d = shipped_error("bridge-exc7.toml", {"model.bents.1.column_diameter=1e99"});
  CHECK(contains(d, "model.bents[1].column_diameter (override): the column design"));
  // A value beyond a double is said so, not printed as inf.
  CHECK(contains(d, "stiffness k = beyond the range of a double"));
  CHECK(d.find("inf") == std::string::npos);
  CHECK(contains(d, "expected positive numbers within 1e-100 ... 1e+100"));
}

TEST_CASE("a seat shorter than its gap is refused at the seat, with the gap and its unit") {
  // bridge-unseating's abutment seats are 0.02 m; a gap of 10 (mm typed as m) exceeds them.
  const std::string e = shipped_error("bridge-unseating.toml", {"model.gaps.left=10"});
  CHECK(contains(e, "bridge-unseating.toml:"));
  CHECK(contains(e, ": model.abutments.seat_length: seat_length "));
  CHECK(contains(e, "is shorter than the left joint's opening at t0 (overlap -9.98 m), set by "
                    "[model.gaps] left = 10 m"));
  CHECK(contains(e, "a gap in mm? 10 mm is 0.01 m"));
}

TEST_CASE("a scene that is not a regular file is named so, not read") {
  const fs::path fifo = scratch_dir() / "scene.fifo";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  try {
    nsb::scene::load_scene(fifo, {});
    FAIL("a FIFO was read");
  } catch (const std::invalid_argument& e) {
    CHECK(contains(e.what(), "scene.fifo: cannot open scene file (not a regular file)"));
  }
  try {
    nsb::scene::load_scene(scratch_dir(), {});
    FAIL("a directory was read");
  } catch (const std::invalid_argument& e) {
    CHECK(contains(e.what(), "cannot open scene file (not a regular file)"));
  }
}
