// Compliance (gap element) method on the benchmark bridge under excitation 5: wall time and
// step count against the contact stiffness k = factor * k0, beside the nonsmooth methods, and
// the error of the compliance theta(t) against the nonsmooth (Moreau–Jean) history computed
// with eps = e_effective of the same damping law (docs/compliance.md). Also the first
// pounding's penetration depth and contact duration (the paper's Figure 8 trend).
//
// Usage: compliance_bench [--scene FILE] [--law NAME] [--restitution E] [--end-time T]
//                         [--tolerance TOL] [--factors f1,f2,...] [--repeat N] [--reference-step H]
//                         [--event-driven] [--csv FILE] [--history-dir DIR]
// Writes one CSV row per run; compliance_plot.gp turns it into pictures.
#include "benchmarks/output.hpp"
#include "integrators/compliance.hpp"
#include "integrators/event_driven.hpp"
#include "integrators/moreau_jean.hpp"
#include "io/build_info.hpp"
#include "scene/scene.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

namespace {

using nsb::integrators::Recorder;
using nsb::integrators::RunResult;

struct History {
  std::vector<double> t, theta;
};

History history(const Recorder& rec) { return {rec.series("t"), rec.series("theta")}; }

// Linear interpolation of h at time t (h.t ascending).
double interpolate(const History& h, double t) {
  auto it = std::lower_bound(h.t.begin(), h.t.end(), t);
  if (it == h.t.begin()) return h.theta.front();
  if (it == h.t.end()) return h.theta.back();
  const auto i = static_cast<std::size_t>(it - h.t.begin());
  const double s = (t - h.t[i - 1]) / (h.t[i] - h.t[i - 1]);
  return (1 - s) * h.theta[i - 1] + s * h.theta[i];
}

double peak_abs(const History& h) {
  double p = 0.0;
  for (double v : h.theta) p = std::max(p, std::abs(v));
  return p;
}

struct ThetaError {
  double rms = 0.0;  // RMS of theta - theta_ref over the reference samples, / peak |theta_ref|
  double max = 0.0;  // max |theta - theta_ref| / peak |theta_ref|
  double peak = 0.0; // (peak |theta| - peak |theta_ref|) / peak |theta_ref|
};

ThetaError theta_error(const History& h, const History& ref) {
  ThetaError e;
  const double scale = std::max(peak_abs(ref), 1e-12);
  double sum = 0.0;
  for (std::size_t i = 0; i < ref.t.size(); ++i) {
    const double d = interpolate(h, ref.t[i]) - ref.theta[i];
    sum += d * d;
    e.max = std::max(e.max, std::abs(d));
  }
  e.rms = std::sqrt(sum / static_cast<double>(std::max<std::size_t>(1, ref.t.size()))) / scale;
  e.max /= scale;
  e.peak = (peak_abs(h) - peak_abs(ref)) / scale;
  return e;
}

// The first pounding: the first close event and the open event of the same contact; the
// largest penetration of that contact in between.
struct Pounding {
  int contact = 0;
  double t_close = 0.0, duration = 0.0, penetration = 0.0, peak_force = 0.0;
};

Pounding first_pounding(const Recorder& rec) {
  Pounding p;
  for (const auto& ev : rec.events()) {
    const bool closing = ev.kind == nsb::integrators::EventKind::kClose ||
                         ev.kind == nsb::integrators::EventKind::kImpact;
    if (p.contact == 0 && closing && ev.contact > 0) {
      p.contact = ev.contact;
      p.t_close = ev.t;
    } else if (p.contact != 0 && ev.contact == p.contact &&
               ev.kind == nsb::integrators::EventKind::kOpen) {
      p.duration = ev.t - p.t_close;
      break;
    }
  }
  if (p.contact == 0) return p;
  const auto t = rec.series("t");
  const auto g = rec.series("gN" + std::to_string(p.contact));
  const auto f = rec.series("lambdaN" + std::to_string(p.contact));
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] < p.t_close || t[i] > p.t_close + p.duration) continue;
    p.penetration = std::max(p.penetration, -g[i]);
    p.peak_force = std::max(p.peak_force, f[i]);
  }
  return p;
}

