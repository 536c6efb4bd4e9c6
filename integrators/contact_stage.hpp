// The contact stage shared by every integrator (docs/contact-stage.md):
//
//   contact data of an index set ─► columns, contact velocities, Delassus G   (contact_kinematics)
//        ─► lcp::FrictionalProblem (eq. 6 of Shi & Dimitrakopoulos 2017, or its natural form)
//        ─► the configured solver, then one fallback chain, each answer checked
//        ─► a ContactStatus and the impulses [Lambda_N; Lambda_T], applied as v += A^-1 B Lambda
//
// Moreau–Jean (one velocity-level problem per step), the event-driven impact problem (velocity
// level with M^-1) and the event-driven contact problem (acceleration level) all call it.
//
// The fallback chain, one for every caller: the configured solver, then Lemke, PGS on the
// natural form, and enumeration of the complementary bases when eq. (6) has at most
// lcp::EnumerationOptions::max_size unknowns; a solver already tried is skipped. This is the
// only fallback policy: lcp's solvers each run alone (lcp::FrictionalSolver), and whether a
// problem needed the chain is its ContactStatus (kSolvedByFallback). An answer is accepted
// when the solver reports kSolved, its impulses are finite and its residual (the frictional residual
// of lcp::frictional_residual, which every solver fills into FrictionalResult::residual) is
// at most options.tolerance. If the problem's data are not finite the stage solves nothing
// and says so: the caller stops with RunStatus::kDiverged.
//
// Allocation: after the first call with each index-set size, a call allocates nothing
// unless the chain reaches enumeration (a rare, small problem).
//
// Observation: a ContactObserver given in ContactStageOptions is shown every problem handed
// to solve(), after the chain, with where it came from (ProblemOrigin) and what the chain
// did. Without one the stage tests one pointer per solve and does nothing else.
#pragma once

#include "config/schema.hpp"
#include "integrators/contact_kinematics.hpp"
#include "lcp/frictional.hpp"

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

namespace nsb::integrators {

// Index-set decisions compare quantities that are exactly zero in exact arithmetic (the gap
// of a resting contact) with zero. In
// floating point they are round-off of the quantities they are computed from, so the
// decisions use a threshold of kRoundOff times the scale of those quantities. This is the
// one place that states it; docs/contact-stage.md gives the scales each decision uses.
struct ContactTolerances {
  // 2^10 unit round-offs: a gap computed from O(10) terms of the coordinates' scale carries
  // a round-off error of a few eps times that scale (measured: |g_N| <= 2.2e-15 m with
  // positions to 3.5 m over 1000 steps against an accelerating wall), far below it.
  static constexpr double kRoundOff = 1024.0 * std::numeric_limits<double>::epsilon();
  // Gap [m] below which a contact counts as touching: round-off of g_N = g(q), whose scale
  // is the size of the coordinates (1 + |q|_inf, with 1 m as the floor).
  static double gap(const Vector& q) { return kRoundOff * (1.0 + q.cwiseAbs().maxCoeff()); }
};

// The state of one contact between events, shared by Moreau–Jean (for its events) and the
// event-driven integrator (the mode of a smooth phase).
enum class ContactState {
  kOpen,          // not in contact
  kClosed,        // closed, frictionless (no tangential law)
  kStick,         // closed and sticking, gdot_T = 0
  kSlipPositive,  // closed and sliding with gdot_T > 0 (friction force -mu lambda_N)
  kSlipNegative,  // closed and sliding with gdot_T < 0 (friction force +mu lambda_N)
};
inline bool closed(ContactState s) { return s != ContactState::kOpen; }
inline bool sliding(ContactState s) {
  return s == ContactState::kSlipPositive || s == ContactState::kSlipNegative;
}
// sgn(gdot_T) of a sliding contact, else 0.
inline double slip_sign(ContactState s) {
  return s == ContactState::kSlipPositive ? 1.0 : s == ContactState::kSlipNegative ? -1.0 : 0.0;
}

// What the contact stage did with one problem.
enum class ContactStatus {
  kSolved,            // the configured solver's answer passed the checks
  kSolvedByFallback,  // the configured solver failed; a later solver of the chain succeeded
  kUnsolved,          // no solver of the chain produced an answer that passes the checks;
                      //   the impulses are the last finite answer, or zero
  kNonFiniteInput,    // the problem's data were not finite; nothing was solved, impulses zero
};
// Their names in the manifest of `nsbridge run --dump-lcp` (docs/outputs.md).
inline constexpr std::array<config::Name<ContactStatus>, 4> kContactStatusNames{
    {{"solved", ContactStatus::kSolved},
     {"solved_by_fallback", ContactStatus::kSolvedByFallback},
     {"unsolved", ContactStatus::kUnsolved},
     {"non_finite_input", ContactStatus::kNonFiniteInput}}};

// Which problem of which integrator the stage solves.
enum class ProblemKind {
  kImpact,      // event-driven: the velocity-level impact problem at an event (eq. 6)
  kContinuous,  // event-driven: the acceleration-level contact problem after an event
  kStep,        // Moreau–Jean: the velocity-level problem of one time step
};
// Their names in the manifest of `nsbridge run --dump-lcp` (docs/outputs.md).
inline constexpr std::array<config::Name<ProblemKind>, 3> kProblemKindNames{
    {{"impact", ProblemKind::kImpact},
     {"continuous", ProblemKind::kContinuous},
     {"step", ProblemKind::kStep}}};

// Where a problem handed to ContactStage::solve comes from.
struct ProblemOrigin {
  ProblemKind kind = ProblemKind::kStep;
  double t = 0.0;          // the time at which the contact law is imposed [s]
  std::int64_t step = 0;   // the integrator's accepted steps before this problem
};

// One problem as the stage solved it: the data, the chain's answer and outcome.
struct SolvedProblem {
  ProblemOrigin origin;
  const lcp::FrictionalProblem& problem;  // as solved (eq. 6 of it: lcp::build_eq6)
  const lcp::FrictionalResult& result;    // the accepted answer, or the chain's last one;
                                          //   status kNotRun for kNonFiniteInput
  ContactStatus status;
  bool closed_form;  // one frictionless contact, solved as max(0, -b / G) without a solver
};

// Shown every problem the stage solves (ContactStageOptions::observer), e.g. to write it to
// a file (runs/lcp_dump.hpp). Called on the integrator's thread, once per solve.
class ContactObserver {
 public:
  virtual ~ContactObserver() = default;
  virtual void solved(const SolvedProblem& problem) = 0;
};

struct ContactStageOptions {
  lcp::Solver solver = lcp::Solver::kLemke;  // the configured solver, first in the chain
  double tolerance = 1e-12;  // residual (lcp::frictional_residual) an answer must reach, > 0
  bool fallback = true;      // run the rest of the chain when the configured solver fails
  ContactObserver* observer = nullptr;  // shown every solve when not null; not owned
  void validate() const;     // throws std::invalid_argument naming the field
};

// Counts of the stage's outcomes over a run, for RunResult.
struct ContactStageCounts {
  std::int64_t solves = 0;      // problems handed to the stage
  std::int64_t fallbacks = 0;   // solved by a later solver of the chain
  std::int64_t unsolved = 0;    // kUnsolved
  std::int64_t non_finite = 0;  // kNonFiniteInput
  // Final lcp::Status per solve (the accepted solver's, or the last one tried).
  std::int64_t by_status[static_cast<int>(lcp::Status::kTooLarge) + 1] = {};
};

class ContactStage {
 public:
  ContactStage() = default;
  ContactStage(int dofs, int max_contacts, const ContactStageOptions& options);

