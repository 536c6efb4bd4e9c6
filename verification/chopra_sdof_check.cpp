// Elastic SDOF peaks under the 1940 El Centro N-S record against Chopra, Dynamics of
// Structures, §6.4 (deformation response of SDF systems to the El Centro ground motion): the
// reference numbers come from the piecewise-linear excitation (the exact recurrence of §5.2),
// without baseline correction.
//
// Two independent routes reach them: (1) the exact piecewise-linear recurrence of Chopra §5.2
// (Nigam & Jennings 1969) on the record samples; (2) classical RK4 with a fine fixed step on
// the cubic-spline acceleration of models::GroundMotion. Both must agree with Chopra within 1 %.
// (3) the project's integrators, Moreau–Jean and event-driven, on a bent with no contacts:
// one mass on an elastic Takeda column spring (its yield force out of reach) under the spline
// ground acceleration, through integrators::integrate like every scene.
// The same record in PEER NGA processing (RSN6, PGA 0.281 g) does not reproduce them: a
// documented property of that file (docs/ground-motions.md), checked here as such.
#include "integrators/run.hpp"
#include "models/ground_motion.hpp"
#include "models/takeda.hpp"
#include "scene/records.hpp"

#include <doctest/doctest.h>

#include <boost/numeric/odeint.hpp>

#include <array>
#include <cmath>
#include <numbers>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using nsb::models::GroundMotion;
using nsb::models::GroundMotionOptions;
using nsb::scene::read_at2;

// Chopra quotes peaks to 3 significant figures; the task is agreement within 1 %.
constexpr double kChopraTolerance = 0.01;
// A peak of the PEER NGA version counts as different from Chopra's beyond this deviation.
constexpr double kDifferentRecordMargin = 0.05;
// Chopra's numbers are in inches with g = 386 in/s^2; the record is read with g = 9.81 m/s^2
// and the peaks converted with 1 in = 0.0254 m (g differs from 386 in/s^2 by 0.06 %).
constexpr double kMetresPerInch = 0.0254;
// RK4 substeps per record step: RK4's error scales with (omega h)^4 ~ 1e-8 here.
constexpr int kRk4Substeps = 20;
// Peaks of the same spline excitation by RK4 and by the project's integrators agree to this
// (measured worst 2.0e-5, Moreau–Jean at T = 1 s; 5x margin).
constexpr double kIntegratorAgreement = 1e-4;
// Chopra Table 5.2.1 coefficients reproduce closed-form responses to round-off.
constexpr double kRecurrenceTolerance = 1e-9;

const fs::path kElCentro = fs::path(NSB_DATA_DIR) / "ground-motions/elCentro_NS_1940_Peknold.AT2";
const fs::path kPeerElc = fs::path(NSB_DATA_DIR) / "ground-motions/RSN6_IMPVALL.I_I-ELC180.AT2";

struct Case {
  double period, zeta, peak_in;
};
// Chopra §6.4: peak deformations [in] for (T_n, zeta).
constexpr std::array<Case, 5> kCases{{{0.5, 0.02, 2.67},
                                      {1.0, 0.02, 5.97},
                                      {2.0, 0.02, 7.47},
                                      {2.0, 0.00, 9.91},
                                      {2.0, 0.05, 5.37}}};

// Chopra §5.2, Table 5.2.1: exact update of u, v over a step dt for
// u'' + 2 zeta w u' + w^2 u = p(t)/m with p linear within the step (unit mass, k = w^2).
struct Recurrence {
  double A, B, C, D, Ap, Bp, Cp, Dp;
  Recurrence(double w, double zeta, double dt) {
    const double k = w * w;
    const double s1 = std::sqrt(1.0 - zeta * zeta);
    const double wd = w * s1;
    const double e = std::exp(-zeta * w * dt);
    const double s = std::sin(wd * dt), c = std::cos(wd * dt);
    A = e * (zeta / s1 * s + c);
    B = e * (s / wd);
    C = (2.0 * zeta / (w * dt) +
         e * (((1.0 - 2.0 * zeta * zeta) / (wd * dt) - zeta / s1) * s -
              (1.0 + 2.0 * zeta / (w * dt)) * c)) /
        k;
    D = (1.0 - 2.0 * zeta / (w * dt) +
         e * ((2.0 * zeta * zeta - 1.0) / (wd * dt) * s + 2.0 * zeta / (w * dt) * c)) /
        k;
    Ap = -e * (w / s1 * s);
    Bp = e * (c - zeta / s1 * s);
    Cp = (-1.0 / dt + e * ((w / s1 + zeta / (dt * s1)) * s + c / dt)) / k;
    Dp = (1.0 - e * (zeta / s1 * s + c)) / (k * dt);
  }
};

