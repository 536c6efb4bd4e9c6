// Simple benchmark systems behind the integrators::System interface. See simple_systems.hpp.
//
// Energy convention: gravity is conservative and appears in EnergyState::stored as its
// potential, so PowerTerms::external holds only the work rate of the driving forces; the
// balance kinetic + stored = initial + external - damping + (impacts, friction) then counts
// gravity once.
#include "models/simple_systems.hpp"

#include "models/field_checks.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace nsb::models {
namespace {

using integrators::ContactData;
using integrators::EnergyState;
using integrators::Matrix;
using integrators::PowerTerms;
using integrators::Vector;

// Harmonic forcing F0 sin(2 pi f t); f = 0 gives sin(0) = 0, i.e. no force.
double harmonic(double amplitude, double frequency_hz, double t) {
  return amplitude * std::sin(2.0 * std::numbers::pi * frequency_hz * t);
}

}  // namespace

// ---------------------------------------------------------------------------------------
// BouncingBall: m y'' = -m g + Lambda_N, g_N = y.

void BouncingBall::Parameters::validate() const {
  config::validate_fields<Parameters>(*this, bouncing_ball_fields());
}

BouncingBall::BouncingBall(const Parameters& p) : SystemBase({"y"}, {"vy"}), p_(p) {
  p_.validate();
  set_mass(Matrix::Constant(1, 1, p_.mass));
  set_initial_state(Vector::Constant(1, p_.height), Vector::Constant(1, p_.velocity));
}

void BouncingBall::forces(double, const Vector&, const Vector&, Vector& f) {
  f(0) = -p_.mass * p_.gravity;
}

void BouncingBall::contact_data(double, const Vector& q, const Vector&,
                                std::vector<ContactData>& out) const {
  static const Vector kWn = Vector::Constant(1, 1.0);
  static const Vector kWt = Vector::Zero(1);
  integrators::set_fixed_contact(out.at(0), q(0), kWn, kWt, p_.restitution, 0.0);
}

EnergyState BouncingBall::energy(double, const Vector& q) const {
  EnergyState e;
  e.stored = p_.mass * p_.gravity * q(0);
  return e;
}

// ---------------------------------------------------------------------------------------
// ImpactOscillator: m x'' + c x' + k x = F0 sin(2 pi f t) - Lambda_N, g_N = gap - x.

void ImpactOscillator::Parameters::validate() const {
  config::validate_fields<Parameters>(*this, impact_oscillator_fields());
  require(initial_position <= gap, "initial_position",
          "must be <= gap (an initial position beyond the stop is a penetration) (got " +
              std::to_string(initial_position) + ")");
}

ImpactOscillator::ImpactOscillator(const Parameters& p) : SystemBase({"x"}, {"vx"}), p_(p) {
  p_.validate();
  c_ = 2.0 * p_.damping_ratio * std::sqrt(p_.stiffness * p_.mass);
  set_mass(Matrix::Constant(1, 1, p_.mass));
  set_initial_state(Vector::Constant(1, p_.initial_position),
                    Vector::Constant(1, p_.initial_velocity));
}

double ImpactOscillator::external_force(double t) const {
  return harmonic(p_.force_amplitude, p_.force_frequency, t);
}

void ImpactOscillator::forces(double t, const Vector& q, const Vector& u, Vector& f) {
  f(0) = -p_.stiffness * q(0) - c_ * u(0) + external_force(t);
}

void ImpactOscillator::tangent(double, const Vector&, const Vector&, Matrix& K, Matrix& C) {
  K.setConstant(1, 1, p_.stiffness);
  C.setConstant(1, 1, c_);
}

void ImpactOscillator::contact_data(double, const Vector& q, const Vector&,
                                    std::vector<ContactData>& out) const {
  static const Vector kWn = Vector::Constant(1, -1.0);  // d(gap - x)/dx
  static const Vector kWt = Vector::Zero(1);
  integrators::set_fixed_contact(out.at(0), p_.gap - q(0), kWn, kWt, p_.restitution, 0.0);
}

PowerTerms ImpactOscillator::power(double t, const Vector&, const Vector& u) const {
  PowerTerms pw;
  pw.damping = c_ * u(0) * u(0);
  pw.external = external_force(t) * u(0);
  return pw;
}

EnergyState ImpactOscillator::energy(double, const Vector& q) const {
  EnergyState e;
  e.stored = 0.5 * p_.stiffness * q(0) * q(0);
  return e;
}

// ---------------------------------------------------------------------------------------
// SlidingBlock: m x'' = F(t) + m g_x + Lambda_T, m y'' = m g_y + Lambda_N, g_N = y.

void SlidingBlock::Parameters::validate() const {
  config::validate_fields<Parameters>(*this, sliding_block_fields());
}

