// The limit-state keys of a bridge scene (docs/limit-states.md): seat_length and
// [model.limit_states] make the bridge watch them; their errors name the key.
#include "scene/scene.hpp"

#include "models/assembly.hpp"

#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace {

std::filesystem::path scene_file(const std::string& text) {
  const auto p = std::filesystem::temp_directory_path() /
                 ("nsb-limit-watch-test-" + std::to_string(::getpid()) + ".toml");
  std::ofstream(p) << text;
  return p;
}

const std::string kBridge = R"([model]
kind = "bridge"
[[model.bents]]
position = -8.0
height = 1.83
[[model.bents]]
position = 8.0
stiffness_longitudinal = 1.0e4
yield_force_longitudinal = 100.0
stiffness_transverse = 1.0e4
yield_force_transverse = 100.0
[solver]
method = "moreau"
end_time = 0.1
step = 1.0e-3
)";

}  // namespace

TEST_CASE("scene: seat_length and [model.limit_states] make the bridge an Assembly") {
  const auto s = nsb::scene::load_scene(
      scene_file(kBridge + "[model.abutments]\nseat_length = 0.3\n"));
  CHECK(dynamic_cast<const nsb::models::Assembly*>(s.system.get()) != nullptr);
  const auto plain = nsb::scene::load_scene(scene_file(kBridge));
  CHECK(plain.system->limit_states().empty());  // a plain bridge watches nothing
  // drift_ratio needs every bent's height: the error names the bent and the key.
  try {
    nsb::scene::load_scene(scene_file(kBridge + "[model.limit_states]\ndrift_ratio = 0.02\n"));
    FAIL("expected an error");
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    CHECK(m.find("model.bents[1]") != std::string::npos);
    CHECK(m.find("missing key height") != std::string::npos);
    CHECK(m.find("drift_ratio") != std::string::npos);
  }
  CHECK_THROWS_WITH_AS(
      nsb::scene::load_scene(scene_file(kBridge + "[model.abutments]\nseat_length = -1\n")),
      doctest::Contains("seat_length"), std::invalid_argument);
  std::filesystem::remove(scene_file(""));
}
