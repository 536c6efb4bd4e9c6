// The models' ground motions and response spectra on records read by the scene's record
// reader (scene/records.hpp, its own tests: records_test.cpp): the recorded motions of data/
// through models::GroundMotion (the spline against GSL's evaluation, derivatives, values(),
// scaling, time compression, delay, copies) and the g with which a .AT2 file's PSA is given.
// The models' own tests (models/test/) use synthetic records only.
#include "models/ground_motion.hpp"
#include "models/response_spectrum.hpp"
#include "scene/records.hpp"

#include <doctest/doctest.h>
#include <gsl/gsl_spline.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using nsb::models::GroundMotion;
using nsb::models::GroundMotionOptions;
using nsb::models::Record;
using nsb::models::SpectrumOptions;

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

TEST_CASE("response_spectrum: PSA in g uses the g with which read_at2 reads .AT2 files") {
  // A record of peak 0.5 g read with the reader's default g: PSA(T = 0) is 0.5 again only if
  // kSpectrumGravity is that same g.
  std::istringstream at2("PEER\nevent\nACCELERATION TIME SERIES IN UNITS OF G\n"
                         "NPTS=    4, DT=   .0100 SEC\n0.1 -0.5 0.25 0.0\n");
  const Record r = nsb::scene::read_at2(at2, "half-g.AT2");
  SpectrumOptions o;
  o.periods = {0.0};
  CHECK(nsb::models::response_spectrum(r, o).psa_g[0] == doctest::Approx(0.5).epsilon(1e-15));
}
