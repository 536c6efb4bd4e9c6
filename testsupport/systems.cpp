#include "testsupport/systems.hpp"

#include <cmath>
#include <string>
#include <utility>

namespace nsb::testsupport {

namespace {

std::vector<std::string> numbered(char prefix, int n) {
  std::vector<std::string> names;
  for (int i = 1; i <= n; ++i) names.push_back(prefix + std::to_string(i));
  return names;
}

Vector vector2(double a, double b) { return (Vector(2) << a, b).finished(); }

}  // namespace

// ---------------------------------------------------------------------------------------
FreeMass::FreeMass(int dofs) : TestSystem(numbered('q', dofs), numbered('u', dofs)) {}

FreeMass::FreeMass(std::vector<std::string> coordinate_names,
                   std::vector<std::string> velocity_names)
    : TestSystem(std::move(coordinate_names), std::move(velocity_names)) {}

// ---------------------------------------------------------------------------------------
SpringMass::SpringMass(const Parameters& p) : TestSystem({"x"}, {"vx"}), p_(p) {
  set_mass(Matrix::Constant(1, 1, p_.mass));
  set_initial_state(Vector::Constant(1, p_.initial_position),
                    Vector::Constant(1, p_.initial_velocity));
}

double SpringMass::load(double t) const {
  return p_.force_amplitude * std::sin(p_.force_frequency * t);
}

void SpringMass::forces(double t, const Vector& q, const Vector& u, Vector& f) {
  f[0] = -p_.stiffness * q[0] - p_.damping * u[0] + load(t);
}

void SpringMass::tangent(double, const Vector&, const Vector&, Matrix& K, Matrix& C) {
  K.setConstant(1, 1, p_.stiffness);
  C.setConstant(1, 1, p_.damping);
}

void SpringMass::contact_data(double t, const Vector& q, const Vector&,
                              std::vector<ContactData>& out) const {
  if (!p_.wall) return;
  integrators::set_fixed_contact(out[0], q[0] - p_.wall_velocity * t, Vector::Ones(1),
                                 Vector::Zero(1), p_.restitution, 0.0);
  out[0].what_normal = -p_.wall_velocity;  // the wall moves at constant speed: wbar_N = 0
}

PowerTerms SpringMass::power(double t, const Vector&, const Vector& u) const {
  PowerTerms pw;
  pw.damping = p_.damping * u[0] * u[0];
  pw.external = load(t) * u[0];
  return pw;
}

EnergyState SpringMass::energy(double, const Vector& q) const {
  EnergyState e;
  e.stored = 0.5 * p_.stiffness * q[0] * q[0];
  return e;
}

// ---------------------------------------------------------------------------------------
Ball::Ball(const Parameters& p) : TestSystem({"y"}, {"vy"}), p_(p) {
  set_mass(Matrix::Constant(1, 1, p_.mass));
  set_initial_state(Vector::Constant(1, p_.initial_height),
                    Vector::Constant(1, p_.initial_velocity));
}

double Ball::floor_height(double t) const {
  return p_.floor_velocity * t + p_.floor_amplitude * std::sin(p_.floor_frequency * t);
}

void Ball::forces(double t, const Vector&, const Vector&, Vector& f) {
  f[0] = -p_.mass * p_.gravity + p_.ramp * t;
}

void Ball::contact_data(double t, const Vector& q, const Vector&,
                        std::vector<ContactData>& out) const {
  const double a = p_.floor_amplitude, w = p_.floor_frequency;
  integrators::set_fixed_contact(out[0], q[0] - floor_height(t), Vector::Ones(1),
                                 Vector::Zero(1), p_.restitution, 0.0);
  out[0].what_normal = -(p_.floor_velocity + a * w * std::cos(w * t));  // -y_f'
  out[0].wbar_normal = a * w * w * std::sin(w * t);                     // -y_f''
}

PowerTerms Ball::power(double t, const Vector&, const Vector& u) const {
  PowerTerms pw;
  pw.external = p_.ramp * t * u[0];
  return pw;
}

EnergyState Ball::energy(double, const Vector& q) const {
  EnergyState e;
  e.stored = p_.mass * p_.gravity * q[0];
  return e;
}

// ---------------------------------------------------------------------------------------
Block::Block(const Parameters& p) : TestSystem({"x", "y"}, {"vx", "vy"}), p_(p) {
  set_mass(Matrix::Identity(2, 2) * p_.mass);
  set_initial_state(vector2(p_.initial_position, p_.initial_height),
                    vector2(p_.initial_velocity, 0.0));
}

double Block::driving_force(double t) const {
  return p_.force + p_.force_amplitude * std::sin(p_.force_frequency * t);
}

void Block::forces(double t, const Vector& q, const Vector&, Vector& f) {
  f[0] = driving_force(t) - p_.stiffness * q[0];
  f[1] = -p_.mass * p_.gravity;
}

void Block::tangent(double, const Vector&, const Vector&, Matrix& K, Matrix& C) {
  K.setZero(2, 2);
  K(0, 0) = p_.stiffness;
  C.setZero(2, 2);
}

void Block::contact_data(double, const Vector& q, const Vector&,
                         std::vector<ContactData>& out) const {
  static const Vector kWn = vector2(0.0, 1.0), kWt = vector2(1.0, 0.0);
  integrators::set_fixed_contact(out[0], q[1], kWn, kWt, p_.restitution, p_.friction);
}

PowerTerms Block::power(double t, const Vector&, const Vector& u) const {
  PowerTerms pw;
  pw.external = driving_force(t) * u[0];
  return pw;
}

EnergyState Block::energy(double, const Vector& q) const {
  EnergyState e;
  e.stored = 0.5 * p_.stiffness * q[0] * q[0] + p_.mass * p_.gravity * q[1];
  return e;
}

// ---------------------------------------------------------------------------------------
WallBlock::WallBlock(const Parameters& p) : TestSystem({"x", "y"}, {"vx", "vy"}), p_(p) {
  set_mass(Matrix::Identity(2, 2) * p_.mass);
  set_initial_state(vector2(p_.wall_position + p_.initial_gap, 0.0),
                    vector2(p_.wall_velocity, 0.0));
}

double WallBlock::wall_position(double t) const {
  return p_.wall_position + p_.wall_velocity * t + 0.5 * p_.wall_acceleration * t * t;
}

double WallBlock::wall_velocity(double t) const {
  return p_.wall_velocity + p_.wall_acceleration * t;
}

void WallBlock::forces(double, const Vector&, const Vector&, Vector& f) {
  f[0] = -p_.pressing_force;
  f[1] = -p_.mass * p_.gravity;
}

void WallBlock::contact_data(double t, const Vector& q, const Vector&,
                             std::vector<ContactData>& out) const {
  static const Vector kWn = vector2(1.0, 0.0), kWt = vector2(0.0, 1.0);
  integrators::set_fixed_contact(out[0], q[0] - wall_position(t), kWn, kWt, p_.restitution,
                                 p_.friction);
  out[0].what_normal = -wall_velocity(t);
  out[0].wbar_normal = -p_.wall_acceleration;
}

EnergyState WallBlock::energy(double, const Vector& q) const {
  EnergyState e;
  e.stored = p_.pressing_force * q[0] + p_.mass * p_.gravity * q[1];
  return e;
}

// ---------------------------------------------------------------------------------------
TwoMasses::TwoMasses(const Parameters& p) : TestSystem({"x1", "x2"}, {"v1", "v2"}), p_(p) {
  Matrix m = Matrix::Zero(2, 2);
  m(0, 0) = p_.mass1;
  m(1, 1) = p_.mass2;
  set_mass(std::move(m));
  set_initial_state(vector2(p_.position1, p_.position2), vector2(p_.velocity1, p_.velocity2));
}

void TwoMasses::forces(double, const Vector& q, const Vector&, Vector& f) {
  f[0] = -p_.stiffness1 * q[0];
  f[1] = -p_.stiffness2 * q[1];
}

void TwoMasses::tangent(double, const Vector&, const Vector&, Matrix& K, Matrix& C) {
  K.setZero(2, 2);
  K(0, 0) = p_.stiffness1;
  K(1, 1) = p_.stiffness2;
  C.setZero(2, 2);
}

void TwoMasses::contact_data(double, const Vector& q, const Vector&,
                             std::vector<ContactData>& out) const {
  static const Vector kWn = vector2(-1.0, 1.0), kWt = Vector::Zero(2);
  integrators::set_fixed_contact(out[0], q[1] - q[0] - p_.distance, kWn, kWt, p_.restitution,
                                 0.0);
}

EnergyState TwoMasses::energy(double, const Vector& q) const {
  EnergyState e;
  e.stored = 0.5 * (p_.stiffness1 * q[0] * q[0] + p_.stiffness2 * q[1] * q[1]);
  return e;
}

// ---------------------------------------------------------------------------------------
TwoCornerBody::TwoCornerBody(const Parameters& p)
    : TestSystem({"x", "y", "theta"}, {"vx", "vy", "omega"}), p_(p) {
  Matrix m = Matrix::Zero(3, 3);
  m(0, 0) = m(1, 1) = p_.mass;
  m(2, 2) = p_.inertia;
  set_mass(std::move(m));
  set_initial_state(p_.initial_position, p_.initial_velocity);
}

void TwoCornerBody::forces(double, const Vector&, const Vector&, Vector& f) {
  f.setZero();
  f[1] = -p_.mass * p_.gravity;
}

void TwoCornerBody::contact_data(double, const Vector& q, const Vector& u,
                                 std::vector<ContactData>& out) const {
  const double c = std::cos(q[2]), s = std::sin(q[2]), w2 = u[2] * u[2];
  for (int i = 0; i < 2; ++i) {
    ContactData& ci = out[static_cast<std::size_t>(i)];
    const double arm = (i == 0 ? -1.0 : 1.0) * p_.half_length;  // s_i l
    ci.gap_normal = q[1] + arm * s;
    ci.w_normal << 0.0, 1.0, arm * c;
    ci.w_tangent << 1.0, 0.0, -arm * s;
    ci.what_normal = 0.0;
    ci.what_tangent = 0.0;
    ci.wbar_normal = -arm * s * w2;
    ci.wbar_tangent = -arm * c * w2;
    ci.restitution = p_.restitution;
    ci.friction = p_.friction;
    ci.far = false;
  }
}

EnergyState TwoCornerBody::energy(double, const Vector& q) const {
  EnergyState e;
  e.stored = p_.mass * p_.gravity * q[1];
  return e;
}

// ---------------------------------------------------------------------------------------
PlasticOscillator::PlasticOscillator(const Parameters& p) : TestSystem({"x"}, {"vx"}), p_(p) {}

void PlasticOscillator::forces(double t, const Vector& q, const Vector&, Vector& f) {
  double s = p_.stiffness * (q[0] - plastic_);
  trial_plastic_ = plastic_;
  trial_yielding_ = false;
  if (std::abs(s) > p_.yield_force) {  // return map onto the yield surface |F_s| = f_y
    const double sign = s > 0.0 ? 1.0 : -1.0;
    trial_plastic_ = q[0] - sign * p_.yield_force / p_.stiffness;
    s = sign * p_.yield_force;
    trial_yielding_ = true;
  }
  trial_force_ = s;
  f[0] = -s + p_.force_amplitude * std::sin(p_.force_frequency * t);
}

void PlasticOscillator::tangent(double, const Vector&, const Vector&, Matrix& K, Matrix& C) {
  K.setConstant(1, 1, trial_yielding_ ? 0.0 : p_.stiffness);
  C.setZero(1, 1);
}

void PlasticOscillator::commit() {
  plastic_ = trial_plastic_;
  yielding_ = trial_yielding_;
  TestSystem::commit();
}

void PlasticOscillator::revert() {
  trial_plastic_ = plastic_;
  trial_yielding_ = yielding_;
}

PowerTerms PlasticOscillator::power(double t, const Vector&, const Vector& u) const {
  PowerTerms pw;
  pw.external = p_.force_amplitude * std::sin(p_.force_frequency * t) * u[0];
  return pw;
}

EnergyState PlasticOscillator::energy(double, const Vector&) const {
  EnergyState e;
  e.stored = 0.5 * trial_force_ * trial_force_ / p_.stiffness;
  return e;
}

}  // namespace nsb::testsupport