SlidingBlock::SlidingBlock(const Parameters& p)
    : SystemBase({"x", "y"}, {"vx", "vy"}), p_(p) {
  p_.validate();
  const double beta = p_.incline_deg * std::numbers::pi / 180.0;
  gx_ = -p_.mass * p_.gravity * std::sin(beta);
  gy_ = -p_.mass * p_.gravity * std::cos(beta);
  set_mass(Matrix::Identity(2, 2) * p_.mass);
  Vector u0 = Vector::Zero(2);
  u0(0) = p_.initial_velocity;
  set_initial_state(Vector::Zero(2), u0);
}

double SlidingBlock::driving_force(double t) const {
  return p_.force + harmonic(p_.force_amplitude, p_.force_frequency, t);
}

void SlidingBlock::forces(double t, const Vector&, const Vector&, Vector& f) {
  f(0) = driving_force(t) + gx_;
  f(1) = gy_;
}

void SlidingBlock::contact_data(double, const Vector& q, const Vector&,
                                std::vector<ContactData>& out) const {
  static const Vector kWn = (Vector(2) << 0.0, 1.0).finished();
  static const Vector kWt = (Vector(2) << 1.0, 0.0).finished();
  // Restitution 0: the block rests on the ground; the contact is persistent.
  integrators::set_fixed_contact(out.at(0), q(1), kWn, kWt, 0.0, p_.friction);
}

PowerTerms SlidingBlock::power(double t, const Vector&, const Vector& u) const {
  PowerTerms pw;
  pw.external = driving_force(t) * u(0);
  return pw;
}

EnergyState SlidingBlock::energy(double, const Vector& q) const {
  EnergyState e;
  e.stored = -(gx_ * q(0) + gy_ * q(1));  // potential of the constant gravity force
  return e;
}

std::span<const config::Field<BouncingBall::Parameters>> bouncing_ball_fields() {
  namespace c = config;
  using P = BouncingBall::Parameters;
  static const c::Field<P> f[] = {
      c::number<&P::mass>("mass", "t", c::positive(), "mass m"),
      c::number<&P::height>("height", "m", c::non_negative(),
                            "initial height = the initial gap (< 0 would penetrate)"),
      c::number<&P::velocity>("velocity", "m/s", c::any(), "initial velocity, upward positive"),
      c::number<&P::restitution>("restitution", "-", c::closed(0, 1), "Newton's coefficient e"),
      c::number<&P::gravity>("gravity", "m/s^2", c::non_negative(), "g"),
  };
  return f;
}

std::span<const config::Field<ImpactOscillator::Parameters>> impact_oscillator_fields() {
  namespace c = config;
  using P = ImpactOscillator::Parameters;
  static const c::Field<P> f[] = {
      c::number<&P::mass>("mass", "t", c::positive(), "mass m"),
      c::number<&P::stiffness>("stiffness", "kN/m", c::non_negative(), "spring k"),
      c::number<&P::damping_ratio>("damping_ratio", "-", c::non_negative(),
                                   "ζ; c = 2ζ√(km)"),
      c::number<&P::gap>("gap", "m", c::any(), "position of the stop"),
      c::number<&P::restitution>("restitution", "-", c::closed(0, 1), "Newton's coefficient e"),
      c::number<&P::initial_position>("initial_position", "m", c::any(),
                                      "x₀; at most gap (else an initial penetration)"),
      c::number<&P::initial_velocity>("initial_velocity", "m/s", c::any(), "v₀"),
      c::number<&P::force_amplitude>("force_amplitude", "kN", c::any(), "F₀ of F₀ sin(2π f t)"),
      c::number<&P::force_frequency>("force_frequency", "Hz", c::non_negative(), "f"),
  };
  return f;
}

std::span<const config::Field<SlidingBlock::Parameters>> sliding_block_fields() {
  namespace c = config;
  using P = SlidingBlock::Parameters;
  static const c::Field<P> f[] = {
      c::number<&P::mass>("mass", "t", c::positive(), "mass m"),
      c::number<&P::friction>("friction", "-", c::non_negative(), "Coulomb μ"),
      c::number<&P::gravity>("gravity", "m/s^2", c::non_negative(), "g"),
      c::number<&P::initial_velocity>("initial_velocity", "m/s", c::any(), "v₀ along x"),
      c::number<&P::force>("force", "kN", c::any(), "constant driving force along x"),
      c::number<&P::force_amplitude>("force_amplitude", "kN", c::any(),
                                     "F₀ of F₀ sin(2π f t) along x"),
      c::number<&P::force_frequency>("force_frequency", "Hz", c::non_negative(), "f"),
      c::number<&P::incline_deg>("incline_deg", "deg", c::open(-90, 90), "slope angle β"),
  };
  return f;
}

}  // namespace nsb::models
