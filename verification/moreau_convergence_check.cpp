// Measured orders of convergence of Moreau–Jean: about 1 with impacts (bouncing ball against
// its closed form), and the theta-method's order on a smooth manufactured solution with
// Takeda springs and Rayleigh damping active (no contacts).
#include "integrators/moreau_jean.hpp"
#include "models/analytic.hpp"
#include "models/rayleigh.hpp"
#include "models/simple_systems.hpp"
#include "models/takeda.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

namespace nsb {
namespace {

using integrators::ContactData;
using integrators::EnergyState;
using integrators::Matrix;
using integrators::PowerTerms;
using integrators::Recorder;
using integrators::Vector;

// Least-squares slope of log(error) against log(h).
double order(const std::vector<double>& h, const std::vector<double>& e) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(h.size());
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double x = std::log(h[i]), y = std::log(e[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// Two masses in a chain: a Takeda spring from the ground to mass 1 (d1 = x1) and one between
// the masses (d2 = x2 - x1), Rayleigh damping C = a0 M + a1 K0 (5 % on both modes), and a
// manufactured load p(t) = M x*'' + C x*' + F(x*) that makes x*(t) the exact solution:
//   x1*(t) = A1 sin(w1 t),   x2*(t) = x1*(t) + A2 sin(w2 t + phi),
// amplitudes beyond yield so that both springs yield, unload and reload. F(x*(t)) is the
// force of "shadow" Takeda springs driven along x*(t) at the times the integrator asks for.
class ManufacturedChain final : public integrators::System {
 public:
  ManufacturedChain()
      : mass_(Matrix::Identity(2, 2)),
        s1_(models::takeda::Parameters::bilinear(4.0, 0.01)),
        s2_(models::takeda::Parameters::bilinear(3.0, 0.01)),
        shadow1_(s1_),
        shadow2_(s2_) {
    mass_(0, 0) = 1.0;
    mass_(1, 1) = 0.5;
    const double k1 = 400.0, k2 = 300.0;
    Matrix k0(2, 2);
    k0 << k1 + k2, -k2, -k2, k2;
    const auto r = models::rayleigh(mass_, k0, 1, 0.05, 2, 0.05);
    c_ = r.a0 * mass_ + r.a1 * k0;
  }
  static constexpr double A1 = 0.02, W1 = 3.0, A2 = 0.015, W2 = 5.0, PHI = 0.3;
  static Eigen::Vector2d exact(double t) {
    const double x1 = A1 * std::sin(W1 * t);
    return {x1, x1 + A2 * std::sin(W2 * t + PHI)};
  }
  static Eigen::Vector2d exact_velocity(double t) {
    const double v1 = A1 * W1 * std::cos(W1 * t);
    return {v1, v1 + A2 * W2 * std::cos(W2 * t + PHI)};
  }
  static Eigen::Vector2d exact_acceleration(double t) {
    const double a1 = -A1 * W1 * W1 * std::sin(W1 * t);
    return {a1, a1 - A2 * W2 * W2 * std::sin(W2 * t + PHI)};
  }

  int dofs() const override { return 2; }
  std::vector<std::string> coordinate_names() const override { return {"x1", "x2"}; }
  std::vector<std::string> velocity_names() const override { return {"v1", "v2"}; }
  const Matrix& mass() const override { return mass_; }
  Vector initial_position() const override { return exact(0.0); }
  Vector initial_velocity() const override { return exact_velocity(0.0); }
  void forces(double t, const Vector& q, const Vector& u, Vector& f) override {
    const double f1 = s1_.set_trial(q[0]);
    const double f2 = s2_.set_trial(q[1] - q[0]);
    f[0] = -f1 + f2;
    f[1] = -f2;
    f.noalias() -= c_ * u;
    f += load(t);
  }
  void tangent(double, const Vector&, const Vector&, Matrix& K, Matrix& C) override {
    const double k1 = s1_.tangent(), k2 = s2_.tangent();
    K << k1 + k2, -k2, -k2, k2;
    C = c_;
  }
  bool tangent_changed() const override { return s1_.tangent_changed() || s2_.tangent_changed(); }
  void commit() override {
    s1_.commit();
    s2_.commit();
  }
  void revert() override {
    s1_.revert();
    s2_.revert();
  }
  int contacts() const override { return 0; }
  void contact_data(double, const Vector&, const Vector&,
                    std::vector<ContactData>&) const override {}
  // The load's power uses the load of the last forces() call, made at this same time.
  PowerTerms power(double, const Vector&, const Vector& u) const override {
    const Eigen::Vector2d cu = c_ * u;
    return {u.dot(cu), 0.0, last_load_.dot(u)};
  }
  EnergyState energy(double, const Vector&) const override {
    return {s1_.stored_energy() + s2_.stored_energy(),
            s1_.dissipated_energy() + s2_.dissipated_energy()};
  }

 private:
  // p(t) = M x*'' + C x*' + F_shadow(x*(t)); the shadow springs advance (commit) each time the
  // integrator moves to a new time, so they follow x*(t) sampled at the step times.
  Eigen::Vector2d load(double t) {
    if (t != shadow_t_) {
      if (shadow_started_) {
        shadow1_.commit();
        shadow2_.commit();
      }
      const Eigen::Vector2d x = exact(t);
      shadow1_.set_trial(x[0]);
      shadow2_.set_trial(x[1] - x[0]);
      shadow_t_ = t;
      shadow_started_ = true;
    }
    const double f1 = shadow1_.force(), f2 = shadow2_.force();
    const Eigen::Vector2d internal(f1 - f2, f2);
    last_load_ = mass_ * exact_acceleration(t) + c_ * exact_velocity(t) + internal;
    return last_load_;
  }
  Matrix mass_, c_;
  models::takeda::Spring s1_, s2_, shadow1_, shadow2_;
  double shadow_t_ = -1e300;
  bool shadow_started_ = false;
  Eigen::Vector2d last_load_ = Eigen::Vector2d::Zero();
};

}  // namespace

TEST_CASE("with impacts the global error converges at order about 1") {
  // Bouncing ball, e = 0.8 from 1 m; error in (y, v) at T = 1.5 s (between the 2nd and 3rd
  // impacts at 1.174 s and 1.752 s) against analytic::ball_state.
  models::BouncingBall::Parameters p;
  p.restitution = 0.8;
  const double T = 1.5;
  const auto exact = models::analytic::ball_state(p, T);
  std::vector<double> hs{4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4}, errors;
  for (double h : hs) {
    models::BouncingBall ball(p);
    Recorder rec(ball, 1e9);
    integrators::MoreauJeanOptions o;
    o.step = h;
    o.end_time = T;
    integrators::moreau_jean(ball, o, rec);
    errors.push_back(std::abs(rec.series("y").back() - exact.position) +
                     std::abs(rec.series("vy").back() - exact.velocity) * 0.1);
  }
  const double measured = order(hs, errors);
  MESSAGE("ball with impacts: errors ", errors[0], " ... ", errors.back(), "; order ", measured);
  CHECK(measured > 0.7);
  CHECK(measured < 1.5);
}

TEST_CASE("a manufactured smooth solution with Takeda and Rayleigh converges at order 2") {
  // theta = 1/2 is second order for smooth solutions; the kinks of the Takeda force along
  // x*(t) add O(h^2) locally at finitely many times, which keeps the global order 2.
  // theta = 1 is first order.
  const double T = 3.0;
  const Eigen::Vector2d xs = ManufacturedChain::exact(T);
  for (double theta : {0.5, 1.0}) {
    std::vector<double> hs{4e-3, 2e-3, 1e-3, 5e-4}, errors;
    for (double h : hs) {
      ManufacturedChain s;
      Recorder rec(s, 1e9);
      integrators::MoreauJeanOptions o;
      o.step = h;
      o.end_time = T;
      o.theta = theta;
      const auto stats = integrators::moreau_jean(s, o, rec);
      REQUIRE(stats.completed);
      CHECK(stats.factorizations > 4);  // the springs changed branch
      errors.push_back(std::hypot(rec.series("x1").back() - xs[0], rec.series("x2").back() - xs[1]));
    }
    const double measured = order(hs, errors);
    CAPTURE(theta);
    MESSAGE("manufactured Takeda + Rayleigh, theta = ", theta, ": errors ", errors[0], " ... ",
            errors.back(), "; order ", measured);
    const double expected = theta == 0.5 ? 2.0 : 1.0;
    CHECK(measured == doctest::Approx(expected).epsilon(0.15));
  }
}

}  // namespace nsb
