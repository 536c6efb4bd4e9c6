// nsbridge run SCENE.toml [--out DIR] [--method moreau|event_driven|compliance]
//                         [--set key=value ...] [--quiet] [--strict]
//
// Loads a scene (with overrides), checks the output directory and the initial state, then
// integrates the scene with the chosen method, and writes history.csv, events.csv and
// summary.json (docs/outputs.md) into DIR, by default out/<scene name>/, as one set
// (integrators::write_file_set). Exit code 1 when the run stopped early or a contact problem
// stayed unsolved (the files are still written, and say so), or with --strict when a warning
// says the run is not to be trusted (docs/cli.md).
#include "app/commands.hpp"
#include "app/format.hpp"
#include "app/trust.hpp"

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
  bool out_given = false;  // --out was on the command line (possibly as "")
  std::string method;
  std::vector<std::string> overrides;
  bool quiet = false;
  bool strict = false;
};

// A progress bar on stderr, drawn only when stderr is a terminal and only once the run has
// lasted kDelay: short runs and redirected output stay clean. It shows the simulated time
// reached, the speed (simulated seconds per wall-clock second) and the time left at that
// speed, for every method (each calls the run's Progress callback).
class ProgressBar {
 public:
  ProgressBar(double t0, double t1, bool enabled)
      : t0_(t0), t1_(t1), enabled_(enabled && ::isatty(STDERR_FILENO) == 1),
        start_(std::chrono::steady_clock::now()) {}
  ~ProgressBar() { finish(); }
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  void update(double t) {
    if (!enabled_) return;
    const double elapsed = seconds_since(start_);
    if (elapsed < kDelay || elapsed - last_draw_ < kRedraw) return;
    last_draw_ = elapsed;
    const double span = t1_ - t0_;
    const double fraction = span > 0.0 ? std::clamp((t - t0_) / span, 0.0, 1.0) : 1.0;
    constexpr int kWidth = 30;
    std::string bar(static_cast<std::size_t>(fraction * kWidth), '#');
    bar.resize(kWidth, ' ');
    const double speed = (t - t0_) / elapsed;  // simulated s per wall s
    char left[32] = "?";
    if (speed > 0.0) std::snprintf(left, sizeof left, "%.0f s", (t1_ - t) / speed);
    std::fprintf(stderr, "\r[%s] %3.0f%%  t = %.4g / %.4g s  %.3g x real time  %s left ",
                 bar.c_str(), 100.0 * fraction, t, t1_, speed, left);
    std::fflush(stderr);
    drawn_ = true;
  }
  // Ends the bar's line, so that what follows starts on a fresh line.
  void finish() {
    if (drawn_) std::fputs("\n", stderr);
    drawn_ = false;
  }

 private:
  static double seconds_since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  }
  static constexpr double kDelay = 1.0;   // [s] of wall time before the bar appears
  static constexpr double kRedraw = 0.2;  // [s] of wall time between redraws
  double t0_, t1_;
  bool enabled_;
  bool drawn_ = false;
  double last_draw_ = 0.0;
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
            << recorder.count(integrators::EventKind::kWarning) << " warning events\n";
  // Peak of every generalized coordinate.
  const std::size_t ncoord = static_cast<std::size_t>(scene.system->dofs());
  std::cout << "peaks     ";
  for (std::size_t c = 1; c <= ncoord && c < recorder.columns().size(); ++c) {
    double peak = 0.0;
    for (std::size_t r = 0; r < recorder.rows(); ++r) {
      peak = std::max(peak, std::abs(recorder.at(r, c)));
    }
    std::cout << " |" << recorder.columns()[c] << "| "
              << (std::isfinite(peak) ? shortest(peak) : std::string("not finite"));
  }
  std::cout << '\n';
  // A diverged run's balance is not a number: say so rather than print "nan".
  std::cout << "energy     balance error "
            << (std::isfinite(stats.energy.error) ? shortest(stats.energy.error)
                                                  : std::string("not finite (the run diverged)"))
            << '\n';
  std::cout << "warnings   " << stats.warnings.size()
            << (stats.warnings.empty() ? "" : " (on standard error and in summary.json)") << '\n';
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

  // Everything a user can get wrong is found before the integration starts.
  if (args.out_given && args.out.empty())
    throw InputError("--out: empty path; expected a directory (default out/<scene name>)");
  const std::filesystem::path out =
      args.out_given ? std::filesystem::path(args.out) : std::filesystem::path("out") / scene.name;
  try {
    integrators::prepare_output_dir(out);
  } catch (const std::invalid_argument& e) {
    throw InputError("--out " + out.string() + ": " + e.what());
  }
  try {
    check_initial_state(*scene.system);
  } catch (const std::invalid_argument& e) {
    throw InputError(args.scene + ": " + e.what());
  }
  std::vector<std::string> warnings =
      step_warnings(*scene.system, scene.run, scene.record_step);

  integrators::Recorder recorder(*scene.system, scene.output.sample_dt);
  ProgressBar bar(scene.system->initial_time(), integrators::end_time(scene.run), !args.quiet);
  integrators::RunResult stats = integrators::integrate(
      *scene.system, scene.run, recorder, [&bar](double t) { bar.update(t); });
  bar.finish();

  for (auto& w : result_warnings(recorder, stats)) warnings.push_back(std::move(w));
  stats.warnings.insert(stats.warnings.end(), warnings.begin(), warnings.end());
  try {
    integrators::write_outputs(out, scene.name, recorder, stats);
  } catch (const std::runtime_error& e) {
    throw InputError(std::string("--out: ") + e.what());  // an unwritable place is bad input
  }
  print_summary(scene, recorder, stats, out);
  for (const auto& w : warnings) std::cerr << "nsbridge: warning: " << w << '\n';
  if (!integrators::succeeded(stats.status)) {
    exit_code() = 1;
  } else if (args.strict && !stats.warnings.empty()) {
    std::cerr << "nsbridge: --strict: " << stats.warnings.size()
              << " warning(s): the run is not to be trusted (docs/cli.md)\n";
    exit_code() = 1;
  }
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  auto* cmd = app.add_subcommand("run", "Integrate a scene and write its history, events and "
                                        "summary");
  cmd->add_option("scene", args->scene, "Scene file (TOML)")->required()->check(CLI::ExistingFile);
  auto* out = cmd->add_option("--out", args->out, "Output directory (default out/<scene name>)");
  cmd->add_option("--method", args->method, "Integration method (overrides solver.method)")
      ->check(CLI::IsMember({"moreau", "event_driven", "compliance"}));
  cmd->add_option("--set", args->overrides,
                  "Override a scene key, e.g. --set solver.step=1e-5 (repeatable)")
      ->allow_extra_args(false);
  cmd->add_flag("--quiet", args->quiet, "No progress bar on standard error");
  cmd->add_flag("--strict", args->strict,
                "Exit 1 when a warning says the run is not to be trusted (docs/cli.md)");
  cmd->callback([args, out] {
    args->out_given = out->count() > 0;
    run(*args);
  });
}

}  // namespace nsb::app
