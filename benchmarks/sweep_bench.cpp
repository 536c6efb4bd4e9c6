// Parallel efficiency of `nsbridge sweep` on one machine: the Fig. 6 design (36 runs of the
// benchmark bridge, scenes/sweeps/fig6.toml) on one worker thread and on every core. Each
// configuration runs `repeats` times into a fresh folder; the medians give
//   efficiency = T(1 worker) / (N * T(N workers))   (1 = linear speed-up; goal >= 0.85).
// The load average is printed, since other processes on the machine lower the efficiency; the
// process CPU time is printed too: its ratio between the two configurations is the work the
// parallel run adds (1 = none), independent of the load.
// The MPI counterpart is benchmarks/sweep_mpi_bench.sh.
//
//   sweep_bench [repeats = 3] [csv = out/sweep_bench.csv] [end_time = scene's] [workers = all cores]
#include "benchmarks/output.hpp"
#include "io/build_info.hpp"
#include "sweep/runner.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double load_average() {
  std::ifstream in("/proc/loadavg");
  double l = 0.0;
  in >> l;
  return l;
}

}  // namespace

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  using namespace nsb::sweep;
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  const std::string csv_path = argc > 2 ? argv[2] : (nsb::benchmarks::kOutputDir / "sweep_bench.csv").string();
  const std::string end_time = argc > 3 ? argv[3] : "";
  const int cores = static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
  const int workers = argc > 4 ? std::max(1, std::atoi(argv[4])) : cores;
  const fs::path design = fs::path(NSB_SCENES_DIR) / "sweeps" / "fig6.toml";
  std::printf("sweep_bench: %s, 1 and %d workers (%d cores), %d repeats (median)%s%s\n",
              design.c_str(), workers, cores, repeats, end_time.empty() ? "" : ", end_time ",
              end_time.c_str());
  std::printf("build %s, revision %s, load average before %.2f\n", NSB_BUILD_TYPE,
              nsb::io::build_info().revision.c_str(),
              load_average());
  // One folder per process: two benchmarks running at once (a CTest smoke run beside a timed
  // one) must not write into each other's runs.
  const fs::path scratch = fs::temp_directory_path() /
                           ("nsb_sweep_bench-" + std::to_string(static_cast<long>(::getpid())));
  std::ofstream csv = nsb::benchmarks::open_output(csv_path);
  csv << "workers,repeat,wall_s,cpu_s,runs,runs_per_s\n";
  std::vector<double> medians, cpu_medians;
  std::size_t runs = 0;
  for (const int w : {1, workers}) {
    std::vector<double> walls, cpus;
    for (int r = 0; r < repeats; ++r) {
      SweepOptions o;
      std::string name = "w";
      name += std::to_string(w);
      o.out = scratch / name;
      o.jobs = w;
      o.restart = true;
      o.progress = false;
      fs::remove_all(o.out);
      if (!end_time.empty()) o.set.push_back("solver.end_time=" + end_time);
      const auto start = std::chrono::steady_clock::now();
      const std::clock_t cpu_start = std::clock();
      const SweepSummary s = run_sweep(design, o);
      const double wall =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
      cpus.push_back(cpu);
      runs = s.runs;
      walls.push_back(wall);
      csv << w << ',' << r << ',' << wall << ',' << cpu << ',' << s.runs << ',' << s.runs / wall
          << '\n';
    }
    medians.push_back(median(walls));
    cpu_medians.push_back(median(cpus));
    std::printf("%2d worker%s: median %.3f s wall, %.3f s CPU for %zu runs (%.2f runs/s)\n", w,
                w == 1 ? " " : "s", medians.back(), cpu_medians.back(), runs,
                static_cast<double>(runs) / medians.back());
    std::fflush(stdout);
  }
  const double efficiency = medians[0] / (workers * medians[1]);
  std::printf(
      "parallel efficiency %.3f (speed-up %.2f on %d workers; goal >= 0.85), load "
      "average after %.2f\n",
      efficiency, medians[0] / medians[1], workers, load_average());
  std::printf("CPU time ratio %.3f (CPU of 1 worker / CPU of %d; 1 = no parallel overhead)\n",
              cpu_medians[0] / cpu_medians[1], workers);
  fs::remove_all(scratch);
  return 0;
}
