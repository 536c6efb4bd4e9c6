// The event-driven integrator against closed-form solutions (models/analytic.hpp) on the
// shared simple systems and the free rigid deck, and its stress cases.
#include "integrators/event_driven.hpp"
#include "models/analytic.hpp"
#include "models/bridge_parts.hpp"
#include "models/ground_motion.hpp"
#include "models/simple_systems.hpp"
#include "scene/scene.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace ni = nsb::integrators;
namespace nm = nsb::models;
namespace na = nsb::models::analytic;

namespace {

// Event times: Brent locates them to 1e-13 s on a dense output accurate to the Odeint
// tolerance 1e-11; the requirement is 1e-8 s.
constexpr double kEventTimeTol = 1e-8;
// Accumulation time of the bouncing ball: the requirement.
constexpr double kAccumulationTol = 1e-6;
// Velocities after an impact: the LCP is solved to 1e-12, the pre-impact state comes from a
// tolerance-1e-11 integration.
constexpr double kVelocityTol = 1e-8;

std::vector<ni::Event> events_of(const ni::Recorder& r, ni::EventKind kind, int contact = -1) {
  std::vector<ni::Event> out;
  for (const auto& e : r.events()) {
    if (e.kind == kind && (contact < 0 || e.contact == contact)) out.push_back(e);
  }
  return out;
}

bool all_finite(const ni::Recorder& r) {
  for (std::size_t i = 0; i < r.rows(); ++i) {
    for (std::size_t j = 0; j < r.columns().size(); ++j) {
      if (!std::isfinite(r.at(i, j))) return false;
    }
  }
  return true;
}

ni::EventDrivenOptions options(double end_time, double tolerance) {
  ni::EventDrivenOptions o;
  o.end_time = end_time;
  o.tolerance = tolerance;
  return o;
}

}  // namespace

TEST_CASE("bouncing ball: impact times, accumulation time, rest") {
  nm::BouncingBall::Parameters p;
  p.height = 1.0;
  p.restitution = 0.8;
  nm::BouncingBall ball(p);
  ni::Recorder rec(ball, 0.01);
  const auto stats = ni::event_driven(ball, options(6.0, 1e-10), rec);
  REQUIRE(stats.completed);
  const auto impacts = events_of(rec, ni::EventKind::kImpact);
  const auto exact = na::ball_impacts(p, 30);
  REQUIRE(impacts.size() >= exact.size());
  for (std::size_t k = 0; k < exact.size(); ++k) {
    CHECK_MESSAGE(std::abs(impacts[k].t - exact[k].time) < kEventTimeTol, "impact ", k + 1);
  }
  // The last event that closes the contact is the accumulation point; the flights cut by
  // the closing velocity 10 * tolerance = 1e-9 m/s sum to 2 v / (g (1 - e)) ~ 1e-9 s.
  const auto closes = events_of(rec, ni::EventKind::kClose);
  REQUIRE(!closes.empty());
  CHECK(std::abs(closes.back().t - na::ball_accumulation_time(p)) < kAccumulationTol);
  CHECK(events_of(rec, ni::EventKind::kOpen).empty());
  // At rest afterwards: on the ground, carrying its weight.
  CHECK(std::abs(rec.series("y").back()) < 1e-9);
  CHECK(std::abs(rec.series("vy").back()) < 1e-9);
  CHECK(rec.series("lambdaN1").back() == doctest::Approx(p.mass * p.gravity).epsilon(1e-9));
  CHECK(stats.energy.error < 1e-6);
  CHECK(all_finite(rec));
}

