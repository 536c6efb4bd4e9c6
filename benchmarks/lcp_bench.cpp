// Run time and final residual of each LCP solver on
//   1. eq. (6) problems of a planar rigid body with 1 to 4 contacts (n = 3 to 12), the
//      problems the bridge solves every step (eps = 0, mu = 0.5 as in the paper);
//   2. dense symmetric positive definite problems, n = 50, 200, 500;
//   3. Siconos's LCP test collection (data/siconos-lcp).
// With Siconos Numerics, its lcp_lexicolemke, lcp_pgs and lcp_newton_FB run on the same
// problems with the same tolerance, and the ratio ours / theirs of the median times is printed.
//
// Usage: lcp_bench [--quick] [--csv FILE]   (CSV default: out/lcp_bench.csv)
#include "benchmarks/lcp_bench_timing.hpp"
#include "benchmarks/output.hpp"
#include "benchmarks/siconos_lcp.hpp"
#include "io/build_info.hpp"
#include "lcp/frictional.hpp"
#include "lcp/lemke.hpp"
#include "lcp/newton_fb.hpp"
#include "lcp/pgs.hpp"
#include "lcp/siconos_format.hpp"
#include "lcp/test/problems.hpp"


#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include <ctime>
#include <dlfcn.h>
#include <fcntl.h>
#include <unistd.h>

using namespace nsb::lcp;

