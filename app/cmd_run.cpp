// nsbridge run SCENE.toml [--out DIR] [--method moreau|event_driven|compliance]
//                         [--set key=value ...] [--quiet] [--strict] [--dump-lcp DIR]
//                         [--plot]
//                         [--cross-check moreau|event_driven|compliance]
//
// Loads a scene (with overrides) and checks its initial state (runs::prepare), checks the
// output directory (creating nothing), then integrates the scene with the chosen method
// (runs::run), and writes history.csv, events.csv and summary.json (docs/outputs.md) into DIR,
// by default out/<scene name>/, as one set (runs::write_record). Exit code 1 when the run
// stopped early or a contact problem stayed unsolved (the files are still written, and say
// so), or with --strict when a warning says the run is not to be trusted (docs/cli.md).
// --dump-lcp DIR writes every contact problem of the run to DIR in Siconos's .dat format, with
// DIR/manifest.csv (runs/lcp_dump.hpp); a DIR that cannot be created is refused before the run.
// --cross-check METHOD runs the same scene under METHOD too and compares the peaks
// (summary.json "cross_check"; a disagreement beyond the estimates warns "cross_check: ...").
// A place that cannot be written, before the run or while writing (a full disk), is bad input:
// exit 2 naming the option. Ctrl-C interrupts the run: nothing is written, exit 130.
// --plot draws DIR/response.png once the files are written (app/run_plot.hpp); a drawing
// that fails is reported and exits 1, the run's files staying.
#include "app/commands.hpp"
#include "app/interrupt.hpp"
#include "app/run_plot.hpp"

#include "integrators/run.hpp"
#include "io/csv.hpp"
#include "io/files.hpp"
#include "runs/files.hpp"
#include "runs/run.hpp"

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
  std::string dump_lcp;
  bool dump_lcp_given = false;  // --dump-lcp was on the command line (possibly as "")
  bool plot = false;            // draw <out>/response.png after the run
  std::string cross_check;
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

