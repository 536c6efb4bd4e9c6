// One Siconos Numerics LCP and its solver options, owning their memory: the peer that
// lcp_bench and lcp_compare_bench time our solvers against. Only with NSB_HAVE_SICONOS
// (Debian's libsiconos-numerics-dev, optional: nothing needs it).
#pragma once

#ifdef NSB_HAVE_SICONOS
#include "lcp/lcp.hpp"

#include <siconos/numerics/LCP_Solvers.h>
#include <siconos/numerics/LinearComplementarityProblem.h>
#include <siconos/numerics/NumericsMatrix.h>
#include <siconos/numerics/SolverOptions.h>
#include <siconos/numerics/lcp_cst.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace nsb::bench {

struct SiconosRun {
  LinearComplementarityProblem problem{};
  SolverOptions* options = nullptr;
  std::vector<double> z, w;
  int info = 0;
  int solver_id = 0;  // SICONOS_LCP_LEMKE (lexicolemke), SICONOS_LCP_PGS or SICONOS_LCP_NEWTONFB

  // The dense problem p for the solver id, stopping at Siconos's error <= tolerance.
  SiconosRun(const lcp::Problem& p, int id, double tolerance) : solver_id(id) {
    const int n = static_cast<int>(p.size());
    problem.size = n;
    problem.M = NM_create(NM_DENSE, n, n);
    std::memcpy(problem.M->matrix0, p.M.data(), sizeof(double) * static_cast<std::size_t>(n * n));
    problem.q = static_cast<double*>(std::malloc(sizeof(double) * static_cast<std::size_t>(n)));
    std::memcpy(problem.q, p.q.data(), sizeof(double) * static_cast<std::size_t>(n));
    options = solver_options_create(id);
    options->dparam[SICONOS_DPARAM_TOL] = tolerance;
    z.assign(static_cast<std::size_t>(n), 0.0);
    w.assign(static_cast<std::size_t>(n), 0.0);
  }
  SiconosRun(const SiconosRun&) = delete;
  SiconosRun& operator=(const SiconosRun&) = delete;
  ~SiconosRun() {
    solver_options_delete(options);
    NM_free(problem.M);
    std::free(problem.q);
  }
  // Solves from z = 0.
  void solve() {
    std::fill(z.begin(), z.end(), 0.0);
    std::fill(w.begin(), w.end(), 0.0);
    if (solver_id == SICONOS_LCP_LEMKE)
      lcp_lexicolemke(&problem, z.data(), w.data(), &info, options);
    else if (solver_id == SICONOS_LCP_PGS)
      lcp_pgs(&problem, z.data(), w.data(), &info, options);
    else
      lcp_newton_FB(&problem, z.data(), w.data(), &info, options);
  }
  int iterations() const { return options->iparam[SICONOS_IPARAM_ITER_DONE]; }
};

}  // namespace nsb::bench
#endif
