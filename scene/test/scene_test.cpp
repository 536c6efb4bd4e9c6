// Scene files (scene/scene.hpp): every shipped scene loads; every bad input gives an error
// naming the file and the key or line; overrides apply before validation.
#include "scene/scene.hpp"
#include "scene/test/scene_files.hpp"

#include "integrators/run.hpp"
#include "models/bridge_design.hpp"
#include "models/simple_systems.hpp"

#include <doctest/doctest.h>
#include <toml++/toml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <unistd.h>

namespace fs = std::filesystem;
using nsb::scene::load_scene;
namespace ni = nsb::integrators;

namespace {

using nsb::scene::test_files::error_of;
using nsb::scene::test_files::scratch_dir;
using nsb::scene::test_files::write;

bool contains(const std::string& s, const std::string& part) {
  const bool ok = s.find(part) != std::string::npos;
  if (!ok) MESSAGE("'" << s << "' does not contain '" << part << "'");
  return ok;
}

const std::string kBall = R"([model]
kind = "bouncing_ball"
mass = 1.0
height = 1.0
restitution = 0.9
)";

const std::string kDeck = R"([model]
kind = "rigid_deck"
mass = 140.5
inertia = 13090.0
length = 33.35
width = 2.44
gap_right = 0.0127
gap_left = 0.0127
restitution = 0.0
friction = 0.5
)";

// A bridge scene with the record files given by the caller (line 14 holds the record).
std::string bridge_scene(const std::string& record) {
  return R"([model]
kind = "bridge"
[[model.bents]]
position = -8.34
height = 1.83
[[model.bents]]
position = 0.0
height = 2.44
[[model.bents]]
position = 8.34
height = 1.52
[model.excitation]
time_scale = 0.5
transverse_record = ")" + record + R"("
target_pga = 0.5
)";
}

}  // namespace

TEST_CASE("every scene in scenes/ loads and builds its system") {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(NSB_SCENES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    CAPTURE(entry.path().string());
    const auto scene = load_scene(entry.path());
    CHECK(scene.system != nullptr);
    CHECK(scene.name == entry.path().stem().string());
    CHECK(ni::end_time(scene.run) > 0);
    if (scene.kind == "bridge") {
      // N deck segments (N = 1: [model.deck]): 3 N coordinates, two contacts per joint (two
      // seats, N - 1 hinges); one deck has 3 and 4. Shear keys add four contacts; backfill
      // abutments add a backwall body each (3 coordinates, no contact of its own: the deck's
      // corners touch it).
      const toml::table file = toml::parse_file(entry.path().string());
      const bool backfill =
          file["model"]["abutments"]["seat"].value_or(std::string()) == "backfill";
      const int keys = file["model"]["shear_keys"] ? 4 : 0;
      const int segments = scene.system->dofs() / 3 - (backfill ? 2 : 0);
      CHECK(scene.system->dofs() == 3 * (segments + (backfill ? 2 : 0)));
      CHECK(scene.system->contacts() == 2 * (segments + 1) + keys);
      if (scene.name.rfind("bridge-exc", 0) == 0) CHECK(scene.system->dofs() == 3);
      // The record is covered: RSN 1084 (43.9 s) compressed by 0.5, or RSN 988 (39.98 s).
      CHECK(ni::end_time(scene.run) >= 21.9);
    }
    ++count;
  }
  CHECK(count >= 16);  // 8 bridge runs, 2 rigid decks, 3 simple systems, 3 bridges in parts
}

