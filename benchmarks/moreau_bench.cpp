// Moreau–Jean on the benchmark bridge (scenes/bridge-exc1..7.toml) at h = 1e-4 and 1e-3:
// wall time (median of the repeats), steps, the share of steps that solved a contact problem,
// wall time per simulated second, the speed-up over real time, and the peak deck rotation.
// Scene loading (records, splines) is outside the timing. The process CPU time is reported
// beside the wall time, since a shared machine inflates the latter. Writes CSV for moreau_plot.gp.
//
//   moreau_bench [repeats = 3] [csv = out/moreau_bench.csv] [excitation = all (1..7)]
//                [step = both (1e-4 and 1e-3)]
#include "benchmarks/output.hpp"
#include "integrators/moreau_jean.hpp"
#include "io/build_info.hpp"
#include "scene/scene.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <string>
#include <variant>
#include <vector>

namespace {

struct Arguments {
  int repeats = 3;
  std::string csv_path = (nsb::benchmarks::kOutputDir / "moreau_bench.csv").string();
  int only = 0;            // one excitation only (1..7), for quick measurements while profiling
  double only_step = 0.0;  // one step only [s], for profiles of a single configuration
};

// The positional arguments of the usage line above; false (after a message) if one is invalid.
bool parse_arguments(int argc, char** argv, Arguments& a) {
  a.repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  if (argc > 2) a.csv_path = argv[2];
  a.only = argc > 3 ? std::atoi(argv[3]) : 0;
  if (argc > 3 && (a.only < 1 || a.only > 7)) {
    std::fprintf(stderr, "moreau_bench: excitation must be 1..7, got '%s'\n", argv[3]);
    return false;
  }
  // Callgrind counts per step need a single configuration.
  a.only_step = argc > 4 ? std::atof(argv[4]) : 0.0;
  if (argc > 4 && !(a.only_step > 0.0)) {
    std::fprintf(stderr, "moreau_bench: step must be a number > 0, got '%s'\n", argv[4]);
    return false;
  }
  return true;
}

// One excitation at one step: the statistics and peak rotation of the last repeat, the
// median (and minimum) wall time and the median process CPU time over the repeats [s].
struct Measurement {
  nsb::integrators::RunResult stats;
  double peak_rotation = 0.0;
  double duration = 0.0;  // simulated time [s]
  double wall_median = 0.0, wall_min = 0.0, cpu_median = 0.0;
};

Measurement measure(const std::string& scene_file, double h, int repeats) {
  using namespace nsb;
  Measurement m;
  std::vector<double> walls, cpus;  // wall and process CPU time of each repeat [s]
  for (int r = 0; r < repeats; ++r) {
    scene::Scene scene = scene::load_scene(scene_file, {"solver.method=moreau"});
    integrators::Recorder rec(*scene.system, scene.output.sample_dt);
    const auto& read = std::get<integrators::MoreauJeanOptions>(scene.run);
    integrators::MoreauJeanOptions o;
    o.end_time = read.end_time;
    o.step = h;
    o.theta = read.theta;
    m.duration = o.end_time - scene.system->initial_time();
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    m.stats = integrators::moreau_jean(*scene.system, o, rec);
    walls.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    cpus.push_back(static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC);
    m.peak_rotation = 0.0;
    for (double th : rec.series("theta"))
      m.peak_rotation = std::max(m.peak_rotation, std::abs(th));
  }
  std::sort(walls.begin(), walls.end());
  std::sort(cpus.begin(), cpus.end());
  m.wall_median = walls[walls.size() / 2];
  m.wall_min = walls.front();
  m.cpu_median = cpus[cpus.size() / 2];
  return m;
}

// One line of the table and one CSV row.
void report(int exc, double h, const Measurement& m, std::ofstream& csv) {
  const auto& stats = m.stats;
  const double median = m.wall_median;
  const double cpu = m.cpu_median;
  const double duration = m.duration;
  const double share = stats.steps > 0 ? static_cast<double>(stats.steps_with_lcp) /
                                             static_cast<double>(stats.steps)
                                       : 0.0;
  std::printf("%3d %7.0e %8.2f %8lld %8lld %8.2f%% %9.3f %11.2e %9.0f %9.3f %9.0f %12.3e "
              "%10.2e%s\n",
              exc, h, duration, static_cast<long long>(stats.steps),
              static_cast<long long>(stats.steps_with_lcp), 100.0 * share, median,
              median / duration, duration / median, cpu, duration / cpu, m.peak_rotation,
              stats.energy.error,
              stats.completed ? "" : "  (stopped early)");
  csv << exc << ',' << h << ',' << duration << ',' << stats.steps << ','
      << stats.steps_with_lcp << ',' << share << ',' << median << ',' << m.wall_min << ','
      << median / duration << ',' << duration / median << ',' << cpu << ','
      << duration / cpu << ',' << m.peak_rotation << ','
      << stats.energy.error << '\n';
}

}  // namespace

int main(int argc, char** argv) {
  Arguments args;
  if (!parse_arguments(argc, argv, args)) return 2;
  const std::vector<double> steps = args.only_step > 0.0 ? std::vector<double>{args.only_step}
                                                         : std::vector<double>{1e-4, 1e-3};
  std::printf("moreau_bench: Moreau-Jean on the benchmark bridge, %d repeats (median)\n",
              args.repeats);
  std::printf("build %s, revision %s\n", NSB_BUILD_TYPE, nsb::io::build_info().revision.c_str());
  std::ofstream csv = nsb::benchmarks::open_output(args.csv_path);
  csv << "excitation,step,duration,steps,steps_with_lcp,lcp_share,wall_median,wall_min,"
         "wall_per_simulated_second,speedup,cpu_median,cpu_speedup,peak_rotation,energy_error\n";
  std::printf("%3s %7s %8s %8s %8s %9s %9s %11s %9s %9s %9s %12s %10s\n", "exc", "h", "T [s]",
              "steps", "lcp", "lcp share", "wall [s]", "wall/T", "x real", "cpu [s]", "x real",
              "peak |theta|", "E error");
  for (int exc = 1; exc <= 7; ++exc) {
    if (args.only != 0 && exc != args.only) continue;
    const std::string scene_file =
        std::string(NSB_SCENES_DIR) + "/bridge-exc" + std::to_string(exc) + ".toml";
    for (double h : steps) report(exc, h, measure(scene_file, h, args.repeats), csv);
  }
  std::printf("wrote %s\n", args.csv_path.c_str());
  return 0;
}
