#include "integrators/system.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace nsb::integrators {

SystemBase::SystemBase(std::vector<std::string> coordinate_names,
                       std::vector<std::string> velocity_names)
    : coordinates_(std::move(coordinate_names)), velocities_(std::move(velocity_names)) {
  if (coordinates_.empty() || coordinates_.size() != velocities_.size()) {
    throw std::invalid_argument(
        "SystemBase: give one coordinate name and one velocity name per degree of freedom");
  }
  const int n = dofs();
  mass_ = Matrix::Identity(n, n);
  q0_ = Vector::Zero(n);
  u0_ = Vector::Zero(n);
}

void SystemBase::set_mass(Matrix mass) { mass_ = std::move(mass); }

void SystemBase::set_initial_state(Vector position, Vector velocity) {
  q0_ = std::move(position);
  u0_ = std::move(velocity);
}

void SystemBase::forces(double, const Vector&, const Vector&, Vector& f) { f.setZero(); }

void SystemBase::tangent(double, const Vector&, const Vector&, Matrix& K, Matrix& C) {
  K.setZero(dofs(), dofs());
  C.setZero(dofs(), dofs());
}

void SystemBase::contact_data(double, const Vector&, const Vector&,
                              std::vector<ContactData>&) const {}

PowerTerms SystemBase::power(double, const Vector&, const Vector&) const { return {}; }

EnergyState SystemBase::energy(double, const Vector&) const { return {}; }

void set_fixed_contact(ContactData& c, double gap, const Vector& w_normal,
                       const Vector& w_tangent, double restitution, double friction) {
  c.gap_normal = gap;
  c.w_normal = w_normal;
  c.w_tangent = w_tangent;
  c.what_normal = 0.0;
  c.what_tangent = 0.0;
  c.wbar_normal = 0.0;
  c.wbar_tangent = 0.0;
  c.restitution = restitution;
  c.friction = friction;
  c.far = false;
}

Matrix checked_inverse_mass(const System& system, std::string_view method) {
  const auto fail = [method](const std::string& what) {
    throw std::invalid_argument(std::string(method) + ": " + what);
  };
  const int n = system.dofs();
  if (n <= 0) fail("the system has no degrees of freedom");
  if (system.contacts() < 0) fail("the system reports contacts() < 0");
  const Matrix& M = system.mass();
  if (M.rows() != n || M.cols() != n) fail("the mass matrix is not dofs() x dofs()");
  if (!M.allFinite()) fail("the mass matrix has a non-finite entry");
  // Symmetric to round-off of its largest entry: the mass of a mechanical system is.
  const double scale = M.cwiseAbs().maxCoeff();
  if ((M - M.transpose()).cwiseAbs().maxCoeff() > 1e-12 * scale) {
    fail("the mass matrix is not symmetric");
  }
  Eigen::LLT<Matrix> llt(M);
  if (llt.info() != Eigen::Success) fail("the mass matrix is not positive definite");
  const Vector q0 = system.initial_position();
  const Vector u0 = system.initial_velocity();
  if (q0.size() != n || u0.size() != n) {
    fail("initial_position() or initial_velocity() is not of size dofs()");
  }
  if (!q0.allFinite() || !u0.allFinite()) fail("the initial state has a non-finite entry");
  return llt.solve(Matrix::Identity(n, n));
}

std::vector<double> natural_periods(System& system) {
  const int n = system.dofs();
  Matrix K = Matrix::Zero(n, n);
  Matrix C = Matrix::Zero(n, n);
  system.tangent(system.initial_time(), system.initial_position(), system.initial_velocity(), K,
                 C);
  system.revert();
  const Matrix Ks = 0.5 * (K + K.transpose());
  if (!Ks.allFinite()) return {};
  // K phi = omega^2 M phi, M symmetric positive definite (checked by every integrator).
  Eigen::GeneralizedSelfAdjointEigenSolver<Matrix> eig(Ks, system.mass(), Eigen::EigenvaluesOnly);
  if (eig.info() != Eigen::Success) return {};
  // Eigen sorts the eigenvalues in increasing order: the longest period comes first.
  std::vector<double> periods;
  for (const double omega2 : eig.eigenvalues()) {
    periods.push_back(omega2 > 0.0 ? 2.0 * std::numbers::pi / std::sqrt(omega2) : INFINITY);
  }
  return periods;
}

}  // namespace nsb::integrators
