// Every LCP solver on the contact problems the bridge itself solves, and on Siconos's LCP
// collection, compared by performance profiles (Dolan & Moré 2002; benchmarks/
// performance_profile.hpp) of the CPU time to a solution and of the residual reached
// (docs/benchmarks/lcp-compare.md).
//
// Collections: the problems of the benchmark bridge under excitations 1..7 with Moreau–Jean
// (scenes/bridge-exc<k>.toml), harvested by the run pipeline's LCP dump (runs/lcp_dump.hpp,
// as `nsbridge run --dump-lcp`) into a temporary folder, or read from an earlier harvest; and
// data/siconos-lcp (the dense files). Solvers: Lemke, PGS, Newton–FB and enumeration (only
// where n <= its limit of 12) at tolerances 1e-8 and 1e-12; with Siconos Numerics linked, its
// lcp_lexicolemke, lcp_pgs and lcp_newton_FB too.
//
// A solve succeeds when the solver reports success and lcp::residual (one measure for every
// solver) is at most kAcceptSlack times the tolerance. Its time cost is the median CPU time of
// one call (+inf on failure); its residual cost is the residual reached, floored at
// kResidualFloor (+inf when the status says the iterate is not usable).
//
//   lcp_compare_bench [--quick] [--from DIR] [--harvest-into DIR] [--excitations 1,..,7]
//                     [--every K] [--csv FILE] [--profiles FILE]
//   --csv, --profiles   the outputs (default out/lcp_compare.csv, out/lcp_compare_profiles.csv)
//   --from DIR          read DIR/exc<k>/ (each a --dump-lcp folder) instead of harvesting
//   --harvest-into DIR  keep the harvested folders in DIR/exc<k>/ (default: a temporary folder,
//                       removed at the end)
//   --every K           keep every K-th problem of each harvested collection (default 1)
//   --quick             excitation 3, every 8th problem, shorter timing (the CTest smoke run)
#include "benchmarks/output.hpp"
#include "benchmarks/performance_profile.hpp"
#include "benchmarks/siconos_lcp.hpp"
#include "io/build_info.hpp"
#include "io/csv.hpp"
#include "lcp/enumeration.hpp"
#include "lcp/lemke.hpp"
#include "lcp/newton_fb.hpp"
#include "lcp/pgs.hpp"
#include "lcp/siconos_format.hpp"
#include "runs/run.hpp"


#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <iterator>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace nsb;
namespace fs = std::filesystem;

constexpr double kTolerances[] = {1e-8, 1e-12};
// Residuals below about the unit round-off (2.2e-16) differ by round-off only: the residual
// profile compares them as equal.
constexpr double kResidualFloor = 1e-16;
// Siconos stops on its own error measure (lcp::siconos_error), not on lcp::residual: an answer
// within 1e3 times the tolerance on lcp::residual counts (as in lcp_bench). Ours reach the
// tolerance itself whenever they report success.
constexpr double kAcceptSlack = 1e3;
constexpr double kInf = std::numeric_limits<double>::infinity();

struct Options {
  bool quick = false;
  fs::path from, harvest_into;
  std::vector<int> excitations{1, 2, 3, 4, 5, 6, 7};
  int every = 1;
  std::string csv = (benchmarks::kOutputDir / "lcp_compare.csv").string();
  std::string profiles = (benchmarks::kOutputDir / "lcp_compare_profiles.csv").string();
};

struct Item {
  std::string set, name;  // set: exc<k> or siconos
  lcp::Problem problem;
};

// What one solver did on one problem at one tolerance.
struct Outcome {
  std::string status;
  bool solved = false;
  bool usable = false;  // the iterate is a genuine residual reached (not a refusal)
  int iterations = 0;
  double residual = kInf, time_us = 0.0;
};

// A solver: fills r (z, status, iterations) for p at a tolerance; returns false when it does
// not apply to p (enumeration above its size limit).
struct SolverEntry {
  std::string name;
  std::function<bool(const lcp::Problem&, double, lcp::Result&)> run;
};