TEST_CASE("the bridge runs scale each component to its own target PGA") {
  // Runs 6 and 7: about 1.0 g transverse and 1.2 g longitudinal (Saiidi, Vosooghi & Nelson
  // 2013); RSN 988 has 2000 samples at 0.02 s (data/README.md), not compressed in time.
  const auto scene = load_scene(fs::path(NSB_SCENES_DIR) / "bridge-exc7.toml");
  const nsb::models::BridgeDesign& b = scene.design.value();
  const auto& e = b.excitation;
  REQUIRE(e.bents.size() == 3);
  REQUIRE(e.bents[0].transverse != nullptr);
  REQUIRE(e.bents[0].longitudinal != nullptr);
  // Baseline correction changes the peak acceleration slightly: 2 %.
  CHECK(e.bents[0].transverse->pga() == doctest::Approx(1.0 * 9.81).epsilon(0.02));
  CHECK(e.bents[0].longitudinal->pga() == doctest::Approx(1.2 * 9.81).epsilon(0.02));
  CHECK(e.bents[0].transverse->duration() == doctest::Approx(1999 * 0.02).epsilon(1e-9));
  // The deck is 110 ft = 33.528 m long (published), the bents at -L/4, 0, +L/4.
  CHECK(b.deck.length == doctest::Approx(110 * 0.3048).epsilon(1e-4));
  // The seats follow the longitudinal motion only (published: longitudinal actuators).
  CHECK(e.seats[0].longitudinal != nullptr);
  CHECK(e.seats[0].transverse == nullptr);
  CHECK(b.friction == 0.5);
  CHECK(b.restitution == 0.0);
  CHECK(b.mass == 140.5);
}

TEST_CASE("without longitudinal_pga both components take the factor of target_pga") {
  // RSN 988: 090 has a PGA of 0.2556669 g, 360 of 0.2216674 g (the largest |value| in each
  // file). Scaling 360 to 1.0 g with one factor scales 090 to 0.2556669 / 0.2216674 g.
  const auto scene = load_scene(fs::path(NSB_SCENES_DIR) / "bridge-exc7.toml",
                                {"model.excitation.longitudinal_pga=0"});
  const auto& e = scene.design.value().excitation;
  const double ratio = 0.2556669 / 0.2216674;
  // The two motions' baseline corrections differ: measured ratio error 0.3 %, allowed 1 %.
  CHECK(e.bents[0].longitudinal->pga() / e.bents[0].transverse->pga() ==
        doctest::Approx(ratio).epsilon(0.01));
}

TEST_CASE("longitudinal_pga without a longitudinal record is an error naming the key") {
  const std::string record = std::string(NSB_DATA_DIR) + "/ground-motions/RSN988_NORTHR_CCN360.AT2";
  const auto e = error_of("lpga.toml", bridge_scene(record) + "longitudinal_pga = 1.2\n");
  CHECK(contains(e, "lpga.toml:16:"));  // the line after the 15 of bridge_scene
  CHECK(contains(e, "model.excitation.longitudinal_pga"));
  CHECK(contains(e, "longitudinal_record"));
}

TEST_CASE("a scene without [model] is reported at the file's first position, with no empty key") {
  // The top-level table has no key of its own: "<file>:1:1: missing table [model]", not
  // "<file>:1:1: : missing table [model]".
  const auto e = error_of("nomodel.toml", "[solver]\nmethod = \"moreau\"\n");
  CHECK(e.find("nomodel.toml:1:1: missing table [model]") != std::string::npos);
  CHECK(e.find(": :") == std::string::npos);
}