// Peak |u| for the ground acceleration samples ag (p = -ag per unit mass), linear between
// samples, starting at rest.
double peak_piecewise_linear(const std::vector<double>& ag, double dt, double period,
                             double zeta) {
  const double w = 2.0 * std::numbers::pi / period;
  const Recurrence r(w, zeta, dt);
  double u = 0.0, v = 0.0, peak = 0.0;
  for (std::size_t i = 0; i + 1 < ag.size(); ++i) {
    const double p0 = -ag[i], p1 = -ag[i + 1];
    const double un = r.A * u + r.B * v + r.C * p0 + r.D * p1;
    const double vn = r.Ap * u + r.Bp * v + r.Cp * p0 + r.Dp * p1;
    u = un;
    v = vn;
    peak = std::max(peak, std::abs(u));
  }
  return peak;
}

// Peak |u| by RK4 with a fixed step dt/substeps on the spline acceleration of gm. Like
// Chopra's, the peak is taken over the record's sample times: the continuous peak between
// samples is up to 0.7 % higher at T = 0.5 s, which is not what the reference numbers measure.
double peak_rk4_spline(const GroundMotion& gm, double dt, double period, double zeta) {
  namespace odeint = boost::numeric::odeint;
  using State = std::array<double, 2>;
  const double w = 2.0 * std::numbers::pi / period;
  auto rhs = [&](const State& x, State& dxdt, double t) {
    dxdt[0] = x[1];
    dxdt[1] = -gm.acceleration(t) - 2.0 * zeta * w * x[1] - w * w * x[0];
  };
  odeint::runge_kutta4<State> stepper;
  State x{0.0, 0.0};
  const double h = dt / kRk4Substeps;
  const auto steps = static_cast<long>(std::llround((gm.end_time() - gm.start_time()) / h));
  double peak = 0.0;
  for (long i = 0; i < steps; ++i) {
    stepper.do_step(rhs, x, gm.start_time() + static_cast<double>(i) * h, h);
    if ((i + 1) % kRk4Substeps == 0) peak = std::max(peak, std::abs(x[0]));
  }
  return peak;
}

// A bent with no contacts: mass m on a Takeda column spring and a viscous damper,
// m x'' + c x' + F_takeda(x) = -m a_g(t), relative coordinate x. The yield force is set a
// thousand times above any force of the run, so the spring stays on its elastic branch
// F = k x, which is what Chopra's elastic spectrum assumes.
class ElasticBent final : public nsb::integrators::System {
 public:
  ElasticBent(const GroundMotion& gm, double period, double zeta)
      : gm_(gm),
        k_(std::pow(2.0 * std::numbers::pi / period, 2.0) * kMass),
        c_(2.0 * zeta * std::sqrt(k_ * kMass)),
        spring_(nsb::models::takeda::Parameters::bilinear(kUnreachableYield,
                                                          kUnreachableYield / k_)),
        mass_(nsb::integrators::Matrix::Constant(1, 1, kMass)) {}

  bool elastic() const { return spring_.elastic(); }  // never left the elastic branch
  int dofs() const override { return 1; }
  std::vector<std::string> coordinate_names() const override { return {"x"}; }
  std::vector<std::string> velocity_names() const override { return {"vx"}; }
  const nsb::integrators::Matrix& mass() const override { return mass_; }
  nsb::integrators::Vector initial_position() const override {
    return nsb::integrators::Vector::Zero(1);
  }
  nsb::integrators::Vector initial_velocity() const override {
    return nsb::integrators::Vector::Zero(1);
  }
  void forces(double t, const nsb::integrators::Vector& q, const nsb::integrators::Vector& u,
              nsb::integrators::Vector& f) override {
    f(0) = -kMass * gm_.acceleration(t) - c_ * u(0) - spring_.set_trial(q(0));
  }
  void tangent(double, const nsb::integrators::Vector&, const nsb::integrators::Vector&,
               nsb::integrators::Matrix& K, nsb::integrators::Matrix& C) override {
    K.setConstant(1, 1, spring_.tangent());
    C.setConstant(1, 1, c_);
  }
  bool tangent_changed() const override { return spring_.tangent_changed(); }
  void commit() override { spring_.commit(); }
  void revert() override { spring_.revert(); }
  int contacts() const override { return 0; }
  void contact_data(double, const nsb::integrators::Vector&, const nsb::integrators::Vector&,
                    std::vector<nsb::integrators::ContactData>&) const override {}
  nsb::integrators::PowerTerms power(double t, const nsb::integrators::Vector&,
                                     const nsb::integrators::Vector& u) const override {
    nsb::integrators::PowerTerms p;
    p.damping = c_ * u(0) * u(0);
    p.ground = -kMass * gm_.acceleration(t) * u(0);
    return p;
  }
  nsb::integrators::EnergyState energy(double, const nsb::integrators::Vector&) const override {
    nsb::integrators::EnergyState e;
    e.stored = spring_.stored_energy();
    e.hysteretic = spring_.dissipated_energy();
    return e;
  }

