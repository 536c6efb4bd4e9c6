// A chain of free decks between two fixed abutments (models/deck_chain.hpp): rest geometry,
// conservation of linear momentum across hinge impacts, and the closed-form head-on impact of
// two equal decks, under Moreau–Jean and the event-driven integrator.
#include "models/deck_chain.hpp"

#include "integrators/event_driven.hpp"
#include "integrators/moreau_jean.hpp"
#include "models/bridge_parts.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace {

namespace ni = nsb::integrators;
using nsb::models::Assembly;
using nsb::models::DeckChain;

// Rest gaps come from a few sums and a cosine of O(10 m) numbers.
constexpr double kGeomTol = 1e-12;
// Momentum and the closed-form velocities are round-off exact: the impulses are internal and
// the decks carry no force between impacts; 1e-12 of the momentum scale covers the sums over
// the steps' velocity updates.
constexpr double kRoundOff = 1e-12;

DeckChain::Parameters chain(int decks, double skew_deg) {
  DeckChain::Parameters p;
  p.width = 2.44;
  p.skew_deg = skew_deg;
  for (int i = 0; i < decks; ++i) {
    p.decks.push_back({.mass = 140.5 + 10.0 * i, .inertia = 13090.0 + 500.0 * i,
                       .length = 20.0 + 2.0 * i});
  }
  for (int k = 0; k <= decks; ++k) {
    p.joints.push_back({.gap = 0.01 + 0.002 * k, .restitution = 0.5, .friction = 0.3});
  }
  return p;
}

std::string error_of(const DeckChain::Parameters& p) {
  try {
    Assembly a(DeckChain::parts(p));
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

// Total linear momentum (sum m_i vx_i, sum m_i vy_i) in row r of a history [t m/s].
Eigen::Vector2d momentum(const DeckChain::Parameters& p, const ni::Recorder& rec, std::size_t r) {
  Eigen::Vector2d m = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < p.decks.size(); ++i) {
    const std::string k = std::to_string(i + 1);
    m.x() += p.decks[i].mass * rec.at(r, rec.column("vx" + k));
    m.y() += p.decks[i].mass * rec.at(r, rec.column("vy" + k));
  }
  return m;
}

ni::RunResult run(ni::System& s, bool moreau, double end, ni::Recorder& rec) {
  if (moreau) {
    ni::MoreauJeanOptions o;
    o.end_time = end;
    o.step = 1e-4;
    return ni::moreau_jean(s, o, rec);
  }
  ni::EventDrivenOptions o;
  o.end_time = end;
  o.tolerance = 1e-10;
  return ni::event_driven(s, o, rec);
}

}  // namespace

TEST_CASE("at rest the left face is at x = 0 and every joint's normal gap is gap cos(alpha)") {
  for (double skew : {0.0, 20.0, -35.0}) {
    const auto p = chain(3, skew);
    Assembly a(DeckChain::parts(p));
    REQUIRE(a.dofs() == 9);
    REQUIRE(a.contacts() == 8);
    CHECK(a.coordinate_names()[3] == "x2");
    CHECK(a.velocity_names()[8] == "omega3");
    // x_0 = gap_0 + L_0/2; x_1 = gap_0 + L_0 + gap_1 + L_1/2; ...
    CHECK(DeckChain::rest_position(p, 0) == doctest::Approx(0.01 + 10.0).epsilon(kGeomTol));
    CHECK(DeckChain::rest_position(p, 1) ==
          doctest::Approx(0.01 + 20.0 + 0.012 + 11.0).epsilon(kGeomTol));
    auto c = a.make_contact_buffer();
    a.contact_data(0.0, a.initial_position(), a.initial_velocity(), c);
    const double ca = std::cos(skew * std::numbers::pi / 180.0);
    for (int i = 0; i < 8; ++i) {
      INFO("skew ", skew, ", contact ", i);
      const double gap = p.joints[static_cast<std::size_t>(i / 2)].gap;
      CHECK(c[static_cast<std::size_t>(i)].gap_normal ==
            doctest::Approx(gap * ca).epsilon(kGeomTol));
      CHECK(c[static_cast<std::size_t>(i)].restitution == 0.5);
      CHECK(c[static_cast<std::size_t>(i)].friction == 0.3);
    }
    // A hinge contact (joint 1: deck 2's left corners on deck 1's right face) spans both decks'
    // DOFs with opposite translational parts; an abutment contact only its deck's.
    CHECK(c[2].w_normal.segment<2>(3).isApprox(-c[2].w_normal.segment<2>(0)));
    CHECK(c[2].w_normal.segment<3>(6).isZero());
    CHECK(c[0].w_normal.segment<6>(3).isZero());
    CHECK(c[7].w_normal.segment<6>(0).isZero());
  }
}

