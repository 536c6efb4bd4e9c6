// Ground motions: the readers, the spline motion and its integrals, scaling, time
// compression, delay and baseline correction.
#include "models/ground_motion.hpp"

#include <doctest/doctest.h>
#include <gsl/gsl_spline.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
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
// Values printed with 5-7 significant digits in the files, compared after parsing.
constexpr double kParseTolerance = 1e-12;
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

// A scratch directory for files written by the tests, removed at the end.
struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() /
           ("nsb_ground_motion_test_" + std::to_string(std::random_device{}()));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path p = path / name;
    std::ofstream(p) << text;
    return p;
  }
};

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

TEST_CASE("ground motion: PEER AT2 files in both header forms") {
  SUBCASE("NPTS=  1559, DT= .02000 SEC (Peknold El Centro)") {
    const Record r = nsb::models::read_at2(kMotions / "elCentro_NS_1940_Peknold.AT2");
    REQUIRE(r.a.size() == 1559);
    CHECK(r.t[1] == doctest::Approx(0.02));
    CHECK(r.t.back() == doctest::Approx(1558 * 0.02));
    // First and last values of the file, in g.
    CHECK(r.a.front() == doctest::Approx(0.00630 * kG).epsilon(kParseTolerance));
    CHECK(r.a.back() == doctest::Approx(0.0).scale(1.0));
    // Chopra's PGA of this version: 0.319 g.
    CHECK(peak_of(r.a).second / kG == doctest::Approx(0.319).epsilon(0.002));
  }
  SUBCASE("NPTS=   8773, DT=   .0050 SEC, ... (Northridge, Sylmar)") {
    // bridge-parameters: component 142 has 0.923 g at t = 7.0 s, 052 has 0.623 g at 4.7 s.
    for (const auto& [file, pga, time] :
         {std::tuple{"RSN1084_NORTHR_SCS142.AT2", 0.923, 7.0},
          std::tuple{"RSN1084_NORTHR_SCS052.AT2", 0.623, 4.7}}) {
      const Record r = nsb::models::read_at2(kMotions / file, kG);
      REQUIRE(r.a.size() == 8773);
      CHECK(r.t[1] == doctest::Approx(0.005));
      const auto [k, peak] = peak_of(r.a);
      CHECK(peak / kG == doctest::Approx(pga).epsilon(1e-3));
      CHECK(r.t[k] == doctest::Approx(time).epsilon(0.01));
    }
    const Record first = nsb::models::read_at2(kMotions / "RSN1084_NORTHR_SCS052.AT2", 1.0);
    CHECK(first.a.front() == doctest::Approx(-0.4981725e-2).epsilon(kParseTolerance));
  }
}

TEST_CASE("ground motion: reader errors name the file and the line") {
  TempDir dir;
  const std::string head = "PEER\nevent\nUNITS OF G\n";
  {
    const auto p = dir.write("bad_token.AT2", head + "NPTS=  4, DT= .01 SEC\n 0.1 0.2\n 0.3 x4\n");
    expect_error([&] { nsb::models::read_at2(p); }, {"bad_token.AT2:6:", "non-numeric", "x4"});
  }
  {
    const auto p = dir.write("short.AT2", head + "NPTS=  5, DT= .01 SEC\n 0.1 0.2\n 0.3 0.4\n");
    expect_error([&] { nsb::models::read_at2(p); }, {"short.AT2:6:", "NPTS = 5", "4 values"});
  }
  {
    const auto p = dir.write("long.AT2", head + "NPTS=  3, DT= .01 SEC\n 0.1 0.2\n 0.3 0.4\n");
    expect_error([&] { nsb::models::read_at2(p); }, {"long.AT2:6:", "more values than NPTS"});
  }
  {
    const auto p = dir.write("header.AT2", head + "POINTS 3 STEP 0.01\n 0.1 0.2 0.3\n");
    expect_error([&] { nsb::models::read_at2(p); }, {"header.AT2:4:", "NPTS="});
  }
  {
    const auto p = dir.write("nan.AT2", head + "NPTS=  3, DT= .01 SEC\n 0.1 nan 0.3\n");
    expect_error([&] { nsb::models::read_at2(p); }, {"nan.AT2:5:", "not finite"});
  }
  {
    const auto p = dir.write("dt.AT2", head + "NPTS=  3, DT= 0 SEC\n 0.1 0.2 0.3\n");
    expect_error([&] { nsb::models::read_at2(p); }, {"dt.AT2:4:", "DT"});
  }
  expect_error([&] { nsb::models::read_at2(dir.path / "missing.AT2"); },
               {"missing.AT2", "does not exist"});
  {
    const auto p = dir.write("time.txt", "# t a\n0 0.1\n0.01 0.2\n\n0.01 0.3\n0.03 0.1\n");
    expect_error([&] { nsb::models::read_two_column(p); },
                 {"time.txt:5:", "not greater than the previous"});
  }
  {
    const auto p = dir.write("fields.txt", "0 0.1\n0.01 0.2 7\n");
    expect_error([&] { nsb::models::read_two_column(p); }, {"fields.txt:2:", "two numbers"});
  }
  {
    const auto p = dir.write("csvbad.csv", "t,a\n0,0.1\n0.01,abc\n0.02,0\n");
    expect_error([&] { nsb::models::read_csv(p); }, {"csvbad.csv:3:", "non-numeric", "abc"});
  }
  {
    const auto p = dir.write("csvhead.csv", "time,x,y\n0,1,2\n");
    expect_error([&] { nsb::models::read_csv(p); }, {"csvhead.csv:1:", "'t' and 'a'"});
  }
  {
    const auto p = dir.write("csvfields.csv", "t,a\n0,1\n0.1\n");
    expect_error([&] { nsb::models::read_csv(p); }, {"csvfields.csv:3:", "2 comma-separated"});
  }
  {
    const auto p = dir.write("two.txt", "0 0.1\n0.01 0.2\n");
    expect_error([&] { nsb::models::read_two_column(p); }, {"two.txt", "at least 3"});
  }
}

