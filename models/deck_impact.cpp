// The frictional impact of a free rigid planar deck (eqs. 3-7): the contact columns and the
// exact solution of the impact problem by enumeration of its cases; see analytic.hpp for the
// formulas and docs/analytic.md for the derivations.
#include "models/analytic.hpp"
#include "models/field_checks.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace nsb::models::analytic {

namespace {

// Relative tolerance of the feasibility tests in the case enumeration: the linear systems
// are of size <= 8 and well scaled (G ~ 1/m), so a solution is accurate to a few ulps of
// the data; 1e-10 separates round-off from a genuinely violated sign condition.
constexpr double kCaseTolerance = 1e-10;
// Two case solutions are the same solution when their post-impact contact velocities agree
// to this relative accuracy (cases sharing a boundary, e.g. stick with gdot_T+ = 0 and
// slide, coincide).
constexpr double kSameSolution = 1e-8;

}  // namespace

void DeckBody::validate() const {
  require(std::isfinite(mass) && mass > 0.0, "mass", "must be > 0 [t]");
  require(std::isfinite(inertia) && inertia > 0.0, "inertia", "must be > 0 [t m^2]");
  deck.validate();
}

Eigen::Vector2d deck_corner(const DeckGeometry& g, int corner) {
  g.validate();
  require(corner >= 1 && corner <= 4, "corner", "must be 1, 2, 3 or 4");
  return g.corner(corner - 1);
}

ContactColumns deck_contact_columns(const DeckGeometry& g, int corner) {
  const Eigen::Vector2d r = deck_corner(g, corner);
  // Unit normal of the abutment face, pointing from the abutment to the deck.
  const Eigen::Vector2d n = g.face_normal(corner - 1);
  const Eigen::Vector2d t(-n.y(), n.x());  // n rotated by +90 degrees
  auto cross = [&](const Eigen::Vector2d& v) { return r.x() * v.y() - r.y() * v.x(); };
  return {Eigen::Vector3d(n.x(), n.y(), cross(n)), Eigen::Vector3d(t.x(), t.y(), cross(t))};
}

void ImpactProblem::validate() const {
  const auto m = restitution.size();
  require(m >= 1 && m <= 4, "restitution", "1 to 4 contacts are supported");
  require(friction.size() == m, "friction", "size must equal the number of contacts");
  require(gdot_minus.size() == 2 * m, "gdot_minus", "size must be 2m");
  require(delassus.rows() == 2 * m && delassus.cols() == 2 * m, "delassus", "must be 2m x 2m");
  require(delassus.allFinite() && gdot_minus.allFinite(), "delassus, gdot_minus", "must be finite");
  for (Eigen::Index i = 0; i < m; ++i) {
    require(restitution(i) >= 0.0 && restitution(i) <= 1.0, "restitution", "must be in [0, 1]");
    require(std::isfinite(friction(i)) && friction(i) >= 0.0, "friction", "must be >= 0");
  }
}

namespace {

// The cases of the m contacts encoded in code (base 4, contact 0 lowest); false for a case
// that repeats another: without friction stick and slide coincide (Lambda_T = 0).
bool decode_cases(int code, const ImpactProblem& p, std::vector<ImpactCase>& st) {
  int c = code;
  bool skip = false;
  for (Eigen::Index i = 0; i < p.restitution.size(); ++i) {
    st[static_cast<std::size_t>(i)] = static_cast<ImpactCase>(c % 4);
    c /= 4;
    if (p.friction(i) == 0.0 && (st[static_cast<std::size_t>(i)] == ImpactCase::kStick ||
                                 st[static_cast<std::size_t>(i)] ==
                                     ImpactCase::kSlideNegative)) {
      skip = true;
    }
  }
  return !skip;
}

// The linear system A z = b of one case. Unknowns z = [Lambda_N; Lambda_T]; rows i (normal)
// and m + i (tangential).
void case_system(const ImpactProblem& p, const std::vector<ImpactCase>& st, Eigen::MatrixXd& A,
                 Eigen::VectorXd& b) {
  const auto m = p.restitution.size();
  A.setZero();
  b.setZero();
  for (Eigen::Index i = 0; i < m; ++i) {
    const double e = p.restitution(i);
    const double mu = p.friction(i);
    switch (st[static_cast<std::size_t>(i)]) {
      case ImpactCase::kInactive:
        A(i, i) = 1.0;          // Lambda_N = 0
        A(m + i, m + i) = 1.0;  // Lambda_T = 0
        break;
      case ImpactCase::kStick:
        // gdot_N+ + e gdot_N- = 0 and gdot_T+ = 0, gdot+ = G z + gdot-.
        A.row(i) = p.delassus.row(i);
        b(i) = -(1.0 + e) * p.gdot_minus(i);
        A.row(m + i) = p.delassus.row(m + i);
        b(m + i) = -p.gdot_minus(m + i);
        break;
      case ImpactCase::kSlidePositive:
      case ImpactCase::kSlideNegative: {
        const double s = st[static_cast<std::size_t>(i)] == ImpactCase::kSlidePositive ? 1.0
                                                                                      : -1.0;
        A.row(i) = p.delassus.row(i);
        b(i) = -(1.0 + e) * p.gdot_minus(i);
        A(m + i, m + i) = 1.0;  // Lambda_T + s mu Lambda_N = 0
        A(m + i, i) = s * mu;
        break;
      }
    }
  }
}

// Whether the impulses z and post-impact velocities gp of a case satisfy its sign conditions,
// to the velocity tolerance vtol and the impulse tolerance itol.
bool case_feasible(const ImpactProblem& p, const std::vector<ImpactCase>& st,
                   const Eigen::VectorXd& z, const Eigen::VectorXd& gp, double vtol, double itol) {
  const auto m = p.restitution.size();
  bool ok = z.allFinite();
  for (Eigen::Index i = 0; i < m && ok; ++i) {
    const double ln = z(i), lt = z(m + i);
    const double e = p.restitution(i), mu = p.friction(i);
    const double gn0 = gp(i) + e * p.gdot_minus(i);
    switch (st[static_cast<std::size_t>(i)]) {
      case ImpactCase::kInactive:
        ok = gn0 >= -vtol;
        break;
      case ImpactCase::kStick:
        ok = ln >= -itol && std::abs(lt) <= mu * ln + itol;
        break;
      case ImpactCase::kSlidePositive:
        ok = ln >= -itol && (mu == 0.0 || gp(m + i) >= -vtol);
        break;
      case ImpactCase::kSlideNegative:
        ok = ln >= -itol && gp(m + i) <= vtol;
        break;
    }
  }
  return ok;
}

}  // namespace

