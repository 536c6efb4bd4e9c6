// Work–precision study: error against wall time for the event-driven scheme (tolerances
// 1e-3 .. 1e-10) and Moreau–Jean (h = 1e-2 .. 1e-5), on the bridge (excitation 5) and the
// bouncing ball. The reference of each scene is its tightest event-driven run.
//
// Usage: work_precision_bench [--out DIR = out/work_precision] [--end-time T] [--repeats N] [--quick]
// Writes DIR/work_precision.csv (one row per run) and prints the same table.
// Plot: gnuplot -e "csv='DIR/work_precision.csv'; png='docs/benchmarks/work-precision.png'"
//       benchmarks/plot_work_precision.gp
#include "benchmarks/output.hpp"
#include "integrators/event_driven.hpp"
#include "integrators/compliance.hpp"
#include "integrators/event_driven.hpp"
#include "integrators/moreau_jean.hpp"
#include "io/build_info.hpp"
#include "models/simple_systems.hpp"
#include "scene/scene.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace ni = nsb::integrators;
namespace nm = nsb::models;

namespace {

struct Run {
  std::string scene, method;
  double parameter = 0.0;  // tolerance or step
  double wall = 0.0;       // median wall time [s]
  ni::RunResult stats;
  std::vector<double> t, x;  // sampled history of the compared coordinate
  std::size_t impacts = 0, events = 0;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// Max and RMS of |a - b| over a's samples, b interpolated linearly.
std::pair<double, double> history_error(const Run& a, const Run& b) {
  double mx = 0.0, ss = 0.0;
  std::size_t n = 0, j = 0;
  for (std::size_t i = 0; i < a.t.size(); ++i) {
    while (j + 2 < b.t.size() && b.t[j + 1] < a.t[i]) ++j;
    if (j + 1 >= b.t.size() || a.t[i] > b.t.back()) break;
    const double w = b.t[j + 1] > b.t[j] ? (a.t[i] - b.t[j]) / (b.t[j + 1] - b.t[j]) : 0.0;
    const double d = std::abs(a.x[i] - ((1.0 - w) * b.x[j] + w * b.x[j + 1]));
    mx = std::max(mx, d);
    ss += d * d;
    ++n;
  }
  return {mx, n ? std::sqrt(ss / static_cast<double>(n)) : 0.0};
}

// Largest |x| over the samples at t >= from.
double peak_abs(const Run& r, double from) {
  double p = 0.0;
  for (std::size_t i = 0; i < r.x.size(); ++i) {
    if (r.t[i] >= from) p = std::max(p, std::abs(r.x[i]));
  }
  return p;
}

using Factory = std::function<std::unique_ptr<ni::System>()>;

Run measure(const std::string& scene, const std::string& method, double parameter,
            const Factory& make, double end_time, double sample_dt, const char* column,
            int repeats) {
  Run run;
  run.scene = scene;
  run.method = method;
  run.parameter = parameter;
  std::vector<double> walls;
  for (int r = 0; r < repeats; ++r) {
    auto sys = make();
    ni::Recorder rec(*sys, sample_dt);
    const auto t0 = std::chrono::steady_clock::now();
    if (method == "event_driven") {
      ni::EventDrivenOptions o;
      o.end_time = end_time;
      o.tolerance = parameter;
      run.stats = ni::event_driven(*sys, o, rec);
    } else if (method == "compliance") {
      // parameter = stiffness factor on the default Hertz stiffness. The exact Hunt–Crossley
      // law reproduces each contact's restitution, so the compliance answer tends to the
      // nonsmooth reference as k grows (docs/compliance.md).
      ni::ComplianceOptions o;
      o.end_time = end_time;
      o.stiffness *= parameter;
      o.law = ni::DampingLaw::kHuntCrossleyExact;
      run.stats = ni::compliance(*sys, o, rec);
    } else {
      ni::MoreauJeanOptions o;
      o.end_time = end_time;
      o.step = parameter;
      run.stats = ni::moreau_jean(*sys, o, rec);
    }
    walls.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    if (r == 0) {
      run.t = rec.series("t");
      run.x = rec.series(column);
      run.impacts = rec.count(ni::EventKind::kImpact);
      run.events = rec.events().size();
    }
    // A single run longer than 5 s is timed once: its spread is far below the differences
    // the study looks at.
    if (walls.back() > 5.0) break;
  }
  run.wall = median(walls);
  return run;
}

struct Arguments {
  std::filesystem::path out = nsb::benchmarks::kOutputDir / "work_precision";
  double bridge_end = 22.0;  // [s]
  int repeats = 3;
  bool quick = false;
};

// The options of the usage line above; exits with status 2 on a bad one.
Arguments parse_arguments(int argc, char** argv) {
  Arguments args;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << "work_precision_bench: " << a << " needs a value\n";
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--out") {
      args.out = next();
    } else if (a == "--end-time") {
      args.bridge_end = std::atof(next().c_str());
    } else if (a == "--repeats") {
      args.repeats = std::max(1, std::atoi(next().c_str()));
    } else if (a == "--quick") {
      args.quick = true;
    } else {
      std::cerr << "usage: work_precision_bench [--out DIR] [--end-time T] [--repeats N] "
                   "[--quick]\n";
      std::exit(2);
    }
  }
  return args;
}

