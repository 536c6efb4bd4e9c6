#include "integrators/contact_stage.hpp"

#include "lcp/enumeration.hpp"

#include <cmath>
#include <stdexcept>

namespace nsb::integrators {

void ContactStageOptions::validate() const {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) {
    throw std::invalid_argument("ContactStageOptions.tolerance must be a finite number > 0");
  }
}

ContactStage::ContactStage(int dofs, int max_contacts, const ContactStageOptions& options)
    : options_(options), kinematics_(dofs, max_contacts) {
  options_.validate();
  solve_options_.tolerance = options.tolerance;
  const auto sizes = static_cast<std::size_t>(max_contacts) + 1;
  frictional_.resize(sizes);
  frictionless_.resize(sizes);
  frictional_result_.resize(sizes);
  frictionless_result_.resize(sizes);
  for (int k = 1; k <= max_contacts; ++k) {
    const auto uk = static_cast<std::size_t>(k);
    for (const bool tangential : {true, false}) {
      lcp::FrictionalProblem& p = tangential ? frictional_[uk] : frictionless_[uk];
      const int size = tangential ? 2 * k : k;
      p.delassus = Matrix::Zero(size, size);
      p.gdot_free = Vector::Zero(size);
      p.gdot_n_minus = Vector::Zero(k);
      p.restitution = Vector::Zero(k);
      p.friction = Vector::Zero(k);
      lcp::FrictionalResult& r = tangential ? frictional_result_[uk] : frictionless_result_[uk];
      for (Vector* v : {&r.lambda_n, &r.lambda_t, &r.gdot_n_plus, &r.gdot_t_plus}) {
        *v = Vector::Zero(k);
      }
    }
  }
  solver_.reserve(max_contacts);
  impulses_ = Vector::Zero(2 * max_contacts);
}

lcp::FrictionalProblem& ContactStage::build(const std::vector<ContactData>& contacts,
                                            const std::vector<int>& index, bool tangential,
                                            const Matrix& a_inv, const Vector& v_free,
                                            ContactLevel level, const double* slip_coupling) {
  const auto k = index.size();
  problem_ = tangential ? &frictional_[k] : &frictionless_[k];
  result_ = tangential ? &frictional_result_[k] : &frictionless_result_[k];
  lcp::FrictionalProblem& p = *problem_;
  kinematics_.gather(contacts, index, tangential, slip_coupling);
  kinematics_.delassus(a_inv, p.delassus);
  kinematics_.velocities(contacts, index, v_free, level, p.gdot_free);
  const bool velocity = level == ContactLevel::kVelocity;
  for (std::size_t j = 0; j < k; ++j) {
    const ContactData& c = contacts[static_cast<std::size_t>(index[j])];
    const auto jj = static_cast<Eigen::Index>(j);
    p.gdot_n_minus[jj] = 0.0;
    p.restitution[jj] = velocity ? c.restitution : 0.0;
    p.friction[jj] = velocity && tangential ? c.friction : 0.0;
  }
  return p;
}

bool ContactStage::finite_input(const lcp::FrictionalProblem& p) const {
  return p.delassus.allFinite() && p.gdot_free.allFinite() && p.gdot_n_minus.allFinite() &&
         p.restitution.allFinite() && p.friction.allFinite();
}

bool ContactStage::accept(const lcp::FrictionalResult& r) const {
  return r.status == lcp::Status::kSolved && r.lambda_n.allFinite() && r.lambda_t.allFinite() &&
         r.residual <= options_.tolerance;
}

ContactStatus ContactStage::solve(const ProblemOrigin& origin) {
  bool closed_form = false;
  const ContactStatus status = solve_chain(closed_form);
  if (options_.observer != nullptr) {
    options_.observer->solved({origin, *problem_, *result_, status, closed_form});
  }
  return status;
}

ContactStatus ContactStage::solve_chain(bool& closed_form) {
  lcp::FrictionalProblem& p = *problem_;
  lcp::FrictionalResult& r = *result_;
  const int k = kinematics_.contacts();
  const int size = kinematics_.size();
  ++counts_.solves;
  impulses_.head(size).setZero();
  if (!finite_input(p)) {
    ++counts_.non_finite;
    r.status = lcp::Status::kNotRun;
    return ContactStatus::kNonFiniteInput;
  }

  // One frictionless contact: the 1 x 1 LCP  G Lambda + b >= 0, Lambda >= 0, complementary,
  // has the unique solution Lambda = max(0, -b / G) when G > 0 (no solver needed).
  if (size == 1 && p.delassus(0, 0) > 0.0) {
    const double b = p.gdot_free[0] + p.restitution[0] * p.gdot_n_minus[0];
    impulses_[0] = b >= 0.0 ? 0.0 : -b / p.delassus(0, 0);
    r.lambda_n[0] = impulses_[0];
    r.lambda_t[0] = 0.0;
    r.gdot_n_plus[0] = p.gdot_free[0] + p.delassus(0, 0) * impulses_[0];
    r.gdot_t_plus[0] = 0.0;
    r.status = lcp::Status::kSolved;
    r.solver_used = options_.solver;
    r.residual = 0.0;
    closed_form = true;
    ++counts_.by_status[static_cast<int>(lcp::Status::kSolved)];
    return ContactStatus::kSolved;
  }

  // The chain: configured, Lemke, PGS, enumeration (small problems only); each once.
  const lcp::Solver chain[] = {options_.solver, lcp::Solver::kLemke, lcp::Solver::kPgs,
                               lcp::Solver::kEnumeration};
  const bool enumerable = lcp::eq6_size(p) <= lcp::EnumerationOptions{}.max_size;
  double best = std::numeric_limits<double>::infinity();
  bool tried[4] = {};
  for (int a = 0; a < 4; ++a) {
    const lcp::Solver s = chain[a];
    if (tried[static_cast<int>(s)]) continue;
    if (a > 0 && !options_.fallback) break;
    if (s == lcp::Solver::kEnumeration && a > 0 && !enumerable) continue;
    tried[static_cast<int>(s)] = true;
    solver_.solve(p, s, solve_options_, r);
    const bool finite = r.lambda_n.allFinite() && r.lambda_t.allFinite() &&
                        r.lambda_n.size() == k && r.lambda_t.size() == k;
    if (finite && r.residual < best) {
      // Keep the best finite answer: it is what an unsolved problem leaves behind.
      best = r.residual;
      impulses_.head(k) = r.lambda_n;
      if (size > k) impulses_.segment(k, k) = r.lambda_t;
    }
    if (accept(r)) {
      impulses_.head(k) = r.lambda_n;
      if (size > k) impulses_.segment(k, k) = r.lambda_t;
      ++counts_.by_status[static_cast<int>(r.status)];
      if (a == 0) return ContactStatus::kSolved;
      ++counts_.fallbacks;
      return ContactStatus::kSolvedByFallback;
    }
  }
  ++counts_.by_status[static_cast<int>(r.status)];
  ++counts_.unsolved;
  return ContactStatus::kUnsolved;
}

}  // namespace nsb::integrators