// Six significant digits for the terminal summary; summary.json keeps every digit.
std::string six_digits(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

// Three significant digits for a peak, one for its error estimate.
std::string three_digits(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", x);
  return text;
}
std::string one_digit(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1g", x);
  return text;
}

// The error estimate (docs/error-estimates.md): the companion, its cost, the impact count and
// first impact's time with their errors, and the accuracy target met or not.
void print_estimate(const runs::Digest& d) {
  const runs::ErrorEstimate& e = d.estimate;
  std::cout << "estimate   ";
  if (!e.enabled) {
    std::cout << "off (solver.error_estimate = false)\n";
    return;
  }
  if (!e.computed) {
    std::cout << "none: "
              << (e.companion_status.empty() ? std::string("no companion for these settings")
                                             : "the companion run ended " + e.companion_status)
              << '\n';
    return;
  }
  std::cout << "companion at " << e.setting << ' ' << three_digits(e.companion_value) << ", order "
            << e.order << "; impacts " << e.impacts << " ± " << e.impacts_error;
  if (!std::isnan(e.first_impact)) {
    std::cout << ", first at " << six_digits(e.first_impact) << " ± "
              << one_digit(e.first_impact_error) << " s";
  }
  if (e.run_cpu_seconds > 0.0) {
    std::cout << "; cost x" << three_digits((e.run_cpu_seconds + e.companion_cpu_seconds) /
                                           e.run_cpu_seconds);
  }
  std::cout << '\n';
  const runs::Accuracy& a = d.accuracy;
  std::cout << "accuracy   " << three_digits(100.0 * a.target) << " % "
            << (a.met ? "met" : "not met") << " (largest: |" << a.worst << "| "
            << three_digits(100.0 * a.worst_relative) << " %)";
  if (d.adaptation.enabled) {
    std::cout << "; adapted in " << d.adaptation.attempts.size() << " runs to " << e.setting
              << ' ' << three_digits(e.value) << ", " << three_digits(d.adaptation.cpu_seconds)
              << " CPU s";
  }
  std::cout << '\n';
}

// The cross-check: the other method's peaks with their errors and the differences.
void print_cross_check(const runs::Digest& d) {
  const runs::CrossCheck& x = d.cross_check;
  std::cout << "cross      " << x.method << ": ";
  if (!x.compared) {
    std::cout << "ended " << x.status << ", not compared\n";
    return;
  }
  for (const runs::CrossPeak& p : x.coordinates) {
    std::cout << '|' << p.name << "| " << three_digits(p.peak);
    if (!std::isnan(p.error)) std::cout << " ± " << one_digit(p.error);
    std::cout << (p.agrees ? " (agrees) " : " (differs) ");
  }
  std::cout << "impacts " << x.impacts << '\n';
}

// The watched limit states (docs/limit-states.md): how many, and each exceeded one with when.
void print_limit_states(const runs::Digest& d) {
  std::size_t exceeded = 0;
  for (const auto& v : d.limit_states) exceeded += v.exceeded ? 1 : 0;
  std::cout << "limits     " << d.limit_states.size() << " watched, " << exceeded << " exceeded";
  const char* sep = ": ";
  for (const auto& v : d.limit_states) {
    if (!v.exceeded) continue;
    std::cout << sep << v.name << " at t = " << six_digits(v.time) << " s";
    sep = ", ";
  }
  std::cout << '\n';
}

void print_summary(const runs::RunRecord& record, const std::filesystem::path& out) {
  const integrators::RunResult& stats = record.result;
  const runs::Digest& d = record.digest;
  auto events = [&d](integrators::EventKind k) { return d.count(k); };
  std::cout << "scene      " << record.scene_name << " (" << record.kind << "), method "
            << stats.method << '\n';
  std::cout << "status     " << integrators::to_string(stats.status);
  if (stats.status == integrators::RunStatus::kUnseated) {
    std::cout << " at t = " << stats.failure_time << " s";
  } else if (!integrators::succeeded(stats.status)) {
    std::cout << " at t = " << stats.failure_time << " s (" << stats.lcp_unsolved
              << " contact problems unsolved)";
  }
  std::cout << '\n';
  std::cout << "time       " << stats.end_time << " s in " << stats.steps << " steps"
            << (stats.completed ? "" : " (stopped early: " + stats.message + ")") << '\n';
  std::cout << "contacts   " << stats.steps_with_lcp << " steps with a contact problem, "
            << stats.lcp_solves << " solves, " << stats.lcp_fallbacks << " fallbacks";
  const char* sep = "; ";
  for (const auto& [status, count] : stats.lcp_status) {
    std::cout << sep << status << ' ' << count;
    sep = " ";
  }
  std::cout << '\n';
  std::cout << "events     " << events(integrators::EventKind::kImpact) << " impacts, "
            << events(integrators::EventKind::kSlip) << " slips, "
            << events(integrators::EventKind::kStick) << " sticks, "
            << events(integrators::EventKind::kWarning) << " warning events\n";
  std::cout << "peaks     ";
  for (const runs::CoordinatePeak& c : d.coordinates) {
    std::cout << " |" << c.name << "| "
              << (std::isfinite(c.peak) ? three_digits(c.peak) : std::string("not finite"));
    if (!std::isnan(c.error)) std::cout << " ± " << one_digit(c.error);
  }
  std::cout << '\n';
  print_estimate(d);
  if (!d.cross_check.method.empty()) print_cross_check(d);
  // A diverged run's balance is not a number: say so rather than print "nan".
  std::cout << "energy     balance error "
            << (std::isfinite(d.energy.error) ? six_digits(d.energy.error)
                                              : std::string("not finite (the run diverged)"))
            << '\n';
  if (!d.limit_states.empty()) print_limit_states(d);
  std::cout << "warnings   " << d.warnings.size()
            << (d.warnings.empty() ? "" : " (on standard error and in summary.json)") << '\n';
  std::cout << "wall time  " << stats.wall_time << " s ("
            << (stats.wall_time > 0.0 ? stats.end_time / stats.wall_time : 0.0)
            << " x real time)\n";
  std::cout << "outputs    " << out.string() << "/{history.csv,events.csv,summary.json}\n";
}

void run(const RunArgs& args) {
  // Everything a user can get wrong is found before the integration starts.
  if (args.dump_lcp_given && args.dump_lcp.empty())
    throw InputError("--dump-lcp: empty path; expected a directory for the contact problems");
  if (!args.dump_lcp.empty()) {
    try {
      io::check_output_dir(args.dump_lcp);
    } catch (const std::invalid_argument& e) {
      throw InputError("--dump-lcp " + args.dump_lcp + ": " + e.what());
    }
  }
  runs::RunRequest request{args.scene, args.overrides, args.method, {}, args.dump_lcp};
  request.stop = &stop_on_interrupt();
  request.cross_check = args.cross_check;
  runs::PreparedRun prepared;
  try {
    prepared = runs::prepare(request);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  if (args.out_given && args.out.empty())
    throw InputError("--out: empty path; expected a directory (default out/<scene name>)");
  const std::filesystem::path out = args.out_given ? std::filesystem::path(args.out)
                                                   : std::filesystem::path("out") /
                                                         prepared.scene.name;
  try {
    io::check_output_dir(out);
  } catch (const std::invalid_argument& e) {
    throw InputError("--out " + out.string() + ": " + e.what());
  }

  const double end_time = integrators::end_time(prepared.scene.run);
  ProgressBar bar(prepared.scene.system->initial_time(), end_time, !args.quiet);
  const runs::RunRecord record = [&] {
    try {
      return runs::run(std::move(prepared), [&bar](double t) { bar.update(t); });
    } catch (const io::WriteError& e) {
      // Only the dump writes during a run: its folder became unwritable, as for --out.
      throw InputError("--dump-lcp " + args.dump_lcp + ": " + e.what());
    }
  }();
  bar.finish();
  const integrators::RunResult& stats = record.result;
  if (stats.status == integrators::RunStatus::kInterrupted) {
    // Ctrl-C: the run is not a result, and nothing of it is written.
    std::cerr << "nsbridge: interrupted at t = " << six_digits(stats.end_time) << " s of "
              << six_digits(end_time) << " s; nothing written to " << out.string() << '\n';
    exit_code() = kInterruptedExit;
    return;
  }
  try {
    runs::write_record(out, record);
  } catch (const io::WriteError& e) {
    // A place that became unwritable (a full disk, a quota, a lost permission) is bad input,
    // as one found before the run.
    throw InputError("--out " + out.string() + ": " + e.what());
  }
  print_summary(record, out);
  if (args.plot) {
    const std::string failed = plot_run(out, "response", default_plot_file(out, "response"));
    if (!failed.empty()) {
      std::cerr << "nsbridge: --plot: " << failed << "; no figure written\n";
      exit_code() = 1;
    } else {
      std::cout << "figure     " << default_plot_file(out, "response").string() << '\n';
    }
  }
  // The trust checks' warnings; the integrator's own are in summary.json and events.csv.
  const auto& warnings = record.digest.warnings;
  for (std::size_t i = record.digest.integrator_warnings; i < warnings.size(); ++i)
    std::cerr << "nsbridge: warning: " << warnings[i] << '\n';
  if (!integrators::is_result(stats.status)) {
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
  cmd->add_flag("--plot", args->plot,
                "Draw the response to <out>/response.png after the run (nsbridge plot)");
  auto* dump = cmd->add_option("--dump-lcp", args->dump_lcp,
                               "Write every contact problem to this directory (Siconos .dat "
                               "files and manifest.csv)");
  cmd->add_option("--cross-check", args->cross_check,
                  "Run the scene under this method too and compare the peaks "
                  "(docs/error-estimates.md)")
      ->check(CLI::IsMember({"moreau", "event_driven", "compliance"}));
  cmd->callback([args, out, dump] {
    args->out_given = out->count() > 0;
    args->dump_lcp_given = dump->count() > 0;
    run(*args);
  });
}

}  // namespace nsb::app