// The parameters each method runs with: event-driven tolerances, Moreau–Jean steps [s] and
// compliance stiffness factors.
struct Grid {
  std::vector<double> tolerances{1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
  std::vector<double> steps{1e-2, 1e-3, 1e-4, 1e-5};
  std::vector<double> stiffness_factors{1e-4, 1e-2, 1.0, 1e2};
};

struct SceneSpec {
  std::string name;
  Factory make;
  double end_time, sample_dt;
  const char* column;
  double peak_from;  // [s]: the peak is taken over t >= peak_from
};

// The bridge under excitation 5 (until bridge_end) and the bouncing ball.
std::vector<SceneSpec> study_scenes(double bridge_end) {
  const std::filesystem::path bridge_file =
      std::filesystem::path(NSB_SCENES_DIR) / "bridge-exc5.toml";
  return {
      {"bridge-exc5",
       [bridge_file] { return std::move(nsb::scene::load_scene(bridge_file).system); }, bridge_end,
       0.005, "theta", 0.0},
      {"bouncing-ball",
       [] {
         nm::BouncingBall::Parameters p;
         p.restitution = 0.8;
         return std::unique_ptr<ni::System>(std::make_unique<nm::BouncingBall>(p));
       },
       // The ball's peak: the apex of the first rebound, after the first impact at
       // sqrt(2 h / g) = 0.4515 s.
       6.0, 0.001, "y", 0.5},
  };
}

// Every method over its grid on one scene, event-driven first.
std::vector<Run> run_scene(const SceneSpec& sc, const Grid& grid, int repeats) {
  std::vector<Run> runs;
  for (double tol : grid.tolerances) {
    runs.push_back(measure(sc.name, "event_driven", tol, sc.make, sc.end_time, sc.sample_dt,
                           sc.column, repeats));
  }
  for (double h : grid.steps) {
    runs.push_back(measure(sc.name, "moreau", h, sc.make, sc.end_time, sc.sample_dt,
                           sc.column, repeats));
  }
  for (double k : grid.stiffness_factors) {
    runs.push_back(measure(sc.name, "compliance", k, sc.make, sc.end_time, sc.sample_dt,
                           sc.column, repeats));
  }
  return runs;
}

// One table line and one CSV row per run, its errors against the reference run ref.
void report(const std::vector<Run>& runs, const Run& ref, double peak_from, std::ofstream& csv) {
  const double ref_peak = peak_abs(ref, peak_from);
  for (const auto& r : runs) {
    const auto [hmax, hrms] = history_error(r, ref);
    const double peak = peak_abs(r, peak_from);
    std::printf("%-14s %-12s %9.1e %10.3e %12.6e %12.3e %12.3e %9lld %8lld %7zu %7zu %6lld\n",
                r.scene.c_str(), r.method.c_str(), r.parameter, r.wall, peak,
                std::abs(peak - ref_peak), hmax, static_cast<long long>(r.stats.steps),
                static_cast<long long>(r.stats.rejected_steps), r.events, r.impacts,
                static_cast<long long>(r.stats.lcp_solves));
    csv << r.scene << ',' << r.method << ',' << r.parameter << ',' << r.wall << ',' << peak
        << ',' << std::abs(peak - ref_peak) << ',' << hmax << ',' << hrms << ','
        << r.stats.steps << ',' << r.stats.rejected_steps << ',' << r.events << ','
        << r.impacts << ',' << r.stats.lcp_solves << ',' << r.stats.energy.error << ','
        << (r.stats.completed ? 1 : 0) << '\n';
  }
}

}  // namespace

int main(int argc, char** argv) {
  Arguments args = parse_arguments(argc, argv);
  std::printf("work_precision_bench: build %s, revision %s\n", NSB_BUILD_TYPE,
              nsb::io::build_info().revision.c_str());
  std::filesystem::create_directories(args.out);

  Grid grid;
  if (args.quick) {
    grid.tolerances = {1e-4, 1e-6, 1e-8};
    grid.steps = {1e-2, 1e-3};
    grid.stiffness_factors = {1e-2, 1.0};
    args.bridge_end = std::min(args.bridge_end, 6.0);
  }

  std::ofstream csv(args.out / "work_precision.csv");
  csv << "scene,method,parameter,wall_s,peak,peak_error,history_max_error,history_rms_error,"
         "steps,rejected_steps,events,impacts,lcp_solves,energy_error,completed\n";
  std::printf("%-14s %-12s %9s %10s %12s %12s %12s %9s %8s %7s %7s %6s\n", "scene", "method",
              "param", "wall[s]", "peak", "peak_err", "hist_max", "steps", "rejected",
              "events", "impacts", "lcp");
  for (const auto& sc : study_scenes(args.bridge_end)) {
    const std::vector<Run> runs = run_scene(sc, grid, args.repeats);
    const Run& ref = runs[grid.tolerances.size() - 1];  // tightest event-driven tolerance
    report(runs, ref, sc.peak_from, csv);
  }
  std::printf("wrote %s\n", (args.out / "work_precision.csv").c_str());
  return 0;
}
