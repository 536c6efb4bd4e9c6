// Ground motions: the spline motion and its integrals, scaling, time compression, delay and
// baseline correction, on recorded motions read with scene/records.hpp (its own tests:
// scene/test/records_test.cpp).
#include "models/ground_motion.hpp"
#include "scene/records.hpp"

#include <doctest/doctest.h>
#include <gsl/gsl_spline.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <filesystem>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using nsb::models::GroundMotion;
using nsb::models::GroundMotionOptions;
using nsb::models::Record;

namespace {

const fs::path kMotions = fs::path(NSB_DATA_DIR) / "ground-motions";
constexpr double kG = 9.81;
// Spline evaluation: our per-interval polynomials against GSL's evaluation of the same spline;
// both are exact up to round-off of sums over a few thousand intervals.
constexpr double kSplineTolerance = 1e-9;
// Central differences of d and v with step kFdStep: the truncation error is
// O(kFdStep^2 * jerk) and the round-off O(eps * |d| / kFdStep).
constexpr double kFdStep = 1e-5;
constexpr double kFdTolerance = 1e-5;
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

// Index and value of the largest |a|.
std::pair<std::size_t, double> peak_of(const std::vector<double>& a) {
  std::size_t k = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::abs(a[i]) > std::abs(a[k])) k = i;
  }
  return {k, std::abs(a[k])};
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

TEST_CASE("ground motion: spline and integrals agree with GSL's own evaluation") {
  const Record r = nsb::scene::read_at2(kMotions / "elCentro_NS_1940_Peknold.AT2");
  GroundMotionOptions o;
  o.baseline_correction = false;
  const GroundMotion gm(r, o);
  std::unique_ptr<gsl_spline, void (*)(gsl_spline*)> sp(
      gsl_spline_alloc(gsl_interp_cspline, r.t.size()), gsl_spline_free);
  gsl_spline_init(sp.get(), r.t.data(), r.a.data(), r.t.size());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, r.t.back());
  const double a_scale = peak_of(r.a).second;
  for (int i = 0; i < 300; ++i) {
    const double x = u(rng);
    CHECK(gm.acceleration(x) == doctest::Approx(gsl_spline_eval(sp.get(), x, nullptr))
                                    .epsilon(kSplineTolerance)
                                    .scale(a_scale));
    // GSL integrates the spline exactly over [0, x].
    CHECK(gm.velocity(x) == doctest::Approx(gsl_spline_eval_integ(sp.get(), 0.0, x, nullptr))
                                .epsilon(kSplineTolerance)
                                .scale(a_scale));
  }
  for (std::size_t i = 0; i < r.t.size(); i += 97) {
    CHECK(gm.acceleration(r.t[i]) == doctest::Approx(r.a[i]).epsilon(kSplineTolerance).scale(a_scale));
  }
}

TEST_CASE("ground motion: d, v, a are derivatives of each other (with baseline correction)") {
  const Record r = nsb::scene::read_at2(kMotions / "RSN1084_NORTHR_SCS142.AT2");
  const GroundMotion gm(r);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.01, r.t.back() - 0.01);
  double v_scale = 0.0, d_scale = 0.0;
  for (double x = 0.0; x < r.t.back(); x += 0.01) {
    v_scale = std::max(v_scale, std::abs(gm.velocity(x)));
    d_scale = std::max(d_scale, std::abs(gm.displacement(x)));
  }
  for (int i = 0; i < 300; ++i) {
    const double x = u(rng), h = kFdStep;
    const double dv = (gm.displacement(x + h) - gm.displacement(x - h)) / (2 * h);
    const double da = (gm.velocity(x + h) - gm.velocity(x - h)) / (2 * h);
    CHECK(gm.velocity(x) == doctest::Approx(dv).epsilon(kFdTolerance).scale(v_scale));
    CHECK(gm.acceleration(x) == doctest::Approx(da).epsilon(kFdTolerance).scale(gm.pga()));
  }
}