 private:
  static constexpr double kMass = 1.0;                 // [t]
  static constexpr double kUnreachableYield = 1e4;     // [kN]: peak forces here are < 10 kN
  const GroundMotion& gm_;
  double k_, c_;
  nsb::models::takeda::Spring spring_;
  nsb::integrators::Matrix mass_;
};

// Peak |x| over the record's sample times (as Chopra's), through integrate().
double peak_integrated(const GroundMotion& gm, double dt, const Case& c,
                       const nsb::integrators::RunConfig& config) {
  ElasticBent bent(gm, c.period, c.zeta);
  nsb::integrators::Recorder rec(bent, dt);
  const auto result = nsb::integrators::integrate(bent, config, rec);
  REQUIRE(nsb::integrators::succeeded(result.status));
  REQUIRE(bent.elastic());
  double peak = 0.0;
  for (double x : rec.series("x")) peak = std::max(peak, std::abs(x));
  return peak;
}

}  // namespace

TEST_CASE("chopra: the section 5.2 recurrence is exact for a linearly varying load") {
  // p(t) = t (per unit mass) from rest: u = (t - sin(w t)/w)/w^2 for zeta = 0, and the
  // recurrence must reproduce it at every step, whatever the step.
  const double w = 2.0 * std::numbers::pi, dt = 0.37;
  const Recurrence r(w, 0.0, dt);
  double u = 0.0, v = 0.0;
  for (int i = 0; i < 20; ++i) {
    const double t0 = i * dt, t1 = t0 + dt;
    const double un = r.A * u + r.B * v + r.C * t0 + r.D * t1;
    const double vn = r.Ap * u + r.Bp * v + r.Cp * t0 + r.Dp * t1;
    u = un;
    v = vn;
    const double exact_u = (t1 - std::sin(w * t1) / w) / (w * w);
    const double exact_v = (1.0 - std::cos(w * t1)) / (w * w);
    CHECK(u == doctest::Approx(exact_u).epsilon(kRecurrenceTolerance).scale(1.0 / (w * w)));
    CHECK(v == doctest::Approx(exact_v).epsilon(kRecurrenceTolerance).scale(1.0 / (w * w)));
  }
  // Damped: a constant load settles at the static deflection p/k.
  const Recurrence rd(w, 0.05, 0.01);
  u = v = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const double un = rd.A * u + rd.B * v + (rd.C + rd.D) * 1.0;
    v = rd.Ap * u + rd.Bp * v + (rd.Cp + rd.Dp) * 1.0;
    u = un;
  }
  CHECK(u == doctest::Approx(1.0 / (w * w)).epsilon(kRecurrenceTolerance));
}

TEST_CASE("chopra: El Centro 1940 N-S (Peknold) SDOF peaks within 1 %") {
  const auto rec = read_at2(kElCentro);
  const double dt = rec.t[1] - rec.t[0];
  GroundMotionOptions o;
  o.baseline_correction = false;  // Chopra integrates the record as it is
  const GroundMotion gm(rec, o);
  CHECK(gm.pga() / 9.81 == doctest::Approx(0.319).epsilon(0.002));
  for (const auto& c : kCases) {
    const double exact = peak_piecewise_linear(rec.a, dt, c.period, c.zeta) / kMetresPerInch;
    const double spline = peak_rk4_spline(gm, dt, c.period, c.zeta) / kMetresPerInch;
    std::printf("T = %.1f s, zeta = %.2f: Chopra %.2f in, piecewise-linear %.3f in (%+.2f %%), "
                "spline + RK4 %.3f in (%+.2f %%)\n",
                c.period, c.zeta, c.peak_in, exact, 100.0 * (exact / c.peak_in - 1.0), spline,
                100.0 * (spline / c.peak_in - 1.0));
    INFO("T = " << c.period << " s, zeta = " << c.zeta);
    CHECK(exact == doctest::Approx(c.peak_in).epsilon(kChopraTolerance));
    CHECK(spline == doctest::Approx(c.peak_in).epsilon(kChopraTolerance));
  }
}

