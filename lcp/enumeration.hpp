// Enumeration of complementary bases: an exhaustive oracle for small problems.
//
// For every support alpha of z (by increasing size), solve M_aa z_a = -q_a, set z_rest = 0,
// and accept the first z with lcp::residual <= tolerance. Every LCP that has a solution has
// one of this form (Cottle, Pang & Stone 1992, §4.1: a solution is a basic solution of a
// complementary basis, or a limit handled here by the least-norm solve of a singular block).
// The cost is O(2^n n^3), so n is limited.
#pragma once

#include "lcp/lcp.hpp"

namespace nsb::lcp {

struct EnumerationOptions {
  double tolerance = 1e-12;  // accept a basis when lcp::residual <= tolerance; > 0
  int max_size = 12;         // larger problems return kTooLarge; in [0, 20]
  void validate() const;     // throws std::invalid_argument naming the field
};

Result enumerate(const Problem& p, const EnumerationOptions& options = {});

}  // namespace nsb::lcp
