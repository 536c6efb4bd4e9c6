// Record files as a scene reads them ([model.excitation], [model.seats]): the unit a file
// names against record_unit, files of values only with record_dt, amplitude keys that have no
// record to scale, and time_scale that collapses the sample times; each error names the scene
// file, the line and the key, and the record file.
#include "scene/scene.hpp"
#include "scene/test/scene_files.hpp"

#include "models/ground_motion.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>

using nsb::scene::load_scene;
using nsb::scene::test_files::error_of;
using nsb::scene::test_files::write;

namespace {

bool contains(const std::string& s, const std::string& part) {
  const bool ok = s.find(part) != std::string::npos;
  if (!ok) MESSAGE("'" << s << "' does not contain '" << part << "'");
  return ok;
}

// A bridge with the benchmark's bents and [model.excitation] from line 12 on: `excitation`
// holds its keys, one per line from line 13.
std::string bridge_with(const std::string& excitation) {
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
)" + excitation;
}

// A short record: 0.2 s of a 5 Hz sine of amplitude 0.5 (file units), sampled at 0.01 s.
std::string sine_values(const std::string& separator) {
  std::string out;
  for (int i = 0; i <= 20; ++i) {
    out += std::to_string(i * 0.01) + separator +
           std::to_string(0.5 * std::sin(2 * M_PI * 5 * i * 0.01)) + "\n";
  }
  return out;
}

double peak(const nsb::scene::Scene& s) {
  REQUIRE(s.input.transverse);
  return s.input.transverse->pga_g;
}

}  // namespace

TEST_CASE("a CSV header's unit sets the record's unit; record_unit must agree with it") {
  // The same samples in g (header) and in m/s^2 with record_unit = 9.80665: the same PGA.
  write("sine-g.csv", "t [s],a [g]\n" + sine_values(","));
  write("sine.txt", sine_values(" "));
  const auto g = load_scene(write("g.toml", bridge_with("transverse_record = \"sine-g.csv\"\n")));
  const auto si = load_scene(write("si.toml", bridge_with("transverse_record = \"sine.txt\"\n"
                                                          "record_unit = 9.80665\n")));
  // pga_g is in the scenes' g = 9.81: 0.5 * 9.80665 / 9.81 (sin reaches 1 at sample 5).
  CHECK(peak(g) == doctest::Approx(0.5 * 9.80665 / 9.81).epsilon(1e-6));
  CHECK(peak(g) == doctest::Approx(peak(si)).epsilon(1e-15));
  // record_unit = 1 says m/s^2: the file says g.
  const auto e = error_of("conflict.toml", bridge_with("transverse_record = \"sine-g.csv\"\n"
                                                       "record_unit = 1.0\n"));
  CHECK(contains(e, "conflict.toml:13:"));
  CHECK(contains(e, "model.excitation.transverse_record"));
  CHECK(contains(e, "sine-g.csv:1:"));
  CHECK(contains(e, "[g]"));
  CHECK(contains(e, "model.excitation.record_unit = 1"));
  // .AT2 files are in g: record_unit = 1 contradicts them too.
  const std::string at2 = std::string(NSB_DATA_DIR) + "/ground-motions/RSN988_NORTHR_CCN360.AT2";
  const auto a = error_of("at2.toml", bridge_with("transverse_record = \"" + at2 +
                                                  "\"\nrecord_unit = 1.0\n"));
  CHECK(contains(a, "RSN988_NORTHR_CCN360.AT2:3:"));
  CHECK(contains(a, "conflicts with model.excitation.record_unit"));
}

TEST_CASE("a file of acceleration values only needs record_dt, declared in the schema") {
  std::string values;
  for (int i = 0; i <= 20; ++i) values += std::to_string(0.5 * std::sin(2 * M_PI * 5 * i * 0.01)) + "\n";
  write("values.txt", values);
  const auto s = load_scene(write("dt.toml", bridge_with("transverse_record = \"values.txt\"\n"
                                                         "record_dt = 0.01\n")));
  CHECK(peak(s) == doctest::Approx(0.5 / 9.81).epsilon(1e-6));
  CHECK(s.record_step == doctest::Approx(0.01).epsilon(1e-15));
  const auto e = error_of("nodt.toml", bridge_with("transverse_record = \"values.txt\"\n"));
  CHECK(contains(e, "nodt.toml:13:"));
  CHECK(contains(e, "values.txt:1:"));
  CHECK(contains(e, "model.excitation.record_dt [s]"));
  const auto n = error_of("negdt.toml", bridge_with("transverse_record = \"values.txt\"\n"
                                                    "record_dt = -0.01\n"));
  CHECK(contains(n, "negdt.toml:14:"));
  CHECK(contains(n, "model.excitation.record_dt"));
}