namespace {

constexpr double kTolerance = 1e-12;
// Siconos stops on its own error measure; an answer within 1e3 times our tolerance on our
// residual is counted as solved.
constexpr double kAcceptSiconos = 1e-9;

struct Row {
  std::string set;      // eq6 | spd | siconos
  std::string problem;  // name
  int n = 0;
  std::string solver;   // e.g. lemke, siconos_lexicolemke
  double median_us = 0.0;
  std::string status;
  int iterations = 0;
  double residual = 0.0;
  double siconos_error = 0.0;
};

std::vector<Row> rows;
// Per body of the eq. (6) sets: (time [us], solved) of each solver, keyed "label/contacts".
std::map<std::string, std::vector<std::pair<double, bool>>> body_times;

using namespace nsb::bench;  // median, median_time, Silence

#ifdef NSB_HAVE_SICONOS

// Siconos's dense LU (its Newton-FB step) calls LAPACK; an OpenBLAS build spreads a
// factorization of n >= 100 over helper threads, whose CPU time the thread clock does not
// count. The comparison runs it on one thread, as ours runs. Returns false if the linked BLAS
// has no thread control (then it is single-threaded or not OpenBLAS).
bool single_threaded_blas() {
  using SetThreads = void (*)(int);
  const auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  if (set == nullptr) return false;
  set(1);
  return true;
}

const std::pair<int, const char*> kSiconosSolvers[] = {
    {SICONOS_LCP_LEMKE, "siconos_lexicolemke"},
    {SICONOS_LCP_PGS, "siconos_pgs"},
    {SICONOS_LCP_NEWTON_FB_FBLSA, "siconos_newton_fb"}};
#endif

// Runs our solvers (and Siconos's) on one problem; records one row per solver.
void run_all(const std::string& set, const std::string& name, const Problem& p, int batches,
             double min_time) {
  // Our solvers through their in-place forms: the workspace and the Result are reused, as an
  // integrator does; no clock, no message (Siconos's functions also write into the caller's
  // z and w).
  Lemke lemke_solver(p.size());
  NewtonFb nfb_solver;
  LemkeOptions lemke_options;
  lemke_options.tolerance = kTolerance;
  PgsOptions pgs_options;
  pgs_options.tolerance = kTolerance;
  NewtonFbOptions nfb_options;
  nfb_options.tolerance = kTolerance;
  Result r;
  const struct {
    const char* label;
    std::function<void()> run;
  } ours[] = {
      {"lemke", [&] { lemke_solver.solve(p, lemke_options, r); }},
      {"pgs", [&] { pgs(p, pgs_options, r); }},
      {"nfb", [&] { nfb_solver.solve(p, nfb_options, r); }},
  };
  for (const auto& s : ours) {
    s.run();
    Row row{set, name, static_cast<int>(p.size()), s.label, 0.0, std::string(to_string(r.status)),
            r.iterations, r.residual, r.siconos_error};
    row.median_us = 1e6 * median_time(s.run, batches, min_time);
    rows.push_back(row);
  }
#ifdef NSB_HAVE_SICONOS
  for (const auto& [id, label] : kSiconosSolvers) {
    const Silence quiet;
    SiconosRun run(p, id, kTolerance);
    run.solve();
    r.z = Eigen::Map<const Vector>(run.z.data(), p.size());
    evaluate(p, r);
    // Siconos's info = 0 is not always a solution (its Lemke reports 0 after a ray, e.g. on
    // CPS_3): it counts as solved only if our residual agrees.
    const bool solved = run.info == 0 && r.residual <= kAcceptSiconos;
    Row row{set, name, static_cast<int>(p.size()), label, 0.0,
            solved ? "solved" : "info=" + std::to_string(run.info) + (run.info == 0 ? ",not_sol" : ""),
            run.iterations(), r.residual, r.siconos_error};
    row.median_us = 1e6 * median_time([&] { run.solve(); }, batches, min_time);
    rows.push_back(row);
  }
#else
  (void)name;
#endif
}

void print_rows(const std::string& set) {
  std::printf("\n%-28s %4s %-20s %12s %-18s %6s %10s %10s\n", "problem", "n", "solver",
              "median [us]", "status", "iter", "residual", "siconos_e");
  for (const Row& r : rows) {
    if (r.set != set) continue;
    std::printf("%-28s %4d %-20s %12.3f %-18s %6d %10.2e %10.2e\n", r.problem.c_str(), r.n,
                r.solver.c_str(), r.median_us, r.status.c_str(), r.iterations, r.residual,
                r.siconos_error);
  }
}

#ifdef NSB_HAVE_SICONOS
// Ratios ours / Siconos of the median times on the same problem, with the outcome of ours:
// "solved", or "refused" for a status decided before any iteration (zero diagonal), or
// "failed". The largest ratio per solver and outcome closes the table.
void print_ratios(const std::string& set) {
  std::printf("\nratio ours / Siconos (median times, same problem, same run):\n");
  const std::pair<const char*, const char*> pairs[] = {{"lemke", "siconos_lexicolemke"},
                                                       {"pgs", "siconos_pgs"},
                                                       {"nfb", "siconos_newton_fb"}};
  std::map<std::string, std::pair<double, std::string>> worst;
  for (const Row& a : rows) {
    if (a.set != set) continue;
    for (const auto& [ours, theirs] : pairs) {
      if (a.solver != ours) continue;
      for (const Row& b : rows) {
        if (b.set != set || b.problem != a.problem || b.solver != theirs) continue;
        const std::string outcome = a.status == "solved"          ? "solved"
                                    : a.status == "zero_diagonal" ? "refused"
                                                                  : "failed";
        const double ratio = a.median_us / b.median_us;
        std::printf("  %-32s %-6s / %-20s = %8.3f  (%s)\n", a.problem.c_str(), ours, theirs,
                    ratio, outcome.c_str());
        auto& w = worst[std::string(ours) + " " + outcome];
        if (ratio > w.first) w = {ratio, a.problem};
      }
    }
  }
  for (const auto& [key, value] : worst)
    std::printf("  largest ratio, %-16s %8.3f  (%s)\n", key.c_str(), value.first,
                value.second.c_str());
}
#endif

const Row* find_row(const std::string& set, const std::string& problem, const std::string& solver) {
  for (const Row& r : rows)
    if (r.set == set && r.problem == problem && r.solver == solver) return &r;
  return nullptr;
}

const char* verdict(bool met) { return met ? "met" : "NOT met"; }

// Goals on the collection: per solver, the largest ratio ours / Siconos over the problems our
// solver solves (and, for PGS, refuses); without Siconos, our slowest time.
void print_collection_goals() {
  std::map<std::string, std::string> ours_of = {{"lemke", "siconos_lexicolemke"},
                                                {"pgs", "siconos_pgs"},
                                                {"nfb", "siconos_newton_fb"}};
  for (const auto& [ours, theirs] : ours_of) {
    for (const char* outcome : {"solved", "zero_diagonal"}) {
      if (std::string(outcome) == "zero_diagonal" && ours != "pgs") continue;
      double worst = 0.0;
      double worst_abs = 0.0;
      std::string where = "-";
      int count = 0;
      for (const Row& a : rows) {
        if (a.set != "siconos" || a.solver != ours || a.status != outcome) continue;
        ++count;
        const Row* b = find_row(a.set, a.problem, theirs);
        const double ratio = b != nullptr ? a.median_us / b->median_us : 0.0;
        if (b != nullptr ? ratio > worst : a.median_us > worst_abs) {
          worst = ratio;
          worst_abs = a.median_us;
          where = a.problem;
        }
      }
      const double target = std::string(outcome) == "solved" ? 0.5 : 1.0;
      const std::string what = std::string(outcome) == "solved"
                                   ? ours + " <= 0.5x, collection, problems it solves"
                                   : ours + " refusal <= 1x, collection";
      if (find_row("siconos", where, theirs) != nullptr)
        std::printf("  %-44s largest %.3f (%s, %d problems)  %s\n", what.c_str(), worst,
                    where.c_str(), count, verdict(worst <= target));
      else
        std::printf("  %-44s slowest %.3f us (%s, %d problems)\n", what.c_str(), worst_abs,
                    where.c_str(), count);
    }
  }
}

// Goals on eq. (6), 1 to 4 contacts: the ratios of the medians over the bodies, and for
// Newton-FB the median over the bodies both solve of the per-body ratio (Siconos's gives up
// early on the others, so their times do not compare).
void print_eq6_goals() {
  const std::pair<const char*, const char*> eq6[] = {{"lemke_eq6", "siconos_lexicolemke"},
                                                     {"pgs_eq6 (refuses)", "siconos_pgs"},
                                                     {"nfb_eq6", "siconos_newton_fb"}};
  for (const auto& [ours, theirs] : eq6) {
    const bool refusal = std::string(ours).find("refuses") != std::string::npos;
    const double target = refusal ? 1.0 : 0.5;
    std::printf("  %-17s <= %.1fx, eq. (6), 1-4 contacts:", ours, target);
    bool met = true;
    bool compared = true;
    for (int m = 1; m <= 4; ++m) {
      const std::string key = "contacts=" + std::to_string(m);
      const Row* a = find_row("eq6", key, ours);
      const Row* b = find_row("eq6", key, theirs);
      if (a == nullptr) continue;
      if (b == nullptr) {
        compared = false;
        std::printf(" %.3f us", a->median_us);
        continue;
      }
      const double ratio = a->median_us / b->median_us;
      met = met && ratio <= target;
      std::printf(" %.3f", ratio);
    }
    std::printf("%s%s\n", compared ? "  " : "", compared ? verdict(met) : "");
  }
  if (body_times.count("siconos_newton_fb/1") == 0) return;
  std::printf("  %-44s", "nfb_eq6, bodies both solve (count)");
  bool met = true;
  for (int m = 1; m <= 4; ++m) {
    const auto& a = body_times["nfb_eq6/" + std::to_string(m)];
    const auto& b = body_times["siconos_newton_fb/" + std::to_string(m)];
    std::vector<double> ratios;
    for (std::size_t k = 0; k < a.size() && k < b.size(); ++k)
      if (a[k].second && b[k].second) ratios.push_back(a[k].first / b[k].first);
    if (ratios.empty()) {
      std::printf(" -");
      continue;
    }
    const double r = median(ratios);
    met = met && r <= 0.5;
    std::printf(" %.3f (%zu)", r, ratios.size());
  }
  std::printf("  %s\n", verdict(met));
}

// Goals on Newton-FB's steps: the most over the SPD study, and the cost per step at n = 200
// (median time of the solve / its steps).
void print_nfb_step_goals(int nfb_worst_steps) {
  std::printf("  %-44s %d  %s\n", "nfb steps, SPD n <= 200, cond <= 1e6 (<= 15)",
              nfb_worst_steps, verdict(nfb_worst_steps <= 15));
  const Row* a = find_row("spd", "spd_n200", "nfb");
  const Row* b = find_row("spd", "spd_n200", "siconos_newton_fb");
  if (a == nullptr || a->iterations <= 0) return;
  const double ours = a->median_us / a->iterations;
  if (b != nullptr && b->iterations > 0) {
    const double theirs = b->median_us / b->iterations;
    std::printf("  %-28s %.1f us (%d steps) / %.1f us (%d steps) = %.3f  %s\n",
                "nfb per step, n = 200 (<= 1x)", ours, a->iterations, theirs, b->iterations,
                ours / theirs, verdict(ours <= theirs));
  } else {
    std::printf("  %-28s %.1f us (%d steps)\n", "nfb per step, n = 200", ours, a->iterations);
  }
}

// One line per goal of docs/benchmarks/lcp.md, from the rows of this run: the ratio ours /
// Siconos (or, without Siconos, our absolute figure) and whether it is met.
void print_goals(int nfb_worst_steps) {
  std::printf("\n== goals (this run) ==\n");
  print_collection_goals();
  print_eq6_goals();
  print_nfb_step_goals(nfb_worst_steps);
}

// The eq. (6) problems of `bodies` random bodies with m contacts, and their LCPs (size n).
struct Eq6Set {
  int m = 0;
  int n = 0;
  std::vector<FrictionalProblem> problems;
  std::vector<Problem> lcps;
};

using Outcome = std::pair<bool, std::pair<int, double>>;  // solved, (iterations, residual)

// Times run(k) on every body of the set; one row with the median time, the solved count and
// the worst iterations and residual, and each body's time in body_times.
void measure_bodies(const Eq6Set& set, bool quick, const char* label,
                    const std::function<void(std::size_t)>& run,
                    const std::function<Outcome(std::size_t)>& outcome) {
  std::vector<double> t;
  int solved = 0;
  int worst_iter = 0;
  double worst_res = 0.0;
  auto& per_body = body_times[std::string(label) + "/" + std::to_string(set.m)];
  for (std::size_t k = 0; k < set.problems.size(); ++k) {
    t.push_back(median_time([&] { run(k); }, quick ? 3 : 5, quick ? 2e-4 : 1e-3));
    const auto o = outcome(k);
    per_body.emplace_back(1e6 * t.back(), o.first);
    solved += o.first;
    worst_iter = std::max(worst_iter, o.second.first);
    worst_res = std::max(worst_res, o.second.second);
  }
  const double med = 1e6 * median(t);
  rows.push_back(Row{"eq6", "contacts=" + std::to_string(set.m), set.n, label, med,
                     std::to_string(solved) + "/" + std::to_string(set.problems.size()),
                     worst_iter, worst_res, 0.0});
}

// Our frictional solvers (through solver and out) on the problems, and our LCP solvers on
// their LCPs, through the in-place forms (workspace and Result reused).
void time_eq6_ours(const Eq6Set& set, bool quick, FrictionalSolver& solver,
                   FrictionalResult& out) {
  const auto& problems = set.problems;
  const auto& lcps = set.lcps;
  for (Solver s : {Solver::kLemke, Solver::kPgs, Solver::kNewtonFb}) {
    const std::string label = std::string("frictional_") + std::string(to_string(s));
    measure_bodies(
        set, quick, label.c_str(),
        [&](std::size_t k) { solver.solve(problems[k], s, {}, out); },
        [&](std::size_t k) {
          solver.solve(problems[k], s, {}, out);
          return std::make_pair(out.ok(), std::make_pair(out.iterations, out.residual));
        });
  }
  Lemke lemke_solver(12);
  NewtonFb nfb_solver;
  Result r;
  const auto lcp_outcome = [&](std::size_t) {
    return std::make_pair(r.ok(), std::make_pair(r.iterations, r.residual));
  };
  measure_bodies(
      set, quick, "lemke_eq6",
      [&](std::size_t k) { lemke_solver.solve(lcps[k], LemkeOptions{}, r); },
      [&](std::size_t k) {
        lemke_solver.solve(lcps[k], LemkeOptions{}, r);
        return lcp_outcome(k);
      });
  measure_bodies(
      set, quick, "pgs_eq6 (refuses)", [&](std::size_t k) { pgs(lcps[k], PgsOptions{}, r); },
      [&](std::size_t k) {
        pgs(lcps[k], PgsOptions{}, r);
        return std::make_pair(r.status == Status::kZeroDiagonal,
                              std::make_pair(r.iterations, 0.0));
      });
  measure_bodies(
      set, quick, "nfb_eq6",
      [&](std::size_t k) { nfb_solver.solve(lcps[k], NewtonFbOptions{}, r); },
      [&](std::size_t k) {
        nfb_solver.solve(lcps[k], NewtonFbOptions{}, r);
        return lcp_outcome(k);
      });
}

#ifdef NSB_HAVE_SICONOS
// Siconos's solvers on the LCPs of the set.
void time_eq6_siconos(const Eq6Set& set, bool quick) {
  const auto& lcps = set.lcps;
  const int n = set.n;
  for (const auto& [id, label] : kSiconosSolvers) {
    const Silence quiet;
    std::vector<std::unique_ptr<SiconosRun>> runs;
    for (const auto& p : lcps) runs.push_back(std::make_unique<SiconosRun>(p, id, kTolerance));
    const bool refusal = id == SICONOS_LCP_PGS;
    measure_bodies(
        set, quick, label, [&](std::size_t k) { runs[k]->solve(); },
        [&](std::size_t k) {
          runs[k]->solve();
          const Vector zz = Eigen::Map<const Vector>(runs[k]->z.data(), n);
          const double res = residual(lcps[k].M, lcps[k].q, zz);
          const bool ok = refusal ? runs[k]->info != 0 : runs[k]->info == 0 && res <= kAcceptSiconos;
          return std::make_pair(ok, std::make_pair(runs[k]->iterations(), res));
        });
  }
}

void print_eq6_ratios() {
  std::printf("\nratio ours / Siconos on the LCP of eq. (6) (medians over the bodies, same run):\n");
  for (int m = 1; m <= 4; ++m) {
    const std::string key = "contacts=" + std::to_string(m);
    const auto find = [&](const std::string& solver) {
      for (const Row& row : rows)
        if (row.set == "eq6" && row.problem == key && row.solver == solver) return row.median_us;
      return 0.0;
    };
    std::printf("  %d contacts: lemke %.3f   pgs refusal %.3f   nfb %.3f\n", m,
                find("lemke_eq6") / find("siconos_lexicolemke"),
                find("pgs_eq6 (refuses)") / find("siconos_pgs"),
                find("nfb_eq6") / find("siconos_newton_fb"));
  }
}
#endif

// 1. Eq. (6): the per-step problem of the integrators, through the reusable solvers.
void run_eq6(std::mt19937& rng, bool quick) {
  std::printf("\n== eq. (6) problems, eps = 0, mu = 0.5: median over %d random bodies ==\n",
              quick ? 50 : 200);
  std::printf("%-9s %4s %-22s %12s %10s %10s %12s\n", "contacts", "n", "solver", "median [us]",
              "solved", "max iter", "max resid");
  const int bodies = quick ? 50 : 200;
  for (int m = 1; m <= 4; ++m) {
    Eq6Set set;
    set.m = m;
    for (int k = 0; k < bodies; ++k)
      set.problems.push_back(testing::rigid_body_impact(rng, m, 0.0, 0.5).problem);
    // The frictional solver's workspace is allocated before the LCPs: Lemke's time at n = 9
    // moves by ~30% (0.37 vs 0.49 us) with where its own workspace lands on the heap.
    FrictionalSolver solver(4);
    FrictionalResult out;
    for (const auto& fp : set.problems) set.lcps.push_back(build_eq6(fp));
    set.n = static_cast<int>(set.lcps.front().size());
    time_eq6_ours(set, quick, solver, out);
#ifdef NSB_HAVE_SICONOS
    time_eq6_siconos(set, quick);
#endif
    // Printed after the Siconos runs, whose output is silenced.
    for (const Row& row : rows)
      if (row.set == "eq6" && row.problem == "contacts=" + std::to_string(m))
        std::printf("%-9d %4d %-22s %12.3f %10s %10d %12.2e\n", m, set.n, row.solver.c_str(),
                    row.median_us, row.status.c_str(), row.iterations, row.residual);
  }
#ifdef NSB_HAVE_SICONOS
  print_eq6_ratios();
#endif
}

// 2. Dense SPD problems (cond 100, manufactured with complementary supports).
void run_spd(std::mt19937& rng, bool quick) {
  std::printf("\n== dense SPD problems, cond(M) = 100 ==");
  for (int n : quick ? std::vector<int>{50, 200} : std::vector<int>{50, 200, 500}) {
    const auto m = testing::manufacture(rng, testing::spd(rng, n, 100.0), 0.0);
    run_all("spd", "spd_n" + std::to_string(n), m.problem, quick ? 3 : (n >= 500 ? 5 : 9),
            quick ? 1e-3 : 1e-2);
  }
  print_rows("spd");
#ifdef NSB_HAVE_SICONOS
  print_ratios("spd");
#endif
}

// Newton–FB iterations to 1e-12 on SPD problems of several sizes and conditionings; prints
// and returns the most.
int nfb_most_iterations(std::mt19937& rng) {
  int worst = 0;
  std::string worst_case;
  for (int n : {10, 50, 200}) {
    for (double cond : {1.0, 1e2, 1e4, 1e6}) {
      for (int k = 0; k < 5; ++k) {
        const auto m = testing::manufacture(rng, testing::spd(rng, n, cond), 0.0);
        const Result r = newton_fb(m.problem);
        if (r.iterations > worst) {
          worst = r.iterations;
          worst_case = "n = " + std::to_string(n) + ", cond = " + std::to_string(cond) +
                       ", status " + std::string(to_string(r.status));
        }
      }
    }
  }
  std::printf("\nNewton-FB: most iterations to 1e-12 over 60 SPD problems (n 10-200, cond 1-1e6): "
              "%d (%s)\n", worst, worst_case.c_str());
  return worst;
}

// 3. Siconos's collection (the dense files).
void run_collection(bool quick) {
  std::printf("\n== Siconos LCP collection ==");
  std::vector<std::filesystem::path> files;
  for (const auto& e :
       std::filesystem::directory_iterator(std::filesystem::path(NSB_DATA_DIR) / "siconos-lcp"))
    if (e.path().filename().string().find("_block") == std::string::npos) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const auto& f : files)
    run_all("siconos", f.stem().string(), read_siconos_lcp(f), quick ? 3 : 7, quick ? 1e-3 : 5e-3);
  print_rows("siconos");
#ifdef NSB_HAVE_SICONOS
  print_ratios("siconos");
#endif
}

