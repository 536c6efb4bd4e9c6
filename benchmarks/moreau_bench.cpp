// Moreau–Jean on the benchmark bridge (scenes/bridge-exc1..7.toml) at h = 1e-4 and 1e-3:
// wall time (median of the repeats), steps, the share of steps that solved a contact problem,
// wall time per simulated second, the speed-up over real time, and the peak deck rotation.
// Scene loading (records, splines) is outside the timing. The process CPU time is reported
// beside the wall time, since a shared machine inflates the latter. Writes CSV for moreau_plot.gp.
//
//   moreau_bench [repeats = 3] [csv = moreau_bench.csv] [excitation = all (1..7)]
//                [step = both (1e-4 and 1e-3)]
#include "integrators/moreau_jean.hpp"
#include "io/build_info.hpp"
#include "models/scene.hpp"

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

int main(int argc, char** argv) {
  using namespace nsb;
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  const std::string csv_path = argc > 2 ? argv[2] : "moreau_bench.csv";
  // One excitation only (1..7), for quick measurements while profiling.
  const int only = argc > 3 ? std::atoi(argv[3]) : 0;
  if (argc > 3 && (only < 1 || only > 7)) {
    std::fprintf(stderr, "moreau_bench: excitation must be 1..7, got '%s'\n", argv[3]);
    return 2;
  }
  // One step only, for profiles of a single configuration (callgrind counts per step).
  const double only_step = argc > 4 ? std::atof(argv[4]) : 0.0;
  if (argc > 4 && !(only_step > 0.0)) {
    std::fprintf(stderr, "moreau_bench: step must be a number > 0, got '%s'\n", argv[4]);
    return 2;
  }
  const std::vector<double> steps =
      only_step > 0.0 ? std::vector<double>{only_step} : std::vector<double>{1e-4, 1e-3};
  std::printf("moreau_bench: Moreau-Jean on the benchmark bridge, %d repeats (median)\n", repeats);
  std::printf("build %s, revision %s\n", NSB_BUILD_TYPE, nsb::io::build_info().revision.c_str());
  std::ofstream csv(csv_path);
  csv << "excitation,step,duration,steps,steps_with_lcp,lcp_share,wall_median,wall_min,"
         "wall_per_simulated_second,speedup,cpu_median,cpu_speedup,peak_rotation,energy_error\n";
  std::printf("%3s %7s %8s %8s %8s %9s %9s %11s %9s %9s %9s %12s %10s\n", "exc", "h", "T [s]",
              "steps", "lcp", "lcp share", "wall [s]", "wall/T", "x real", "cpu [s]", "x real",
              "peak |theta|", "E error");
  for (int exc = 1; exc <= 7; ++exc) {
    if (only != 0 && exc != only) continue;
    const std::string scene_file =
        std::string(NSB_SCENES_DIR) + "/bridge-exc" + std::to_string(exc) + ".toml";
    for (double h : steps) {
      std::vector<double> walls, cpus;  // wall and process CPU time of each repeat [s]
      integrators::RunResult stats;
      double peak_rotation = 0.0;
      double duration = 0.0;
      for (int r = 0; r < repeats; ++r) {
        models::Scene scene = models::load_scene(scene_file, {"solver.method=moreau"});
        integrators::Recorder rec(*scene.system, scene.output.sample_dt);
        const auto& read = std::get<integrators::MoreauJeanOptions>(scene.run);
        integrators::MoreauJeanOptions o;
        o.end_time = read.end_time;
        o.step = h;
        o.theta = read.theta;
        duration = o.end_time - scene.system->initial_time();
        const auto start = std::chrono::steady_clock::now();
        const std::clock_t cpu_start = std::clock();
        stats = integrators::moreau_jean(*scene.system, o, rec);
        walls.push_back(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        cpus.push_back(static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC);
        peak_rotation = 0.0;
        for (double th : rec.series("theta")) peak_rotation = std::max(peak_rotation, std::abs(th));
      }
      std::sort(walls.begin(), walls.end());
      std::sort(cpus.begin(), cpus.end());
      const double median = walls[walls.size() / 2];
      const double cpu = cpus[cpus.size() / 2];
      const double share = stats.steps > 0 ? static_cast<double>(stats.steps_with_lcp) /
                                                 static_cast<double>(stats.steps)
                                           : 0.0;
      std::printf("%3d %7.0e %8.2f %8lld %8lld %8.2f%% %9.3f %11.2e %9.0f %9.3f %9.0f %12.3e "
                  "%10.2e%s\n",
                  exc, h, duration, static_cast<long long>(stats.steps),
                  static_cast<long long>(stats.steps_with_lcp), 100.0 * share, median,
                  median / duration, duration / median, cpu, duration / cpu, peak_rotation,
                  stats.energy.error,
                  stats.completed ? "" : "  (stopped early)");
      csv << exc << ',' << h << ',' << duration << ',' << stats.steps << ','
          << stats.steps_with_lcp << ',' << share << ',' << median << ',' << walls.front() << ','
          << median / duration << ',' << duration / median << ',' << cpu << ','
          << duration / cpu << ',' << peak_rotation << ','
          << stats.energy.error << '\n';
    }
  }
  std::printf("wrote %s\n", csv_path.c_str());
  return 0;
}