TEST_CASE("impact oscillator: 20 impacts against the closed form") {
  nm::ImpactOscillator::Parameters p;
  p.mass = 2.0;
  p.stiffness = 50.0;
  p.gap = 0.05;
  p.restitution = 0.9;
  p.initial_position = 0.0;
  p.initial_velocity = 1.0;
  nm::ImpactOscillator osc(p);
  const auto exact = na::oscillator_impacts(p, 20);
  REQUIRE(exact.size() == 20);
  ni::Recorder rec(osc, 0.0);
  const auto stats = ni::event_driven(osc, options(exact.back().time + 0.01, 1e-11), rec);
  REQUIRE(stats.completed);
  const auto impacts = events_of(rec, ni::EventKind::kImpact);
  REQUIRE(impacts.size() >= 20);
  for (std::size_t k = 0; k < 20; ++k) {
    CHECK_MESSAGE(std::abs(impacts[k].t - exact[k].time) < kEventTimeTol, "impact ", k + 1);
  }
  // Amplitude after the last impact: A' = sqrt(x^2 + (v/w)^2) of the final state (no impact
  // in the last 0.01 s: the free period is 2 pi sqrt(m/k) = 1.26 s).
  const double w = std::sqrt(p.stiffness / p.mass);
  const double x = rec.series("x").back(), v = rec.series("vx").back();
  CHECK(std::hypot(x, v / w) == doctest::Approx(exact.back().amplitude_after).epsilon(1e-8));
}

TEST_CASE("block: stick below mu, exact slip above, harmonic stick-slip times") {
  SUBCASE("incline below and above the friction angle") {
    // On an incline beta the block sticks iff tan(beta) <= mu; otherwise it slides down
    // with a = g (sin beta - mu cos beta) (block_state gives x(t)).
    for (double beta : {20.0, 35.0}) {
      nm::SlidingBlock::Parameters p;
      p.friction = 0.5;  // friction angle atan(0.5) = 26.57 deg
      p.incline_deg = beta;
      nm::SlidingBlock block(p);
      ni::Recorder rec(block, 0.0);
      const auto stats = ni::event_driven(block, options(1.0, 1e-10), rec);
      REQUIRE(stats.completed);
      const auto exact = na::block_state(p, 1.0);
      CHECK(rec.series("x").back() == doctest::Approx(exact.position).epsilon(1e-8).scale(1e-12));
      CHECK(rec.series("vx").back() == doctest::Approx(exact.velocity).epsilon(1e-8).scale(1e-12));
    }
  }
  SUBCASE("harmonic force: slip start and stick times") {
    // F(t) = F0 sin(2 pi f t) with F0 > mu m g: the block starts to slip when
    // F0 sin(2 pi f t_b) = mu m g, and sticks again when v(t) = (1/m) int_{t_b}^{t}
    // (F - mu m g) dt = 0 (block_harmonic_first_slip).
    nm::SlidingBlock::Parameters p;
    p.friction = 0.3;
    p.force_amplitude = 2.0 * p.friction * p.mass * p.gravity;
    p.force_frequency = 1.0;
    nm::SlidingBlock block(p);
    const auto exact = na::block_harmonic_first_slip(p);
    REQUIRE(exact.slips);
    ni::Recorder rec(block, 0.0);
    const auto stats = ni::event_driven(block, options(exact.end_time + 0.05, 1e-11), rec);
    REQUIRE(stats.completed);
    // Events after the initial close and stick: slip at t_b, then at the end of the slip
    // either stick (|F_a| <= mu N there) or a reversal, which is again a kSlip event.
    std::vector<ni::Event> transitions;
    for (const auto& e : rec.events()) {
      if (e.t > 0.0 && (e.kind == ni::EventKind::kSlip || e.kind == ni::EventKind::kStick)) {
        transitions.push_back(e);
      }
    }
    REQUIRE(transitions.size() >= 2);
    CHECK(transitions[0].kind == ni::EventKind::kSlip);
    CHECK(std::abs(transitions[0].t - exact.start_time) < kEventTimeTol);
    CHECK(std::abs(transitions[1].t - exact.end_time) < kEventTimeTol);
    const double load =
        p.force_amplitude * std::sin(2.0 * M_PI * p.force_frequency * exact.end_time);
    const bool sticks = na::block_sticks(load, p.friction, p.mass * p.gravity);
    CHECK(transitions[1].kind == (sticks ? ni::EventKind::kStick : ni::EventKind::kSlip));
  }
}

