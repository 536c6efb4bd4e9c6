// The limit states an assembled bridge watches (models/limit_watch.hpp, docs/limit-states.md),
// fed accepted steps by hand: a straight benchmark deck moved by x opens its left joint by x
// and closes its right one by x, so every overlap, gap, drift ratio and residual rotation
// below is a hand value.
#include "models/assembly.hpp"

#include "models/bridge_parts.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

namespace {

using nsb::models::Assembly;
using nsb::models::BridgeDesign;
namespace ni = nsb::integrators;

constexpr double kGap = 0.0127;  // the benchmark's joints at rest [m]
constexpr double kTol = 1e-12;   // sums of a few lengths of O(0.1 m)

Assembly bridge(const nsb::models::BridgeLimits& limits) {
  Assembly::Parts p = nsb::models::bridge_parts(BridgeDesign::benchmark());
  p.limits = nsb::models::bridge_limit_spec(limits, 1);
  return Assembly(std::move(p));
}

std::map<std::string, ni::LimitStateValue> by_name(const Assembly& a) {
  std::map<std::string, ni::LimitStateValue> out;
  for (const auto& v : a.limit_states()) out[v.name] = v;
  return out;
}

// Accepts a step ending at t in state q = (x, y, theta) at rest velocity.
ni::StepVerdict step(Assembly& a, double t, double x, double y, double theta,
                     const ni::Vector* impulse = nullptr) {
  const ni::Vector q = ni::Vector{{x, y, theta}}, u = ni::Vector::Zero(3);
  return a.accept_step({.t = t, .h = 1e-3, .q = &q, .u = &u, .normal_impulse = impulse});
}

}  // namespace

TEST_CASE("unseating: overlap = seat_length - opening; a lost seat stops the run once") {
  nsb::models::BridgeLimits l;
  l.abutment_seat = 0.1;
  Assembly a = bridge(l);
  CHECK(step(a, 0.5, 0.05, 0.0, 0.0) == ni::StepVerdict::kContinue);
  auto v = by_name(a);
  REQUIRE(v.count("unseating_left") == 1);
  CHECK(!v["unseating_left"].exceeded);
  CHECK(std::isnan(v["unseating_left"].time));
  CHECK(v["unseating_left"].margin == doctest::Approx(0.1 - kGap - 0.05).epsilon(kTol));
  CHECK(v["unseating_left"].unit == "m");
  // The left end moves 0.09 m away from its backwall: 0.1027 m > 0.1 m of seat.
  CHECK(step(a, 0.6, 0.09, 0.0, 0.0) == ni::StepVerdict::kUnseated);
  v = by_name(a);
  CHECK(v["unseating_left"].exceeded);
  CHECK(v["unseating_left"].time == 0.6);
  CHECK(v["unseating_left"].margin == doctest::Approx(0.1 - kGap - 0.09).epsilon(kTol));
  CHECK(!v["unseating_right"].exceeded);
  // The first time stays; a later step does not report the same loss again.
  CHECK(step(a, 0.7, 0.095, 0.0, 0.0) == ni::StepVerdict::kContinue);
  CHECK(by_name(a)["unseating_left"].time == 0.6);
}

TEST_CASE("unseating: without seat_length only closure is watched") {
  Assembly a = bridge({});
  CHECK(step(a, 0.5, 1.0, 0.0, 0.0) == ni::StepVerdict::kContinue);
  const auto v = by_name(a);
  CHECK(v.count("unseating_left") == 0);
  CHECK(v.count("closure_left") == 1);
  CHECK(v.count("closure_right") == 1);
  CHECK(v.count("residual_rotation") == 0);
  CHECK(v.count("drift_bent_1") == 0);
}

TEST_CASE("closure: the first step with a gap <= 0 or a contact impulse") {
  Assembly a = bridge({});
  CHECK(by_name(a)["closure_right"].margin == doctest::Approx(kGap).epsilon(kTol));
  step(a, 0.2, 0.005, 0.0, 0.0);
  CHECK(!by_name(a)["closure_right"].exceeded);
  step(a, 0.3, kGap + 1e-4, 0.0, 0.0);
  auto v = by_name(a);
  CHECK(v["closure_right"].exceeded);
  CHECK(v["closure_right"].time == 0.3);
  CHECK(v["closure_right"].margin == doctest::Approx(-1e-4).epsilon(1e-9));
  CHECK(!v["closure_left"].exceeded);
  // A contact that carried an impulse closed its joint even at a gap of round-off size.
  ni::Vector impulse = ni::Vector::Zero(4);
  impulse(0) = 1e-3;  // contact 1: corner 0 on the left seat
  step(a, 0.4, 0.0, 0.0, 0.0, &impulse);
  CHECK(by_name(a)["closure_left"].exceeded);
  CHECK(by_name(a)["closure_left"].time == 0.4);
}