// CPU time of this thread [s]: a shared machine's waits for a core are not the solver's work.
double cpu_now() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Median over `batches` of the mean CPU time of one call [s], each batch at least min_time
// long so that the clock's resolution and cost do not matter.
double time_per_call(const std::function<void()>& f, int batches, double min_time) {
  int reps = 1;
  for (;;) {
    const double t0 = cpu_now();
    for (int i = 0; i < reps; ++i) f();
    if (cpu_now() - t0 >= min_time || reps >= (1 << 20)) break;
    reps *= 2;
  }
  std::vector<double> times;
  for (int b = 0; b < batches; ++b) {
    const double t0 = cpu_now();
    for (int i = 0; i < reps; ++i) f();
    times.push_back((cpu_now() - t0) / reps);
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

// An iterate whose residual means something: not a refusal before any iteration, not a
// Lemke ray, not an enumeration that found nothing.
bool usable(lcp::Status s) {
  return s == lcp::Status::kSolved || s == lcp::Status::kMaxIterations ||
         s == lcp::Status::kSingularJacobian || s == lcp::Status::kLineSearchFailed;
}

std::vector<SolverEntry> our_solvers() {
  auto lemke = std::make_shared<lcp::Lemke>(64);
  auto nfb = std::make_shared<lcp::NewtonFb>();
  return {
      {"lemke",
       [lemke](const lcp::Problem& p, double tol, lcp::Result& r) {
         lcp::LemkeOptions o;
         o.tolerance = tol;
         lemke->solve(p, o, r);
         return true;
       }},
      {"pgs",
       [](const lcp::Problem& p, double tol, lcp::Result& r) {
         lcp::PgsOptions o;
         o.tolerance = tol;
         lcp::pgs(p, o, r);
         return true;
       }},
      {"nfb",
       [nfb](const lcp::Problem& p, double tol, lcp::Result& r) {
         lcp::NewtonFbOptions o;
         o.tolerance = tol;
         nfb->solve(p, o, r);
         return true;
       }},
      {"enum",
       [](const lcp::Problem& p, double tol, lcp::Result& r) {
         lcp::EnumerationOptions o;
         o.tolerance = tol;
         if (p.size() > o.max_size) return false;
         r = lcp::enumerate(p, o);
         return true;
       }},
  };
}

Outcome run_ours(const SolverEntry& s, const lcp::Problem& p, double tol, bool quick) {
  lcp::Result r;
  Outcome o;
  if (!s.run(p, tol, r)) {
    o.status = "too_large";
    return o;
  }
  o.status = std::string(lcp::to_string(r.status));
  o.usable = usable(r.status) && r.z.size() == p.size();
  if (o.usable) o.residual = lcp::residual(p.M, p.q, r.z);
  o.solved = r.ok() && o.residual <= kAcceptSlack * tol;
  o.iterations = r.iterations;
  o.time_us = 1e6 * time_per_call([&] { s.run(p, tol, r); }, quick ? 1 : 3, quick ? 2e-5 : 1e-4);
  return o;
}

#ifdef NSB_HAVE_SICONOS
using bench::SiconosRun;

const std::pair<int, const char*> kSiconosSolvers[] = {
    {SICONOS_LCP_LEMKE, "siconos_lexicolemke"},
    {SICONOS_LCP_PGS, "siconos_pgs"},
    {SICONOS_LCP_NEWTON_FB_FBLSA, "siconos_newton_fb"}};

// Siconos's info = 0 is not always a solution (its Lemke reports 0 after a ray): our residual
// decides. Its diagnostics on stdout are not silenced here; redirect them if they disturb.
Outcome run_siconos(int id, const lcp::Problem& p, double tol, bool quick) {
  SiconosRun run(p, id, tol);
  run.solve();
  Outcome o;
  o.status = "info=" + std::to_string(run.info);
  o.usable = true;
  o.residual = lcp::residual(p.M, p.q, Eigen::Map<const lcp::Vector>(run.z.data(), p.size()));
  o.solved = run.info == 0 && o.residual <= kAcceptSlack * tol;
  o.iterations = run.options->iparam[SICONOS_IPARAM_ITER_DONE];
  o.time_us = 1e6 * time_per_call([&] { run.solve(); }, quick ? 1 : 3, quick ? 2e-5 : 1e-4);
  return o;
}
#endif

// The problems of one --dump-lcp folder, every k-th row of its manifest with a file.
std::vector<Item> load_dump(const fs::path& dir, const std::string& set, int every) {
  std::ifstream in(dir / "manifest.csv");
  if (!in) throw std::invalid_argument((dir / "manifest.csv").string() + ": cannot be read");
  std::string line;
  std::getline(in, line);
  const auto header = io::csv_fields(line);
  const auto file_col = std::find(header.begin(), header.end(), "file") - header.begin();
  std::vector<Item> items;
  for (long row = 0; std::getline(in, line); ++row) {
    const auto fields = io::csv_fields(line);
    const std::string& file = fields.at(static_cast<std::size_t>(file_col));
    if (file.empty() || row % every != 0) continue;
    items.push_back({set, file, lcp::read_siconos_lcp(dir / file)});
  }
  return items;
}

// Harvests excitation k under Moreau–Jean into dir/exc<k> (or reads it from --from).
std::vector<Item> bridge_collection(const Options& o, const fs::path& dir, int k) {
  const std::string set = "exc" + std::to_string(k);
  if (o.from.empty()) {
    const std::string scene =
        std::string(NSB_SCENES_DIR) + "/bridge-exc" + std::to_string(k) + ".toml";
    const runs::RunRecord r = runs::execute({scene, {}, "moreau", {}, dir / set});
    std::printf("harvested %-5s %6lld problems (summary lcp_solves), status %s\n", set.c_str(),
                static_cast<long long>(r.result.lcp_solves),
                std::string(integrators::to_string(r.result.status)).c_str());
  }
  return load_dump((o.from.empty() ? dir : o.from) / set, set, o.every);
}

std::vector<Item> siconos_collection() {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(fs::path(NSB_DATA_DIR) / "siconos-lcp"))
    if (e.path().filename().string().find("_block") == std::string::npos) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  std::vector<Item> items;
  for (const auto& f : files) items.push_back({"siconos", f.stem().string(), lcp::read_siconos_lcp(f)});
  return items;
}

// outcomes[solver][problem] at one tolerance.
using Table = std::vector<std::vector<Outcome>>;

Table solve_all(const std::vector<Item>& items, const std::vector<SolverEntry>& ours,
                const std::vector<std::string>& names, double tol, bool quick) {
  Table t(names.size());
  for (std::size_t s = 0; s < names.size(); ++s) {
    for (const Item& it : items) {
#ifdef NSB_HAVE_SICONOS
      if (s >= ours.size()) {
        t[s].push_back(run_siconos(kSiconosSolvers[s - ours.size()].first, it.problem, tol, quick));
        continue;
      }
#endif
      t[s].push_back(run_ours(ours[s], it.problem, tol, quick));
    }
  }
  return t;
}

// The profile of one measure over the problems of the given sets.
benchmarks::PerformanceProfile profile_of(const Table& t, const std::vector<Item>& items,
                                          const std::string& group, bool time) {
  std::vector<std::vector<double>> cost(t.size());
  for (std::size_t s = 0; s < t.size(); ++s) {
    for (std::size_t p = 0; p < items.size(); ++p) {
      if (group != "all" && (group == "siconos") != (items[p].set == "siconos")) continue;
      const Outcome& o = t[s][p];
      cost[s].push_back(time ? (o.solved ? std::max(o.time_us, 1e-6) : kInf)
                             : (o.usable ? std::max(o.residual, kResidualFloor) : kInf));
    }
  }
  return benchmarks::PerformanceProfile(cost);
}

void write_outcomes(std::ofstream& csv, const std::vector<Item>& items,
                    const std::vector<std::string>& names, const Table& t, double tol) {
  for (std::size_t s = 0; s < names.size(); ++s) {
    for (std::size_t p = 0; p < items.size(); ++p) {
      const Outcome& o = t[s][p];
      csv << items[p].set << ',' << items[p].name << ',' << items[p].problem.size() << ','
          << names[s] << ',' << tol << ',' << o.status << ',' << (o.solved ? 1 : 0) << ','
          << o.iterations << ',' << io::csv_number(o.residual) << ','
          << io::csv_number(o.time_us) << '\n';
    }
  }
}

// Failure counts per set and solver.
void print_failures(const std::vector<Item>& items, const std::vector<std::string>& names,
                    const Table& t, double tol) {
  std::map<std::string, int> sizes;
  for (const Item& it : items) ++sizes[it.set];
  std::printf("\nfailures at tolerance %g (problems not solved / problems):\n  %-8s %7s", tol,
              "set", "problems");
  for (const auto& n : names) std::printf(" %20s", n.c_str());
  std::printf("\n");
  for (const auto& [set, count] : sizes) {
    std::printf("  %-8s %7d", set.c_str(), count);
    for (std::size_t s = 0; s < names.size(); ++s) {
      int failed = 0;
      for (std::size_t p = 0; p < items.size(); ++p)
        failed += items[p].set == set && !t[s][p].solved;
      std::printf(" %20d", failed);
    }
    std::printf("\n");
  }
}

// rho at a few tau, and the profile on a grid of tau (log spaced from 1 to past the largest
// ratio) into the profiles CSV.
void report_profile(std::ofstream& csv, const benchmarks::PerformanceProfile& pr,
                    const std::vector<std::string>& names, const std::string& group,
                    const char* measure, double tol) {
  std::printf("  %-8s %-8s %6d problems:", group.c_str(), measure, pr.problems());
  for (int s = 0; s < pr.solvers(); ++s)
    std::printf("  %s %.3f/%.3f/%.3f", names[static_cast<std::size_t>(s)].c_str(), pr.rho(s, 1.0),
                pr.rho(s, 10.0), pr.rho(s, kInf));
  std::printf("\n");
  const double top = std::max(10.0, 2.0 * pr.max_ratio());
  constexpr int kPoints = 120;
  // One solver's points on consecutive lines: gnuplot joins only those.
  for (int s = 0; s < pr.solvers(); ++s) {
    for (int i = 0; i <= kPoints; ++i) {
      const double tau = std::pow(top, static_cast<double>(i) / kPoints);
      csv << group << ',' << measure << ',' << tol << ',' << names[static_cast<std::size_t>(s)]
          << ',' << io::csv_number(tau) << ',' << io::csv_number(pr.rho(s, tau)) << '\n';
    }
  }
}

std::vector<int> parse_list(const std::string& text) {
  std::vector<int> v;
  for (const auto& f : io::csv_fields(text)) {
    const int k = std::atoi(f.c_str());
    if (k < 1 || k > 7) throw std::invalid_argument("--excitations: " + f + "; expected 1..7");
    v.push_back(k);
  }
  return v;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--quick") {
      o.quick = true;
      o.excitations = {3};
      o.every = 8;
    } else if (a == "--from" && has_value) {
      o.from = argv[++i];
    } else if (a == "--harvest-into" && has_value) {
      o.harvest_into = argv[++i];
    } else if (a == "--excitations" && has_value) {
      o.excitations = parse_list(argv[++i]);
    } else if (a == "--every" && has_value) {
      o.every = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--csv" && has_value) {
      o.csv = argv[++i];
    } else if (a == "--profiles" && has_value) {
      o.profiles = argv[++i];
    } else {
      throw std::invalid_argument("unknown or incomplete argument '" + a + "'");
    }
  }
  return o;
}