namespace {

nm::BridgeDesign deck_parameters() {
  // The benchmark deck's mass, inertia and plan (docs/bridge.md).
  nm::BridgeDesign p = nm::BridgeDesign::free_deck();
  p.mass = 140.5;
  p.inertia = 13090.0;
  p.deck = {.length = 33.35, .width = 2.44, .skew_deg = 0.0, .gap_right = 0.0127,
            .gap_left = 0.0127};
  p.restitution = 0.5;
  p.friction = 0.5;
  return p;
}

// Velocity just after the first impact: the first sample after it (free flight, so the
// velocity is constant until the next event).
Eigen::Vector3d velocity_after(const ni::Recorder& rec, double t_impact) {
  const auto t = rec.series("t");
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] > t_impact) {
      return {rec.at(i, rec.column("vx")), rec.at(i, rec.column("vy")),
              rec.at(i, rec.column("omega"))};
    }
  }
  return Eigen::Vector3d::Constant(std::nan(""));
}

}  // namespace

TEST_CASE("free deck: two-corner impacts against the analytic solution and eta") {
  // Deck moving right with vx, not rotating; corners 3 and 4 strike together at
  // t = gap_right / vx (the end face is parallel to the abutment face). A straight deck
  // rotates only when the corners slide (|eta| > 1 on the sliding branch); a skewed deck
  // (30 degrees: sin(2a) L / (2 W) = 5.9) rotates even when they stick.
  for (const auto& [skew, vy] : std::vector<std::pair<double, double>>{
           {0.0, 0.0}, {0.0, 0.05}, {0.0, 0.5}, {30.0, 0.0}, {30.0, -0.5}, {5.0, 0.02}}) {
    auto p = deck_parameters();
    p.deck.skew_deg = skew;
    p.initial_velocity = {0.5, vy, 0.0};
    nm::Assembly deck(nm::bridge_parts(p));
    ni::Recorder rec(deck, 0.0);
    // The normal gap is gap cos(a), closed at the normal speed vx cos(a) - vy sin(a)...
    // with vy != 0 on a skewed deck; the face moves along itself otherwise.
    const double t1 = p.deck.gap_right * std::cos(skew * M_PI / 180.0) /
                      (p.initial_velocity.x() * std::cos(skew * M_PI / 180.0) -
                       vy * std::sin(skew * M_PI / 180.0));
    const auto stats = ni::event_driven(deck, options(t1 + 0.01, 1e-11), rec);
    REQUIRE(stats.completed);
    const auto impacts = events_of(rec, ni::EventKind::kImpact);
    REQUIRE(impacts.size() >= 2);
    CHECK(std::abs(impacts[0].t - t1) < kEventTimeTol);
    na::DeckBody g{p.mass, p.inertia, p.deck};
    const auto exact = na::deck_impact(g, {3, 4}, p.initial_velocity, p.restitution, p.friction);
    const Eigen::Vector3d u = velocity_after(rec, impacts[0].t);
    CHECK_MESSAGE((u - exact.velocity_after).cwiseAbs().maxCoeff() < kVelocityTol, "skew ", skew,
                  " vy = ", vy);
    const auto pred = na::predict_right_end_impact({p.deck.skew_deg, p.deck.width, p.deck.length, p.friction},
                                                   p.initial_velocity.x(), vy, p.restitution);
    CHECK_MESSAGE(pred.rotation == (std::abs(u.z()) > 1e-9), "skew ", skew, " vy = ", vy,
                  " eta = ", pred.eta);
  }
}