TEST_CASE("closure: contact normals at the watched state are the ones evaluated afresh") {
  Assembly watched = bridge({});
  Assembly plain(nsb::models::bridge_parts(BridgeDesign::benchmark()));
  const ni::Vector q{{0.004, -0.002, 1e-3}}, u{{0.1, -0.2, 0.03}};
  const ni::Vector other{{0.008, -0.004, 2e-3}};
  watched.accept_step({.t = 0.25, .h = 1e-3, .q = &q, .u = &u});
  auto a = watched.make_contact_buffer(), b = plain.make_contact_buffer();
  for (const ni::Vector* at : {&q, &other}) {  // the watched state, then another
    watched.contact_normals(0.25, *at, u, a);
    plain.contact_normals(0.25, *at, u, b);
    for (std::size_t i = 0; i < a.size(); ++i) {
      CHECK(a[i].gap_normal == b[i].gap_normal);
      CHECK(a[i].w_normal == b[i].w_normal);
      CHECK(a[i].what_normal == b[i].what_normal);
      CHECK(a[i].far == b[i].far);
    }
  }
}

TEST_CASE("drift: |(dx, dy + s theta)| / H against drift_ratio, margin = limit - peak") {
  const BridgeDesign bp = BridgeDesign::benchmark();
  nsb::models::BridgeLimits l;
  l.bent_heights = {1.83, 2.44, 1.52};
  l.drift_ratio = 0.01;
  Assembly a = bridge(l);
  // dx = 0.01, dy = 0.011 + s theta: bent 3 (H = 1.52 m, s = L/4) drifts most.
  const double theta = 1e-4;
  step(a, 1.0, 0.01, 0.011, theta);
  const auto v = by_name(a);
  for (int j = 0; j < 3; ++j) {
    const double s = bp.bents[static_cast<std::size_t>(j)].position;
    const double r =
        std::hypot(0.01, 0.011 + s * theta) / l.bent_heights[static_cast<std::size_t>(j)];
    const auto& d = v.at("drift_bent_" + std::to_string(j + 1));
    CHECK(d.margin == doctest::Approx(0.01 - r).epsilon(kTol));
    CHECK(d.exceeded == (r >= 0.01));
    CHECK(d.unit == "-");
  }
  CHECK(v.at("drift_bent_3").exceeded);   // |(0.01, 0.01184)| / 1.52 = 0.0102 >= 0.01
  CHECK(!v.at("drift_bent_2").exceeded);  // |(0.01, 0.011)| / 2.44 = 0.0061 < 0.01
}

TEST_CASE("residual rotation: |theta| at the last accepted step") {
  nsb::models::BridgeLimits l;
  l.residual_rotation = 1e-3;
  Assembly a = bridge(l);
  step(a, 1.0, 0.0, 0.0, 5e-3);
  step(a, 2.0, 0.0, 0.0, -2e-3);
  auto v = by_name(a).at("residual_rotation");
  CHECK(v.exceeded);
  CHECK(v.time == 2.0);
  CHECK(v.margin == doctest::Approx(-1e-3).epsilon(kTol));
  CHECK(v.unit == "rad");
  step(a, 3.0, 0.0, 0.0, 5e-4);
  v = by_name(a).at("residual_rotation");
  CHECK(!v.exceeded);
  CHECK(v.margin == doctest::Approx(5e-4).epsilon(kTol));
}

TEST_CASE("limit specs: a seat shorter than the initial opening, drift without heights") {
  nsb::models::BridgeLimits l;
  l.abutment_seat = 0.01;  // < the 0.0127 m gap at rest
  CHECK_THROWS_WITH_AS(bridge(l), doctest::Contains("limits.unseating_left: seat_length"),
                       std::invalid_argument);
  nsb::models::BridgeLimits d;
  d.drift_ratio = 0.01;
  CHECK_THROWS_WITH_AS(bridge(d), doctest::Contains("limits.bent_heights"), std::invalid_argument);
}
