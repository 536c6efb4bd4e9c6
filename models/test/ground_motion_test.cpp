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
