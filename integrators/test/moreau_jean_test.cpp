// Unit tests of the Moreau–Jean scheme on small systems defined here, with the expected values
// from closed forms derived in the comments and from Siconos's reference output.
#include "integrators/moreau_jean.hpp"
#include "integrators/run.hpp"
#include "testsupport/systems.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <new>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

// Counts every heap allocation of this test executable, to check that a step allocates
// nothing: a run of 2N steps must allocate exactly as often as a run of N steps.
namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t n) {
  ++g_allocations;
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace nsb::integrators {
namespace {

namespace ts = nsb::testsupport;

// A point mass m = 1 under gravity g = 9.81 above a platform moving upward at constant speed
// V: gap g_N = y - V t, so gdot_N = u - V (W_N = 1, what_N = -V).
ts::Ball::Parameters ball_on_platform(double y0, double v0, double e, double platform_speed = 0.0) {
  return {.initial_height = y0, .initial_velocity = v0, .restitution = e,
          .floor_velocity = platform_speed};
}

// m x'' + c x' + k x = F0 sin(w t), no contact.
ts::SpringMass::Parameters oscillator(double m, double k, double c, double x0, double v0,
                                      double f0 = 0.0, double w = 0.0) {
  return {.mass = m, .stiffness = k, .damping = c, .force_amplitude = f0, .force_frequency = w,
          .initial_position = x0, .initial_velocity = v0};
}

// An elastic-perfectly-plastic spring (stiffness k, yield force fy) driven by F0 sin(w t): its
// tangent switches between k and 0 as it yields and unloads, so the scheme re-factorizes
// inside the run.
ts::PlasticOscillator::Parameters plastic(double k, double fy, double f0, double w) {
  return {.stiffness = k, .yield_force = fy, .force_amplitude = f0, .force_frequency = w};
}

// A block of mass 2 on the ground y = 0 with Coulomb friction mu, sliding at v0 along x.
ts::Block::Parameters sliding(double v0, double mu) {
  return {.friction = mu, .initial_velocity = v0};
}

// Reads data/siconos-bouncing-ball/result.ref: a "rows cols" line, then rows of t q v p lambda.
std::vector<std::vector<double>> read_siconos_reference() {
  std::ifstream f(std::string(NSB_DATA_DIR) + "/siconos-bouncing-ball/result.ref");
  REQUIRE(f.good());
  int rows = 0, cols = 0;
  f >> rows >> cols;
  std::vector<std::vector<double>> data(static_cast<std::size_t>(rows),
                                        std::vector<double>(static_cast<std::size_t>(cols)));
  for (auto& r : data) {
    for (auto& v : r) f >> v;
  }
  REQUIRE(f.good());
  return data;
}

long allocations_of(auto&& run) {
  const long before = g_allocations.load();
  run();
  return g_allocations.load() - before;
}

}  // namespace

TEST_CASE("options are validated, naming the field") {
  MoreauJeanOptions o;
  CHECK_NOTHROW(o.validate());
  o.theta = 0.3;
  CHECK_THROWS_WITH_AS(o.validate(), doctest::Contains("theta"), std::invalid_argument);
  o = {};
  o.step = 0.0;
  CHECK_THROWS_WITH_AS(o.validate(), doctest::Contains("step"), std::invalid_argument);
  o = {};
  o.step = NAN;
  CHECK_THROWS_AS(o.validate(), std::invalid_argument);
  o = {};
  o.lcp_tolerance = -1.0;
  CHECK_THROWS_WITH_AS(o.validate(), doctest::Contains("lcp_tolerance"), std::invalid_argument);

  ts::SpringMass s(oscillator(1.0, 1.0, 0.0, 1.0, 0.0));
  Recorder rec(s, 0.0);
  MoreauJeanOptions bad;
  bad.end_time = 0.0;  // not after the initial time 0
  CHECK_THROWS_WITH_AS(moreau_jean(s, bad, rec), doctest::Contains("end_time"),
                       std::invalid_argument);
}

TEST_CASE("Siconos's bouncing-ball reference output is reproduced to 1e-10") {
  // Siconos 4.4 BouncingBallTS: m = 1, g = 9.81, e = 0.9, theta = 0.5, h = 0.005, 2000 steps
  // from y = 1 at rest; columns t, q, v, impulse p and lambda (= p in that output).
  constexpr double kTolerance = 1e-10;  // the brief's bound; both compute the same arithmetic
  const auto ref = read_siconos_reference();
  REQUIRE(ref.size() == 2001);
  ts::Ball ball(ball_on_platform(1.0, 0.0, 0.9));
  Recorder rec(ball, 0.0);
  MoreauJeanOptions o;
  o.step = 0.005;
  o.end_time = 10.0;
  o.theta = 0.5;
  const RunResult stats = moreau_jean(ball, o, rec);
  CHECK(stats.completed);
  CHECK(stats.steps == 2000);
  REQUIRE(rec.rows() == ref.size());
  const auto t = rec.series("t"), y = rec.series("y"), v = rec.series("vy"),
             lambda = rec.series("lambdaN1");
  double worst = 0.0;
  std::size_t worst_row = 0;
  for (std::size_t r = 0; r < ref.size(); ++r) {
    const double impulse = lambda[r] * o.step;
    const double err = std::max({std::abs(t[r] - ref[r][0]), std::abs(y[r] - ref[r][1]),
                                 std::abs(v[r] - ref[r][2]), std::abs(impulse - ref[r][3]),
                                 std::abs(impulse - ref[r][4])});
    if (err > worst) worst = err, worst_row = r;
  }
  INFO("largest difference at row ", worst_row, " (t = ", ref[worst_row][0], ")");
  CHECK(worst <= kTolerance);
  // 345 steps carry an impulse in the reference.
  std::size_t impulses = 0;
  for (double l : lambda) impulses += (l > 0.0);
  CHECK(impulses == 345);
}

TEST_CASE("theta = 1/2 conserves the energy of an undamped linear oscillator") {
  // For a linear system the linearisation is exact and theta = 1/2 is the trapezoidal rule,
  // which conserves (1/2) m u^2 + (1/2) k q^2 exactly (up to round-off).
  constexpr double kRoundOff = 1e-12;  // relative, 10^4 steps of O(1e-16) each
  ts::SpringMass s(oscillator(2.0, 50.0, 0.0, 0.1, 0.3));
  Recorder rec(s, 0.0);
  MoreauJeanOptions o;
  o.step = 1e-3;
  o.end_time = 10.0;
  const RunResult stats = moreau_jean(s, o, rec);
  const double e0 = 0.5 * 2.0 * 0.3 * 0.3 + 0.5 * 50.0 * 0.1 * 0.1;
  const auto x = rec.series("x"), v = rec.series("vx");
  for (std::size_t r = 0; r < rec.rows(); r += 97) {
    CHECK(std::abs(0.5 * 2.0 * v[r] * v[r] + 0.5 * 50.0 * x[r] * x[r] - e0) <= kRoundOff * e0);
  }
  CHECK(stats.energy.error <= kRoundOff);
  CHECK(stats.factorizations == 1);  // linear: factorized once
  CHECK(stats.steps_with_lcp == 0);  // no contact: no LCP
}

TEST_CASE("the damped oscillator converges at order 2 for theta = 1/2 and 1 for theta = 1") {
  // Exact solution of m x'' + c x' + k x = 0 (underdamped): with w = sqrt(k/m),
  // zeta = c / (2 m w), wd = w sqrt(1 - zeta^2):
  //   x(t) = exp(-zeta w t) (x0 cos(wd t) + (v0 + zeta w x0) / wd sin(wd t)).
  const double m = 1.0, k = 40.0, c = 0.8, x0 = 0.05, v0 = -0.2, T = 2.0;
  const double w = std::sqrt(k / m), zeta = c / (2.0 * m * w), wd = w * std::sqrt(1 - zeta * zeta);
  const double exact = std::exp(-zeta * w * T) *
                       (x0 * std::cos(wd * T) + (v0 + zeta * w * x0) / wd * std::sin(wd * T));
  auto error = [&](double h, double theta) {
    ts::SpringMass s(oscillator(m, k, c, x0, v0));
    Recorder rec(s, 1e9);
    MoreauJeanOptions o;
    o.step = h;
    o.end_time = T;
    o.theta = theta;
    moreau_jean(s, o, rec);
    return std::abs(rec.series("x").back() - exact);
  };
  const double order_half = std::log2(error(2e-3, 0.5) / error(1e-3, 0.5));
  const double order_one = std::log2(error(2e-3, 1.0) / error(1e-3, 1.0));
  constexpr double kOrderSlack = 0.15;  // asymptotic regime reached at these h (w h < 0.02)
  CHECK(order_half == doctest::Approx(2.0).epsilon(kOrderSlack / 2.0));
  CHECK(order_one == doctest::Approx(1.0).epsilon(kOrderSlack));
}

TEST_CASE("a shortened last step is taken with its own factorization") {
  ts::SpringMass s(oscillator(1.0, 1.0, 0.1, 1.0, 0.0));
  Recorder rec(s, 0.0);
  MoreauJeanOptions o;
  o.step = 0.03;
  o.end_time = 1.0;  // 33 full steps and one of 0.01
  const RunResult stats = moreau_jean(s, o, rec);
  CHECK(stats.steps == 34);
  CHECK(stats.factorizations == 2);
  CHECK(rec.series("t").back() == 1.0);
}

TEST_CASE("an inelastic ball comes to rest on the ground with no drift") {
  // e = 0, dropped from 0.5 m: impact at t* = sqrt(2 * 0.5 / 9.81) = 0.3193 s; after it the
  // ball rests: the velocity is zero and the height constant (no drift through the ground).
  ts::Ball ball(ball_on_platform(0.5, 0.0, 0.0));
  Recorder rec(ball, 0.0);
  MoreauJeanOptions o;
  o.step = 1e-3;
  o.end_time = 3.0;
  const RunResult stats = moreau_jean(ball, o, rec);
  CHECK(stats.completed);
  REQUIRE(rec.count(EventKind::kImpact) == 1);
  CHECK(rec.count(EventKind::kClose) == 1);
  CHECK(rec.count(EventKind::kOpen) == 0);
  const double t_impact = rec.events().front().t;
  CHECK(std::abs(t_impact - std::sqrt(1.0 / 9.81)) <= 2 * o.step);
  const auto y = rec.series("y"), v = rec.series("vy"), lambda = rec.series("lambdaN1");
  // The ball enters the index set once y + (h/2) v <= 0 and its position moves by (h/2) v in
  // the impact step: it rests at or below the ground by at most (h/2) |v_impact|.
  const double v_impact = std::sqrt(2.0 * 9.81 * 0.5);
  const double y_rest = y[1000];
  CHECK(y_rest <= 0.0);
  CHECK(y_rest >= -0.5 * o.step * v_impact);
  for (std::size_t r = 1000; r < rec.rows(); ++r) {
    CHECK(y[r] == y_rest);
    CHECK(v[r] == 0.0);
    CHECK(lambda[r] == doctest::Approx(9.81));  // resting: lambda_N = m g
  }
  // Energy: the impact removes the kinetic energy m g h0; the balance closes.
  CHECK(stats.energy.impacts == doctest::Approx(-9.81 * 0.5).epsilon(0.02));
  CHECK(stats.energy.error <= 1e-12);
}

TEST_CASE("a ball on a rising platform moves with it (rheonomic contact)") {
  // Platform y_p(t) = V t, V = 0.5 m/s; ball starts on it at rest, e = 0: Newton's law on
  // gdot_N = u - V gives u = V after the first step, and the gap stays at zero.
  ts::Ball ball(ball_on_platform(0.0, 0.0, 0.0, 0.5));
  Recorder rec(ball, 0.0);
  MoreauJeanOptions o;
  o.step = 1e-3;
  o.end_time = 1.0;
  moreau_jean(ball, o, rec);
  const auto v = rec.series("vy"), g = rec.series("gN1"), l = rec.series("lambdaN1");
  // The first step moves the ball by (h/2)(0 + V) while the platform moves by h V: the gap
  // settles at -(h/2) V and stays there (no drift).
  for (std::size_t r = 1; r < rec.rows(); ++r) {
    CHECK(v[r] == doctest::Approx(0.5).epsilon(1e-12));
    CHECK(g[r] == doctest::Approx(-0.5 * o.step * 0.5).epsilon(1e-6));
  }
  for (std::size_t r = 2; r < rec.rows(); ++r) CHECK(l[r] == doctest::Approx(9.81));
}

TEST_CASE("a sliding block stops at v0 / (mu g) after v0^2 / (2 mu g)") {
  // While it slides each step's friction impulse is -mu m g h, so the velocity falls by
  // mu g h per step: the stop is within one step of t_s = v0 / (mu g) and the distance within
  // v0 h of v0^2 / (2 mu g).
  const double v0 = 2.0, mu = 0.4, g = 9.81, h = 1e-3;
  ts::Block block(sliding(v0, mu));
  Recorder rec(block, 0.0);
  MoreauJeanOptions o;
  o.step = h;
  o.end_time = 1.0;
  const RunResult stats = moreau_jean(block, o, rec);
  CHECK(stats.completed);
  CHECK(stats.steps_with_lcp == stats.steps);
  CHECK(stats.lcp_status.at("solved") == stats.lcp_solves);
  const auto t = rec.series("t"), x = rec.series("x"), vx = rec.series("vx"),
             y = rec.series("y"), lt = rec.series("lambdaT1");
  std::size_t stop = 0;
  while (stop < rec.rows() && vx[stop] > 0.0) ++stop;
  REQUIRE(stop < rec.rows());
  CHECK(std::abs(t[stop] - v0 / (mu * g)) <= h);
  CHECK(std::abs(x.back() - v0 * v0 / (2 * mu * g)) <= v0 * h);
  CHECK(lt[stop / 2] == doctest::Approx(-mu * 2.0 * g));  // sliding: lambda_T = -mu m g
  for (std::size_t r = stop; r < rec.rows(); ++r) CHECK(vx[r] == doctest::Approx(0.0));
  for (double yi : y) CHECK(std::abs(yi) <= 1e-12);
  // Friction dissipates the initial kinetic energy (1/2) m v0^2.
  CHECK(stats.energy.friction == doctest::Approx(-0.5 * 2.0 * v0 * v0).epsilon(1e-9));
  CHECK(stats.energy.error <= 1e-9);
  CHECK(rec.count(EventKind::kSlip) == 1);
  CHECK(rec.count(EventKind::kStick) == 1);
}

TEST_CASE("every LCP solver gives the same sliding block") {
  // The contact problem of each step has a unique solution; whichever solver is chosen, the
  // trajectory is the same (to the solvers' tolerance) and no fallback is needed.
  std::vector<double> reference;
  for (lcp::Solver solver : {lcp::Solver::kLemke, lcp::Solver::kPgs, lcp::Solver::kNewtonFb,
                             lcp::Solver::kEnumeration}) {
    CAPTURE(lcp::to_string(solver));
    ts::Block block(sliding(2.0, 0.4));
    Recorder rec(block, 0.0);
    MoreauJeanOptions o;
    o.step = 1e-3;
    o.end_time = 0.6;
    o.solver = solver;
    o.lcp_tolerance = 1e-10;
    const RunResult stats = moreau_jean(block, o, rec);
    CHECK(stats.lcp_fallbacks == 0);
    CHECK(stats.lcp_status.at("solved") == stats.lcp_solves);
    const auto x = rec.series("x");
    if (reference.empty()) reference = x;
    REQUIRE(x.size() == reference.size());
    double worst = 0.0;
    for (std::size_t r = 0; r < x.size(); ++r) worst = std::max(worst, std::abs(x[r] - reference[r]));
    CHECK(worst <= 1e-8);  // 600 steps of impulses accurate to 1e-10 relative
  }
}

TEST_CASE("hysteresis is committed once per accepted step and the tangent is refactorized") {
  ts::PlasticOscillator s(plastic(100.0, 1.0, 2.0, 3.0));
  Recorder rec(s, 0.0);
  MoreauJeanOptions o;
  o.step = 1e-3;
  o.end_time = 6.0;
  const RunResult stats = moreau_jean(s, o, rec);
  CHECK(s.commits == stats.steps + 1);  // + the initial state
  CHECK(stats.factorizations > 2);      // it yielded and unloaded
  CHECK(stats.factorizations < stats.steps / 10);  // but only when the tangent changed
}

// Runs `system` to `until` saving a checkpoint there, then a copy of it (its state at
// `until`) from the checkpoint to `end`, and checks that every history row after `until` and
// the final energy balance equal those of one run of another copy straight to `end`.
template <class S>
void check_resumed_run(const S& system, double h, double until, double end) {
  S whole = system, first = system;
  MoreauJeanOptions o;
  o.step = h;
  o.end_time = end;
  Recorder straight(whole, 0.0);
  const RunResult r = moreau_jean(whole, o, straight);
  MoreauJeanCheckpoint saved;
  o.end_time = until;
  RunHooks save;
  save.checkpoint = &saved;
  Recorder head(first, 0.0);
  moreau_jean(first, o, head, {}, save);
  CHECK(saved.time == until);
  S second = first;
  o.end_time = end;
  RunHooks resume;
  resume.resume = &saved;
  Recorder tail(second, 0.0);
  const RunResult rt = moreau_jean(second, o, tail, {}, resume);
  REQUIRE(straight.rows() == head.rows() + tail.rows() - 1);
  const std::size_t offset = head.rows() - 1;
  for (std::size_t i = 1; i < tail.rows(); ++i) {
    for (std::size_t c = 0; c < tail.columns().size(); ++c) {
      REQUIRE(tail.at(i, c) == straight.at(offset + i, c));
    }
  }
  CHECK(rt.energy.error == r.energy.error);
  CHECK(rt.energy.hysteretic == r.energy.hysteretic);
  CHECK(rt.energy.impacts == r.energy.impacts);
  CHECK(rt.steps == r.steps - (head.rows() - 1));
}

TEST_CASE("a run resumed from a checkpoint continues as the run that saved it") {
  // The plastic oscillator yields and unloads on both sides of the checkpoint (its plastic
  // state travels in the copy of the system); the ball bounces (e = 0.5) across it. The step
  // h = 2^-10 s puts every grid time k h, and so the saving run's end_time, exactly on the
  // grid: the two runs then read the same times.
  const double h = 1.0 / 1024.0;
  check_resumed_run(ts::PlasticOscillator(plastic(100.0, 1.0, 2.0, 3.0)), h, 2560 * h, 6.0);
  check_resumed_run(ts::Ball(ball_on_platform(1.0, 0.0, 0.5)), h, 717 * h, 3.0);
}

TEST_CASE("a checkpoint off its step grid or past end_time is refused") {
  ts::Ball ball(ball_on_platform(1.0, 0.0, 0.5));
  MoreauJeanOptions o;
  o.step = 1e-3;
  o.end_time = 0.5;
  MoreauJeanCheckpoint saved;
  RunHooks save;
  save.checkpoint = &saved;
  Recorder rec(ball, 0.0);
  moreau_jean(ball, o, rec, {}, save);
  RunHooks resume;
  resume.resume = &saved;
  o.end_time = 1.0;
  saved.time += 0.25e-3;
  Recorder off(ball, 0.0);
  CHECK_THROWS_WITH_AS(moreau_jean(ball, o, off, {}, resume),
                       doctest::Contains("resume.time (0.5) is not on the step grid"),
                       std::invalid_argument);
  saved.time = 1.0;
  Recorder late(ball, 0.0);
  CHECK_THROWS_WITH_AS(moreau_jean(ball, o, late, {}, resume), doctest::Contains("must exceed"),
                       std::invalid_argument);
}

TEST_CASE("a restart is for Moreau–Jean only: the other methods refuse one in their hooks") {
  ts::Ball ball(ball_on_platform(1.0, 0.0, 0.5));
  MoreauJeanCheckpoint saved;
  RunHooks hooks;
  hooks.checkpoint = &saved;
  for (const std::string_view method : {"event_driven", "compliance"}) {
    Recorder rec(ball, 0.0);
    CHECK_THROWS_WITH_AS(integrate(ball, default_config(method), rec, {}, hooks),
                         doctest::Contains("RunHooks::resume and checkpoint are for moreau runs"),
                         std::invalid_argument);
  }
}

TEST_CASE("a step allocates nothing") {
  MoreauJeanOptions o;
  o.step = 1e-3;
  auto run = [&](System& s, double end_time) {
    Recorder rec(s, 1e9);  // records the first and the last state only
    o.end_time = end_time;
    return allocations_of([&] { moreau_jean(s, o, rec); });
  };
  SUBCASE("no contact") {
    ts::SpringMass a(oscillator(1.0, 10.0, 0.1, 0.1, 0.0, 1.0, 2.0));
    ts::SpringMass b(oscillator(1.0, 10.0, 0.1, 0.1, 0.0, 1.0, 2.0));
    const long short_run = run(a, 1.0);
    CHECK(short_run > 0);  // the counter sees the workspace being set up
    CHECK(short_run == run(b, 2.0));
  }
  SUBCASE("refactorizations") {
    ts::PlasticOscillator a(plastic(100.0, 1.0, 2.0, 3.0)), b(plastic(100.0, 1.0, 2.0, 3.0));
    CHECK(run(a, 3.0) == run(b, 6.0));
  }
  SUBCASE("a resting contact") {
    ts::Ball a(ball_on_platform(0.1, 0.0, 0.0)), b(ball_on_platform(0.1, 0.0, 0.0));
    CHECK(run(a, 1.0) == run(b, 2.0));
  }
  SUBCASE("a frictional contact problem in every step (Lemke workspace)") {
    // The block slides until t = 0.51 s, then sticks: both runs see the same events.
    ts::Block a(sliding(2.0, 0.4)), b(sliding(2.0, 0.4));
    CHECK(run(a, 0.6) == run(b, 1.2));
  }
}

namespace {

// A mass m = 1 t pressed by a constant force -F against a wall that moves with constant
// acceleration a: x_w(t) = v0 t + a t^2 / 2, gap g_N = q - x_w(t), W_N = 1,
// what_N = -v_w(t) = -(v0 + a t), wbar_N = -a. With force_nan_after set, the force turns
// NaN from that time on (a blown-up model).
class AcceleratingWall final : public System {
 public:
  AcceleratingWall(double a, double v0, double press, double force_nan_after = 1e300)
      : a_(a), v0_(v0), press_(press), nan_after_(force_nan_after),
        mass_(Matrix::Constant(1, 1, 1.0)) {}
  double wall(double t) const { return v0_ * t + 0.5 * a_ * t * t; }
  double wall_speed(double t) const { return v0_ + a_ * t; }
  int dofs() const override { return 1; }
  std::vector<std::string> coordinate_names() const override { return {"x"}; }
  std::vector<std::string> velocity_names() const override { return {"vx"}; }
  const Matrix& mass() const override { return mass_; }
  Vector initial_position() const override { return Vector::Constant(1, wall(0.0)); }
  Vector initial_velocity() const override { return Vector::Constant(1, wall_speed(0.0)); }
  void forces(double t, const Vector&, const Vector&, Vector& f) override {
    f[0] = t > nan_after_ ? std::numeric_limits<double>::quiet_NaN() : -press_;
  }
  void tangent(double, const Vector&, const Vector&, Matrix& K, Matrix& C) override {
    K.setZero();
    C.setZero();
  }
  int contacts() const override { return 1; }
  void contact_data(double t, const Vector& q, const Vector&,
                    std::vector<ContactData>& out) const override {
    out[0].gap_normal = q[0] - wall(t);
    out[0].w_normal[0] = 1.0;
    out[0].w_tangent[0] = 0.0;
    out[0].what_normal = -wall_speed(t);
    out[0].wbar_normal = -a_;
    out[0].restitution = 0.0;
    out[0].friction = 0.0;
  }
  PowerTerms power(double, const Vector&, const Vector& u) const override {
    return {0.0, 0.0, -press_ * u[0]};
  }
  EnergyState energy(double, const Vector&) const override { return {0.0, 0.0}; }

 private:
  double a_, v0_, press_, nan_after_;
  Matrix mass_;
};

}  // namespace

TEST_CASE("a body pressed against an accelerating wall moves with it (rheonomic term at t_k+1)") {
  // Newton's law with eps = 0 on the relative velocity at t_k+1 makes the step end at
  // gdot_N,k+1 = u_k+1 - v_w(t_k+1) = 0 while the wall pushes (Lambda_N > 0): u_k+1 is the
  // wall's speed at t_k+1 exactly. With theta = 1/2, q_k+1 = q_k + h (u_k + u_k+1) / 2 =
  // x_w(t_k) + h (v_w(t_k) + v_w(t_k+1)) / 2 = x_w(t_k+1), the trapezoidal rule being exact
  // for the quadratic x_w: the gap stays 0 up to round-off. Taking what at t_k instead leaves
  // u_k+1 = v_w(t_k), h a = 3e-3 m/s behind, and the wall gains h^2 a / 2 per step on the body.
  // Measured over the 1000 steps (speeds to 5 m/s, positions to 3.5 m): |u - v_w| = 0 and
  // |g_N| <= 2.2e-15 m; the bounds are 1e-14 m/s (a few ulps of 5 m/s) and 1e-13 m (45 times
  // the measured gap).
  AcceleratingWall wall(3.0, 2.0, 10.0);
  Recorder rec(wall, 0.0);
  MoreauJeanOptions o;
  o.step = 1e-3;
  o.end_time = 1.0;
  const RunResult stats = moreau_jean(wall, o, rec);
  REQUIRE(stats.status == RunStatus::kCompleted);
  const auto t = rec.series("t"), v = rec.series("vx");
  const auto gap = rec.series("gN1"), force = rec.series("lambdaN1");
  REQUIRE(t.size() == 1001);
  double worst_speed = 0.0, worst_gap = 0.0;
  for (std::size_t r = 1; r < t.size(); ++r) {
    worst_speed = std::max(worst_speed, std::abs(v[r] - wall.wall_speed(t[r])));
    worst_gap = std::max(worst_gap, std::abs(gap[r]));
    // The contact force is m a + F = 13 kN: the wall pushes in every step.
    CHECK(force[r] == doctest::Approx(13.0).epsilon(1e-9));
  }
  CHECK(worst_speed <= 1e-14);
  CHECK(worst_gap <= 1e-13);
  // No spurious events: one close at the first step, and nothing after it.
  CHECK(rec.count(EventKind::kOpen) == 0);
  CHECK(rec.count(EventKind::kImpact) == 0);
  CHECK(rec.count(EventKind::kClose) <= 1);
}

TEST_CASE("a non-finite force ends the run as diverged, never as an exception") {
  AcceleratingWall wall(3.0, 2.0, 10.0, 0.5);
  Recorder rec(wall, 0.0);
  MoreauJeanOptions o;
  o.step = 1e-3;
  o.end_time = 1.0;
  RunResult stats;
  CHECK_NOTHROW(stats = moreau_jean(wall, o, rec));
  CHECK(stats.status == RunStatus::kDiverged);
  CHECK_FALSE(stats.completed);
  // The first step whose predictor force (at t_k+1) is NaN is the one ending at 0.501 s.
  CHECK(stats.failure_time == doctest::Approx(0.501).epsilon(1e-12));
  CHECK(stats.end_time == doctest::Approx(0.5).epsilon(1e-12));
  for (double v : rec.series("x")) CHECK(std::isfinite(v));
  REQUIRE_FALSE(stats.warnings.empty());
  CHECK(stats.warnings.front().find("0.501") != std::string::npos);
}

TEST_CASE("the progress callback is called with increasing times up to end_time") {
  ts::Ball::Parameters bp;
  bp.initial_height = 0.1;
  bp.restitution = 0.0;
  ts::Ball ball(bp);
  Recorder rec(ball, 1e9);
  MoreauJeanOptions o;
  o.step = 1e-4;
  o.end_time = 1.0;
  std::vector<double> seen;
  moreau_jean(ball, o, rec, [&](double t) { seen.push_back(t); });
  REQUIRE(seen.size() >= 2);
  CHECK(std::is_sorted(seen.begin(), seen.end()));
  CHECK(seen.back() == doctest::Approx(1.0));
}

// Adaptive steps (local_tolerance > 0; docs/moreau-jean.md, "Adaptive steps").

TEST_CASE("adaptive steps: a bouncing ball's impact times and apex heights are the closed form's") {
  // Dropped from y0 = 1 m at rest, e = 0.8, g = 9.81 m/s^2. The first impact is at
  // t_1 = sqrt(2 y0 / g) at the speed v_1 = sqrt(2 g y0); the k-th rebound leaves at e^k v_1,
  // so t_k+1 = t_k + 2 e^k v_1 / g and the apex after it is e^(2k) y0.
  const double g = 9.81, y0 = 1.0, e = 0.8;
  ts::Ball ball(ball_on_platform(y0, 0.0, e));
  Recorder rec(ball, 0.0);
  MoreauJeanOptions o;
  o.step = 1e-3;
  o.end_time = 2.0;
  o.local_tolerance = 1e-4;
  o.min_step = 1e-6;
  const RunResult stats = moreau_jean(ball, o, rec);
  CHECK(stats.completed);
  const double v1 = std::sqrt(2.0 * g * y0);
  std::vector<double> expected{std::sqrt(2.0 * y0 / g)};
  for (int k = 1; k < 3; ++k) expected.push_back(expected.back() + 2.0 * std::pow(e, k) * v1 / g);
  std::vector<double> impacts;
  for (const auto& ev : rec.events()) {
    if (ev.kind == EventKind::kImpact) impacts.push_back(ev.t);
  }
  REQUIRE(impacts.size() == 3);  // the fourth is at 2.214 s
  // The impact is located to within a few min_step: the step that takes the contact into the
  // index set is min_step long, and it closes the gap left of (h/2) |v|.
  constexpr double kImpactTime = 1e-5;  // [s], 10 min_step
  for (std::size_t k = 0; k < impacts.size(); ++k) {
    CAPTURE(k);
    CHECK(std::abs(impacts[k] - expected[k]) <= kImpactTime);
  }
  // The apex between two impacts, the largest y over the steps between them: within the
  // local tolerance of the peak (the step ending nearest the apex misses at most that).
  const auto t = rec.series("t"), y = rec.series("y");
  for (std::size_t k = 0; k + 1 < impacts.size(); ++k) {
    double apex = 0.0;
    for (std::size_t r = 0; r < t.size(); ++r) {
      if (t[r] > impacts[k] && t[r] < impacts[k + 1]) apex = std::max(apex, y[r]);
    }
    CAPTURE(k);
    CHECK(std::abs(apex - std::pow(e, 2.0 * static_cast<double>(k + 1)) * y0) <= 2e-4 * y0);
  }
  // Free flight is exact for the scheme, so the steps grow there: a fixed step of min_step
  // would take 2e6 steps.
  CHECK(stats.steps < 5000);
  CHECK(stats.rejected_steps > 0);
  // The energy balance is bookkeeping of the accepted steps, whatever their lengths.
  CHECK(stats.energy.error <= 1e-12);
}

TEST_CASE("adaptive steps: on a smooth oscillator the step follows the local order 3 of theta = 1/2") {
  // Undamped m x'' + k x = 0, w = sqrt(k / m): the scheme is the trapezoidal rule, whose local
  // error is (h^3 / 12) |x'''| = (h^3 / 12) w^3 A |sin|. Holding it at tol A asks for
  // h ~ tol^(1/3): a tolerance 8 times tighter doubles the number of steps (step doubling).
  // The global error at a fixed time is then ~ h^2 ~ tol^(2/3): 4 times smaller.
  const double m = 1.0, k = 40.0, x0 = 0.05, T = 5.0;
  const double w = std::sqrt(k / m);
  auto run = [&](double tol, std::int64_t& steps) {
    ts::SpringMass s(oscillator(m, k, 0.0, x0, 0.0));
    Recorder rec(s, 1e9);
    MoreauJeanOptions o;
    o.step = 1e-3;
    o.end_time = T;
    o.local_tolerance = tol;
    o.max_step = T;  // no bound but the tolerance
    const RunResult stats = moreau_jean(s, o, rec);
    steps = stats.steps;
    return std::abs(rec.series("x").back() - x0 * std::cos(w * T));
  };
  std::int64_t coarse = 0, fine = 0;
  const double error_coarse = run(1e-4, coarse);
  const double error_fine = run(1e-4 / 8.0, fine);
  const double step_ratio = static_cast<double>(fine) / static_cast<double>(coarse);
  constexpr double kRatioSlack = 0.1;  // the steps near the extrema and the first ones
  CHECK(step_ratio == doctest::Approx(2.0).epsilon(kRatioSlack));
  CHECK(error_coarse / error_fine == doctest::Approx(4.0).epsilon(0.35));
  // And the error itself: at most about w T (w h)^2 / 12 of the amplitude (the phase error of
  // the trapezoidal rule), with (w h)^3 / 12 = tol.
  CHECK(error_coarse <= x0 * w * T * std::pow(12.0 * 1e-4, 2.0 / 3.0) / 12.0);
}

TEST_CASE("adaptive steps: the options' ranges") {
  ts::SpringMass s(oscillator(1.0, 1.0, 0.0, 1.0, 0.0));
  Recorder rec(s, 0.0);
  MoreauJeanOptions o;
  o.local_tolerance = 1.0;
  CHECK_THROWS_WITH_AS(moreau_jean(s, o, rec), doctest::Contains("local_tolerance"),
                       std::invalid_argument);
  o.local_tolerance = 1e-3;
  o.min_step = 0.0;
  CHECK_THROWS_WITH_AS(moreau_jean(s, o, rec), doctest::Contains("min_step"),
                       std::invalid_argument);
}

}  // namespace nsb::integrators
