// Performance profiles (Dolan & Moré 2002, "Benchmarking optimization software with
// performance profiles", Math. Program. 91:201–213), as Acary, Brémond & Huber (2018, "On
// solving contact problems with Coulomb friction: formulations and numerical comparisons")
// use them for contact solvers.
//
// For solvers s and problems p with a cost t_p,s > 0 (a time, a residual reached; +inf when
// s failed on p), the performance ratio is
//
//   r_p,s = t_p,s / min_s' t_p,s'          (+inf when s failed, or every solver failed on p)
//
// and the profile of s is the fraction of the problems on which s is within a factor tau of
// the best:
//
//   rho_s(tau) = |{ p : r_p,s <= tau }| / n_p,     tau >= 1.
//
// rho_s(1) is the share of problems on which s is the best (ties count for every solver
// tied); rho_s(tau) for large tau is the share s solves at all.
#pragma once

#include <string>
#include <vector>

namespace nsb::benchmarks {

class PerformanceProfile {
 public:
  // cost[s][p]: the cost of solver s on problem p, > 0 or +inf (failure). Throws
  // std::invalid_argument for rows of different lengths, a cost <= 0 or NaN.
  explicit PerformanceProfile(const std::vector<std::vector<double>>& cost);

  int solvers() const { return static_cast<int>(ratio_.size()); }
  int problems() const { return ratio_.empty() ? 0 : static_cast<int>(ratio_[0].size()); }
  // r_p,s, +inf for a failure.
  double ratio(int s, int p) const;
  // rho_s(tau); 0 when there are no problems. rho_s(+inf) is the share s did not fail on.
  double rho(int s, double tau) const;
  // The problems s failed on (cost +inf).
  int failures(int s) const;
  // The largest finite ratio over every solver and problem (1 when there is none): beyond it
  // every profile is flat.
  double max_ratio() const;

 private:
  std::vector<std::vector<double>> ratio_;  // [s][p]
  std::vector<std::vector<double>> sorted_;  // ratio_[s], sorted, for rho()
};

}  // namespace nsb::benchmarks
