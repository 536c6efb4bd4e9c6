// Moreau–Jean on two bridges assembled from parts (models/assembly.hpp), h = 1e-4: the
// one-deck benchmark bridge of scenes/bridge-exc7.toml and the two-frame bridge
// (scenes/bridge-two-frame.toml: two segments joined by a hinge, four bents), alternating
// within each repetition so that both see the same load of a shared machine. The process CPU
// time and the wall time of each run are kept and their medians printed. Scene loading is
// outside the timing.
//
//   parts_bench [repeats = 5] [csv = out/parts_bench.csv] [end time = the scenes', 40 s]
#include "benchmarks/output.hpp"
#include "integrators/moreau_jean.hpp"
#include "io/build_info.hpp"
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
  double end_time = 0.0;         // [s]
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

// One run of a scene file of scenes/ over [0, end_time] (0: the scene's) at h = 1e-4.
Timing time_scene(const std::string& name, double end_time) {
  using namespace nsb;
  scene::Scene scene = scene::load_scene(std::string(NSB_SCENES_DIR) + "/" + name);
  integrators::MoreauJeanOptions o = std::get<integrators::MoreauJeanOptions>(scene.run);
  if (end_time > 0.0) o.end_time = end_time;
  o.step = 1e-4;
  Timing t = time_run(*scene.system, o, scene.output.sample_dt);
  t.end_time = o.end_time;
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace nsb;
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  const std::string csv_path =
      argc > 2 ? argv[2] : (nsb::benchmarks::kOutputDir / "parts_bench.csv").string();
  const double end_arg = argc > 3 ? std::atof(argv[3]) : 0.0;
  if (argc > 3 && !(end_arg > 0.0)) {
    std::fprintf(stderr, "parts_bench: end time must be a number > 0 [s], got '%s'\n", argv[3]);
    return 2;
  }
  std::printf("parts_bench: Moreau-Jean, h = 1e-4, bridge-exc7 and bridge-two-frame, %d repeats "
              "(median)\n", repeats);
  std::printf("build %s, revision %s\n", NSB_BUILD_TYPE, nsb::io::build_info().revision.c_str());
  struct Model {
    const char* name;   // in the table and the CSV
    const char* scene;  // file in scenes/
    std::vector<double> cpu, wall;
    Timing last;
  };
  Model models[] = {{"bridge", "bridge-exc7.toml", {}, {}, {}},
                    {"two_frame", "bridge-two-frame.toml", {}, {}, {}}};
  for (int r = 0; r < repeats; ++r) {
    for (Model& m : models) {
      m.last = time_scene(m.scene, end_arg);
      m.cpu.push_back(m.last.cpu);
      m.wall.push_back(m.last.wall);
    }
  }
  std::printf("%-10s %8s %10s %10s %10s %9s\n", "model", "T [s]", "steps", "cpu [s]", "wall [s]",
              "x real");
  std::ofstream csv = nsb::benchmarks::open_output(csv_path);
  csv << "model,end_time,steps,cpu_median,wall_median\n";
  for (const Model& m : models) {
    const double c = median(m.cpu), w = median(m.wall), t = m.last.end_time;
    std::printf("%-10s %8.2f %10lld %10.4f %10.4f %9.0f\n", m.name, t, m.last.steps, c, w, t / c);
    csv << m.name << ',' << t << ',' << m.last.steps << ',' << c << ',' << w << '\n';
  }
  std::printf("wrote %s\n", csv_path.c_str());
  return 0;
}