TEST_CASE("an amplitude key without a record is an error at that key") {
  for (const char* key : {"target_pga = 0.6", "longitudinal_pga = 0.6", "scale = 2.0"}) {
    const auto e = error_of("amp.toml", bridge_with("time_scale = 0.5\n" + std::string(key) + "\n"));
    CAPTURE(key);
    const std::string name = std::string(key).substr(0, std::string(key).find(' '));
    CHECK(contains(e, "amp.toml:14:"));
    CHECK(contains(e, "model.excitation." + name + ": needs a record"));
  }
}

TEST_CASE("time_scale that makes the sample times coincide names the key and the record") {
  write("long.txt", "0 0\n1 0.1\n2 -0.1\n3 0\n");
  // 1e308 and 5e-324 are outside time_scale's range [0.001, 1000], refused at the key.
  const auto e = error_of("ts.toml", bridge_with("transverse_record = \"long.txt\"\n"
                                                 "time_scale = 1e308\n"));
  CHECK(contains(e, "ts.toml:14:"));
  CHECK(contains(e, "model.excitation.time_scale"));
  CHECK(contains(e, "1e+308"));
  // Within the range: 3 and the next double, 3.0000000000000004, both times 0.003 round to
  // the same double (checked in IEEE 754 binary64 arithmetic), so samples 1 and 2 coincide.
  write("close.txt", "0 0\n3 0.1\n3.0000000000000004 -0.1\n4 0\n");
  const auto c = error_of("ts2.toml", bridge_with("transverse_record = \"close.txt\"\n"
                                                  "time_scale = 0.003\n"));
  CHECK(contains(c, "ts2.toml:14:"));
  CHECK(contains(c, "model.excitation.time_scale"));
  CHECK(contains(c, "close.txt"));
  CHECK(contains(c, "coincide"));
}

TEST_CASE("a record whose motion overflows is reported at [model.excitation] with a short number") {
  // DT = 1e300 s: 6 samples span 5e300 s, and the integrated motion overflows. The span is
  // written with three significant digits, not as 301 digits.
  write("huge.AT2", "A\nB\nUNITS OF G\nNPTS= 6, DT= 1e300 SEC\n 0.1 -0.2 0.3\n -0.4 0.5 -0.6\n");
  const auto e = error_of("huge.toml", bridge_with("transverse_record = \"huge.AT2\"\n"));
  CHECK(contains(e, "huge.toml:12:"));
  CHECK(contains(e, "model.excitation"));
  CHECK(contains(e, "huge.AT2"));
  CHECK(contains(e, "overflows (time span 5e+300 s)"));
  CHECK(e.size() < 300);
}

TEST_CASE("a record too weak for its target is refused at the target's key") {
  // Peak 1e-306 m/s^2 scaled to 20 g: the factor 9.81 * 20 / 1e-306 = 1.96e308 is finite, and
  // times scale = 1000 it overflows; before the check, the overflow reached the ground
  // motion's own check as "GroundMotionOptions: scale must be finite".
  write("weak.txt", "0 0\n0.01 1e-306\n0.02 -1e-306\n0.03 0\n");
  const auto e = error_of("weak.toml", bridge_with("transverse_record = \"weak.txt\"\n"
                                                   "target_pga = 20\n"
                                                   "scale = 1000\n"));
  CHECK(contains(e, "weak.toml:14:"));
  CHECK(contains(e, "model.excitation.target_pga"));
  CHECK(contains(e, "too small to scale to 20 g with scale = 1000"));
  CHECK(e.find("GroundMotionOptions") == std::string::npos);
}
