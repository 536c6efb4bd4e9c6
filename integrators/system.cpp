#include "integrators/system.hpp"

#include <stdexcept>
#include <string>

namespace nsb::integrators {

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

}  // namespace nsb::integrators