TEST_CASE("scale_to = \"sa\": errors name the file, the line and the key") {
  const std::string record = std::string(NSB_DATA_DIR) + "/ground-motions/RSN988_NORTHR_CCN360.AT2";
  const std::string sa = "scale_to = \"sa\"\ntarget_sa = 0.5\n";  // lines 16 and 17
  struct Case {
    std::string text, line, key, what;
  };
  // A record of zeros: its PSA is zero at every period.
  const fs::path zero = write("zero.txt", "0 0\n0.01 0\n0.02 0\n0.03 0\n");
  std::string no_record = bridge_scene(record);
  no_record.replace(no_record.find("transverse_record"), 17, "# transverse_record");
  const std::vector<Case> cases = {
      {no_record + sa, ":16:", "model.excitation.scale_to", "needs a transverse_record"},
      {bridge_scene(zero.string()) + sa, ":17:", "model.excitation.target_sa",
       "spectral acceleration at sa_period"},
      {bridge_scene(record) + sa + "sa_period = 0\n", ":18:", "model.excitation.sa_period", "> 0"},
      {bridge_scene(record) + sa + "sa_period = -1\n", ":18:", "model.excitation.sa_period", "> 0"},
      {bridge_scene(record) + "scale_to = \"sa\"\ntarget_sa = -0.5\n", ":17:",
       "model.excitation.target_sa", "must be in [0, 20] [g]"},
      {bridge_scene(record) + "target_sa = 0.5\n", ":16:", "model.excitation.target_sa",
       "needs scale_to = \"sa\""},
      {bridge_scene(record) + "scale_to = \"spectral\"\n", ":16:", "model.excitation.scale_to",
       "pga"},
      {bridge_scene(record) + sa + "longitudinal_sa = 0.5\n", ":18:",
       "model.excitation.longitudinal_sa", "needs a longitudinal_record"},
  };
  for (const auto& c : cases) {
    const auto e = error_of("sa.toml", c.text);
    INFO(c.text);
    CHECK(contains(e, "sa.toml" + c.line));
    CHECK(contains(e, c.key));
    CHECK(contains(e, c.what));
  }
}

