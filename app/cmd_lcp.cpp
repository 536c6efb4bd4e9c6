// nsbridge lcp: solve one LCP read from a file in Siconos's .dat format (lcp/siconos_format.hpp)
// and print z, w, the status, the iterations, both residuals and the time.
#include "app/commands.hpp"
#include "io/csv.hpp"
#include "io/json.hpp"
#include "lcp/siconos_format.hpp"
#include "lcp/solve.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

namespace nsb::app {
namespace {

struct LcpArgs {
  std::string file;
  std::string solver = "lemke";
  double tolerance = 1e-12;
  int max_iterations = 0;
  bool json = false;
};

std::string number(double x, bool json) {
  return json ? io::json_number(x) : io::shortest(x);
}

std::string vector_text(const lcp::Vector& v, bool json) {
  std::string s = json ? "[" : "";
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (i > 0) s += json ? ", " : " ";
    s += number(v(i), json);
  }
  return json ? s + "]" : s;
}

void run_lcp(const LcpArgs& a) {
  const auto solver = lcp::parse_solver(a.solver);
  if (!solver) throw InputError("lcp: --solver " + a.solver + ": expected lemke, pgs, nfb or enum");
  lcp::SolveOptions options;
  options.tolerance = a.tolerance;
  options.max_iterations = a.max_iterations;
  if (!(a.tolerance > 0.0) || !std::isfinite(a.tolerance))
    throw InputError("lcp: --tol " + number(a.tolerance, false) + ": expected a finite number > 0");
  if (a.max_iterations < 0)
    throw InputError("lcp: --max-iter " + std::to_string(a.max_iterations) +
                     ": expected an integer >= 0 (0: the solver's default)");
  lcp::Problem problem;
  try {
    problem = lcp::read_siconos_lcp(a.file);
  } catch (const lcp::FormatError& e) {
    throw InputError(e.what());
  }
  const lcp::Result r = lcp::solve(problem, *solver, options);
  // The whole output is composed first and written at once: nothing reaches standard output
  // unless it is complete.
  std::ostringstream out;
  if (a.json) {
    out << "{\"file\": " << io::json_string(a.file) << ", \"n\": " << problem.size()
          << ", \"solver\": \"" << lcp::to_string(*solver) << "\", \"status\": \""
          << lcp::to_string(r.status) << "\", \"iterations\": " << r.iterations
          << ", \"residual\": " << number(r.residual, true)
          << ", \"siconos_error\": " << number(r.siconos_error, true)
          << ", \"wall_time\": " << number(r.wall_time, true)
          << ", \"tolerance\": " << number(a.tolerance, true)
          << ", \"message\": " << io::json_string(r.message)
          << ", \"z\": " << vector_text(r.z, true) << ", \"w\": " << vector_text(r.w, true)
          << "}\n";
  } else {
    out << "file:          " << a.file << " (n = " << problem.size() << ")\n"
          << "solver:        " << lcp::to_string(*solver) << '\n'
          << "status:        " << lcp::to_string(r.status) << " (" << r.message << ")\n"
          << "iterations:    " << r.iterations << '\n'
          << "residual:      " << number(r.residual, false)
          << "   (||min(z, w)||_inf / (1 + ||q||_inf), tolerance " << number(a.tolerance, false)
          << ")\n"
          << "siconos error: " << number(r.siconos_error, false)
          << "   (||z - max(0, z - w)||_2 / ||q||_2)\n"
          << "time:          " << number(r.wall_time, false) << " s\n"
          << "z:             " << vector_text(r.z, false) << '\n'
          << "w:             " << vector_text(r.w, false) << '\n';
  }
  std::cout << out.str() << std::flush;
  exit_code() = r.ok() ? 0 : 1;
}

}  // namespace

void add_lcp_command(CLI::App& app) {
  auto args = std::make_shared<LcpArgs>();
  auto* cmd = app.add_subcommand(
      "lcp", "Solve an LCP read from a file in Siconos's .dat format (M stored column by column)");
  cmd->add_option("FILE", args->file, "the problem file")->required();
  cmd->add_option("--solver", args->solver, "lemke | pgs | nfb | enum (default lemke)");
  cmd->add_option("--tol", args->tolerance, "residual tolerance, > 0 (default 1e-12)");
  cmd->add_option("--max-iter", args->max_iterations,
                  "iteration or pivot limit, >= 0; 0 keeps the solver's default");
  cmd->add_flag("--json", args->json, "print one JSON object");
  cmd->callback([args] { run_lcp(*args); });
}

}  // namespace nsb::app