void write_csv(const std::string& csv) {
  std::ofstream out = nsb::benchmarks::open_output(csv);
  out << "set,problem,n,solver,median_us,status,iterations,residual,siconos_error\n";
  for (const Row& r : rows)
    out << r.set << ',' << r.problem << ',' << r.n << ',' << r.solver << ',' << r.median_us << ','
        << r.status << ',' << r.iterations << ',' << r.residual << ',' << r.siconos_error << '\n';
  std::printf("\nwrote %s\n", csv.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string csv = (nsb::benchmarks::kOutputDir / "lcp_bench.csv").string();
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") {
      quick = true;
    } else if (a == "--csv" && i + 1 < argc) {
      csv = argv[++i];
    } else {
      std::cerr << "usage: lcp_bench [--quick] [--csv FILE]\n";
      return 2;
    }
  }
  std::printf("lcp_bench: build type %s, git revision %s, tolerance %g, Siconos %s\n",
              NSB_BUILD_TYPE, nsb::io::build_info().revision.c_str(), kTolerance,
#ifdef NSB_HAVE_SICONOS
              "linked"
#else
              "not available"
#endif
  );
#ifdef NSB_HAVE_SICONOS
  std::printf("BLAS under Siconos: %s\n", single_threaded_blas()
                                              ? "OpenBLAS, set to one thread"
                                              : "no OpenBLAS thread control found");
#endif
  std::mt19937 rng(6);
  run_eq6(rng, quick);
  run_spd(rng, quick);
  const int worst = nfb_most_iterations(rng);
  run_collection(quick);
  print_goals(worst);
  write_csv(csv);
  return 0;
}