TEST_CASE("free deck: one-corner impact against the impact problem solved by cases") {
  // A small counter-clockwise spin omega makes corner 4 (right end, y_b = -W/2) strike
  // first: its velocity along x is vx - omega y_b = vx + omega W / 2. The pre-impact state
  // is the free flight q0 + u0 t; the impact at the located time is solved by enumeration
  // of contact cases.
  auto p = deck_parameters();
  p.initial_velocity = {0.4, 0.1, 0.004};
  nm::Assembly deck(nm::bridge_parts(p));
  ni::Recorder rec(deck, 0.0);
  const auto stats = ni::event_driven(deck, options(0.05, 1e-11), rec);
  REQUIRE(stats.completed);
  const auto impacts = events_of(rec, ni::EventKind::kImpact);
  REQUIRE(!impacts.empty());
  CHECK(impacts[0].contact == 4);
  const auto ci = static_cast<std::size_t>(impacts[0].contact - 1);
  const double te = impacts[0].t;
  const Eigen::VectorXd q = p.initial_position + te * p.initial_velocity;
  auto cd = deck.make_contact_buffer();
  deck.contact_data(te, q, p.initial_velocity, cd);
  CHECK(std::abs(cd[ci].gap_normal) < 1e-9);
  na::ImpactProblem ip;
  Eigen::MatrixXd W(3, 2);
  W.col(0) = cd[ci].w_normal;
  W.col(1) = cd[ci].w_tangent;
  const Eigen::Matrix3d minv = deck.mass().inverse();
  ip.delassus = W.transpose() * minv * W;
  ip.gdot_minus = W.transpose() * p.initial_velocity;
  ip.restitution = Eigen::VectorXd::Constant(1, p.restitution);
  ip.friction = Eigen::VectorXd::Constant(1, p.friction);
  const auto cases = na::solve_impact_by_cases(ip);
  REQUIRE(cases.unique());
  const auto& s = cases.solutions[0];
  const Eigen::Vector3d u_exact =
      p.initial_velocity + minv * (W.col(0) * s.lambda_n[0] + W.col(1) * s.lambda_t[0]);
  const Eigen::Vector3d u = velocity_after(rec, te);
  CHECK((u - u_exact).cwiseAbs().maxCoeff() < kVelocityTol);
}

TEST_CASE("stress cases end with a result, no NaN, no hang") {
  struct Case {
    std::string name;
    double restitution, friction, gap;
    Eigen::Vector3d velocity;
  };
  const Case cases[] = {
      {"eps = 1, two corners", 1.0, 0.5, 0.0127, {0.5, 0.2, 0.0}},
      {"mu = 2, oblique", 0.5, 2.0, 0.0127, {0.5, 0.5, 0.01}},
      {"four corners touching at once", 0.0, 0.5, 0.0, {0.3, 0.1, 0.0}},
      {"grazing: sliding along both faces", 0.0, 0.5, 0.0, {0.0, 0.3, 0.0}},
      {"eps = 1, mu = 2, four corners", 1.0, 2.0, 0.0, {0.3, 0.3, 0.02}},
  };
  for (const auto& c : cases) {
    auto p = deck_parameters();
    p.restitution = c.restitution;
    p.friction = c.friction;
    p.deck.gap_right = p.deck.gap_left = c.gap;
    p.initial_velocity = c.velocity;
    nm::Assembly deck(nm::bridge_parts(p));
    ni::Recorder rec(deck, 0.001);
    const auto stats = ni::event_driven(deck, options(0.5, 1e-8), rec);
    CHECK_MESSAGE((stats.completed || !stats.message.empty()), c.name);
    CHECK_MESSAGE(all_finite(rec), c.name);
    CHECK_MESSAGE(stats.end_time > 0.0, c.name);
    // Impacts never create energy (eps <= 1, Coulomb friction dissipates).
    CHECK_MESSAGE(stats.energy.impacts <= 1e-9, c.name);
    CHECK_MESSAGE(stats.energy.friction <= 1e-9, c.name);
    // No penetration beyond the tolerances.
    for (int i = 1; i <= 4; ++i) {
      for (double g : rec.series("gN" + std::to_string(i))) {
        CHECK_MESSAGE(g > -1e-6, c.name, " contact ", i);
      }
    }
  }
}