TEST_CASE("bad chains are rejected naming the field") {
  auto p = chain(2, 0.0);
  p.joints.pop_back();
  CHECK(error_of(p).find("joints:") == 0);
  p = chain(2, 0.0);
  p.joints[1].gap = -0.1;
  CHECK(error_of(p) == "joints[1].gap: must be >= 0 [m]");
  p = chain(2, 0.0);
  p.decks[1].mass = 0.0;
  CHECK(error_of(p) == "decks[1].mass: must be > 0 [t]");
  p = chain(2, 0.0);
  p.decks[1].initial_displacement.x() = -0.05;  // into deck 1 through the 0.012 m hinge
  CHECK(error_of(p).find("contacts[2]: initial penetration") == 0);
  p = chain(2, 0.0);
  p.decks.clear();
  CHECK(error_of(p) == "decks: at least one deck is needed");
}

TEST_CASE("hinge impacts conserve the total linear momentum (Moreau–Jean, event-driven)") {
  // Three skewed decks with friction and restitution; deck 1 moves right and spins, deck 2
  // moves left: they collide at hinge 1 after about 0.012 / 1.5 s, and deck 2 may then hit
  // deck 3. The abutment gaps (0.5 m) are not reached within 0.1 s. The hinge impulses act on
  // both decks with opposite translational parts, so sum m_i v_i is conserved; the skew makes
  // the impacts oblique (both components change per deck).
  auto p = chain(3, 20.0);
  p.joints.front().gap = p.joints.back().gap = 0.5;
  p.decks[0].initial_velocity = {1.0, 0.1, 0.01};
  p.decks[1].initial_velocity = {-0.5, 0.0, 0.0};
  for (bool moreau : {true, false}) {
    INFO(std::string(moreau ? "Moreau–Jean" : "event-driven"));
    Assembly a(DeckChain::parts(p));
    ni::Recorder rec(a, 0.0);
    const auto r = run(a, moreau, 0.1, rec);
    REQUIRE(r.completed);
    const std::size_t last = rec.rows() - 1;
    const Eigen::Vector2d p0 = momentum(p, rec, 0), p1 = momentum(p, rec, last);
    const double scale = 140.5 * 1.0 + 150.5 * 0.5;  // sum m |v| at t = 0 [t m/s]
    CHECK((p1 - p0).norm() <= kRoundOff * scale);
    MESSAGE(std::string(moreau ? "Moreau–Jean" : "event-driven"),
            ": |P(0.1) - P(0)| = ", (p1 - p0).norm(), " t m/s, ", r.steps_with_lcp,
            " contact solves, ", rec.count(ni::EventKind::kImpact), " impact events");
    // The decks did collide: deck 1 lost most of its closing speed.
    CHECK(rec.at(last, rec.column("vx1")) < 0.5);
    for (const char* g : {"gN1", "gN2", "gN7", "gN8"}) {
      for (double v : rec.series(g)) CHECK(v > 0.4);  // no abutment contact
    }
  }
}

