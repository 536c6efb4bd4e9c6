// [[model.excitation.sequence]] (docs/scenes.md, docs/ground-motions.md, "Sequences"): the
// records' places in time, the keys that apply per record (amplitude, the trust warnings'
// sampling step), the default end time, and the refused forms, each at its file, line and key.
#include "models/assembly.hpp"
#include "models/ground_motion.hpp"
#include "scene/scene.hpp"
#include "scene/test/scene_files.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

namespace {

namespace tf = nsb::scene::test_files;

// A two-column record of `samples` + 1 samples at step dt from t = 0 (times written exactly):
// a sine of period 0.3 s and amplitude 1 m/s^2.
std::string record(const std::string& name, double dt, int samples) {
  std::string text;
  for (int i = 0; i <= samples; ++i) {
    char line[64];
    std::snprintf(line, sizeof line, "%.3f %.17g\n", i * dt,
                  std::sin(2.0 * std::numbers::pi * i * dt / 0.3));
    text += line;
  }
  return tf::write(name, text).string();
}

// The samples of record(name, dt, samples), as the reader reads them back.
nsb::models::Record samples(double dt, int n) {
  nsb::models::Record r;
  r.source = "synthetic";
  for (int i = 0; i <= n; ++i) {
    char t[32], a[32];
    std::snprintf(t, sizeof t, "%.3f", i * dt);
    std::snprintf(a, sizeof a, "%.17g", std::sin(2.0 * std::numbers::pi * i * dt / 0.3));
    r.t.push_back(std::stod(t));
    r.a.push_back(std::stod(a));
  }
  return r;
}

double peak(const nsb::models::Record& r) {
  double p = 0.0;
  for (double a : r.a) p = std::max(p, std::abs(a));
  return p;
}

const std::string kBridge = R"([model]
kind = "bridge"
[[model.bents]]
position = -8.0
height = 2.0
[[model.bents]]
position = 8.0
height = 2.0
)";

// A: 1.5 s at 0.01 s; B: 1 s at 0.005 s.
std::string two_records(const std::string& extra_first = "", const std::string& extra = "") {
  const std::string a = record("a.txt", 0.01, 150), b = record("b.txt", 0.005, 200);
  return kBridge + "[model.excitation]\n" + extra + "[[model.excitation.sequence]]\n" +
         "transverse_record = \"" + a + "\"\ntarget_pga = 0.5\nrest = 2.0\n" + extra_first +
         "[[model.excitation.sequence]]\ntransverse_record = \"" + b +
         "\"\ntarget_pga = 0.2\nrest = 0.75\n";
}

}  // namespace

TEST_CASE("a sequence places its records in turn, each with its own amplitude") {
  const nsb::scene::Scene s = nsb::scene::load_scene(tf::write("seq.toml", two_records()));
  // Default end: A's last sample 1.5 s + rest 2 s, B's 1 s, its rest 0.75 s.
  CHECK(nsb::integrators::end_time(s.run) == doctest::Approx(5.25).epsilon(1e-15));
  // The trust warnings' sampling step: the finest record's (B's 0.005 s), whichever comes first.
  CHECK(s.record_step == doctest::Approx(0.005).epsilon(1e-12));
  // summary.json's input describes the last record (the aftershock a study varies).
  REQUIRE(s.input.transverse);
  CHECK(s.input.transverse->pga_g == doctest::Approx(0.2).epsilon(1e-12));
  const auto& bridge = dynamic_cast<const nsb::models::Assembly&>(*s.system);
  const auto& motion = bridge.parts().bents[0].ground_transverse;
  REQUIRE(motion);
  CHECK(motion->start_time() == 0.0);
  CHECK(motion->end_time() == doctest::Approx(4.5).epsilon(1e-15));
  // Each record scaled to its own target (factor = target g / its peak sample, the scene's
  // rule): over A's span the motion is A's own motion times A's factor, over B's span B's,
  // delayed to 3.5 s, and nothing in the rest between them.
  const nsb::models::Record ra = samples(0.01, 150), rb = samples(0.005, 200);
  const nsb::models::GroundMotion unit_a(ra);
  nsb::models::GroundMotionOptions ob;
  ob.delay = 3.5;
  const nsb::models::GroundMotion unit_b(rb, ob);
  const double fa = 0.5 * 9.81 / peak(ra), fb = 0.2 * 9.81 / peak(rb);
  for (int i = 0; i <= 4500; ++i) {
    const double t = i * 1e-3;
    INFO("t = " << t);
    const double a = motion->acceleration(t);
    if (t <= 1.5) CHECK(a == doctest::Approx(fa * unit_a.acceleration(t)).epsilon(1e-9));
    if (t > 1.5 && t <= 3.5) CHECK(a == 0.0);
    if (t > 3.5) CHECK(a == doctest::Approx(fb * unit_b.acceleration(t)).epsilon(1e-9));
  }
}

TEST_CASE("a sequence's entries are read by key, with overrides") {
  const nsb::scene::Scene s = nsb::scene::load_scene(
      tf::write("seq-set.toml", two_records()), {"model.excitation.sequence.1.target_pga=0.4",
                                                 "model.excitation.sequence.0.rest=1.0"});
  REQUIRE(s.input.transverse);
  CHECK(s.input.transverse->pga_g == doctest::Approx(0.4).epsilon(1e-12));
  CHECK(nsb::integrators::end_time(s.run) == doctest::Approx(4.25).epsilon(1e-15));
}

TEST_CASE("a bad sequence is refused at its file, line and key") {
  const auto has = [](const std::string& msg, const std::string& fragment) {
    INFO("message: " << msg);
    CHECK(msg.find(fragment) != std::string::npos);
  };
  // An empty sequence.
  std::string msg = tf::error_of("empty.toml", kBridge + "[model.excitation]\nsequence = []\n");
  has(msg, "empty.toml:10:");
  has(msg, "model.excitation.sequence");
  has(msg, "is empty");
  // A negative rest.
  msg = tf::error_of("negative.toml", two_records(), {"model.excitation.sequence.0.rest=-1"});
  has(msg, "model.excitation.sequence[0].rest");
  std::string text = two_records();
  text.replace(text.find("rest = 2.0"), 10, "rest = -2.0");
  msg = tf::error_of("negative-line.toml", text);
  has(msg, "negative-line.toml:");
  has(msg, "model.excitation.sequence[0].rest");
  // The single-record keys beside a sequence.
  msg = tf::error_of("mixed.toml", two_records("", "target_pga = 0.3\n"));
  has(msg, "mixed.toml:10:");
  has(msg, "model.excitation.target_pga");
  has(msg, "not both");
  // A key the sequence shares, given in an entry.
  msg = tf::error_of("shared.toml", two_records("time_scale = 0.5\n"));
  has(msg, "model.excitation.sequence[0].time_scale");
  has(msg, "shared by the records of a sequence");
  // An entry without a record.
  msg = tf::error_of("none.toml", kBridge + "[model.excitation]\n[[model.excitation.sequence]]\n"
                                            "rest = 1.0\n");
  has(msg, "model.excitation.sequence[0]");
  has(msg, "names no record");
}
