// Bridges in parts in scene files (docs/scenes.md, "A deck in segments", kind = "deck_chain"):
// one segment reproduces [model.deck] bit for bit, the outputs name each body's coordinates,
// and every rule of the layout is an error naming the file, line and key.
#include "scene/scene.hpp"
#include "scene/test/scene_files.hpp"

#include "integrators/moreau_jean.hpp"
#include "integrators/recorder.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <unistd.h>

namespace fs = std::filesystem;
namespace ni = nsb::integrators;
using nsb::scene::load_scene;

namespace {

using nsb::scene::test_files::error_of;
using nsb::scene::test_files::write;

bool contains(const std::string& s, const std::string& part) {
  const bool ok = s.find(part) != std::string::npos;
  if (!ok) MESSAGE("'" << s << "' does not contain '" << part << "'");
  return ok;
}

const std::string kSolver = R"(
[solver]
method = "moreau"
end_time = 0.3
step = 1.0e-4
)";

// The benchmark's bents on one deck of 33.53 m, moving towards the right seat.
const std::string kBents = R"(
[[model.bents]]
position = -8.3825
height = 1.83
[[model.bents]]
position = 0.0
height = 2.44
[[model.bents]]
position = 8.3825
height = 1.52
[model.gaps]
left = 0.0127
right = 0.0127
)";

const std::string kDeck = R"([model]
kind = "bridge"
[model.deck]
mass = 140.5
inertia = 13090.0
length = 33.53
width = 2.44
skew_deg = 20.0
initial_velocity = [1.0, 0.05, 0.001]
)";

const std::string kOneSegment = R"([model]
kind = "bridge"
skew_deg = 20.0
[[model.segments]]
mass = 140.5
inertia = 13090.0
length = 33.53
width = 2.44
initial_velocity = [1.0, 0.05, 0.001]
)";

const std::string kTwoSegments = R"([model]
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
)";

const std::string kTwoBents = R"(
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
)";

const std::string kHinge = R"(
[[model.hinges]]
gap = 0.03
restitution = 0.0
friction = 0.5
)";

ni::Recorder run(const std::string& name, const std::string& text) {
  auto scene = load_scene(write(name, text));
  ni::Recorder rec(*scene.system, 0.0);
  const auto r = ni::moreau_jean(*scene.system, std::get<ni::MoreauJeanOptions>(scene.run), rec);
  REQUIRE(r.completed);
  return rec;
}

}  // namespace

TEST_CASE("one [[model.segments]] element is [model.deck], bit for bit") {
  // Within 0.3 s at 1 m/s the deck pounds the right seat (impacts checked below), skewed.
  const ni::Recorder a = run("deck.toml", kDeck + kBents + kSolver);
  const ni::Recorder b = run("one-segment.toml", kOneSegment + kBents + kSolver);
  REQUIRE(a.rows() == b.rows());
  REQUIRE(a.columns() == b.columns());
  CHECK(a.count(ni::EventKind::kImpact) > 0);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.rows(); ++i) {
    for (std::size_t c = 0; c < a.columns().size(); ++c) differ += a.at(i, c) != b.at(i, c);
  }
  CHECK(differ == 0);
}

TEST_CASE("two segments: coordinates x1 ... omega2, then the contacts joint by joint") {
  auto scene = load_scene(write("two.toml", kTwoSegments + kHinge + kTwoBents + kSolver));
  const auto q = scene.system->coordinate_names();
  CHECK(q == std::vector<std::string>{"x1", "y1", "theta1", "x2", "y2", "theta2"});
  CHECK(scene.system->velocity_names() ==
        std::vector<std::string>{"vx1", "vy1", "omega1", "vx2", "vy2", "omega2"});
  CHECK(scene.system->contacts() == 6);  // left seat, hinge, right seat
  // At rest every coordinate is 0 (displacements from the rest layout) and every gap open.
  CHECK(scene.system->initial_position().norm() == 0.0);
  std::vector<ni::ContactData> c;
  scene.system->contact_data(0.0, scene.system->initial_position(),
                             scene.system->initial_velocity(), c);
  CHECK(std::abs(c[0].gap_normal - 0.0127) < 1e-12);  // [model.gaps] default: the benchmark's
  CHECK(std::abs(c[2].gap_normal - 0.03) < 1e-12);    // the hinge
  CHECK(std::abs(c[3].gap_normal - 0.03) < 1e-12);
  CHECK(std::abs(c[5].gap_normal - 0.0127) < 1e-12);
}