// values() evaluates d, v and a together; each must be exactly what the single evaluations
// give, at random times, at the knots, before the start, after the end and at both ends, for
// a uniformly sampled record with a delay and for a non-uniformly sampled one.
TEST_CASE("ground motion: values() equals displacement(), velocity(), acceleration() exactly") {
  GroundMotionOptions delayed;
  delayed.delay = 0.37;
  delayed.target_pga = 3.0;
  const Record uniform = nsb::scene::read_at2(kMotions / "RSN1084_NORTHR_SCS142.AT2");
  std::mt19937 rng(19);
  std::vector<double> tk, ak;  // knots at random spacings
  std::uniform_real_distribution<double> spacing(0.005, 0.03), accel(-3.0, 3.0);
  for (double x = 0.0; tk.size() < 500; x += spacing(rng)) {
    tk.push_back(x);
    ak.push_back(accel(rng));
  }
  const GroundMotion motions[] = {GroundMotion(uniform, delayed),
                                  GroundMotion(make_record(tk, ak)), GroundMotion()};
  for (const GroundMotion& gm : motions) {
    const double t0 = gm.start_time(), t1 = gm.end_time();
    std::vector<double> times{t0, t1, t0 - 1.0, t1 + 1.0, std::nextafter(t0, -1.0),
                              std::nextafter(t1, 1e9)};
    std::uniform_real_distribution<double> u(t0 - 0.5, t1 + 0.5);
    for (int i = 0; i < 2000; ++i) times.push_back(u(rng));
    for (double x : tk) times.push_back(x);
    for (double x : times) {
      const GroundMotion::Values v = gm.values(x);
      INFO("t = " << x);
      CHECK(v.displacement == gm.displacement(x));
      CHECK(v.velocity == gm.velocity(x));
      CHECK(v.acceleration == gm.acceleration(x));
    }
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

TEST_CASE("ground motion: target PGA, scale, time compression and delay") {
  const Record r = nsb::scene::read_at2(kMotions / "RSN1084_NORTHR_SCS052.AT2");
  const GroundMotion base(r);
  GroundMotionOptions o;
  o.target_pga = 0.35 * kG;
  const GroundMotion scaled(r, o);
  CHECK(scaled.pga() == doctest::Approx(0.35 * kG).epsilon(1e-12));
  // The PGA is attained at a sample of the scaled motion.
  double peak = 0.0;
  for (double x : r.t) peak = std::max(peak, std::abs(scaled.acceleration(x)));
  CHECK(peak == doctest::Approx(0.35 * kG).epsilon(1e-12));
  const double factor = 0.35 * kG / base.pga();
  o.scale = -2.0;  // applied after target_pga
  const GroundMotion flipped(r, o);
  CHECK(flipped.pga() == doctest::Approx(0.7 * kG).epsilon(1e-12));
  for (double x : {1.0, 4.7, 12.345}) {
    CHECK(scaled.displacement(x) == doctest::Approx(factor * base.displacement(x)).epsilon(1e-10));
    CHECK(flipped.velocity(x) == doctest::Approx(-2.0 * factor * base.velocity(x)).epsilon(1e-10));
  }
  // Similitude, 1/4 length scale: t -> 0.5 t, same acceleration, displacements x 0.25.
  GroundMotionOptions c;
  c.time_scale = 0.5;
  const GroundMotion compressed(r, c);
  CHECK(compressed.duration() == doctest::Approx(0.5 * base.duration()));
  CHECK(compressed.pga() == doctest::Approx(base.pga()));
  for (double x : {0.77, 3.0, 20.0}) {
    CHECK(compressed.acceleration(0.5 * x) == doctest::Approx(base.acceleration(x)).epsilon(1e-10));
    CHECK(compressed.velocity(0.5 * x) == doctest::Approx(0.5 * base.velocity(x)).epsilon(1e-10));
    CHECK(compressed.displacement(0.5 * x) == doctest::Approx(0.25 * base.displacement(x)).epsilon(1e-10));
  }
  // Wave passage: the same motion, later.
  GroundMotionOptions w;
  w.delay = 0.3;
  const GroundMotion delayed(r, w);
  CHECK(delayed.start_time() == doctest::Approx(0.3));
  CHECK(delayed.end_time() == doctest::Approx(base.end_time() + 0.3));
  CHECK(delayed.displacement(0.29) == 0.0);
  for (double x : {0.1, 5.0, 30.0}) {
    CHECK(delayed.displacement(x + 0.3) == doctest::Approx(base.displacement(x)).epsilon(1e-12));
    CHECK(delayed.acceleration(x + 0.3) == doctest::Approx(base.acceleration(x)).epsilon(1e-12));
  }
}

TEST_CASE("ground motion: copies share the spline safely; default is zero motion") {
  GroundMotion copy;
  CHECK(copy.empty());
  CHECK(copy.displacement(1.0) == 0.0);
  CHECK(copy.velocity(1.0) == 0.0);
  CHECK(copy.acceleration(1.0) == 0.0);
  CHECK(copy.duration() == 0.0);
  CHECK(copy.pga() == 0.0);
  double expected = 0.0;
  {
    const GroundMotion gm(nsb::scene::read_at2(kMotions / "elCentro_NS_1940_Peknold.AT2"));
    expected = gm.velocity(2.5);
    copy = gm;
  }  // the original is gone; the copy still holds the data
  CHECK(copy.velocity(2.5) == expected);
  std::vector<GroundMotion> supports(5, copy);  // several supports
  CHECK(supports[4].velocity(2.5) == expected);
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