int run(const Options& o) {
  const bool temporary = o.from.empty() && o.harvest_into.empty();
  const fs::path dir = !o.harvest_into.empty()
                           ? o.harvest_into
                           : fs::temp_directory_path() /
                                 ("nsb-lcp-compare-" + std::to_string(static_cast<long>(::getpid())));
  std::vector<Item> items;
  for (int k : o.excitations) {
    auto c = bridge_collection(o, dir, k);
    items.insert(items.end(), std::make_move_iterator(c.begin()), std::make_move_iterator(c.end()));
  }
  if (temporary) fs::remove_all(dir);
  auto sic = siconos_collection();
  items.insert(items.end(), std::make_move_iterator(sic.begin()), std::make_move_iterator(sic.end()));

  const std::vector<SolverEntry> ours = our_solvers();
  std::vector<std::string> names;
  for (const auto& s : ours) names.push_back(s.name);
#ifdef NSB_HAVE_SICONOS
  for (const auto& [id, name] : kSiconosSolvers) names.push_back(name);
#endif
  std::ofstream csv = benchmarks::open_output(o.csv);
  std::ofstream profiles = benchmarks::open_output(o.profiles);
  csv << "set,problem,n,solver,tolerance,status,solved,iterations,residual,time_us\n";
  profiles << "group,measure,tolerance,solver,tau,rho\n";
  for (double tol : kTolerances) {
    const Table t = solve_all(items, ours, names, tol, o.quick);
    write_outcomes(csv, items, names, t, tol);
    print_failures(items, names, t, tol);
    std::printf("profiles at tolerance %g, rho(1)/rho(10)/rho(inf) per solver:\n", tol);
    for (const std::string group : {"bridge", "siconos"}) {
      report_profile(profiles, profile_of(t, items, group, true), names, group, "time", tol);
      report_profile(profiles, profile_of(t, items, group, false), names, group, "residual", tol);
    }
  }
  std::printf("\nwrote %s and %s\n", o.csv.c_str(), o.profiles.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    std::printf("lcp_compare_bench: build type %s, git revision %s, Siconos %s\n", NSB_BUILD_TYPE,
                io::build_info().revision.c_str(),
#ifdef NSB_HAVE_SICONOS
                "linked"
#else
                "not available"
#endif
    );
    return run(o);
  } catch (const std::exception& e) {
    std::cerr << "lcp_compare_bench: " << e.what() << '\n';
    return 2;
  }
}