TEST_CASE("chopra: Moreau–Jean and event-driven on an elastic bent reproduce Chopra's peaks") {
  const auto rec = read_at2(kElCentro);
  const double dt = rec.t[1] - rec.t[0];
  GroundMotionOptions o;
  o.baseline_correction = false;
  const GroundMotion gm(rec, o);
  // Moreau–Jean, theta = 1/2, h = dt / 20: the trapezoidal rule's period error (w h)^2 / 12
  // is 1.3e-5 at T = 0.5 s. Event-driven at tolerance 1e-8, sampled on the record's times.
  nsb::integrators::MoreauJeanOptions mj;
  mj.end_time = gm.end_time();
  mj.step = dt / kRk4Substeps;
  nsb::integrators::EventDrivenOptions ed;
  ed.end_time = gm.end_time();
  ed.tolerance = 1e-8;
  for (const auto& c : kCases) {
    const double spline = peak_rk4_spline(gm, dt, c.period, c.zeta) / kMetresPerInch;
    const double moreau = peak_integrated(gm, dt, c, mj) / kMetresPerInch;
    const double event = peak_integrated(gm, dt, c, ed) / kMetresPerInch;
    std::printf("T = %.1f s, zeta = %.2f: Chopra %.2f in, Moreau-Jean %.3f in (%+.2f %%), "
                "event-driven %.3f in (%+.2f %%); against RK4 %.1e, %.1e\n",
                c.period, c.zeta, c.peak_in, moreau, 100.0 * (moreau / c.peak_in - 1.0), event,
                100.0 * (event / c.peak_in - 1.0), std::abs(moreau / spline - 1.0),
                std::abs(event / spline - 1.0));
    INFO("T = " << c.period << " s, zeta = " << c.zeta);
    CHECK(std::abs(moreau / c.peak_in - 1.0) <= kChopraTolerance);
    CHECK(std::abs(event / c.peak_in - 1.0) <= kChopraTolerance);
    // The same spline excitation integrated three ways: agreement far inside Chopra's
    // 3 figures (kIntegratorAgreement).
    CHECK(std::abs(moreau / spline - 1.0) <= kIntegratorAgreement);
    CHECK(std::abs(event / spline - 1.0) <= kIntegratorAgreement);
  }
}

TEST_CASE("chopra: the PEER NGA version of the record does not give Chopra's peaks") {
  // RSN6 is the same accelerogram after PEER NGA processing (re-digitized, filtered, 0.01 s):
  // its PGA is 0.281 g instead of 0.319 g and its spectrum differs, so Chopra's numbers are
  // not a check of it. Measured (piecewise-linear recurrence): T = 0.5 s -29 %, T = 1 s -1.4 %,
  // T = 2 s +25 % (2 %), +58 % (0 %), +44 % (5 %). The T = 1 s ordinate happens to agree;
  // the other four miss by more than 20 %.
  const auto rec = read_at2(kPeerElc);
  const double dt = rec.t[1] - rec.t[0];
  GroundMotionOptions o;
  o.baseline_correction = false;
  const GroundMotion gm(rec, o);
  CHECK(gm.pga() / 9.81 == doctest::Approx(0.281).epsilon(0.005));
  int missed = 0;
  double worst = 0.0;
  for (const auto& c : kCases) {
    const double peak = peak_piecewise_linear(rec.a, dt, c.period, c.zeta) / kMetresPerInch;
    const double dev = peak / c.peak_in - 1.0;
    std::printf("RSN6 (PEER NGA): T = %.1f s, zeta = %.2f: %.3f in against Chopra's %.2f in (%+.1f %%)\n",
                c.period, c.zeta, peak, c.peak_in, 100.0 * dev);
    if (std::abs(dev) > kDifferentRecordMargin) ++missed;
    worst = std::max(worst, std::abs(dev));
  }
  CHECK(missed >= 4);
  CHECK(worst > 4.0 * kDifferentRecordMargin);
}