  // Builds the problem of the index set (indices into `contacts`): its columns, G = W^T A^-1 B
  // and the free velocities W^T v_free + what (velocity level) or accelerations
  // W^T a_free + wbar (acceleration level), with restitution and friction from the contacts
  // (velocity level) or zero (acceleration level), and gdot_N- = 0. The returned problem may
  // be edited (gdot_n_minus, restitution, friction) before solve(). tangential: the problem
  // has tangential unknowns. slip_coupling: see ContactKinematics::gather.
  lcp::FrictionalProblem& build(const std::vector<ContactData>& contacts,
                                const std::vector<int>& index, bool tangential,
                                const Matrix& a_inv, const Vector& v_free, ContactLevel level,
                                const double* slip_coupling = nullptr);
  // Solves the problem built last through the chain; the answer is in impulses() and
  // result(). origin is what the observer (if any) is told about the problem.
  ContactStatus solve(const ProblemOrigin& origin = {});
  // [Lambda_N; Lambda_T] of the last solve (size kinematics().size()).
  Eigen::Ref<const Vector> impulses() const { return impulses_.head(kinematics_.size()); }
  double lambda_n(int j) const { return impulses_[j]; }
  double lambda_t(int j) const {
    return kinematics_.tangential() ? impulses_[kinematics_.contacts() + j] : 0.0;
  }
  // v += A^-1 B Lambda with the last solve's impulses.
  void apply(Vector& v) const { kinematics_.apply(impulses(), v); }

  const lcp::FrictionalResult& result() const { return *result_; }
  const ContactKinematics& kinematics() const { return kinematics_; }
  const ContactStageCounts& counts() const { return counts_; }

 private:
  ContactStatus solve_chain(bool& closed_form);
  bool accept(const lcp::FrictionalResult& r) const;
  bool finite_input(const lcp::FrictionalProblem& p) const;

  ContactStageOptions options_;
  lcp::SolveOptions solve_options_;
  ContactKinematics kinematics_;
  // One preallocated problem and result per index-set size k = 1..m, with (2k) and without
  // (k) tangential unknowns, so that Eigen never resizes in the hot path.
  std::vector<lcp::FrictionalProblem> frictional_, frictionless_;
  std::vector<lcp::FrictionalResult> frictional_result_, frictionless_result_;
  lcp::FrictionalProblem* problem_ = nullptr;
  lcp::FrictionalResult* result_ = nullptr;
  lcp::FrictionalSolver solver_;
  Vector impulses_;
  ContactStageCounts counts_;
};

}  // namespace nsb::integrators
