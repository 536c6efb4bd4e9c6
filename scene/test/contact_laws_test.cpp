// Contact laws per family (docs/compliance.md, "Contact laws per family"): each family's
// compliance_stiffness reaches its contacts' ContactData::stiffness, 0 where a family gives
// none (the run's solver.contact_stiffness), and a bad value is named at its key; an abutment's
// seat length is read in [model.abutments] only, and refused in [model.seats] with that name.
// Every contact reports the mass it stops (ContactData::colliding_mass), which scales the
// compliance method's default stiffness: its body's mass against a seat or a key, the two
// frames' reduced mass at a hinge.
#include "scene/scene.hpp"
#include "scene/test/scene_files.hpp"

#include "models/assembly.hpp"

#include <doctest/doctest.h>

#include <string>
#include <vector>

namespace {

using nsb::scene::load_scene;
using nsb::scene::test_files::error_of;
using nsb::scene::test_files::write;

const std::string kBents = R"(
[[model.bents]]
position = -8.0
height = 1.83
[[model.bents]]
position = 8.0
height = 1.52
[model.gaps]
left = 0.0127
right = 0.0127
)";

const std::string kSolver = R"(
[solver]
method = "compliance"
end_time = 0.1
)";

// The data of every contact at the initial state.
std::vector<nsb::integrators::ContactData> contact_data(nsb::scene::Scene& s) {
  auto& system = *s.system;
  std::vector<nsb::integrators::ContactData> c(static_cast<std::size_t>(system.contacts()));
  for (auto& d : c) {
    d.w_normal = nsb::integrators::Vector::Zero(system.dofs());
    d.w_tangent = nsb::integrators::Vector::Zero(system.dofs());
  }
  system.contact_data(system.initial_time(), system.initial_position(), system.initial_velocity(),
                      c);
  return c;
}

std::vector<double> stiffnesses(nsb::scene::Scene& s) {
  std::vector<double> out;
  for (const auto& d : contact_data(s)) out.push_back(d.stiffness);
  return out;
}

std::vector<double> colliding_masses(nsb::scene::Scene& s) {
  std::vector<double> out;
  for (const auto& d : contact_data(s)) out.push_back(d.colliding_mass);
  return out;
}

}  // namespace

TEST_CASE("each family's compliance_stiffness reaches its contacts") {
  // Abutments (contacts 1-4) and shear keys (5-8) of one deck.
  auto deck = load_scene(write("deck.toml", R"([model]
kind = "bridge"
[model.deck]
mass = 140.5
inertia = 13090.0
length = 33.53
width = 2.44
[model.seats]
compliance_stiffness = 1.0e6
[model.shear_keys]
gap = 0.0127
compliance_stiffness = 2.0e6
)" + kBents + kSolver));
  CHECK(stiffnesses(deck) ==
        std::vector<double>{1e6, 1e6, 1e6, 1e6, 2e6, 2e6, 2e6, 2e6});
  // The deck's mass at the seats and at the keys, both fixed to the ground.
  CHECK(colliding_masses(deck) == std::vector<double>(8, 140.5));
  // Two frames: abutments 1, 2 and 5, 6 give none (0: the solver's), the hinge 3, 4 its own.
  auto frames = load_scene(write("frames.toml", R"([model]
kind = "bridge"
[[model.segments]]
mass = 70.25
inertia = 1636.25
length = 16.75
width = 2.44
[[model.segments]]
mass = 70.25
inertia = 1636.25
length = 16.75
width = 2.44
[[model.hinges]]
gap = 0.03
compliance_stiffness = 3.0e6
[[model.bents]]
position = -4.0
height = 1.83
[[model.bents]]
position = 4.0
height = 2.44
[[model.bents]]
segment = 1
position = -4.0
height = 2.44
[[model.bents]]
segment = 1
position = 4.0
height = 1.52
[model.gaps]
left = 0.0127
right = 0.0127
)" + kSolver));
  CHECK(stiffnesses(frames) == std::vector<double>{0.0, 0.0, 3e6, 3e6, 0.0, 0.0});
  // A frame's own mass at the seats; at the hinge 70.25^2 / 140.5 = 35.125 t (exact in binary).
  CHECK(colliding_masses(frames) ==
        std::vector<double>{70.25, 70.25, 35.125, 35.125, 70.25, 70.25});
}

TEST_CASE("a family's compliance_stiffness is checked at its key") {
  const std::string e = error_of("bad.toml", R"([model]
kind = "bridge"
[model.deck]
mass = 140.5
inertia = 13090.0
length = 33.53
width = 2.44
[model.seats]
compliance_stiffness = -1.0
)" + kBents + kSolver);
  CHECK(e.find("bad.toml:") != std::string::npos);
  CHECK(e.find("model.seats.compliance_stiffness: must be >= 0") != std::string::npos);
}

TEST_CASE("seat_length under [model.seats] is refused with its table named") {
  const std::string e = error_of("seat.toml", R"([model]
kind = "bridge"
[model.deck]
mass = 140.5
inertia = 13090.0
length = 33.53
width = 2.44
[model.seats]
seat_length = 0.3
)" + kBents + kSolver);
  CHECK(e.find("seat.toml:") != std::string::npos);
  CHECK(e.find("model.seats.seat_length: the abutments' seat length is a key of "
               "[model.abutments] (seat_length)") != std::string::npos);
}
