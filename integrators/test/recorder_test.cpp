#include "integrators/recorder.hpp"
#include "testsupport/systems.hpp"

#include <doctest/doctest.h>

namespace {

using nsb::integrators::ContactData;
using nsb::integrators::Vector;

// A one-DOF, one-contact system whose only job is to give the recorder its names: y, vy and
// the gap g_N = y.
nsb::testsupport::Ball point() {
  return nsb::testsupport::Ball({.gravity = 0.0, .initial_height = 0.0});
}

}  // namespace

TEST_CASE("recorder names its columns after the system and samples at sample_dt") {
  auto p = point();
  nsb::integrators::Recorder rec(p, 0.1);
  CHECK(rec.columns() ==
        std::vector<std::string>{"t", "y", "vy", "gN1", "lambdaN1", "lambdaT1", "energy_error"});
  auto c = p.make_contact_buffer();
  Vector q(1), u(1), ln = Vector::Zero(1), lt = Vector::Zero(1);
  // Steps of 0.03 s from 0 to 0.3 s: samples due at 0, 0.1, 0.2, 0.3 are taken at the first
  // step at or after each, i.e. t = 0, 0.12, 0.21, 0.30.
  for (int k = 0; k <= 10; ++k) {
    const double t = 0.03 * k;
    q[0] = t;
    u[0] = 1.0;
    p.contact_data(t, q, u, c);
    rec.sample(t, q, u, c, ln, lt, 0.0);
  }
  REQUIRE(rec.rows() == 4);
  CHECK(rec.at(1, 0) == doctest::Approx(0.12));
  CHECK(rec.at(2, 0) == doctest::Approx(0.21));
  CHECK(rec.at(3, 0) == doctest::Approx(0.30));
  CHECK(rec.series("gN1")[1] == doctest::Approx(0.12));
  CHECK_THROWS_AS(rec.column("nope"), std::out_of_range);
}

TEST_CASE("energy balance error is relative to the largest term") {
  nsb::integrators::EnergyBalance e;
  e.initial = 100.0;
  e.kinetic = 60.0;
  e.damping = 30.0;  // 60 = 100 - 30 - 10 + error: lhs - rhs = 60 - 60 = 0 with impacts -10
  e.impacts = -10.0;
  e.close();
  CHECK(e.error == doctest::Approx(0.0));
  e.kinetic = 61.0;
  e.close();
  CHECK(e.error == doctest::Approx(1.0 / 100.0));
}

TEST_CASE("a negative sample interval is a caller's mistake") {
  auto p = point();
  CHECK_THROWS_AS(nsb::integrators::Recorder(p, -1.0), std::invalid_argument);
}

TEST_CASE("a run's status follows the severity of what it met") {
  using nsb::integrators::RunResult;
  using nsb::integrators::RunStatus;
  RunResult r;
  nsb::integrators::finish_status(r, false, false);
  CHECK(r.status == RunStatus::kCompleted);
  r.lcp_fallbacks = 3;
  nsb::integrators::finish_status(r, false, false);
  CHECK(r.status == RunStatus::kCompletedWithFallbacks);
  CHECK(nsb::integrators::succeeded(r.status));
  r.lcp_unsolved = 1;
  nsb::integrators::finish_status(r, false, false);
  CHECK(r.status == RunStatus::kContactUnsolved);
  nsb::integrators::finish_status(r, false, true);
  CHECK(r.status == RunStatus::kStalled);
  nsb::integrators::finish_status(r, true, true);
  CHECK(r.status == RunStatus::kDiverged);
}
