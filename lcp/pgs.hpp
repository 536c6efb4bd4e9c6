// Projected Gauss–Seidel with successive over-relaxation (Cottle, Pang & Stone 1992, §5.2).
//
// One sweep updates, for i = 1..n in order and with the newest values of z,
//
//   z_i <- max(0, z_i - omega (M_i. z + q_i) / M_ii),
//
// which is the exact minimiser of the i-th coordinate problem when omega = 1. It converges
// for symmetric positive definite M with 0 < omega < 2, and in general needs M_ii > 0: a
// zero or negative diagonal entry is reported as kZeroDiagonal before any sweep. The refusal is
// decided first, from the diagonal alone, and costs O(n): it returns z = 0, w = q and their
// measures, and checks for finiteness only what it read (the diagonal up to the refused entry,
// and q; a non-finite one throws). The rest of M is not read, so a non-finite off-diagonal
// entry of a refused problem is not reported; a problem that is solved is validated whole.
//
// w = M z + q is kept up to date through the sweep (a coordinate step that changes z_i by
// delta adds delta M_.i to w), so a sweep costs one pass over M and the residual after it
// O(n); w is recomputed from z before a solution is reported. For n <= 12 the sweeps run with
// n known at compile time (lcp/fixed_size.hpp).
#pragma once

#include "lcp/lcp.hpp"

namespace nsb::lcp {

struct PgsOptions {
  double tolerance = 1e-12;     // kSolved when lcp::residual <= tolerance; > 0
  int max_iterations = 10000;   // sweep limit; >= 1
  double relaxation = 1.0;      // SOR factor omega; in (0, 2)
  bool record_history = false;  // lcp::residual after every sweep into Result::history
  void validate() const;        // throws std::invalid_argument naming the field
};

// Solves p from z = 0 into r (no clock, no message): r's vectors are resized only when n
// changes, so a reused Result makes the solve allocation-free (unless record_history).
void pgs(const Problem& p, const PgsOptions& options, Result& r);

// Solves p starting from warm_start (if its size is n; otherwise from z = 0), with the wall
// time and Result::message.
Result pgs(const Problem& p, const PgsOptions& options = {}, const Vector& warm_start = {});

}  // namespace nsb::lcp
