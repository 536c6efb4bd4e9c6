// Tests of a run's digest and of the trust checks that read it, on a hand-made history whose
// peaks, penetration and event counts are read off the samples below.
#include "runs/digest.hpp"
#include "runs/trust.hpp"
#include "testsupport/systems.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>

namespace nsb::runs {
namespace {

using integrators::EventKind;
using integrators::Recorder;
using integrators::RunResult;
using integrators::Vector;
using TwoCorners = nsb::testsupport::TwoCornerBody;

// Columns t, x, y, theta, vx, vy, omega, gN1, lambdaN1, lambdaT1, gN2, lambdaN2, lambdaT2,
// energy_error. Three samples: contact 2 closes from 1 m to a penetration of 0.1 m at
// t = 0.25 s and is back at 0 m at t = 0.5 s; x reaches -2 at t = 0.25 s; omega is not a
// number at t = 0.5 s.
Recorder history(TwoCorners& s) {
  Recorder rec(s, 0.0);
  auto c = s.make_contact_buffer();
  Vector q(3), u(3), ln(2), lt(2);
  q << 0.5, 0.0, 1e-3;
  u << 1.0, 0.0, 2.0;
  ln << 0.0, 0.0;
  lt << 0.0, 0.0;
  c[0].gap_normal = 0.2;
  c[1].gap_normal = 1.0;
  rec.step(0.0, q, u, c, ln, lt, 0.0);
  q[0] = -2.0;
  c[1].gap_normal = -0.1;
  rec.step(0.25, q, u, c, ln, lt, 0.0);
  q[0] = 1.5;
  q[2] = -3e-3;
  u[2] = NAN;
  c[1].gap_normal = 0.0;
  rec.step(0.5, q, u, c, ln, lt, 0.0);
  rec.event(0.2, 2, EventKind::kImpact);
  rec.event(0.3, 2, EventKind::kSlip);
  rec.event(0.3, 1, EventKind::kStick);
  rec.event(0.4, 0, EventKind::kWarning, "note");
  return rec;
}

}  // namespace

TEST_CASE("the peaks of every column but t: extremes, their times and the larger magnitude") {
  TwoCorners s({});
  const Recorder rec = history(s);
  const Digest d = make_digest(rec, RunResult{});
  REQUIRE(d.peaks.size() == rec.columns().size() - 1);
  const ColumnPeak* x = find_peak(d, "x");
  REQUIRE(x != nullptr);
  CHECK(x->max == 1.5);
  CHECK(x->t_max == 0.5);
  CHECK(x->min == -2.0);
  CHECK(x->t_min == 0.25);
  CHECK(x->abs_max == 2.0);
  CHECK(x->t_abs_max == 0.25);
  // omega: 2, 2, NaN. The NaN sample is skipped; the first sample that reaches a peak counts.
  const ColumnPeak* omega = find_peak(d, "omega");
  REQUIRE(omega != nullptr);
  CHECK(omega->max == 2.0);
  CHECK(omega->t_max == 0.0);
  CHECK(find_peak(d, "t") == nullptr);
  CHECK(find_peak(d, "none") == nullptr);
}

TEST_CASE("each coordinate's peak magnitude and residual, the deepest penetration") {
  TwoCorners s({});
  const Recorder rec = history(s);
  const Digest d = make_digest(rec, RunResult{});
  REQUIRE(d.coordinates.size() == 3);
  CHECK(d.coordinates[0].name == "x");
  CHECK(d.coordinates[0].peak == 2.0);
  CHECK(d.coordinates[0].residual == 1.5);
  CHECK(d.coordinates[1].peak == 0.0);
  CHECK(d.coordinates[2].name == "theta");
  CHECK(d.coordinates[2].peak == 3e-3);
  CHECK(d.coordinates[2].residual == -3e-3);
  // Over the gap columns gN1 (>= 0.2) and gN2 (down to -0.1).
  CHECK(d.max_penetration == 0.1);
}

TEST_CASE("event counts in total and per contact") {
  TwoCorners s({});
  const Recorder rec = history(s);
  const Digest d = make_digest(rec, RunResult{});
  CHECK(d.count(EventKind::kImpact) == 1);
  CHECK(d.count(EventKind::kSlip) == 1);
  CHECK(d.count(EventKind::kStick) == 1);
  CHECK(d.count(EventKind::kWarning) == 1);
  CHECK(d.count(EventKind::kOpen) == 0);
  REQUIRE(d.contact_events.size() == 2);
  CHECK(d.contact_events[0].contact == 1);
  CHECK(d.contact_events[0].counts[3] == 1);  // stick
  CHECK(d.contact_events[1].counts[0] == 1);  // impact
  CHECK(d.contact_events[1].counts[4] == 1);  // slip
}

TEST_CASE("the trust checks read the digest: energy balance and penetration per contact") {
  TwoCorners s({});
  const Recorder rec = history(s);
  RunResult r;
  r.method = "moreau";
  r.energy.error = 0.05;
  r.warnings = {"from the integrator"};
  const Digest d = make_digest(rec, r);
  CHECK(d.warnings == r.warnings);
  CHECK(d.integrator_warnings == 1);
  const auto w = result_warnings(rec, d, r);
  REQUIRE(w.size() == 2);
  CHECK(w[0].rfind("energy_balance: error 5 % of the largest energy term;", 0) == 0);
  // Contact 2: depth 0.1 m of a range of gaps 1.1 m = 9.09 % > 1 %; contact 1 never penetrates.
  CHECK(w[1] ==
        "penetration: contact 2 penetrates 0.1 m at t = 0.25 s, 9.09 % of its range of gaps "
        "1.1 m; the method is trusted up to 1 % (reduce solver.step)");
  // The compliance method's penetration is its contact model's deformation: not checked.
  r.method = "compliance";
  CHECK(result_warnings(rec, d, r).size() == 1);
}

}  // namespace nsb::runs
