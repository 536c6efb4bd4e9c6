#include "lcp/solve.hpp"

#include "lcp/enumeration.hpp"
#include "lcp/lemke.hpp"
#include "lcp/newton_fb.hpp"
#include "lcp/pgs.hpp"

#include <cmath>
#include <stdexcept>

namespace nsb::lcp {

std::optional<Solver> parse_solver(std::string_view name) {
  for (const Solver s : kSolvers) {
    if (to_string(s) == name) return s;
  }
  return std::nullopt;
}

void SolveOptions::validate() const {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    throw std::invalid_argument("SolveOptions::tolerance must be finite and > 0");
  if (max_iterations < 0)
    throw std::invalid_argument("SolveOptions::max_iterations must be >= 0 (0: solver default)");
}

Result solve(const Problem& p, Solver solver, const SolveOptions& options) {
  options.validate();
  switch (solver) {
    case Solver::kLemke: {
      LemkeOptions o;
      o.tolerance = options.tolerance;
      o.max_pivots = options.max_iterations;
      return lemke(p, o);
    }
    case Solver::kPgs: {
      PgsOptions o;
      o.tolerance = options.tolerance;
      if (options.max_iterations > 0) o.max_iterations = options.max_iterations;
      o.record_history = options.record_history;
      return pgs(p, o);
    }
    case Solver::kNewtonFb: {
      NewtonFbOptions o;
      o.tolerance = options.tolerance;
      if (options.max_iterations > 0) o.max_iterations = options.max_iterations;
      o.record_history = options.record_history;
      return newton_fb(p, o);
    }
    case Solver::kEnumeration: {
      EnumerationOptions o;
      o.tolerance = options.tolerance;
      return enumerate(p, o);
    }
  }
  throw std::invalid_argument("lcp::solve: unknown solver");
}

}  // namespace nsb::lcp
