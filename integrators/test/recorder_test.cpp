#include "integrators/recorder.hpp"
#include "testsupport/systems.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

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

TEST_CASE("output groups: names, the closest name for a typo, and the default of none") {
  using nsb::integrators::OutputGroup;
  using nsb::integrators::OutputGroups;
  const OutputGroups g = OutputGroups::parse(" forces,bents ,energy");
  CHECK(g.has(OutputGroup::kBents));
  CHECK(g.has(OutputGroup::kForces));
  CHECK_FALSE(g.has(OutputGroup::kGround));
  CHECK(g.names() == "bents,energy,forces");  // the order of kOutputGroupNames
  CHECK(OutputGroups::parse("").empty());
  try {
    OutputGroups::parse("bents,energie");
    FAIL("an unknown group was accepted");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()).find("unknown output group 'energie'; did you mean `energy`?") !=
          std::string::npos);
  }
}

TEST_CASE("the groups energy and forces: regrouped balance, forces without the percussion") {
  using nsb::integrators::OutputGroup;
  auto p = point();
  nsb::integrators::OutputGroups groups;
  groups.add(OutputGroup::kEnergy);
  groups.add(OutputGroup::kForces);
  groups.add(OutputGroup::kImpulses);
  nsb::integrators::Recorder rec(p, 0.0, groups);
  CHECK(rec.columns() ==
        std::vector<std::string>{"t", "y", "vy", "gN1", "lambdaN1", "lambdaT1", "energy_error",
                                 "energy_kinetic", "energy_elastic", "energy_hysteretic",
                                 "energy_damping", "energy_contact", "energy_input", "fN1", "fT1",
                                 "fsmooth_y", "fcontact_y"});
  // A balance by hand: 3 + 2 = (10 + 1 + 4) - 5 - 1 + (-4) + 0  -> 5 = 5.
  nsb::integrators::EnergyBalance e;
  e.kinetic = 3.0;
  e.stored = 2.0;
  e.initial = 10.0;
  e.external = 1.0;
  e.ground = 4.0;
  e.damping = 5.0;
  e.hysteretic = 1.0;
  e.impacts = -4.0;
  e.close();
  REQUIRE(e.error == 0.0);
  Vector f(1);
  f[0] = -7.0;
  rec.watch(&e, &f);
  auto c = p.make_contact_buffer();
  Vector q = Vector::Zero(1), u = Vector::Zero(1), ln(1), lt = Vector::Zero(1);
  p.contact_data(0.0, q, u, c);
  ln[0] = 2.5;
  rec.step(0.0, q, u, c, ln, lt, e.error);
  // An impact at t = 0.1: that step's lambda holds the percussion, fN is 0 there.
  rec.impact(0.1, 1, 0.25, 0.0);
  ln[0] = 2.5e3;
  rec.step(0.1, q, u, c, ln, lt, e.error);
  REQUIRE(rec.rows() == 2);
  // kinetic + elastic + hysteretic + damping + contact - input = 3 + 2 + 1 + 5 + 4 - 15 = 0.
  double sum = 0.0;
  for (const char* n : {"energy_kinetic", "energy_elastic", "energy_hysteretic",
                        "energy_damping", "energy_contact"}) {
    sum += rec.series(n)[0];
  }
  CHECK(rec.series("energy_contact")[0] == 4.0);
  CHECK(rec.series("energy_input")[0] == 15.0);
  CHECK(sum - rec.series("energy_input")[0] == 0.0);
  // The ball's W_N = 1: the generalized contact force is fN.
  CHECK(rec.series("fN1") == std::vector<double>{2.5, 0.0});
  CHECK(rec.series("fcontact_y") == std::vector<double>{2.5, 0.0});
  CHECK(rec.series("fsmooth_y") == std::vector<double>{-7.0, -7.0});
  CHECK(rec.mass().rows() == 1);
  REQUIRE(rec.events().size() == 1);
  CHECK(rec.events()[0].impulse_normal == 0.25);
  // The peaks cover the group columns: fN1's largest is 2.5, not the percussion's 2.5e3.
  CHECK(rec.extremes()[rec.column("fN1") - 1].max == 2.5);
}

TEST_CASE("without the group impulses an impact keeps no impulse; no group adds no column") {
  auto p = point();
  nsb::integrators::Recorder rec(p, 0.0);
  rec.impact(0.1, 1, 0.25, 0.1);
  REQUIRE(rec.events().size() == 1);
  CHECK(rec.events()[0].kind == nsb::integrators::EventKind::kImpact);
  CHECK(std::isnan(rec.events()[0].impulse_normal));
  CHECK(rec.columns().size() == 7);
  CHECK(rec.mass().size() == 0);
}
