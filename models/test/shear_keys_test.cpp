// Shear keys (models/shear_keys.hpp): the key contacts' gaps against the deck's transverse
// motion, breaking at the capacity (the contact far from then on, the limit state), and input
// errors naming the key.
#include "models/shear_keys.hpp"

#include "models/bridge_parts.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace {

using nsb::models::Assembly;
namespace ni = nsb::integrators;

constexpr double kGap = 0.05;  // [m]

Assembly::Parts with_keys(double capacity) {
  Assembly::Parts p = nsb::models::bridge_parts(nsb::models::BridgeDesign::benchmark());
  nsb::models::add_shear_keys(p, {.gap = kGap, .restitution = 0.2, .friction = 0.3,
                                  .capacity = capacity});
  return p;
}

TEST_CASE("shear keys: four contacts after the seats', gaps against the deck's side") {
  Assembly a(with_keys(0.0));
  REQUIRE(a.contacts() == 8);
  auto c = a.make_contact_buffer();
  a.contact_data(0.0, Eigen::Vector3d(0.0, 0.0, 0.0), Eigen::Vector3d::Zero(), c);
  for (int i = 4; i < 8; ++i) CHECK(c[static_cast<std::size_t>(i)].gap_normal ==
                                    doctest::Approx(kGap).epsilon(1e-12));
  // The deck moves 0.02 m towards +y: the +y keys' gaps close by as much, the -y ones open.
  a.contact_data(0.0, Eigen::Vector3d(0.0, 0.02, 0.0), Eigen::Vector3d(0.0, 1.0, 0.0), c);
  CHECK(c[4].gap_normal == doctest::Approx(kGap - 0.02));
  CHECK(c[5].gap_normal == doctest::Approx(kGap + 0.02));
  CHECK(c[6].gap_normal == doctest::Approx(kGap - 0.02));
  CHECK(c[7].gap_normal == doctest::Approx(kGap + 0.02));
  CHECK(c[4].gap_rate(Eigen::Vector3d(0.0, 1.0, 0.0)) == doctest::Approx(-1.0));
  CHECK(c[4].friction == 0.3);
  CHECK(c[4].restitution == 0.2);
}

TEST_CASE("a shear key breaks when the step's mean force exceeds its capacity") {
  Assembly a(with_keys(500.0));
  const Eigen::Vector3d q(0.0, kGap, 0.0), u = Eigen::Vector3d::Zero();
  Eigen::VectorXd impulse = Eigen::VectorXd::Zero(8);
  ni::AcceptedStep step{.t = 0.1, .h = 1e-3, .q = nullptr, .u = nullptr,
                        .normal_impulse = &impulse};
  impulse[4] = 0.4;  // 400 kN over the step: holds
  CHECK(a.accept_step(step) == ni::StepVerdict::kContinue);
  auto c = a.make_contact_buffer();
  a.contact_data(0.1, q, u, c);
  CHECK_FALSE(c[4].far);
  step.t = 0.2;
  impulse[4] = 0.6;  // 600 kN > 500 kN: breaks
  CHECK(a.accept_step(step) == ni::StepVerdict::kContactsRemoved);
  a.contact_data(0.2, q, u, c);
  CHECK(c[4].far);
  CHECK_FALSE(c[6].far);
  a.contact_normals(0.2, q, u, c);
  CHECK(c[4].far);
  // A broken key stays broken and is not reported again.
  step.t = 0.3;
  CHECK(a.accept_step(step) == ni::StepVerdict::kContinue);
  const auto states = a.limit_states();
  REQUIRE(states.size() == 4);
  CHECK(states[0].name == "shear_key_left_plus");
  CHECK(states[0].unit == "kN");
  CHECK(states[0].exceeded);
  CHECK(states[0].time == 0.2);
  CHECK(states[0].margin == doctest::Approx(500.0 - 600.0));
  CHECK(states[0].removes_contact == 5);
  CHECK_FALSE(states[1].exceeded);
  CHECK(states[1].margin == 500.0);
  CHECK(states[3].name == "shear_key_right_minus");
}

