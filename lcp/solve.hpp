// Choosing an LCP solver by name, with one signature for all of them.
#pragma once

#include "config/schema.hpp"
#include "lcp/lcp.hpp"

#include <array>

#include <optional>
#include <string_view>

namespace nsb::lcp {

enum class Solver { kLemke, kPgs, kNewtonFb, kEnumeration };
// The one list of solver names (scene keys, the CLI, summary.json).
inline constexpr std::array<config::Name<Solver>, 4> kSolverNames{{{"lemke", Solver::kLemke},
                                                                  {"pgs", Solver::kPgs},
                                                                  {"nfb", Solver::kNewtonFb},
                                                                  {"enum", Solver::kEnumeration}}};

std::string_view to_string(Solver s);
// "lemke" | "pgs" | "nfb" | "enum"; std::nullopt for anything else.
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
