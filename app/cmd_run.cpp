// nsbridge run SCENE.toml [--out DIR] [--method moreau|event_driven|compliance]
//                         [--set key=value ...]
//
// Loads a scene (with overrides), integrates it with the chosen method, and writes
// history.csv, events.csv and summary.json (docs/outputs.md) into DIR, by default
// out/<scene name>/. Exit code 1 when the run stopped early or a contact problem stayed
// unsolved; the files are still written, and say so.
#include "app/commands.hpp"

#include "integrators/output.hpp"
#include "integrators/run.hpp"
#include "models/scene.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace nsb::app {

namespace {

struct RunArgs {
  std::string scene;
  std::string out;
  std::string method;
  std::vector<std::string> overrides;
};

// A progress bar on stderr, drawn only when stderr is a terminal and only once the run has
// lasted kDelay: short runs and redirected output stay clean.
class ProgressBar {
 public:
  ProgressBar(double t0, double t1)
      : t0_(t0), t1_(t1), enabled_(::isatty(STDERR_FILENO) == 1),
        start_(std::chrono::steady_clock::now()) {}
  ~ProgressBar() {
    if (drawn_) std::fputs("\n", stderr);
  }
  void update(double t) {
    if (!enabled_) return;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (elapsed < kDelay) return;
    const double fraction = std::clamp((t - t0_) / (t1_ - t0_), 0.0, 1.0);
    constexpr int kWidth = 40;
    const int filled = static_cast<int>(fraction * kWidth);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(kWidth, ' ');
    const double remaining = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
    std::fprintf(stderr, "\r[%s] %3.0f%%  t = %.3f s  %.0f s left ", bar.c_str(),
                 100.0 * fraction, t, remaining);
    std::fflush(stderr);
    drawn_ = true;
  }

 private:
  static constexpr double kDelay = 2.0;  // [s] of wall time before the bar appears
  double t0_, t1_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
};

void print_summary(const models::Scene& scene, const integrators::Recorder& recorder,
                   const integrators::RunResult& stats, const std::filesystem::path& out) {
  std::cout << "scene      " << scene.name << " (" << scene.kind << "), method " << stats.method
            << '\n';
  std::cout << "status     " << integrators::to_string(stats.status);
  if (!integrators::succeeded(stats.status)) {
    std::cout << " at t = " << stats.failure_time << " s (" << stats.lcp_unsolved
              << " contact problems unsolved)";
  }
  std::cout << '\n';
  std::cout << "time       " << stats.end_time << " s in " << stats.steps << " steps"
            << (stats.completed ? "" : " (stopped early: " + stats.message + ")") << '\n';
  std::cout << "contacts   " << stats.steps_with_lcp << " steps with a contact problem, "
            << stats.lcp_solves << " solves, " << stats.lcp_fallbacks << " fallbacks;";
  for (const auto& [status, count] : stats.lcp_status) std::cout << ' ' << status << ' ' << count;
  std::cout << '\n';
  std::cout << "events     " << recorder.count(integrators::EventKind::kImpact) << " impacts, "
            << recorder.count(integrators::EventKind::kSlip) << " slips, "
            << recorder.count(integrators::EventKind::kStick) << " sticks, "
            << recorder.count(integrators::EventKind::kWarning) << " warnings\n";
  // Peak of every generalized coordinate.
  const std::size_t ncoord = static_cast<std::size_t>(scene.system->dofs());
  std::cout << "peaks     ";
  for (std::size_t c = 1; c <= ncoord && c < recorder.columns().size(); ++c) {
    double peak = 0.0;
    for (std::size_t r = 0; r < recorder.rows(); ++r) {
      peak = std::max(peak, std::abs(recorder.at(r, c)));
    }
    std::cout << " |" << recorder.columns()[c] << "| " << peak;
  }
  std::cout << '\n';
  std::cout << "energy     balance error " << stats.energy.error << '\n';
  std::cout << "wall time  " << stats.wall_time << " s ("
            << (stats.wall_time > 0.0 ? stats.end_time / stats.wall_time : 0.0)
            << " x real time)\n";
  std::cout << "outputs    " << out.string() << "/{history.csv,events.csv,summary.json}\n";
}

void run(const RunArgs& args) {
  std::vector<std::string> overrides = args.overrides;
  if (!args.method.empty()) overrides.push_back("solver.method=" + args.method);
  models::Scene scene = models::load_scene(args.scene, overrides);
  if (!scene.system) throw InputError(args.scene + ": the scene built no system");
  integrators::Recorder recorder(*scene.system, scene.output.sample_dt);
  ProgressBar bar(scene.system->initial_time(), integrators::end_time(scene.run));
  const integrators::RunResult stats = integrators::integrate(
      *scene.system, scene.run, recorder, [&bar](double t) { bar.update(t); });
  const std::filesystem::path out =
      args.out.empty() ? std::filesystem::path("out") / scene.name : std::filesystem::path(args.out);
  try {
    integrators::write_outputs(out, scene.name, recorder, stats);
  } catch (const std::runtime_error& e) {
    throw InputError(std::string("--out: ") + e.what());  // an unwritable place is bad input
  }
  print_summary(scene, recorder, stats, out);
  if (!integrators::succeeded(stats.status)) exit_code() = 1;
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  auto* cmd = app.add_subcommand("run", "Integrate a scene and write its history, events and "
                                        "summary");
  cmd->add_option("scene", args->scene, "Scene file (TOML)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--out", args->out, "Output directory (default out/<scene name>)");
  cmd->add_option("--method", args->method, "Integration method (overrides solver.method)")
      ->check(CLI::IsMember({"moreau", "event_driven", "compliance"}));
  cmd->add_option("--set", args->overrides,
                  "Override a scene key, e.g. --set solver.step=1e-5 (repeatable)")
      ->allow_extra_args(false);
  cmd->callback([args] { run(*args); });
}

}  // namespace nsb::app