TEST_CASE("head-on impact of two equal straight decks: velocities exchanged, scaled by e") {
  // Two decks of mass m, straight (alpha = 0), deck 1 at v, deck 2 at rest. The impact acts
  // through the two left corners of deck 2 at y = +-W/2, symmetric about the axis, so the
  // impulses are equal, the rotations stay zero and only x changes. Momentum and Newton's law:
  //   m v1' + m v2' = m v,      v2' - v1' = e v,
  // give v1' = v (1 - e) / 2 and v2' = v (1 + e) / 2: for e = 1 the velocities are
  // exchanged, for e = 0 both move at v / 2. Friction does not act (no slip along the face).
  for (double e : {0.0, 0.5, 1.0}) {
    DeckChain::Parameters p;
    p.width = 2.44;
    p.decks = {{.mass = 140.5, .inertia = 13090.0, .length = 33.53},
               {.mass = 140.5, .inertia = 13090.0, .length = 33.53}};
    p.joints = {{.gap = 0.5}, {.gap = 0.01, .restitution = e, .friction = 0.5}, {.gap = 0.5}};
    constexpr double v = 1.0;
    p.decks[0].initial_velocity = {v, 0.0, 0.0};
    for (bool moreau : {true, false}) {
      INFO(std::string(moreau ? "Moreau–Jean" : "event-driven"), ", e = ", e);
      Assembly a(DeckChain::parts(p));
      ni::Recorder rec(a, 0.0);
      REQUIRE(run(a, moreau, 0.05, rec).completed);  // impact at 0.01 s
      const std::size_t last = rec.rows() - 1;
      CHECK(std::abs(rec.at(last, rec.column("vx1")) - v * (1.0 - e) / 2.0) <= kRoundOff * v);
      CHECK(std::abs(rec.at(last, rec.column("vx2")) - v * (1.0 + e) / 2.0) <= kRoundOff * v);
      CHECK(std::abs(rec.at(last, rec.column("vy2"))) <= kRoundOff * v);
      CHECK(std::abs(rec.at(last, rec.column("omega2"))) <= kRoundOff * v);
    }
  }
}

TEST_CASE("a chain of one deck is the free deck (bridge_parts) shifted along x") {
  // The same deck, gaps and coefficients: the free deck is centred at x = 0, the chain at
  // gap_left + L/2. The skewed, spinning deck pounds the left abutment and rebounds; the
  // histories differ only by round-off of the shifted coordinates (O(1e-15) of 17 m), which
  // the contact solves carry through the run (measured: 1.2e-11 under Moreau–Jean, whose index
  // set reacts to the gap's last bits, 2e-14 event-driven); 1e-9 allows for that.
  constexpr double kShiftTol = 1e-9;
  DeckChain::Parameters p;
  p.width = 2.44;
  p.skew_deg = 25.0;
  p.decks = {{.mass = 140.5, .inertia = 13090.0, .length = 33.53,
              .initial_velocity = {-0.4, 0.05, 0.02}}};
  p.joints = {{.gap = 0.02, .restitution = 0.6, .friction = 0.5},
              {.gap = 0.03, .restitution = 0.6, .friction = 0.5}};
  nsb::models::BridgeDesign r = nsb::models::BridgeDesign::free_deck();
  r.mass = 140.5;
  r.inertia = 13090.0;
  r.deck = {.length = 33.53, .width = 2.44, .skew_deg = 25.0, .gap_right = 0.03,
            .gap_left = 0.02};
  r.restitution = 0.6;
  r.friction = 0.5;
  r.initial_velocity = p.decks[0].initial_velocity;
  for (bool moreau : {true, false}) {
    INFO(std::string(moreau ? "Moreau–Jean" : "event-driven"));
    Assembly chain1(DeckChain::parts(p));
    Assembly deck(nsb::models::bridge_parts(r));
    ni::Recorder a(chain1, 0.01), b(deck, 0.01);
    REQUIRE(run(chain1, moreau, 1.0, a).completed);
    REQUIRE(run(deck, moreau, 1.0, b).completed);
    REQUIRE(a.rows() == b.rows());
    CHECK(a.count(ni::EventKind::kImpact) == b.count(ni::EventKind::kImpact));
    const double shift = DeckChain::rest_position(p, 0);
    const auto last = a.rows() - 1;
    CHECK(std::abs(a.at(last, a.column("x")) - shift - b.at(last, b.column("x"))) < kShiftTol);
    double largest = 0.0;
    for (const char* c : {"y", "theta", "vx", "vy", "omega", "gN1", "gN2", "gN3", "gN4"}) {
      INFO(c);
      for (std::size_t i = 0; i < a.rows(); ++i) {
        const double d = std::abs(a.at(i, a.column(c)) - b.at(i, b.column(c)));
        CHECK(d < kShiftTol);
        largest = std::max(largest, d);
      }
    }
    MESSAGE(std::string(moreau ? "Moreau–Jean" : "event-driven"), ": largest difference ",
            largest, ", ", b.count(ni::EventKind::kImpact), " impacts");
    CHECK(b.count(ni::EventKind::kImpact) >= 1);  // it pounded
    CHECK(a.at(last, a.column("vx")) > 0.0);      // and rebounded
  }
}
