// Ground motions: the spline motion and its integrals, baseline correction and validation, on
// synthetic records. The cases on the recorded motions of data/ (spline against GSL,
// derivatives, scaling, time compression, delay, copies) read them with the scene's record
// reader and are in scene/test/recorded_motions_test.cpp.
#include "models/ground_motion.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

using nsb::models::GroundMotion;
using nsb::models::GroundMotionOptions;
using nsb::models::Record;

namespace {

// Spline evaluation: our per-interval polynomials against GSL's evaluation of the same spline;
// both are exact up to round-off of sums over a few thousand intervals.
constexpr double kSplineTolerance = 1e-9;
// A synthetic motion whose error is a baseline offset and trend is recovered by the correction
// within this fraction of its peak displacement: the drift lies in the span of the correction
// polynomials, and the least-squares fit also removes the projection of the true motion on
// them, which is small for an oscillation of many cycles (measured 2e-6).
constexpr double kBaselineRecovery = 1e-3;

// Asserts that f throws std::invalid_argument whose message contains every fragment.
template <class F>
void expect_error(F&& f, std::initializer_list<std::string> fragments) {
  try {
    f();
    FAIL("expected std::invalid_argument");
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    for (const auto& frag : fragments) {
      INFO("message: " << msg);
      CHECK(msg.find(frag) != std::string::npos);
    }
  }
}

Record make_record(const std::vector<double>& t, const std::vector<double>& a) {
  Record r;
  r.t = t;
  r.a = a;
  r.source = "synthetic";
  return r;
}

}  // namespace

TEST_CASE("ground motion: linear acceleration is reproduced with exact integrals") {
  // The natural cubic spline of samples of a linear function is that function, so
  // a = alpha + beta t, v = alpha t + beta t^2/2, d = alpha t^2/2 + beta t^3/6 exactly.
  const double alpha = 0.3, beta = -0.7;
  std::vector<double> t, a;
  for (int i = 0; i <= 40; ++i) {
    const double ti = 0.05 * i + 0.002 * (i % 3);  // non-uniform spacing
    t.push_back(ti);
    a.push_back(alpha + beta * ti);
  }
  GroundMotionOptions o;
  o.baseline_correction = false;
  const GroundMotion gm(make_record(t, a), o);
  for (double x = 0.0; x <= t.back(); x += 0.0173) {
    CHECK(gm.acceleration(x) == doctest::Approx(alpha + beta * x).epsilon(kSplineTolerance));
    CHECK(gm.velocity(x) == doctest::Approx(alpha * x + beta * x * x / 2).epsilon(kSplineTolerance));
    CHECK(gm.displacement(x) ==
          doctest::Approx(alpha * x * x / 2 + beta * x * x * x / 6).epsilon(kSplineTolerance));
  }
}

TEST_CASE("ground motion: baseline correction ends at rest and removes an offset drift") {
  // True motion d = D sin^2(pi t/T) sin(2 pi f t): starts and ends at rest, many cycles.
  const double D = 0.05, T = 20.0, f = 1.0, dt = 0.01;
  const double wb = std::numbers::pi / T, wf = 2.0 * std::numbers::pi * f;
  auto d_true = [&](double t) { return D * std::pow(std::sin(wb * t), 2) * std::sin(wf * t); };
  auto a_true = [&](double t) {
    const double w = std::pow(std::sin(wb * t), 2), w1 = wb * std::sin(2 * wb * t),
                 w2 = 2 * wb * wb * std::cos(2 * wb * t);
    const double s = std::sin(wf * t), s1 = wf * std::cos(wf * t), s2 = -wf * wf * s;
    return D * (w2 * s + 2 * w1 * s1 + w * s2);
  };
  std::vector<double> t, a;
  const double offset = 0.02, trend = 0.001;  // m/s^2 and m/s^3: a typical baseline error
  for (int i = 0; i * dt <= T + 1e-12; ++i) {
    t.push_back(i * dt);
    a.push_back(a_true(i * dt) + offset + trend * i * dt);
  }
  const Record r = make_record(t, a);
  GroundMotionOptions raw_o;
  raw_o.baseline_correction = false;
  const GroundMotion raw(r, raw_o), corrected(r);
  // Without correction the offset alone drifts by offset T^2 / 2 = 4 m.
  CHECK(std::abs(raw.displacement(T)) > 1.0);
  // Corrected: at rest at both ends, and close to the true motion throughout.
  CHECK(std::abs(corrected.displacement(0.0)) < 1e-12);
  CHECK(std::abs(corrected.velocity(0.0)) < 1e-12);
  CHECK(std::abs(corrected.displacement(T)) < 1e-9 * D);
  CHECK(std::abs(corrected.velocity(T)) < 1e-9 * D * wf);
  double err = 0.0;
  for (double x = 0.0; x <= T; x += 0.01) err = std::max(err, std::abs(corrected.displacement(x) - d_true(x)));
  MESSAGE("max |d_corrected - d_true| / D = " << err / D);
  CHECK(err < kBaselineRecovery * D);
  // Held after the end; zero velocity and acceleration outside the record.
  CHECK(corrected.displacement(T + 5.0) == doctest::Approx(corrected.displacement(T)));
  CHECK(corrected.velocity(T + 1e-9) == 0.0);
  CHECK(corrected.acceleration(-1e-9) == 0.0);
  CHECK(corrected.displacement(-1.0) == 0.0);
}

