// Moreau–Jean on the benchmark bridge (scenes/bridge-exc7.toml, h = 1e-4): models::Bridge
// against the bridge assembled from parts (models/bridge_parts.hpp) from the same parameters
// and excitation. The two alternate within each repetition, so that both see the same load
// of a shared machine; the process CPU time and the wall time of each run are kept, and the
// medians and their ratio (parts / bridge) are printed. Then the two-frame bridge
// (scenes/bridge-two-frame.toml: two segments joined by a hinge, four bents) on its own, at
// the same step and window. Scene loading is outside the timing.
//
//   parts_bench [repeats = 5] [csv = parts_bench.csv] [end time = the scene's, 40 s]
#include "integrators/moreau_jean.hpp"
#include "io/build_info.hpp"
#include "models/bridge_parts.hpp"
#include "scene/scene.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <string>
#include <variant>
#include <vector>

namespace {

struct Timing {
  double wall = 0.0, cpu = 0.0;  // [s]
  long long steps = 0;
};

Timing time_run(nsb::integrators::System& system, const nsb::integrators::MoreauJeanOptions& o,
                double sample_dt) {
  nsb::integrators::Recorder rec(system, sample_dt);
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  const auto stats = nsb::integrators::moreau_jean(system, o, rec);
  Timing t;
  t.cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  t.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  t.steps = stats.steps;
  return t;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Median CPU and wall time of the two-frame bridge (two bodies, six contacts, two of them
// body-body) over `repeats` runs of [0, end_time] at h = 1e-4.
Timing time_two_frame(int repeats, double end_time) {
  using namespace nsb;
  std::vector<double> cpu, wall;
  for (int r = 0; r < repeats; ++r) {
    scene::Scene scene =
        scene::load_scene(std::string(NSB_SCENES_DIR) + "/bridge-two-frame.toml");
    integrators::MoreauJeanOptions o = std::get<integrators::MoreauJeanOptions>(scene.run);
    o.end_time = end_time;
    o.step = 1e-4;
    const Timing f = time_run(*scene.system, o, scene.output.sample_dt);
    cpu.push_back(f.cpu);
    wall.push_back(f.wall);
  }
  return {.wall = median(wall), .cpu = median(cpu)};
}

}  // namespace

int main(int argc, char** argv) {
  using namespace nsb;
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  const std::string csv_path = argc > 2 ? argv[2] : "parts_bench.csv";
  const double end_arg = argc > 3 ? std::atof(argv[3]) : 0.0;
  if (argc > 3 && !(end_arg > 0.0)) {
    std::fprintf(stderr, "parts_bench: end time must be a number > 0 [s], got '%s'\n", argv[3]);
    return 2;
  }
  const std::string scene_file = std::string(NSB_SCENES_DIR) + "/bridge-exc7.toml";
  std::printf("parts_bench: Moreau-Jean, bridge-exc7, h = 1e-4, models::Bridge against the "
              "parts assembly, %d repeats (median)\n", repeats);
  std::printf("build %s, revision %s\n", NSB_BUILD_TYPE, nsb::io::build_info().revision.c_str());
  std::vector<double> cpu_bridge, cpu_parts, wall_bridge, wall_parts;
  double end_time = 0.0;
  long long steps = 0;
  for (int r = 0; r < repeats; ++r) {
    scene::Scene scene = scene::load_scene(scene_file);
    const auto* bridge = dynamic_cast<const models::Bridge*>(scene.system.get());
    if (bridge == nullptr) {
      std::fprintf(stderr, "parts_bench: %s is not a bridge scene\n", scene_file.c_str());
      return 2;
    }
    models::Assembly parts(models::bridge_parts(bridge->parameters(), bridge->excitation()));
    integrators::MoreauJeanOptions o;
    const auto& mj = std::get<integrators::MoreauJeanOptions>(scene.run);
    o.end_time = end_arg > 0.0 ? end_arg : mj.end_time;
    o.step = 1e-4;
    o.theta = mj.theta;
    end_time = o.end_time;
    const Timing b = time_run(*scene.system, o, scene.output.sample_dt);
    const Timing p = time_run(parts, o, scene.output.sample_dt);
    cpu_bridge.push_back(b.cpu);
    cpu_parts.push_back(p.cpu);
    wall_bridge.push_back(b.wall);
    wall_parts.push_back(p.wall);
    steps = p.steps;
    if (b.steps != p.steps) {
      std::fprintf(stderr, "parts_bench: %lld steps for the bridge, %lld for the parts\n",
                   b.steps, p.steps);
      return 1;
    }
  }
  const Timing frames = time_two_frame(repeats, end_time);
  const double cf = frames.cpu, wf = frames.wall;
  const double cb = median(cpu_bridge), cp = median(cpu_parts);
  const double wb = median(wall_bridge), wp = median(wall_parts);
  std::printf("%-8s %8s %10s %10s %9s\n", "model", "T [s]", "cpu [s]", "wall [s]", "x real");
  std::printf("%-8s %8.2f %10.4f %10.4f %9.0f\n", "bridge", end_time, cb, wb, end_time / cb);
  std::printf("%-8s %8.2f %10.4f %10.4f %9.0f\n", "parts", end_time, cp, wp, end_time / cp);
  std::printf("%-8s %8.2f %10.4f %10.4f %9.0f\n", "2-frame", end_time, cf, wf, end_time / cf);
  std::printf("parts / bridge: cpu %.3f, wall %.3f (%lld steps each)\n", cp / cb, wp / wb, steps);
  std::ofstream csv(csv_path);
  csv << "model,end_time,steps,cpu_median,wall_median,cpu_ratio\n";
  csv << "bridge," << end_time << ',' << steps << ',' << cb << ',' << wb << ",1\n";
  csv << "parts," << end_time << ',' << steps << ',' << cp << ',' << wp << ',' << cp / cb << '\n';
  csv << "two_frame," << end_time << ',' << steps << ',' << cf << ',' << wf << ',' << cf / cb
      << '\n';
  std::printf("wrote %s\n", csv_path.c_str());
  return 0;
}
