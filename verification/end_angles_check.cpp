// The rotation criterion generalised to end faces of their own angles and to a curved deck's
// radial ends (models/criterion.hpp, end_eta; docs/criterion.md, "Unequal end angles and
// curved decks") against impacts run by the event-driven integrator on the free deck
// (models/bridge_parts.hpp): the integrator locates the impact of both corners of one end
// and solves it with the contact stage, knowing nothing of eta. Whether the deck turns
// after the impact must be what |eta| > 1 predicts.
#include "integrators/event_driven.hpp"
#include "models/bridge_parts.hpp"
#include "models/criterion.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace ni = nsb::integrators;
namespace nm = nsb::models;
namespace na = nsb::models::analytic;

namespace {

constexpr double kPi = std::numbers::pi;
// |omega+| L / |v-| above this is a rotation: a rotation-free impact leaves omega at the
// integrator's round-off (1e-13 here), a rotating one above 1e-3 in these cases.
constexpr double kRotating = 1e-7;
// eta within this of 1 is on the boundary and not classified.
constexpr double kBand = 1e-3;

struct Plan {
  const char* name;
  nm::DeckGeometry deck;
};

std::vector<Plan> plans() {
  std::vector<Plan> out;
  nm::DeckGeometry unequal{.length = 30.0, .width = 8.0, .skew_deg = 0.0, .gap_right = 0.01,
                           .gap_left = 0.01};
  unequal.skew_left_deg = 0.0;
  unequal.skew_right_deg = 35.0;
  out.push_back({"left 0, right 35 deg", unequal});
  unequal.skew_left_deg = -40.0;
  unequal.skew_right_deg = 15.0;
  out.push_back({"left -40, right 15 deg", unequal});
  for (double angle : {20.0, 60.0, 100.0}) {
    const double radius = 40.0;
    out.push_back({angle == 20.0 ? "curved 20 deg" : angle == 60.0 ? "curved 60 deg"
                                                                     : "curved 100 deg",
                   {.length = radius * angle * kPi / 180.0, .width = 8.0, .skew_deg = 0.0,
                    .gap_right = 0.01, .gap_left = 0.01, .radius = radius}});
  }
  return out;
}

}  // namespace

TEST_CASE("end angles: |eta| > 1 iff an event-driven two-corner impact turns the deck") {
  // For each plan, end and friction, approach the end's abutment with both corners at once
  // (a translation: the end face stays parallel to the abutment face) along
  //   v = -n + c t,  c in {0 (stick), +-(2 mu (1 + e) + 1) (slide either way)},
  // n, t of that end, so gdot_N- = -1 m/s. The deck starts at rest position, its gap
  // closes at t1 = g cos(a) (the normal gap), and the first sample after the impact gives
  // omega+.
  const double e = 0.2;
  int rotating = 0, still = 0;
  for (const Plan& plan : plans()) {
    for (int end : {0, 1}) {
      for (double mu : {0.0, 0.3, 0.8}) {
        for (double c : {0.0, 1.0, -1.0}) {
          nm::BridgeDesign p = nm::BridgeDesign::free_deck();
          p.deck = plan.deck;
          // The other end's gap is wide: sliding along this end's face moves the other end
          // towards its own abutment, whose face is not parallel to this one.
          (end == 0 ? p.deck.gap_right : p.deck.gap_left) = 1.0;
          const auto sector = plan.deck.curved()
                                  ? nm::annular_sector(plan.deck.radius, plan.deck.width,
                                                       plan.deck.subtended_angle())
                                  : nm::AnnularSector{};
          p.mass = 100.0;
          p.inertia = plan.deck.curved()
                          ? p.mass * sector.inertia_per_mass
                          : p.mass * (plan.deck.length * plan.deck.length + 64.0) / 12.0;
          p.restitution = e;
          p.friction = mu;
          const Eigen::Vector2d n = plan.deck.face_normal(2 * end);
          const Eigen::Vector2d t(-n.y(), n.x());
          const double slide = c * (2.0 * mu * (1.0 + e) + 1.0);
          const Eigen::Vector2d v = -n + slide * t;
          p.initial_velocity = Eigen::Vector3d(v.x(), v.y(), 0.0);
          const auto pred = na::predict_end_impact(plan.deck, end, v, mu, e);
          if (std::abs(std::abs(pred.eta) - 1.0) < kBand) continue;
          // The gap along the axis (straight) or the tangent (curved) is 0.01 m; its normal
          // part closes at 1 m/s.
          const double a = plan.deck.end_skew_deg(end) * kPi / 180.0;
          const double t1 = 0.01 * (plan.deck.curved() ? 1.0 : std::cos(a));
          nm::Assembly deck(nm::bridge_parts(p));
          ni::Recorder rec(deck, 0.0);
          ni::EventDrivenOptions o;
          o.end_time = t1 + 2e-3;
          o.tolerance = 1e-11;
          const auto stats = ni::event_driven(deck, o, rec);
          CAPTURE(std::string(plan.name));
          CAPTURE(end);
          CAPTURE(mu);
          CAPTURE(c);
          CAPTURE(pred.eta);
          REQUIRE(stats.completed);
          // The first impact is at t1, on one of this end's corners.
          const ni::Event* first = nullptr;
          for (const auto& ev : rec.events()) {
            if (ev.kind == ni::EventKind::kImpact) {
              first = &ev;
              break;
            }
          }
          REQUIRE(first != nullptr);
          CHECK(first->t == doctest::Approx(t1).epsilon(1e-6));
          CHECK(nm::DeckGeometry::abutment_of(first->contact - 1) == end);
          const auto times = rec.series("t");
          const auto omega = rec.series("omega");
          double omega_after = NAN;
          for (std::size_t i = 0; i < times.size(); ++i) {
            if (times[i] > first->t) {
              omega_after = omega[i];
              break;
            }
          }
          REQUIRE(std::isfinite(omega_after));
          const bool turns = std::abs(omega_after) * plan.deck.length / v.norm() > kRotating;
          CHECK(turns == pred.rotation);
          (turns ? rotating : still) += 1;
        }
      }
    }
  }
  // Both outcomes occur, so the check can fail either way.
  CHECK(rotating >= 10);
  CHECK(still >= 10);
}

TEST_CASE("end angles: end_eta is eq. (1)'s eta for equal angles at the right end") {
  // The generalised formula reduces to (L/W) cos a (sin a - k cos a) (docs/criterion.md).
  for (double skew : {-50.0, 0.0, 20.0, 60.0}) {
    for (double k : {-0.5, 0.0, 0.3}) {
      const na::CriterionInput in{.skew_deg = skew, .width = 3.0, .length = 25.0, .friction = 0.0};
      const nm::DeckGeometry g{.length = 25.0, .width = 3.0, .skew_deg = skew};
      CHECK(na::end_eta(g, 1, k) == doctest::Approx(na::eta(in, k)).epsilon(1e-12));
    }
  }
}