TEST_CASE("neighbouring segments of different widths: the narrower one's corners meet the hinge") {
  // Segment 0 is 2.44 m wide, segment 1 3.00 m (docs/bridge.md, "Contacts with edges"). At
  // rest each side of the hinge has two pairs: segment 1's corner at y = +-1.50 on segment 0's
  // face, which ends at +-1.22 (beyond its edge), and segment 0's corner at y = +-1.22 on
  // segment 1's face (on it). The side's contact is the latter: with A = segment 0 (the
  // corner, r_A = (8.375, +-1.22) from its centre) and B = segment 1 (its left face, the normal
  // out of B towards A n = (-1, 0), d = r_A - (16.78, 0) from B's centre), the columns are
  // W_N,A = (n, r_A x n) = (-1, 0, +-1.22) and W_N,B = (-n, -d x n) = (1, 0, -+1.22).
  std::string wide = kTwoSegments;
  wide.replace(wide.rfind("width = 2.44"), 12, "width = 3.00");
  auto scene = load_scene(write("wide.toml", wide + kHinge + kTwoBents + kSolver));
  std::vector<ni::ContactData> c;
  scene.system->contact_data(0.0, scene.system->initial_position(),
                             scene.system->initial_velocity(), c);
  REQUIRE(c.size() == 6);
  for (int side = 0; side < 2; ++side) {
    const auto& k = c[static_cast<std::size_t>(2 + side)];
    const double y = side == 0 ? 1.22 : -1.22;
    Eigen::VectorXd expected(6);
    expected << -1.0, 0.0, y, 1.0, 0.0, -y;
    INFO("hinge side " << side << ": W_N = " << k.w_normal.transpose());
    CHECK_FALSE(k.far);
    CHECK(std::abs(k.gap_normal - 0.03) < 1e-12);
    CHECK((k.w_normal - expected).cwiseAbs().maxCoeff() < 1e-12);
  }
  // The right seat's contacts are segment 1's corners, at its own half width: their arms
  // about its centre differ from segment 0's by the widths (r x n = -+1.50 against -+1.22).
  CHECK(std::abs(std::abs(c[4].w_normal(5)) - 1.5) < 1e-12);
  CHECK(std::abs(std::abs(c[0].w_normal(2)) - 1.22) < 1e-12);
}

TEST_CASE("bad layouts are errors naming file, line and key") {
  const std::string no_hinge = error_of("nohinge.toml", kTwoSegments + kTwoBents);
  CHECK(contains(no_hinge, "nohinge.toml:1:1: model: needs 1 [[model.hinges]]"));
  const std::string two_hinges =
      error_of("twohinges.toml", kTwoSegments + kHinge + kHinge + kTwoBents);
  CHECK(contains(two_hinges, "twohinges.toml:"));
  CHECK(contains(two_hinges, "model.hinges: needs 1 [[model.hinges]]"));
  std::string bad_segment = kTwoBents;
  bad_segment.replace(bad_segment.find("segment = 1"), 11, "segment = 2");
  const std::string range = error_of("range.toml", kTwoSegments + kHinge + bad_segment);
  CHECK(contains(range, "model.bents[2].segment: must name one of the 2 [[model.segments]]"));
  std::string off = kTwoBents;
  off.replace(off.find("position = 8.0"), 14, "position = 9.0");
  const std::string off_segment = error_of("off.toml", kTwoSegments + kHinge + off);
  CHECK(contains(off_segment, "model.bents[1].position: must lie on segment 0"));
  const std::string one_bent = error_of(
      "onebent.toml", kTwoSegments + kHinge + "[[model.bents]]\nposition = 0.0\nheight = 1.8\n" +
                          "[[model.bents]]\nposition = 2.0\nheight = 1.8\n");
  CHECK(contains(one_bent, "model.bents: segment 1 needs bents at two distinct positions"));
  const std::string both = error_of("both.toml", kTwoSegments + "[model.deck]\nmass = 1.0\n");
  CHECK(contains(both, "model.deck: give either [model.deck]"));
  const std::string chain = error_of("chain.toml", R"([model]
kind = "deck_chain"
[[model.decks]]
mass = 1.0
inertia = 1.0
length = 10.0
width = 2.0
[[model.joints]]
gap = 0.1
)");
  CHECK(contains(chain, "model.joints: needs 2 [[model.joints]]"));
}

TEST_CASE("every shipped scene in parts loads") {
  for (const char* name : {"bridge-two-frame.toml", "bridge-skew-three-span.toml",
                           "deck-chain-two.toml"}) {
    INFO(name);
    const auto scene = load_scene(fs::path(NSB_SCENES_DIR) / name);
    CHECK(scene.system->dofs() == 6);
    CHECK(scene.system->contacts() == 6);
  }
}