TEST_CASE("the scene reports each component's PGA, PSA and factor; none without a record") {
  // bridge-exc7 scales RSN 988 360 to 1.0 g transverse and 090 to 1.2 g longitudinal.
  const auto scene = load_scene(fs::path(NSB_SCENES_DIR) / "bridge-exc7.toml");
  REQUIRE(scene.input.transverse);
  REQUIRE(scene.input.longitudinal);
  const auto& t = *scene.input.transverse;
  CHECK(t.pga_g == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(scene.input.longitudinal->pga_g == doctest::Approx(1.2).epsilon(1e-12));
  // PGA 0.2216674 g in the file (RSN988_NORTHR_CCN360.AT2): the factor is 1.0 / 0.2216674.
  CHECK(t.scale_factor == doctest::Approx(1.0 / 0.2216674).epsilon(1e-6));
  CHECK(t.sa_damping == 0.05);
  CHECK(t.sa_period == nsb::integrators::natural_periods(*scene.system).front());
  CHECK(t.sa_g > 0);
  const auto ball = load_scene(fs::path(NSB_SCENES_DIR) / "bouncing-ball.toml");
  CHECK(!ball.input.transverse);
  CHECK(!ball.input.longitudinal);
}

TEST_CASE("overrides apply before validation") {
  const fs::path p = fs::path(NSB_SCENES_DIR) / "bouncing-ball.toml";
  const auto scene = load_scene(p, {"model.restitution=0.5", "solver.step=1e-5",
                                    "solver.method=event_driven", "output.sample_dt=0.01"});
  const auto& ball = dynamic_cast<const nsb::models::BouncingBall&>(*scene.system);
  CHECK(ball.parameters().restitution == 0.5);
  CHECK(ni::method_name(scene.run) == "event_driven");
  CHECK(scene.output.sample_dt == 0.01);
  // solver.step is Moreau–Jean's: it reaches the run under that method.
  const auto moreau = load_scene(p, {"solver.step=1e-5"});
  CHECK(std::get<ni::MoreauJeanOptions>(moreau.run).step == 1e-5);

  // A key absent from the file but known to the schema, and an array element.
  const auto bridge = load_scene(fs::path(NSB_SCENES_DIR) / "bridge-exc1.toml",
                                 {"model.bents.1.height=2.0", "model.deck.skew_deg=10",
                                  "solver.end_time=1.0"});
  const nsb::models::BridgeDesign& b = bridge.design.value();
  nsb::models::BentDesign d;
  d.height = 2.0;
  CHECK(b.bents[1].transverse.k0 == doctest::Approx(d.stiffness()));
  CHECK(b.deck.skew_deg == 10.0);
  CHECK(ni::end_time(bridge.run) == 1.0);

  // Unknown keys and bad values through overrides.
  CHECK(contains(error_of("ov1.toml", kBall, {"solver.stepp=1e-5"}), "solver.stepp (override)"));
  CHECK(contains(error_of("ov2.toml", kBall, {"solver.stepp=1e-5"}), "unknown key"));
  CHECK(contains(error_of("ov3.toml", kBall, {"model.mass=-2"}), "model.mass (override)"));
  CHECK(contains(error_of("ov4.toml", kBall, {"nonsense"}), "section.key=value"));
  CHECK(contains(error_of("ov5.toml", kBall, {"bogus.key=1"}), "bogus"));
}

TEST_CASE("an override index out of range is bad input, however many digits it has") {
  const fs::path p = fs::path(NSB_SCENES_DIR) / "bridge-exc1.toml";
  // 2^64 - 1, 2^64 and far beyond: the index is past the end of the three bents.
  for (const std::string index : {"3", "18446744073709551615", "18446744073709551616",
                                  "99999999999999999999"}) {
    INFO(index);
    const std::string o = "model.bents." + index + ".height=1";
    const std::string expected =
        "model.bents." + index + ": index out of range; model.bents has 3 elements";
    CHECK_THROWS_WITH_AS(load_scene(p, {o}), doctest::Contains(expected.c_str()),
                         std::invalid_argument);
  }
}

TEST_CASE("bad input: each case names the file, the key and the line") {
  SUBCASE("negative mass") {
    const auto e = error_of("neg-mass.toml", R"([model]
kind = "bouncing_ball"
mass = -1.0
)");
    CHECK(contains(e, "neg-mass.toml:3:"));
    CHECK(contains(e, "model.mass"));
    CHECK(contains(e, "> 0"));
  }
  SUBCASE("mu < 0") {
    auto text = kDeck;
    text.replace(text.find("friction = 0.5"), 14, "friction = -0.1");
    const auto e = error_of("neg-mu.toml", text);
    CHECK(contains(e, "neg-mu.toml:10:"));
    CHECK(contains(e, "model.friction"));
  }
  SUBCASE("eps outside [0, 1]") {
    const auto e = error_of("eps.toml", R"([model]
kind = "bouncing_ball"
restitution = 1.2
)");
    CHECK(contains(e, "eps.toml:3:"));
    CHECK(contains(e, "model.restitution"));
    CHECK(contains(e, "[0, 1]"));
  }
  SUBCASE("initial penetration of the rigid deck") {
    const auto e = error_of("pen.toml", kDeck + "initial_position = [0.02, 0.0, 0.0]\n");
    CHECK(contains(e, "pen.toml:11:"));
    CHECK(contains(e, "model.initial_position"));
    CHECK(contains(e, "initial penetration"));
  }
  SUBCASE("initial penetration of the impact oscillator") {
    const auto e = error_of("pen-osc.toml", R"([model]
kind = "impact_oscillator"
gap = 0.1
initial_position = 0.2
)");
    CHECK(contains(e, "pen-osc.toml:4:"));
    CHECK(contains(e, "initial penetration"));
  }
  SUBCASE("initial penetration of the bridge") {
    // No record, so no target_pga (line 15 kept as a comment).
    std::string no_record = bridge_scene("");
    no_record.replace(no_record.find("target_pga"), 10, "# target_pga");
    const auto e = error_of("pen-bridge.toml",
                            no_record + "[model.deck]\ninitial_position = [0.0, 0.0, 0.02]\n");
    CHECK(contains(e, "pen-bridge.toml:17:"));
    CHECK(contains(e, "model.deck.initial_position"));
    CHECK(contains(e, "initial penetration"));
  }
  SUBCASE("missing record file") {
    const auto e = error_of("no-record.toml", bridge_scene("no-such-record.AT2"));
    CHECK(contains(e, "no-record.toml:14:"));
    CHECK(contains(e, "model.excitation.transverse_record"));
    CHECK(contains(e, "not found"));
  }
  SUBCASE("record with non-increasing time") {
    write("bad-time.txt", "0.0 0.1\n0.1 0.2\n0.1 0.3\n0.2 0.0\n");
    const auto e = error_of("bad-time.toml", bridge_scene("bad-time.txt"));
    CHECK(contains(e, "bad-time.toml:14:"));
    CHECK(contains(e, "model.excitation.transverse_record"));
    CHECK(contains(e, "increase"));
  }
  SUBCASE("unknown key") {
    const auto e = error_of("typo.toml", R"([model]
kind = "bouncing_ball"
mas = 1.0
)");
    CHECK(contains(e, "typo.toml:3:"));
    CHECK(contains(e, "model.mas"));
    CHECK(contains(e, "unknown key"));
  }
  SUBCASE("unknown key in a bent") {
    const auto e = error_of("typo-bent.toml", bridge_scene("") + "[[model.bents]]\nposition = 1.0\nhieght = 2.0\n");
    CHECK(contains(e, "typo-bent.toml:18:"));
    CHECK(contains(e, "model.bents[3].hieght"));
  }
  SUBCASE("wrong type") {
    const auto e = error_of("type.toml", R"([model]
kind = "bouncing_ball"
mass = "heavy"
)");
    CHECK(contains(e, "type.toml:3:"));
    CHECK(contains(e, "model.mass"));
    CHECK(contains(e, "expected a number"));
  }
  SUBCASE("unknown kind") {
    const auto e = error_of("kind.toml", "[model]\nkind = \"truss\"\n");
    CHECK(contains(e, "kind.toml:2:"));
    CHECK(contains(e, "bouncing_ball"));
  }
  SUBCASE("bad solver settings") {
    CHECK(contains(error_of("s1.toml", kBall + "[solver]\nmethod = \"rk4\"\n"), "s1.toml:7:"));
    CHECK(contains(error_of("s2.toml", kBall + "[solver]\ntheta = 0.2\n"), "solver.theta"));
    CHECK(contains(error_of("s3.toml", kBall + "[solver]\nlcp_solver = \"magic\"\n"), "solver.lcp_solver"));
    CHECK(contains(error_of("s4.toml", kBall + "[solver]\nend_time = 1.0\nstep = 2.0\n"), "solver.step"));
    CHECK(contains(error_of("s5.toml", kBall + "[output]\nsample_dt = -1\n"), "output.sample_dt"));
    CHECK(contains(error_of("s6.toml", kBall + "[solver]\nend_time = nan\n"), "finite"));
  }
  SUBCASE("TOML syntax error") {
    const auto e = error_of("syntax.toml", "[model]\nkind = \"bouncing_ball\"\nmass = = 1\n");
    CHECK(contains(e, "syntax.toml:3:"));
  }
  SUBCASE("missing file") {
    std::string e;
    try {
      load_scene(scratch_dir() / "absent.toml");
    } catch (const std::invalid_argument& ex) {
      e = ex.what();
    }
    CHECK(contains(e, "absent.toml"));
  }
  SUBCASE("bridge without enough bents") {
    const auto e = error_of("bents.toml", "[model]\nkind = \"bridge\"\n[[model.bents]]\nposition = 0.0\nheight = 2.0\n");
    CHECK(contains(e, "bents.toml:"));
    CHECK(contains(e, "model.bents"));
  }
  SUBCASE("a bent without height nor explicit springs") {
    const auto e = error_of("noheight.toml", bridge_scene("") + "[[model.bents]]\nposition = 1.0\n");
    CHECK(contains(e, "noheight.toml:16:"));
    CHECK(contains(e, "height"));
  }
}

TEST_CASE("explicit bent springs replace the derived ones") {
  const std::string text = R"([model]
kind = "bridge"
[[model.bents]]
position = -5.0
stiffness_longitudinal = 1000.0
yield_force_longitudinal = 50.0
stiffness_transverse = 2000.0
yield_force_transverse = 60.0
[[model.bents]]
position = 5.0
height = 2.0
stiffness_transverse = 3000.0
)";
  const fs::path p = write("explicit.toml", text);
  const auto scene = load_scene(p);
  const nsb::models::BridgeDesign& b = scene.design.value();
  CHECK(b.bents[0].longitudinal.k0 == doctest::Approx(1000.0));
  CHECK(b.bents[0].longitudinal.d_yield == doctest::Approx(0.05));
  CHECK(b.bents[0].transverse.f_yield == doctest::Approx(60.0));
  nsb::models::BentDesign d;
  d.height = 2.0;
  CHECK(b.bents[1].transverse.k0 == doctest::Approx(3000.0));
  CHECK(b.bents[1].transverse.f_yield == doctest::Approx(d.yield_force()));
  CHECK(b.bents[1].longitudinal.k0 == doctest::Approx(d.stiffness()));
  // No excitation: the default end time stays.
  CHECK(ni::end_time(scene.run) == 1.0);
}