TEST_CASE("an impact's impulse, delivered at an instant, breaks a key of any capacity") {
  // Event-driven hands an impact's impulse apart (AcceptedStep::impact_impulse). Over a step
  // of 1 ms, 0.1 kN s is a mean force of 100 kN, below the capacity of 500 kN; but it acts at
  // an instant, the limit of Moreau-Jean's impulse / h as h -> 0 (0.1 kN s / h > 500 kN for
  // every h < 2e-4 s): the key breaks, its peak force infinite.
  Assembly a(with_keys(500.0));
  Eigen::VectorXd impulse = Eigen::VectorXd::Zero(8), percussion = Eigen::VectorXd::Zero(8);
  ni::AcceptedStep step{.t = 0.1, .h = 1e-3, .q = nullptr, .u = nullptr,
                        .normal_impulse = &impulse, .impact_impulse = &percussion};
  impulse[5] = 0.1;  // a closed phase's 100 kN over the step: holds
  CHECK(a.accept_step(step) == ni::StepVerdict::kContinue);
  step.t = 0.2;
  percussion[5] = 0.1;  // the same impulse from an impact: breaks
  CHECK(a.accept_step(step) == ni::StepVerdict::kContactsRemoved);
  const auto states = a.limit_states();
  CHECK(states[1].exceeded);
  CHECK(states[1].time == 0.2);
  CHECK(states[1].margin == -std::numeric_limits<double>::infinity());
  CHECK_FALSE(states[0].exceeded);
  // An unbreakable key is not broken by an impact either.
  Assembly unbreakable(with_keys(0.0));
  CHECK(unbreakable.accept_step(step) == ni::StepVerdict::kContinue);
}

TEST_CASE("an unbreakable key never breaks and has no margin") {
  Assembly a(with_keys(0.0));
  Eigen::VectorXd impulse = Eigen::VectorXd::Constant(8, 1e6);
  const ni::AcceptedStep step{.t = 0.1, .h = 1e-4, .q = nullptr, .u = nullptr,
                              .normal_impulse = &impulse};
  CHECK(a.accept_step(step) == ni::StepVerdict::kContinue);
  for (const auto& s : a.limit_states()) {
    CHECK_FALSE(s.exceeded);
    CHECK(std::isnan(s.margin));
  }
}

TEST_CASE("shear keys on a segmented deck sit at its two ends") {
  nsb::models::BridgeDesign p = nsb::models::BridgeDesign::benchmark();
  nsb::models::SegmentedDeck deck;
  deck.segments.assign(2, {.mass = 70.0, .inertia = 3000.0, .length = 16.0, .width = 2.44});
  deck.hinges.resize(1);
  deck.hinges[0].gap = 0.01;
  p.bents.resize(4, p.bents.front());
  p.bents[0].position = -4.0;
  p.bents[1].position = 4.0;
  p.bents[2].position = -4.0;
  p.bents[3].position = 4.0;
  deck.bent_segment = {0, 0, 1, 1};
  Assembly::Parts parts = nsb::models::bridge_parts(p, deck);
  const std::size_t before = parts.contacts.size();
  nsb::models::add_shear_keys(parts, {.gap = kGap});
  REQUIRE(parts.contacts.size() == before + 4);
  CHECK(parts.contacts[before].body == 0);
  CHECK(parts.contacts[before + 1].body == 0);
  CHECK(parts.contacts[before + 2].body == 1);
  CHECK(parts.contacts[before + 3].body == 1);
  Assembly a(parts);
  auto c = a.make_contact_buffer();
  a.contact_data(0.0, a.initial_position(), a.initial_velocity(), c);
  for (std::size_t i = before; i < before + 4; ++i)
    CHECK(c[i].gap_normal == doctest::Approx(kGap).epsilon(1e-12));
}

TEST_CASE("shear keys: bad parameters name the key") {
  Assembly::Parts p = nsb::models::bridge_parts(nsb::models::BridgeDesign::benchmark());
  try {
    nsb::models::add_shear_keys(p, {.gap = -0.01});
    FAIL("no exception");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()).find("shear_keys.gap") == 0);
  }
  CHECK_THROWS_AS(nsb::models::add_shear_keys(p, {.capacity = -1.0}), std::invalid_argument);
  p.shear_keys.push_back({.contact = 9, .name = "k", .capacity = 1.0});
  try {
    Assembly a(p);
    FAIL("no exception");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()).find("shear_keys[0].contact") == 0);
  }
}

}  // namespace