TEST_CASE("ground motion: readers refuse what is not a regular file, and name out-of-range numbers") {
  TempDir dir;
  // A FIFO would block the reader for ever (no writer), a directory is no record.
  const auto fifo = dir.path / "fifo.AT2";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  expect_error([&] { nsb::models::read_at2(fifo); }, {"fifo.AT2", "not a regular file"});
  expect_error([&] { nsb::models::read_csv(dir.path); }, {"not a regular file"});
  // Subnormal values are values; 1e-400 and 1e400 are beyond a double and refused by name.
  const std::string head = "PEER\nevent\nUNITS OF G\n";
  {
    std::istringstream in(head + "NPTS=  3, DT= .01 SEC\n 1e-310 -4.9e-324 0.3\n");
    const Record r = nsb::models::read_at2(in, "sub.AT2", 1.0);
    CHECK(r.a[0] == 1e-310);
    CHECK(r.a[1] == -4.9e-324);
  }
  for (const char* v : {"1e-400", "1e400"}) {
    std::istringstream in(head + "NPTS=  3, DT= .01 SEC\n 0.1 " + v + " 0.3\n");
    expect_error([&] { nsb::models::read_at2(in, "range.AT2", 1.0); },
                 {"range.AT2:5:", "outside the range of a double", v});
  }
  // A header line far longer than any PEER line is refused before the regular expression.
  {
    std::istringstream in(head + "NPTS= " + std::string(100000, ' ') + "3, DT= .01\n0 0 0\n");
    expect_error([&] { nsb::models::read_at2(in, "long.AT2", 1.0); },
                 {"long.AT2:4:", "100016 characters"});
  }
}

TEST_CASE("ground motion: two-column and CSV readers") {
  TempDir dir;
  const auto p2 = dir.write("rec.txt", "# time [s]  acc [g]\n0.0 0.0\n0.5 +1.5e-1\n1.25 -0.25\n2 0\n");
  const Record r2 = nsb::models::read_two_column(p2, kG);
  REQUIRE(r2.t.size() == 4);
  CHECK(r2.t[2] == 1.25);
  CHECK(r2.a[1] == doctest::Approx(0.15 * kG));
  CHECK(r2.source == p2.string());
  const auto pc = dir.write("rec.csv", "a, t ,note\n0.0,0.0,x\n1.0,0.1,y\n-2.0,0.2,z\n");
  const Record rc = nsb::models::read_csv(pc, 0.5);
  REQUIRE(rc.t.size() == 3);
  CHECK(rc.t[2] == doctest::Approx(0.2));
  CHECK(rc.a[2] == doctest::Approx(-1.0));
}

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
  const Record r = nsb::models::read_at2(kMotions / "elCentro_NS_1940_Peknold.AT2");
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
  const Record r = nsb::models::read_at2(kMotions / "RSN1084_NORTHR_SCS142.AT2");
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
  const Record uniform = nsb::models::read_at2(kMotions / "RSN1084_NORTHR_SCS142.AT2");
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
  const Record r = nsb::models::read_at2(kMotions / "RSN1084_NORTHR_SCS052.AT2");
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
    const GroundMotion gm(nsb::models::read_at2(kMotions / "elCentro_NS_1940_Peknold.AT2"));
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