TEST_CASE("ground motion: options and records are validated") {
  auto opt_error = [](GroundMotionOptions o, const std::string& field) {
    expect_error([&] { o.validate(); }, {field});
  };
  { GroundMotionOptions o; o.target_pga = -1.0; opt_error(o, "target_pga"); }
  { GroundMotionOptions o; o.time_scale = 0.0; opt_error(o, "time_scale"); }
  { GroundMotionOptions o; o.delay = -0.1; opt_error(o, "delay"); }
  { GroundMotionOptions o; o.scale = std::nan(""); opt_error(o, "scale"); }
  expect_error([] { GroundMotion(make_record({0, 1, 1}, {0, 1, 2})); }, {"synthetic", "sample 2"});
  expect_error([] { GroundMotion(make_record({0, 1}, {0, 1})); }, {"at least 3"});
  expect_error([] { GroundMotion(make_record({0, 1, 2}, {0, std::nan(""), 2})); }, {"not finite"});
  expect_error([] { GroundMotion(make_record({0, 1, 2}, {0, 1})); }, {"differ in size"});
  GroundMotionOptions o;
  o.target_pga = 1.0;
  expect_error([&] { GroundMotion(make_record({0, 1, 2}, {0, 0, 0}), o); }, {"target_pga"});
}

namespace {

// A sine burst of `cycles` cycles of period T [s] and amplitude A [m/s^2], sampled at dt from
// t = 0: a short synthetic record.
Record burst(double T, double A, int cycles, double dt, const std::string& name) {
  Record r;
  r.source = name;
  const int n = static_cast<int>(std::lround(cycles * T / dt));
  for (int i = 0; i <= n; ++i) {
    r.t.push_back(i * dt);
    r.a.push_back(A * std::sin(2.0 * std::numbers::pi * i * dt / T));
  }
  return r;
}

// The times at which the sequence tests compare: a fine grid over [0, end], with the parts'
// own start and end times.
std::vector<double> probe_times(double end, std::vector<double> extra) {
  std::vector<double> t = std::move(extra);
  for (int i = 0; i <= 4000; ++i) t.push_back(end * i / 4000.0);
  return t;
}

}  // namespace

TEST_CASE("ground motion: a sequence is its records in turn, each the record's own motion") {
  // A from 0 to 1 s, rest 0.5 s, B placed at 1.5 s (its delay): before and at B's start the
  // sequence is A's motion (held after its end), after it B's, bit for bit (baseline
  // corrected records end at rest at their origin, so B starts from displacement 0).
  const Record a = burst(0.25, 3.0, 4, 0.01, "A"), b = burst(0.2, 2.0, 5, 0.01, "B");
  const GroundMotion ma(a);
  GroundMotionOptions ob;
  ob.delay = 1.5;
  ob.scale = 0.7;
  const GroundMotion mb(b, ob);
  const GroundMotion seq = GroundMotion::sequence({ma, mb}, true);
  CHECK(seq.start_time() == 0.0);
  CHECK(seq.end_time() == mb.end_time());
  CHECK(seq.pga() == std::max(ma.pga(), mb.pga()));
  CHECK(seq.source() == "A then B");
  for (double t : probe_times(3.0, {1.0, 1.5, std::nextafter(1.5, 2.0), mb.end_time()})) {
    const GroundMotion& own = t <= 1.5 ? ma : mb;
    const GroundMotion::Values s = seq.values(t), o = own.values(t);
    INFO("t = " << t);
    CHECK(s.displacement == o.displacement);
    CHECK(s.velocity == o.velocity);
    CHECK(s.acceleration == o.acceleration);
    CHECK(seq.displacement(t) == o.displacement);
    CHECK(seq.velocity(t) == o.velocity);
    CHECK(seq.acceleration(t) == o.acceleration);
  }
  // In the rest interval the ground is at rest: zero acceleration and velocity.
  CHECK(seq.acceleration(1.25) == 0.0);
  CHECK(seq.velocity(1.25) == 0.0);
}

TEST_CASE("ground motion: a sequence without baseline correction carries the displacement on") {
  // Without correction a record ends displaced (a sine burst of whole cycles ends at
  // d = A T t1 / (2 pi), a drift of constant velocity A T / (2 pi) held from its start); the
  // next record starts from there: the displacement is continuous at its start and is the
  // record's own plus that offset after it.
  GroundMotionOptions oa;
  oa.baseline_correction = false;
  const GroundMotion ma(burst(0.25, 3.0, 4, 0.01, "A"), oa);
  GroundMotionOptions ob = oa;
  ob.delay = 1.2;
  const GroundMotion mb(burst(0.2, 2.0, 5, 0.01, "B"), ob);
  const GroundMotion seq = GroundMotion::sequence({ma, mb}, false);
  const double held = ma.displacement(ma.end_time());
  CHECK(std::abs(held) > 0.01);
  CHECK(seq.displacement(1.2) == held);
  CHECK(seq.displacement(std::nextafter(1.2, 2.0)) == doctest::Approx(held).epsilon(1e-12));
  for (double t : {1.3, 1.7, 2.2, 3.0}) {
    INFO("t = " << t);
    CHECK(seq.displacement(t) == mb.displacement(t) + held);
    CHECK(seq.velocity(t) == mb.velocity(t));
  }
}

TEST_CASE("ground motion: a sequence's parts are checked") {
  const GroundMotion ma(burst(0.25, 3.0, 4, 0.01, "A"));
  GroundMotionOptions early;
  early.delay = 0.5;  // B would start before A ends (1 s)
  const GroundMotion mb(burst(0.2, 2.0, 5, 0.01, "B"), early);
  expect_error([&] { (void)GroundMotion::sequence({ma, mb}, true); },
               {"'B'", "before the end of 'A'"});
  expect_error([&] { (void)GroundMotion::sequence({}, true); }, {"no part"});
  // One part, or parts with empty ones among them, is that part: the same motion.
  const GroundMotion one = GroundMotion::sequence({GroundMotion(), ma}, true);
  for (double t : {0.1, 0.55, 1.0, 2.0}) CHECK(one.displacement(t) == ma.displacement(t));
}
