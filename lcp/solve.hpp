// Choosing an LCP solver by name, with one signature for all of them.
#pragma once

#include "lcp/lcp.hpp"

#include <array>
#include <optional>
#include <string_view>

namespace nsb::lcp {

enum class Solver { kLemke, kPgs, kNewtonFb, kEnumeration };
// Every solver, in the order their names are listed (scene keys, the CLI, docs).
inline constexpr std::array<Solver, 4> kSolvers{Solver::kLemke, Solver::kPgs, Solver::kNewtonFb,
                                                Solver::kEnumeration};

// The one spelling of each solver's name (scene keys, the CLI, summary.json, .dat manifests):
// "lemke" | "pgs" | "nfb" | "enum".
constexpr std::string_view to_string(Solver s) {
  switch (s) {
    case Solver::kLemke: return "lemke";
    case Solver::kPgs: return "pgs";
    case Solver::kNewtonFb: return "nfb";
    case Solver::kEnumeration: return "enum";
  }
  return "unknown";
}
// The solver named `name` (to_string's spelling); std::nullopt for anything else.
std::optional<Solver> parse_solver(std::string_view name);

// Settings common to all solvers. Each solver maps them onto its own options struct.
struct SolveOptions {
  double tolerance = 1e-12;   // stop when lcp::residual <= tolerance; > 0
  int max_iterations = 0;     // iteration / pivot limit; 0 means the solver's own default
  bool record_history = false;  // fill Result::history
  void validate() const;      // throws std::invalid_argument naming the field
};

// Solves p with the chosen solver. Throws std::invalid_argument for a malformed problem or
// options; every algorithmic outcome is a Status in the result.
Result solve(const Problem& p, Solver solver, const SolveOptions& options = {});

}  // namespace nsb::lcp