TEST_CASE("per-support delays and a prescribed seat rotation") {
  // Angular acceleration 1e-3 rad/s^2 for 1 s, then zero: a two-column record in rad/s^2.
  write("rot.txt", "0.0 0.001\n0.5 0.001\n1.0 0.001\n1.01 0.0\n2.0 0.0\n");
  const std::string text = R"([model]
kind = "bridge"
[[model.bents]]
position = -8.34
height = 1.83
delay = 0.2
[[model.bents]]
position = 8.34
height = 1.52
[model.seats]
delay_right = 0.3
transverse = true
rotation_record_right = "rot.txt"
[model.excitation]
transverse_record = "ground-motions/RSN1084_NORTHR_SCS142.AT2"
longitudinal_record = "ground-motions/RSN1084_NORTHR_SCS052.AT2"
target_pga = 0.2
time_scale = 0.5
)";
  // The scene sits in the scratch folder: the records are found through ./data/ only if the
  // working directory is the project root, so give the absolute data path instead.
  std::string t = text;
  const std::string data = std::string(NSB_DATA_DIR) + "/";
  for (const char* rec : {"ground-motions/RSN1084_NORTHR_SCS142.AT2", "ground-motions/RSN1084_NORTHR_SCS052.AT2"}) {
    t.replace(t.find(rec), std::string(rec).size(), data + rec);
  }
  const fs::path p = write("delays.toml", t);
  const auto scene = load_scene(p);
  const nsb::models::BridgeDesign& b = scene.design.value();
  const auto& e = b.excitation;
  // Delayed supports start later by their delay; undelayed ones share the same motion.
  CHECK(e.bents[0].transverse->start_time() == doctest::Approx(e.bents[1].transverse->start_time() + 0.2));
  CHECK(e.seats[0].longitudinal == e.bents[1].longitudinal);
  CHECK(e.seats[1].longitudinal->start_time() == doctest::Approx(e.seats[0].longitudinal->start_time() + 0.3));
  CHECK(e.seats[1].transverse != nullptr);
  REQUIRE(e.seats[1].rotation != nullptr);
  CHECK(e.seats[0].rotation == nullptr);
  // End time: the longest support motion, including its delay.
  CHECK(ni::end_time(scene.run) == doctest::Approx(e.bents[0].transverse->end_time()));
}