TEST_CASE("stress: a deck pressed against a seat that moves away") {
  // The benchmark bridge with its deck touching the right seat (x = gap_right). The seat
  // acceleration is first one sine cycle -A1 sin(2 pi t), A1 = 0.1 m/s^2: the seat moves
  // towards the deck by A1 / (2 pi) = 0.016 m for good (less than the two gaps, so the deck
  // is never squeezed against the left abutment) and the deck comes to rest against it,
  // held by the bents (closed contacts 3 and 4, rheonomic terms of the moving seat). From
  // t = 1.5 s a cycle A2 sin(2 pi t), A2 = 3 m/s^2, pulls the seat away faster than the
  // bents (about 1 m/s^2 on the deck) let the deck follow, so the contacts must open.
  auto p = nm::BridgeDesign::benchmark();
  p.initial_position = {p.deck.gap_right, 0.0, 0.0};
  nm::Record pulse;
  for (int i = 0; i <= 400; ++i) {
    const double t = 0.01 * i;
    pulse.t.push_back(t);
    const double a1 = t < 1.0 ? -0.1 * std::sin(2.0 * M_PI * t) : 0.0;
    const double a2 = (t >= 1.5 && t < 2.5) ? 3.0 * std::sin(2.0 * M_PI * (t - 1.5)) : 0.0;
    pulse.a.push_back(a1 + a2);
  }
  pulse.source = "one-cycle sine pulse";
  nm::GroundMotionOptions go;
  go.baseline_correction = false;
  p.excitation.seats[1].longitudinal = std::make_shared<const nm::GroundMotion>(pulse, go);
  nm::Assembly bridge(nm::bridge_parts(p));
  ni::Recorder rec(bridge, 0.001);
  const auto stats = ni::event_driven(bridge, options(3.0, 1e-8), rec);
  CHECK(stats.completed);
  CHECK(all_finite(rec));
  CHECK(!events_of(rec, ni::EventKind::kClose, 3).empty());
  CHECK(!events_of(rec, ni::EventKind::kOpen, 3).empty());
  for (int i = 1; i <= 4; ++i) {
    for (double g : rec.series("gN" + std::to_string(i))) CHECK(g > -1e-6);
  }
}

TEST_CASE("stress: the bridge under a strong excitation, mu up to 2, eps = 1") {
  // Excitation 5 scaled to a PGA of 2 g, first 12 s: tens of impacts, sticking and
  // sliding at all four corners. Every run must reach the end with finite output and
  // without penetration.
  const auto scene = std::filesystem::path(NSB_SCENES_DIR) / "bridge-exc5.toml";
  const std::vector<std::vector<std::string>> variants{
      {"model.excitation.target_pga=2.0"},
      {"model.excitation.target_pga=2.0", "model.seats.friction=2.0"},
      {"model.excitation.target_pga=2.0", "model.seats.restitution=1.0"},
  };
  for (const auto& ov : variants) {
    for (double tol : {1e-3, 1e-8}) {
      auto s = nsb::scene::load_scene(scene, ov);
      ni::Recorder rec(*s.system, 0.01);
      const auto stats = ni::event_driven(*s.system, options(12.0, tol), rec);
      const std::string name = ov.back() + " tolerance " + std::to_string(tol);
      CHECK_MESSAGE(stats.completed, name, ": ", stats.message);
      CHECK_MESSAGE(all_finite(rec), name);
      CHECK_MESSAGE(rec.count(ni::EventKind::kImpact) > 0, name);
      for (int i = 1; i <= 4; ++i) {
        double gmin = 0.0;
        for (double g : rec.series("gN" + std::to_string(i))) gmin = std::min(gmin, g);
        // Penetration between the projections of closed contacts (after every step that
        // drifts beyond 1e-9 m) is the integration error of one step: 0.2 m * tolerance
        // bounds it (it scales with the deck displacement of some 0.05 m).
        CHECK_MESSAGE(gmin > -0.2 * tol - 1e-9, name, " contact ", i);
      }
    }
  }
}
