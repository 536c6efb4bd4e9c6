// Connector keys of a bridge scene (scene/part_restrainers.cpp, part_bearings.cpp,
// part_abutments.cpp): which system a scene builds, and bad input naming file:line:col and
// the key.
#include "scene/scene.hpp"
#include "scene/test/scene_files.hpp"

#include "models/assembly.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <unistd.h>

namespace fs = std::filesystem;
using nsb::scene::load_scene;

namespace {

using nsb::scene::test_files::error_of;
using nsb::scene::test_files::write;

const std::string kDeck = R"([model]
kind = "bridge"
[model.deck]
mass = 140.5
inertia = 13090.0
length = 33.53
width = 2.44
[[model.bents]]
position = -8.3825
height = 1.83
[[model.bents]]
position = 8.3825
height = 1.52
[model.gaps]
left = 0.0127
right = 0.0127
)";

const std::string kTwoFrames = R"([model]
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
[[model.bents]]
position = 0.0
height = 1.83
[[model.bents]]
position = 8.0
height = 2.44
[[model.bents]]
segment = 1
position = -8.0
height = 2.44
[[model.bents]]
segment = 1
position = 0.0
height = 1.52
[[model.hinges]]
gap = 0.03
)";

const std::string kSolver = R"(
[solver]
method = "moreau"
end_time = 0.1
step = 1.0e-4
)";

}  // namespace

TEST_CASE("a one-deck bridge is an assembly: its bents and seats, and the connectors given") {
  auto plain = load_scene(write("plain.toml", kDeck + kSolver));
  auto* p = dynamic_cast<nsb::models::Assembly*>(plain.system.get());
  REQUIRE(p != nullptr);
  CHECK(p->parts().links.empty());
  CHECK(p->parts().bodies.size() == 1);
  CHECK(p->parts().prescribed.size() == 2);
  CHECK(p->parts().contacts.size() == 4);
  auto bearing = load_scene(write("bearing.toml", kDeck + R"(
[[model.bearings]]
position = 16.0
stiffness = 2000.0
yield_force = 50.0
)" + kSolver));
  auto* a = dynamic_cast<nsb::models::Assembly*>(bearing.system.get());
  REQUIRE(a != nullptr);
  CHECK(a->parts().links.size() == 1);
  CHECK(a->dofs() == 3);
  // Backfill: a backwall body per abutment (9 coordinates), the deck's four corners on them.
  auto backfill = load_scene(write("backfill.toml", kDeck + R"(
[model.abutments]
seat = "backfill"
restrainer = {stiffness = 1000.0, length = 1.0}
)" + kSolver));
  a = dynamic_cast<nsb::models::Assembly*>(backfill.system.get());
  REQUIRE(a != nullptr);
  CHECK(a->dofs() == 9);
  CHECK(a->contacts() == 4);
  CHECK(a->parts().links.size() == 4);
  CHECK(a->parts().restrainers.size() == 2);
  for (const auto& c : a->parts().contacts) CHECK(c.obstacle == nsb::models::parts::Obstacle::kBody);
  // A hinge restrainer on the two-frame bridge.
  auto hinge = load_scene(write("hinge.toml", kTwoFrames + R"(restrainer = {stiffness = 500.0}
)" + kSolver));
  a = dynamic_cast<nsb::models::Assembly*>(hinge.system.get());
  REQUIRE(a != nullptr);
  CHECK(a->parts().restrainers.size() == 1);
}

TEST_CASE("connector keys: bad input names file:line:col and the key") {
  std::string e = error_of("r1.toml", kTwoFrames + "restrainer = {slack = 0.01}\n" + kSolver);
  CHECK(e.find("r1.toml:") != std::string::npos);
  CHECK(e.find("model.hinges[0].restrainer: missing key stiffness") != std::string::npos);
  e = error_of("r2.toml", kTwoFrames + "restrainer = {stiffness = 1.0, length = 0.02}\n" + kSolver);
  CHECK(e.find("model.hinges[0].restrainer.length: must exceed the joint's gap") !=
        std::string::npos);
  e = error_of("b1.toml", kDeck + "[[model.bearings]]\nposition = 20.0\nstiffness = 1.0\n" + kSolver);
  CHECK(e.find("b1.toml:") != std::string::npos);
  CHECK(e.find("model.bearings[0].position: must lie on its segment") != std::string::npos);
  e = error_of("a1.toml", kDeck + "[model.abutments]\nseat = \"rubber\"\n" + kSolver);
  CHECK(e.find("model.abutments.seat") != std::string::npos);
  e = error_of("a2.toml", kDeck + "[model.abutments]\nseat_height = 1.0\n" + kSolver);
  CHECK(e.find("model.abutments.seat_height: unknown key") != std::string::npos);
}