TEST_CASE("every integrator option is reachable from the [solver] table") {
  const std::string text = kBall + R"([solver]
method = "event_driven"
end_time = 0.5
max_step = 1e-3
max_events_per_window = 50
lcp_solver = "pgs"
step = 1e-3
theta = 1.0
lcp_fallback = false
)";
  const auto scene = load_scene(write("options.toml", text));
  const auto& ed = std::get<ni::EventDrivenOptions>(scene.run);
  CHECK(ed.end_time == 0.5);
  CHECK(ed.max_step == 1e-3);
  CHECK(ed.max_events_per_window == 50);
  CHECK(ed.solver == nsb::lcp::Solver::kPgs);
  // The Moreau–Jean keys of the same table reach the run when --method switches to it.
  const auto mj = load_scene(write("options.toml", text), {"solver.method=moreau"});
  const auto& o = std::get<ni::MoreauJeanOptions>(mj.run);
  CHECK(o.step == 1e-3);
  CHECK(o.theta == 1.0);
  CHECK(!o.lcp_fallback);
  CHECK(o.solver == nsb::lcp::Solver::kPgs);
  // Compliance keeps the Hertz stiffness and its factor as two fields.
  const auto cp = load_scene(write("options.toml", text),
                             {"solver.method=compliance", "solver.contact_stiffness=1e5",
                              "solver.stiffness_factor=100", "solver.damping_law=flores"});
  const auto& c = std::get<ni::ComplianceOptions>(cp.run);
  CHECK(c.stiffness == 1e5);
  CHECK(c.stiffness_factor == 100.0);
  CHECK(c.law == ni::DampingLaw::kFlores);
}