// Processor time of this process [s]: the machine is shared, so wall time alone overstates
// the cost when other jobs run; both are recorded.
double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

std::string number(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

void write_history(const std::filesystem::path& file, const History& h) {
  std::ofstream out(file);
  out << "t,theta\n";
  out.precision(10);
  for (std::size_t i = 0; i < h.t.size(); ++i) out << h.t[i] << ',' << h.theta[i] << '\n';
}

// The command line's settings.
struct Settings {
  std::string scene = std::string(NSB_SCENES_DIR) + "/bridge-exc5.toml";
  std::string law_name = "hertzdamp";
  double restitution = 0.0;  // e_set of the contacts (the paper's eps_N = 0)
  double end_time = 0.0;     // 0: the scene's
  double tolerance = 0.0;    // 0: the scene's solver.tolerance
  std::vector<double> factors{1e-4, 1e-3, 1e-2, 1e-1, 1.0, 1e1, 1e2};
  int repeat = 3;
  double reference_step = 1e-4;
  bool event_driven = false;
  std::string csv = (nsb::benchmarks::kOutputDir / "compliance_bench.csv").string();
  std::string history_dir;
};

void add_options(CLI::App& app, Settings& s) {
  app.add_option("--scene", s.scene, "bridge scene file");
  app.add_option("--law", s.law_name, "damping law")
      ->check(CLI::IsMember(nsb::integrators::damping_law_names()));
  app.add_option("--restitution", s.restitution, "e_set of the gap elements")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--end-time", s.end_time, "simulated time [s]; 0 keeps the scene's");
  app.add_option("--tolerance", s.tolerance, "compliance error tolerance; 0 keeps the scene's");
  app.add_option("--factors", s.factors, "stiffness factors k / k0")->delimiter(',');
  app.add_option("--repeat", s.repeat, "runs per configuration (median wall time)")
      ->check(CLI::PositiveNumber);
  app.add_option("--reference-step", s.reference_step, "Moreau–Jean step of the reference [s]");
  app.add_flag("--event-driven", s.event_driven, "also time the event-driven method");
  app.add_option("--csv", s.csv, "output CSV (default out/compliance_bench.csv)");
  app.add_option("--history-dir", s.history_dir, "write theta(t) of every run here");
}

// One benchmark: the settings, the law, the scene overrides of each method and the CSV.
class Bench {
 public:
  explicit Bench(const Settings& s)
      : s_(s),
        law_(nsb::integrators::parse_damping_law(s.law_name)),
        e_eff_(nsb::integrators::hunt_crossley_restitution(
            nsb::integrators::damping_factor(law_, s.restitution))),
        out_(nsb::benchmarks::open_output(s.csv)) {
    std::vector<std::string> base{"model.seats.restitution=" + number(s.restitution)};
    std::vector<std::string> reference{"model.seats.restitution=" + number(e_eff_)};
    if (s.end_time > 0.0) {
      base.push_back("solver.end_time=" + number(s.end_time));
      reference.push_back("solver.end_time=" + number(s.end_time));
    }
    reference_overrides_ = reference;
    // The scene's [solver] settings as read for each method.
    moreau_overrides_ = with_method(reference, "moreau");
    event_overrides_ = with_method(reference, "event_driven");
    compliance_overrides_ = with_method(base, "compliance");
    out_ << "method,law,e_set,e_effective,factor,stiffness,wall_time_median,cpu_time_median,"
            "steps,rejected_steps,completed,theta_rms_error,theta_max_error,peak_theta,"
            "peak_theta_error,first_contact,first_close,first_duration,first_penetration,"
            "first_peak_force\n";
  }

  void print_header() const {
    std::printf("compliance_bench: build %s, revision %s\n", NSB_BUILD_TYPE,
                nsb::io::build_info().revision.c_str());
    std::printf("scene %s, law %s, e_set %.3f, e_effective %.6f\n", s_.scene.c_str(),
                s_.law_name.c_str(), s_.restitution, e_eff_);
  }

  // The nonsmooth reference: Moreau–Jean with eps = e_effective.
  void run_reference() {
    std::vector<double> walls, cpus;
    RunResult st;
    Recorder keep(*nsb::scene::load_scene(s_.scene, reference_overrides_).system, 0.0);
    for (int r = 0; r < s_.repeat; ++r) {
      auto sc = nsb::scene::load_scene(s_.scene, moreau_overrides_);
      const auto o = moreau_options(sc, s_.reference_step);
      Recorder rec(*sc.system, sc.output.sample_dt);
      const double c0 = cpu_seconds();
      st = nsb::integrators::moreau_jean(*sc.system, o, rec);
      cpus.push_back(cpu_seconds() - c0);
      walls.push_back(st.wall_time);
      if (r == 0) keep = rec;
    }
    ref_ = history(keep);
    const Pounding p = first_pounding(keep);
    std::printf("%-14s h = %.1e: wall %.3f s, cpu %.3f s (medians of %d), steps %lld, peak "
                "|theta| %.4e rad, first contact %d at %.4f s\n",
                "moreau", s_.reference_step, median(walls), median(cpus), s_.repeat,
                static_cast<long long>(st.steps), peak_abs(ref_), p.contact, p.t_close);
    row("moreau", 0.0, 0.0, walls, cpus, st, ThetaError{}, peak_abs(ref_), p);
    if (!s_.history_dir.empty()) write_history(s_.history_dir + "/moreau.csv", ref_);
  }

  // A coarser Moreau–Jean run, for the work-precision comparison.
  void run_moreau(double h) {
    auto sc = nsb::scene::load_scene(s_.scene, moreau_overrides_);
    const auto o = moreau_options(sc, h);
    Recorder rec(*sc.system, sc.output.sample_dt);
    const double c0 = cpu_seconds();
    const RunResult st = nsb::integrators::moreau_jean(*sc.system, o, rec);
    const double cpu = cpu_seconds() - c0;
    const History hh = history(rec);
    const ThetaError err = theta_error(hh, ref_);
    std::printf("%-14s h = %.1e: wall %.3f s, cpu %.3f s, steps %lld, theta rms error %.3e\n",
                "moreau", h, st.wall_time, cpu, static_cast<long long>(st.steps), err.rms);
    row("moreau_h" + number(h), 0.0, 0.0, {st.wall_time}, {cpu}, st, err, peak_abs(hh),
        first_pounding(rec));
  }

  void run_event_driven() {
    auto sc = nsb::scene::load_scene(s_.scene, event_overrides_);
    const auto& read = std::get<nsb::integrators::EventDrivenOptions>(sc.run);
    nsb::integrators::EventDrivenOptions o;
    o.end_time = read.end_time;
    o.tolerance = read.tolerance;
    Recorder rec(*sc.system, sc.output.sample_dt);
    const double c0 = cpu_seconds();
    const RunResult st = nsb::integrators::event_driven(*sc.system, o, rec);
    const double cpu = cpu_seconds() - c0;
    const History hh = history(rec);
    const ThetaError err = theta_error(hh, ref_);
    std::printf("%-14s: wall %.3f s, cpu %.3f s, steps %lld, completed %d, theta rms error "
                "%.3e %s\n",
                "event_driven", st.wall_time, cpu, static_cast<long long>(st.steps),
                st.completed ? 1 : 0, err.rms, st.message.c_str());
    row("event_driven", 0.0, 0.0, {st.wall_time}, {cpu}, st, err, peak_abs(hh),
        first_pounding(rec));
  }

  // The compliance method at stiffness factor * k0, s_.repeat times.
  void run_compliance(double factor) {
    std::vector<double> walls, cpus;
    RunResult st;
    History hh;
    Pounding p;
    double k = 0.0;
    for (int r = 0; r < s_.repeat; ++r) {
      auto sc = nsb::scene::load_scene(s_.scene, compliance_overrides_);
      const auto& read = std::get<nsb::integrators::ComplianceOptions>(sc.run);
      nsb::integrators::ComplianceOptions o;
      o.end_time = read.end_time;
      o.tolerance = s_.tolerance > 0.0 ? s_.tolerance : read.tolerance;
      o.stiffness = k = read.stiffness * factor;
      o.stick_slip_velocity = read.stick_slip_velocity;
      o.law = law_;
      Recorder rec(*sc.system, 0.0);
      const double c0 = cpu_seconds();
      st = nsb::integrators::compliance(*sc.system, o, rec);
      cpus.push_back(cpu_seconds() - c0);
      walls.push_back(st.wall_time);
      if (r == 0) {
        hh = history(rec);
        p = first_pounding(rec);
      }
    }
    const ThetaError err = theta_error(hh, ref_);
    std::printf("compliance %6.0e k0: wall %7.3f s, cpu %7.3f s, steps %8lld (+%lld rejected), "
                "theta rms error %.3e, peak error %+.3e, first pounding: contact %d at %.4f s, "
                "penetration %.3e m, duration %.4e s%s\n",
                factor, median(walls), median(cpus), static_cast<long long>(st.steps),
                static_cast<long long>(st.rejected_steps), err.rms, err.peak, p.contact,
                p.t_close, p.penetration, p.duration, st.completed ? "" : " (NOT COMPLETED)");
    row("compliance", factor, k, walls, cpus, st, err, peak_abs(hh), p);
    if (!s_.history_dir.empty()) {
      write_history(s_.history_dir + "/compliance_" + number(factor) + ".csv", hh);
    }
  }

 private:
  static std::vector<std::string> with_method(std::vector<std::string> o,
                                              const std::string& method) {
    o.push_back("solver.method=" + method);
    return o;
  }
  // The scene's Moreau–Jean options at step h.
  static nsb::integrators::MoreauJeanOptions moreau_options(const nsb::scene::Scene& sc,
                                                           double h) {
    const auto& read = std::get<nsb::integrators::MoreauJeanOptions>(sc.run);
    nsb::integrators::MoreauJeanOptions o;
    o.end_time = read.end_time;
    o.step = h;
    o.theta = read.theta;
    return o;
  }
  void row(const std::string& method, double factor, double k, const std::vector<double>& walls,
           const std::vector<double>& cpus, const RunResult& st, const ThetaError& err,
           double peak, const Pounding& p) {
    out_ << method << ',' << s_.law_name << ',' << s_.restitution << ',' << e_eff_ << ','
         << factor << ',' << k << ',' << median(walls) << ',' << median(cpus) << ',' << st.steps
         << ',' << st.rejected_steps << ',' << (st.completed ? 1 : 0) << ',' << err.rms << ','
         << err.max << ',' << peak << ',' << err.peak << ',' << p.contact << ',' << p.t_close
         << ',' << p.duration << ',' << p.penetration << ',' << p.peak_force << '\n';
    out_.flush();
  }

  Settings s_;
  nsb::integrators::DampingLaw law_;
  double e_eff_;
  std::ofstream out_;
  std::vector<std::string> reference_overrides_, moreau_overrides_, event_overrides_,
      compliance_overrides_;
  History ref_;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"compliance method on the bridge: cost and error against the stiffness"};
  Settings s;
  add_options(app, s);
  CLI11_PARSE(app, argc, argv);
  if (!s.history_dir.empty()) std::filesystem::create_directories(s.history_dir);
  Bench bench(s);
  bench.print_header();
  bench.run_reference();
  for (double h : {1e-3, 3e-4}) bench.run_moreau(h);
  if (s.event_driven) bench.run_event_driven();
  for (double factor : s.factors) bench.run_compliance(factor);
  std::printf("wrote %s\n", s.csv.c_str());
  return 0;
}