ImpactCases solve_impact_by_cases(const ImpactProblem& p) {
  p.validate();
  const auto m = p.restitution.size();
  const Eigen::Index n2 = 2 * m;
  const double vscale = 1.0 + p.gdot_minus.cwiseAbs().maxCoeff();
  const double gscale = p.delassus.cwiseAbs().maxCoeff();
  require(gscale > 0.0, "delassus", "must not be zero");
  const double vtol = kCaseTolerance * vscale;
  const double itol = vtol / gscale;  // impulse tolerance
  ImpactCases out;
  int total = 1;
  for (Eigen::Index i = 0; i < m; ++i) total *= 4;
  Eigen::MatrixXd A(n2, n2);
  Eigen::VectorXd b(n2);
  std::vector<ImpactCase> st(static_cast<std::size_t>(m));
  for (int code = 0; code < total; ++code) {
    if (!decode_cases(code, p, st)) continue;
    case_system(p, st, A, b);
    Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
    Eigen::VectorXd z;
    if (lu.isInvertible()) {
      z = lu.solve(b);
    } else {
      // Singular case (e.g. two corners of one end share W_T, so their tangential impulses
      // split indeterminately): take the minimum-norm solution if the system is consistent.
      ++out.singular_cases;
      z = A.completeOrthogonalDecomposition().solve(b);
      if ((A * z - b).cwiseAbs().maxCoeff() > vtol) continue;
    }
    const Eigen::VectorXd gp = p.delassus * z + p.gdot_minus;
    if (!case_feasible(p, st, z, gp, vtol, itol)) continue;
    ImpactSolution s;
    s.lambda_n = z.head(m);
    s.lambda_t = z.tail(m);
    s.gdot_n_plus = gp.head(m);
    s.gdot_t_plus = gp.tail(m);
    s.cases = st;
    // Distinct solutions are distinct post-impact velocities: G z1 = G z2 <=> W z1 = W z2
    // (G = W^T M^-1 W), so equal contact velocities mean equal u+ even when the impulses
    // differ (an indeterminate split between contacts).
    const bool seen = std::any_of(out.solutions.begin(), out.solutions.end(), [&](const auto& o) {
      return (o.gdot_n_plus - s.gdot_n_plus).cwiseAbs().maxCoeff() <= kSameSolution * vscale &&
             (o.gdot_t_plus - s.gdot_t_plus).cwiseAbs().maxCoeff() <= kSameSolution * vscale;
    });
    if (!seen) out.solutions.push_back(std::move(s));
  }
  return out;
}

DeckImpact deck_impact(const DeckBody& g, const std::vector<int>& corners,
                       const Eigen::Vector3d& velocity_before, double restitution,
                       double friction) {
  g.validate();
  require(!corners.empty() && corners.size() <= 4, "corners", "give 1 to 4 corners");
  require(velocity_before.allFinite(), "velocity_before", "must be finite");
  const auto m = static_cast<Eigen::Index>(corners.size());
  Eigen::MatrixXd W(3, 2 * m);  // [W_N W_T]
  for (Eigen::Index i = 0; i < m; ++i) {
    const auto cc = deck_contact_columns(g.deck, corners[static_cast<std::size_t>(i)]);
    W.col(i) = cc.w_normal;
    W.col(m + i) = cc.w_tangent;
  }
  const Eigen::Vector3d minv(1.0 / g.mass, 1.0 / g.mass, 1.0 / g.inertia);
  DeckImpact out;
  out.problem.delassus = W.transpose() * minv.asDiagonal() * W;  // eq. (8)
  out.problem.gdot_minus = W.transpose() * velocity_before;
  out.problem.restitution = Eigen::VectorXd::Constant(m, restitution);
  out.problem.friction = Eigen::VectorXd::Constant(m, friction);
  const ImpactCases cases = solve_impact_by_cases(out.problem);
  out.solutions = static_cast<int>(cases.solutions.size());
  if (cases.solutions.empty()) {
    out.velocity_after = velocity_before;
    return out;
  }
  out.contact = cases.solutions.front();
  Eigen::VectorXd z(2 * m);
  z << out.contact.lambda_n, out.contact.lambda_t;
  out.velocity_after = velocity_before + minv.asDiagonal() * (W * z);
  return out;
}

}  // namespace nsb::models::analytic
