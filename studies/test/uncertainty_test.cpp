// The uncertainty study's pure logic: shares with their binomial standard error, flips against
// the base point, the overrides of a point, and the claims from hand-made numbers. Expected
// values are worked out by hand beside each case.
#include "studies/uncertainty.hpp"
#include "io/csv.hpp"
#include "scene/cosmos.hpp"
#include "scene/records.hpp"
#include "scene/scene.hpp"
#include "studies/uncertainty_steps.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

using nsb::paper_figures::Peaks;
using nsb::studies::assumptions;
using nsb::studies::claim_runs;
using nsb::studies::find_flips;
using nsb::studies::Flip;
using nsb::studies::nominal_point;
using nsb::studies::OatPoint;
using nsb::studies::point_overrides;
using nsb::studies::SceneTargets;
using nsb::studies::share_of;
using nsb::studies::Verdict;

namespace {
// Shares are ratios of small integers and one square root: round-off only.
constexpr double kTight = 1e-15;
constexpr Verdict H = Verdict::kHolds, F = Verdict::kFails, N = Verdict::kNotEvaluated;

bool has(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

SceneTargets targets() {
  SceneTargets t;
  t.transverse_pga = {{1, 0.17}, {3, 0.5}, {5, 0.83}, {7, 1.0}};
  t.longitudinal_pga = {{1, 0.2}, {3, 0.6}, {5, 1.0}, {7, 1.2}};
  t.longitudinal_record = "ground-motions/x.AT2";
  t.longitudinal_record_pga = 0.25;
  t.rotation_record = "/work/seat-rotation-x.txt";
  return t;
}
}  // namespace

TEST_CASE("share and binomial standard error, by hand") {
  // 3 of 4 hold: p = 0.75, se = sqrt(0.75 * 0.25 / 4) = sqrt(0.046875) = 0.21650635...
  auto s = share_of({H, H, F, H});
  CHECK(s.evaluated == 4);
  CHECK(s.holds == 3);
  CHECK(s.not_evaluated == 0);
  CHECK(s.share == doctest::Approx(0.75).epsilon(kTight));
  CHECK(s.standard_error == doctest::Approx(std::sqrt(0.046875)).epsilon(kTight));

  // Samples that were not evaluated count in neither: 1 of 2 holds, p = 0.5,
  // se = sqrt(0.25 / 2) = 0.35355339...
  s = share_of({N, H, N, F});
  CHECK(s.evaluated == 2);
  CHECK(s.not_evaluated == 2);
  CHECK(s.share == doctest::Approx(0.5).epsilon(kTight));
  CHECK(s.standard_error == doctest::Approx(std::sqrt(0.125)).epsilon(kTight));

  // All hold: p = 1, se = 0 (the binomial error vanishes at the ends).
  s = share_of({H, H, H});
  CHECK(s.share == 1.0);
  CHECK(s.standard_error == 0.0);

  // Nothing evaluated: no share.
  s = share_of({N});
  CHECK(std::isnan(s.share));
  CHECK(std::isnan(s.standard_error));
  CHECK(std::isnan(share_of({}).share));
}

TEST_CASE("flips: the verdicts that differ from the base point's") {
  std::vector<OatPoint> pts{
      {"gap", "low", 0.006, {{"C1", H}, {"C3", F}}},   // C1 as nominal, C3 as nominal
      {"", "", 0.0, {{"C1", H}, {"C3", F}}},           // the base point
      {"gap", "high", 0.019, {{"C1", F}, {"C3", F}}},  // C1 flips
      {"mu", "low", 0.3, {{"C1", N}, {"C3", H}}},      // C1 not evaluated: no flip; C3 flips
  };
  const std::vector<Flip> f = find_flips(pts);
  REQUIRE(f.size() == 2);
  CHECK(f[0].assumption == "gap");
  CHECK(f[0].end == "high");
  CHECK(f[0].value == 0.019);
  CHECK(f[0].claim == "C1");
  CHECK(f[0].nominal == H);
  CHECK(f[0].flipped == F);
  CHECK(f[1].assumption == "mu");
  CHECK(f[1].claim == "C3");
  CHECK(f[1].flipped == H);

  // A base point whose verdict is missing flips nothing.
  pts[1].verdicts["C1"] = N;
  CHECK(find_flips(pts).size() == 1);

  // Exactly one base point.
  CHECK_THROWS_AS(find_flips({pts[0]}), std::invalid_argument);
  CHECK_THROWS_AS(find_flips({pts[1], pts[1]}), std::invalid_argument);
}

TEST_CASE("every assumption has a range about its nominal value and a reason") {
  for (const auto& a : assumptions()) {
    CAPTURE(a.key);
    CHECK(a.low < a.high);
    CHECK(a.nominal >= a.low);
    CHECK(a.nominal <= a.high);
    CHECK(!a.reason.empty());
    CHECK(!a.unit.empty());
  }
}

TEST_CASE("the nominal point gives the scenes' own values") {
  const auto o = point_overrides(nominal_point(), claim_runs()[0], targets());  // exc1
  CHECK(has(o, "model.excitation.target_pga=0.17"));
  CHECK(has(o, "model.excitation.longitudinal_pga=0.2"));  // 0.2 * (1.2 / 1.2)
  CHECK(has(o, "model.deck.width=2.44"));
  CHECK(has(o, "model.bents.0.height=1.83"));
  CHECK(has(o, "model.gaps.left=0.0127"));
  CHECK(has(o, "model.seats.friction=0.5"));
  CHECK(has(o, "model.damping.ratio_j=0.08"));
  CHECK(has(o, "model.excitation.time_scale=1"));
  for (const auto& s : o) CHECK(s.find("rotation") == std::string::npos);  // c = 0: no record
}

TEST_CASE("a point's overrides: no pounding, mu = 0, the ratio and the seat rotation") {
  auto v = nominal_point();
  const auto& as = assumptions();
  for (std::size_t k = 0; k < as.size(); ++k) {
    if (as[k].key == "longitudinal_ratio") v[k] = 1.5;
    if (as[k].key == "seat_rotation") v[k] = 0.05;
    if (as[k].key == "deck_width") v[k] = 2.5;
  }
  for (const auto& r : claim_runs()) {
    if (r.name != "exc5-no-pounding" && r.name != "exc5-mu0") continue;
    const auto o = point_overrides(v, r, targets());
    // Longitudinal target 1.0 g * 1.5 / 1.2 = 1.25 g.
    CHECK(has(o, "model.excitation.longitudinal_pga=1.25"));
    // Rotation scale c / W * (1.25 / 0.25) = 0.05 / 2.5 * 5 = 0.1.
    const auto it = std::find_if(o.begin(), o.end(), [](const std::string& s) {
      return s.rfind("model.seats.rotation_scale=", 0) == 0;
    });
    REQUIRE(it != o.end());
    CHECK(std::stod(it->substr(it->find('=') + 1)) == doctest::Approx(0.1).epsilon(1e-14));
    CHECK(has(o, "model.seats.rotation_record_left=/work/seat-rotation-x.txt"));
    if (r.name == "exc5-no-pounding") {
      CHECK(has(o, "model.gaps.left=1"));
      CHECK(has(o, "model.seats.friction=0.5"));
    } else {
      CHECK(has(o, "model.gaps.left=0.0127"));
      CHECK(has(o, "model.seats.friction=0"));
    }
  }
  CHECK_THROWS_AS(point_overrides({1.0}, claim_runs()[0], targets()), std::invalid_argument);
  SceneTargets none;
  CHECK_THROWS_AS(point_overrides(nominal_point(), claim_runs()[0], none), std::invalid_argument);
  // A seat rotation without the rotation record is refused, not given the .AT2 record.
  SceneTargets no_record = targets();
  no_record.rotation_record.clear();
  CHECK_THROWS_AS(point_overrides(v, claim_runs()[0], no_record), std::invalid_argument);
}

// The seat-rotation record the study writes: the longitudinal record's samples in m/s^2 (its
// .AT2 values in g times 9.80665), which a scene accepts as a rotation record in rad/s^2; the
// .AT2 file itself it refuses (a rotation record is never read in g). The base scene with a
// seat rotation at c = 0.05 loads with it.
TEST_CASE("the seat-rotation record: the record in m/s^2 as rad/s^2, and a scene takes it") {
  const std::filesystem::path scenes = NSB_SCENES_DIR;
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "nsb-uncertainty-rotation-test";
  std::filesystem::remove_all(dir);
  const SceneTargets t = scene_targets(scenes, claim_runs());
  const std::filesystem::path file = write_rotation_record(t, dir);
  const nsb::models::Record at2 = nsb::scene::read_at2(
      scenes / ".." / "data" / t.longitudinal_record, nsb::scene::kStandardGravity);
  const nsb::models::Record text = nsb::scene::read_two_column(file);
  REQUIRE(text.t.size() == at2.t.size());
  for (std::size_t i = 0; i < at2.t.size(); ++i) {
    CHECK(text.t[i] == at2.t[i]);  // 17 digits: the doubles round-trip
    CHECK(text.a[i] == at2.a[i]);
  }
  SceneTargets with_record = t;
  with_record.rotation_record = file;
  auto v = nominal_point();
  const auto& as = assumptions();
  for (std::size_t k = 0; k < as.size(); ++k) {
    if (as[k].key == "seat_rotation") v[k] = 0.05;
  }
  const auto o = point_overrides(v, claim_runs()[0], with_record);
  CHECK_NOTHROW(nsb::scene::load_scene(scenes / "bridge-exc7.toml", o));
  std::vector<std::string> at2_record = o;
  for (auto& s : at2_record) {
    if (s.rfind("model.seats.rotation_record_", 0) == 0) {
      s = s.substr(0, s.find('=') + 1) + t.longitudinal_record;
    }
  }
  CHECK_THROWS_AS(nsb::scene::load_scene(scenes / "bridge-exc7.toml", at2_record),
                  std::invalid_argument);
  std::filesystem::remove_all(dir);
}

TEST_CASE("C4's runs: excitation 5 under the compliance method, both laws, the study's tolerance") {
  std::size_t compliance_runs = 0;
  for (const auto& r : claim_runs()) {
    if (r.factor == 0) continue;
    ++compliance_runs;
    CAPTURE(r.name);
    CHECK(r.excitation == 5);
    const auto o = point_overrides(nominal_point(), r, targets());
    CHECK(has(o, "model.excitation.target_pga=0.83"));
    CHECK(has(o, "solver.method=compliance"));
    const double tol = nsb::studies::uncertainty::kStudyComplianceTolerance;
    CHECK(has(o, "solver.tolerance=" + nsb::io::csv_number(tol)));
    if (r.name == "exc5-k100") {
      CHECK(has(o, "solver.stiffness_factor=100"));
      CHECK(has(o, "solver.damping_law=hertzdamp"));
    }
    if (r.name == "exc5-k0.0001-hunt_crossley_exact") {
      CHECK(has(o, "solver.stiffness_factor=0.0001"));
      CHECK(has(o, "solver.damping_law=hunt_crossley_exact"));
    }
  }
  CHECK(compliance_runs == 8);  // 4 factors x 2 laws
  for (const auto& r : claim_runs()) {
    if (r.factor > 0) continue;
    for (const auto& s : point_overrides(nominal_point(), r, targets())) {
      CHECK(s.rfind("solver.", 0) == std::string::npos);  // the scene's own method
    }
  }
}

TEST_CASE("claims C1-C3 from hand-made peaks") {
  // Runs 5 and 7 with mu = 0: ratios 0.4 / 1 = 0.4 and 1 / 4 = 0.25, both < 0.5: C1 holds.
  std::vector<Peaks> p(4);
  const int runs[4] = {1, 3, 5, 7};
  // theta = PGA^2 exactly: the fitted exponent is 2 (C2 holds).
  const double pga[4] = {0.5, 1.0, 1.5, 2.0};
  for (int i = 0; i < 4; ++i) {
    p[i].run = runs[i];
    p[i].pga_y = pga[i];
    p[i].pounding = pga[i] * pga[i];
    p[i].free = 0.4 * p[i].pounding;  // ratio 0.4 everywhere: C3's first check holds
    p[i].impacts = i == 0 ? 0 : 3;    // run 1 does not pound: it is not compared
  }
  p[2].mu0 = 0.4 * p[2].pounding;
  p[3].mu0 = 0.25 * p[3].pounding;
  const auto c1 = nsb::paper_figures::claim_c1(p);
  CHECK(c1.holds());
  CHECK(c1.checks.size() == 2);
  const auto c2 = nsb::paper_figures::claim_c2(p);
  CHECK(c2.checks[0].value == doctest::Approx(2.0).epsilon(1e-12));
  CHECK(c2.holds());
  auto c3 = nsb::paper_figures::claim_c3(p);
  CHECK(c3.checks[0].value == doctest::Approx(0.4).epsilon(1e-15));
  CHECK(c3.holds());
  // An impact without pounding (gaps of 1 m) fails C3; a larger ratio in run 1, which does not
  // pound, does not.
  p[1].impacts_free = 1;
  p[0].free = 10 * p[0].pounding;
  c3 = nsb::paper_figures::claim_c3(p);
  CHECK(c3.checks[0].value == doctest::Approx(0.4).epsilon(1e-15));
  CHECK_FALSE(c3.holds());
  CHECK(nsb::studies::verdict_of(c3) == F);
  c3.failure = "exc3: diverged";
  CHECK(nsb::studies::verdict_of(c3) == N);
}

TEST_CASE("C6: sliding contacts from events and Coulomb's law over them") {
  using nsb::integrators::Event;
  using nsb::integrators::EventKind;
  // Contact 3 slides 1.0-1.2 s (then sticks), contact 4 from 2.0 s to the end (3.0 s).
  const std::vector<Event> ev{{0.5, 3, EventKind::kImpact, ""},
                              {1.0, 3, EventKind::kSlip, ""},
                              {1.2, 3, EventKind::kStick, ""},
                              {2.0, 4, EventKind::kSlip, ""}};
  const auto s = nsb::paper_figures::sliding_contacts(ev, 3.0);
  REQUIRE(s.size() == 2);
  const auto l = nsb::paper_figures::longest_sliding(s);
  CHECK(l.contact == 4);
  CHECK(l.start == 2.0);
  CHECK(l.end == 3.0);
  // mu = 0.5: lambda_T = -50 for lambda_N = 100 is exact; -50.1 deviates by 0.1 / 50 = 2e-3.
  const std::vector<double> t{1.9, 2.0, 2.5, 3.0}, ln{100, 100, 100, 100}, lt{-10, -50, -50.1, -50};
  const auto st = nsb::paper_figures::measure_sliding(l, 0.5, t, ln, lt);
  CHECK(st.samples == 2);  // 2.0 and 2.5; 3.0 is the end, outside [start, end)
  CHECK(st.max_deviation == doctest::Approx(2e-3).epsilon(1e-12));
  CHECK_FALSE(nsb::paper_figures::claim_c6(st, 0.5).holds());
  // No sample in the slide: the claim does not hold (nothing shown).
  const auto none = nsb::paper_figures::measure_sliding(l, 0.5, {0.1}, {1.0}, {0.5});
  CHECK(none.samples == 0);
  CHECK_FALSE(nsb::paper_figures::claim_c6(none, 0.5).holds());
}