TEST_CASE("a [solver] value is checked against its method's range, naming file and key") {
  const fs::path p = fs::path(NSB_SCENES_DIR) / "bouncing-ball.toml";
  const auto e = error_of("tol.toml", kBall, {"solver.method=compliance", "solver.tolerance=0.5"});
  CHECK(contains(e, "tol.toml: solver.tolerance (override): must be in (0, 0.1)"));
  // A key of another method is accepted when that method accepts it, and refused otherwise.
  CHECK(error_of("tol2.toml", kBall + "[solver]\ntolerance = 0.5\n").empty());
  CHECK(contains(error_of("tol3.toml", kBall + "[solver]\ntolerance = 5.0\n"),
                 "tol3.toml:7:13: solver.tolerance: for event_driven, must be in (0, 1) (got 5)"));
  // The bridge's default end time and the check step <= end_time against it.
  CHECK(contains(error_of("step.toml", kBall + "[solver]\nstep = 2.0\n"),
                 "step.toml:7:8: solver.step: must be <= end_time (1 s)"));
}

TEST_CASE("an unknown [solver] key names every key the methods declare") {
  const auto e = error_of("unknown.toml", kBall + "[solver]\nstepp = 1e-5\n");
  CHECK(contains(e, "unknown.toml:7:9: solver.stepp: unknown key; did you mean `step`?; "
                    "allowed here: method, "
                    "end_time, step, theta, lcp_solver, lcp_tolerance, lcp_fallback, "
                    "event_velocity_tolerance, local_tolerance, min_step, max_step, tolerance, "
                    "event_time_tolerance"));
  CHECK(contains(e, "contact_stiffness, stiffness_factor, reference_mass, damping_law"));
}

TEST_CASE("[output] groups: names checked at the key, with the closest name") {
  CHECK(error_of("groups.toml", kBall + "[output]\ngroups = [\"energy\", \"forces\"]\n").empty());
  CHECK(contains(error_of("groups2.toml", kBall + "[output]\ngroups = [\"energie\"]\n"),
                 "groups2.toml:7:10: output.groups: unknown output group 'energie'; did you mean "
                 "`energy`? (allowed: bents, relative, ground, energy, forces, impulses)"));
  CHECK(contains(error_of("groups3.toml", kBall + "[output]\ngroups = [1]\n"),
                 "groups3.toml:7:10: output.groups: must be an array of group names"));
}
