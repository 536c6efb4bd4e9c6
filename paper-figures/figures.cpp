#include "paper-figures/figures.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "integrators/run.hpp"
#include "models/analytic.hpp"
#include "models/bridge.hpp"
#include "models/contact_geometry.hpp"
#include "models/rigid_deck.hpp"
#include "models/scene.hpp"
#include "paper-figures/plot.hpp"

#ifndef NSB_SCENES_DIR
#error "NSB_SCENES_DIR must name the scenes folder (set by paper-figures/CMakeLists.txt)"
#endif

namespace nsb::paper_figures {

namespace fs = std::filesystem;
using integrators::EventKind;
using integrators::Recorder;

void FigureOptions::validate() const {
  if (out.empty()) throw std::invalid_argument("out: an output folder is required");
  std::error_code ec;
  if (fs::exists(out, ec) && !fs::is_directory(out, ec)) {
    throw std::invalid_argument("out: \"" + out.string() + "\" exists and is not a folder");
  }
  if (!scenes.empty() && !fs::is_directory(scenes, ec)) {
    throw std::invalid_argument("scenes: \"" + scenes.string() + "\" is not a folder");
  }
  if (gnuplot.empty()) throw std::invalid_argument("gnuplot: the executable must be named");
  if (workers < 1 || workers > 64) throw std::invalid_argument("workers: must be in [1, 64]");
}

namespace {

// ---------------------------------------------------------------------------------------------
// The set of runs (docs/paper-figures.md, "What is run").

// The seven runs: target transverse and longitudinal PGA [g] of the scenes bridge-exc<n>.toml.
// Read back from the scenes' excitation, these only label the figure axes.
constexpr int kRuns = 7;
constexpr int kExample = kExampleRun;  // the paper's example, excitation No. 5
// The paper's contact stiffness range: 1e-4 k ... 1e2 k (sec. 4).
const std::vector<double> kFactorsFull{1e-4, 1e-3, 1e-2, 1e-1, 1e0, 1e1, 1e2};
const std::vector<double> kFactorsQuick{1e-4, 1e-2, 1e0, 1e2};
// --quick integrates the compliance runs only over the strong phase of the record (its
// |a| > 0.5 PGA samples lie between 4.1 s and 12.4 s, data/README.md) to save time.
constexpr double kQuickComplianceEnd = 12.0;  // [s]
// Every compliance step is recorded in a window after the first pounding (Fig. 8), long
// enough for the softest contact (1e-4 k) to open again: measured 0.06 s.
constexpr double kFirstPoundingWindow = 0.15;  // [s]
// Fig. 5: the history is recorded at every step from slightly before the sliding contact.
constexpr double kSlidingLead = 0.05;  // [s]
// Free-deck impacts of the eta map, event-driven: the criterion assumes that both corners of
// an end strike at once, which the event-driven method resolves as one impact; Moreau-Jean may
// take them one step apart when round-off makes one gap smaller (seen at 60 deg, W/L = 0.9).
// The deck approaches the right abutment with a normal
// contact velocity of -0.2 m/s and a tangential one of +0.5 m/s (ratio 2.5 > mu (1 + eps) for
// every mu <= 1 with eps = 0: both corners slide, friction fully mobilised, docs/criterion.md).
constexpr double kImpactNormalSpeed = 0.2, kImpactSlipSpeed = 0.5;  // [m/s]
constexpr double kEtaMapFriction = 0.5;  // the paper's mu for the simulated points
// "Rotating": the post-impact angular velocity moves a deck end by more than 1e-6 of the
// impact speed, far above round-off (1e-12 relative) and far below any rotation that counts.
constexpr double kRotatingFraction = 1e-6;

std::string factor_name(double f) {
  std::ostringstream s;
  s << f;
  return s.str();
}

struct RunSpec {
  std::string name;                    // e.g. "exc5-moreau"
  std::string scene;                   // scene file stem
  std::vector<std::string> overrides;  // scene overrides
};

struct RunOutput {
  RunSpec spec;
  std::shared_ptr<models::Scene> scene;
  std::unique_ptr<Recorder> recorder;
  integrators::RunResult result;
  bool ok() const { return integrators::succeeded(result.status); }
};

class Runner {
 public:
  Runner(fs::path scenes, int workers) : scenes_(std::move(scenes)), workers_(workers) {}

  // Loads every scene first (bad input throws before anything runs), then integrates them on
  // `workers` threads. Each run is independent: its own scene, system and recorder.
  std::vector<RunOutput> run(const std::vector<RunSpec>& specs) {
    std::vector<RunOutput> out(specs.size());
    for (std::size_t i = 0; i < specs.size(); ++i) {
      out[i].spec = specs[i];
      out[i].scene = std::make_shared<models::Scene>(
          models::load_scene(scenes_ / (specs[i].scene + ".toml"), specs[i].overrides));
    }
    std::atomic<std::size_t> next{0};
    auto work = [&] {
      for (std::size_t i = next++; i < out.size(); i = next++) {
        auto& r = out[i];
        r.recorder = std::make_unique<Recorder>(*r.scene->system, r.scene->output.sample_dt);
        r.result = integrators::integrate(*r.scene->system, r.scene->run, *r.recorder);
      }
    };
    std::vector<std::thread> pool;
    const int n = std::min<int>(workers_, static_cast<int>(out.size()));
    for (int w = 1; w < n; ++w) pool.emplace_back(work);
    work();
    for (auto& t : pool) t.join();
    count_ += static_cast<int>(out.size());
    return out;
  }
  int count() const { return count_; }

 private:
  fs::path scenes_;
  int workers_;
  int count_ = 0;
};

const RunOutput& find(const std::vector<RunOutput>& runs, const std::string& name) {
  for (const auto& r : runs) {
    if (r.spec.name == name) return r;
  }
  throw std::logic_error("paper-figures: no run named " + name);
}

std::string exc(int n) { return "bridge-exc" + std::to_string(n); }

// ---------------------------------------------------------------------------------------------
// Measures of one history.

double peak(const Recorder& r, const std::string& column, double t_end = 1e300) {
  const std::size_t c = r.column(column), ct = r.column("t");
  double p = 0.0;
  for (std::size_t i = 0; i < r.rows(); ++i) {
    if (r.at(i, ct) > t_end) break;
    p = std::max(p, std::abs(r.at(i, c)));
  }
  return p;
}

// Linear interpolation of column `column` of r at time t (held beyond the ends).
double value_at(const Recorder& r, const std::string& column, double t) {
  const auto ts = r.series("t"), vs = r.series(column);
  if (ts.empty()) return std::numeric_limits<double>::quiet_NaN();
  if (t <= ts.front()) return vs.front();
  if (t >= ts.back()) return vs.back();
  const auto it = std::upper_bound(ts.begin(), ts.end(), t);
  const std::size_t k = static_cast<std::size_t>(it - ts.begin());
  const double w = (t - ts[k - 1]) / (ts[k] - ts[k - 1]);
  return (1 - w) * vs[k - 1] + w * vs[k];
}

// RMS of (theta_b - theta_a) over a's samples up to t_end, divided by the RMS of theta_a.
double normalized_rms_difference(const Recorder& a, const Recorder& b, const std::string& col,
                                 double t_end) {
  const std::size_t ct = a.column("t"), c = a.column(col);
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < a.rows() && a.at(i, ct) <= t_end; ++i) {
    const double va = a.at(i, c), vb = value_at(b, col, a.at(i, ct));
    num += (vb - va) * (vb - va);
    den += va * va;
  }
  return den > 0 ? std::sqrt(num / den) : std::numeric_limits<double>::quiet_NaN();
}

std::size_t impacts(const Recorder& r) { return r.count(EventKind::kImpact); }

// The first impact of a run: its time and contact (contact 0 when there is none).
std::pair<double, int> first_impact(const Recorder& r) {
  for (const auto& e : r.events()) {
    if (e.kind == EventKind::kImpact) return {e.t, e.contact};
  }
  return {0.0, 0};
}

std::string status_text(const RunOutput& r) {
  std::ostringstream s;
  s << r.spec.name << ": " << integrators::to_string(r.result.status)
    << " at t = " << r.result.failure_time << " s";
  return s.str();
}

// Claim bookkeeping: the runs it used, and "not evaluated" when one of them failed.
void use_runs(Claim& c, const std::vector<const RunOutput*>& runs) {
  for (const auto* r : runs) {
    c.runs.push_back(r->spec.name);
    if (!r->ok()) c.failure += (c.failure.empty() ? "" : "; ") + status_text(*r);
  }
}

// ---------------------------------------------------------------------------------------------
// The pieces of the study, each its own figure and claim(s).

struct Setup {
  bool quick = false;
  std::vector<int> pga_runs;       // runs of Fig. 6 and C2, C3
  std::vector<int> mu0_runs;       // runs repeated with mu = 0 (C1)
  std::vector<double> factors;     // compliance stiffness factors (Fig. 7, C4)
  double compliance_end = 0.0;     // 0: the scene's end time
  std::vector<double> eta_skews;   // [deg]
  std::vector<double> eta_ratios;  // W/L
};

Setup setup(bool quick) {
  Setup s;
  s.quick = quick;
  if (quick) {
    s.pga_runs = {1, 3, 5, 7};
    s.mu0_runs = {5, 7};
    s.factors = {1e-4, 1e-2, 1e2};
    s.compliance_end = kQuickComplianceEnd;
    s.eta_skews = {0, 20, 40, 60};
    s.eta_ratios = {0.05, 0.2, 0.5, 0.9};
  } else {
    for (int n = 1; n <= kRuns; ++n) s.pga_runs.push_back(n), s.mu0_runs.push_back(n);
    s.factors = kFactorsFull;
    s.eta_skews = {0, 10, 20, 30, 40, 50, 60};
    s.eta_ratios = {0.05, 0.1, 0.2, 0.35, 0.5, 0.7, 0.9};
  }
  return s;
}

std::vector<RunSpec> bridge_runs(const Setup& s) {
  std::vector<RunSpec> v;
  v.push_back({"exc5-moreau", exc(kExample), {"solver.method=moreau"}});
  v.push_back({"exc5-event", exc(kExample), {"solver.method=event_driven"}});
  for (double f : s.factors) {
    std::vector<std::string> o{"solver.method=compliance",
                               "solver.stiffness_factor=" + factor_name(f)};
    if (s.compliance_end > 0) o.push_back("solver.end_time=" + factor_name(s.compliance_end));
    v.push_back({"exc5-k" + factor_name(f), exc(kExample), o});
  }
  return v;
}

// Free-deck impacts of the eta map (scenes/rigid-deck-straight.toml with the geometry set).
struct EtaPoint {
  double skew_deg = 0.0, ratio = 0.0;
  std::string name;
};

std::vector<EtaPoint> eta_points(const Setup& s) {
  std::vector<EtaPoint> v;
  for (double a : s.eta_skews) {
    for (double r : s.eta_ratios) {
      v.push_back({a, r, "eta-a" + factor_name(a) + "-wl" + factor_name(r)});
    }
  }
  return v;
}

std::vector<RunSpec> eta_runs(const std::vector<EtaPoint>& pts, double length) {
  std::vector<RunSpec> v;
  for (const auto& p : pts) {
    const double a = p.skew_deg * std::numbers::pi / 180.0, c = std::cos(a), sn = std::sin(a);
    // Right abutment: n = (-c, s), t = (-s, -c) (docs/criterion.md); v = gN n + gT t.
    const double gn = -kImpactNormalSpeed, gt = kImpactSlipSpeed;
    const double vx = gn * -c + gt * -sn, vy = gn * sn + gt * -c;
    std::ostringstream vel;
    vel << std::setprecision(17) << "model.initial_velocity=[" << vx << ", " << vy << ", 0.0]";
    v.push_back({p.name,
                 "rigid-deck-straight",
                 {"model.skew_deg=" + factor_name(p.skew_deg),
                  "model.width=" + factor_name(p.ratio * length),
                  "model.friction=" + factor_name(kEtaMapFriction), vel.str(),
                  "model.gap_left=0.0127", "model.gap_right=0.0127", "solver.end_time=0.2",
                  "solver.method=event_driven", "output.sample_dt=0"}});
  }
  return v;
}

// ---------------------------------------------------------------------------------------------
// Figures 3, 4 and 7: histories of excitation 5.

std::string fig3(const fs::path& dir, const Recorder& mj, const Recorder& ed,
                 const std::string& gp) {
  Table t{
      {"t", "x", "y", "theta", "gN1", "gN2", "gN3", "gN4", "x_event", "y_event", "theta_event"}};
  const auto ts = mj.series("t");
  for (std::size_t i = 0; i < ts.size(); ++i) {
    std::vector<double> row{ts[i]};
    for (const char* c : {"x", "y", "theta", "gN1", "gN2", "gN3", "gN4"})
      row.push_back(mj.at(i, mj.column(c)));
    for (const char* c : {"x", "y", "theta"}) row.push_back(value_at(ed, c, ts[i]));
    t.add(row);
  }
  t.write(dir / "fig3-response.csv");
  return plot(gp, dir, "fig3-response", R"(
set multiplot layout 3,2 title 'Fig. 3: response under excitation 5 (Moreau-Jean h = 1e-4 s and event-driven)'
set xlabel 't [s]'
set ylabel 'x_d [m]'
plot data using 't':'x' with lines title 'Moreau-Jean', data using 't':'x_event' with lines dt 2 title 'event-driven'
set ylabel 'g_{N1} [m]'
plot data using 't':'gN1' with lines notitle
set ylabel 'y_d [m]'
plot data using 't':'y' with lines title 'Moreau-Jean', data using 't':'y_event' with lines dt 2 title 'event-driven'
set ylabel 'g_{N2} [m]'
plot data using 't':'gN2' with lines notitle
set ylabel 'theta_d [rad]'
plot data using 't':'theta' with lines title 'Moreau-Jean', data using 't':'theta_event' with lines dt 2 title 'event-driven'
set ylabel 'g_{N3}, g_{N4} [m]'
plot data using 't':'gN3' with lines title 'g_{N3}', data using 't':'gN4' with lines title 'g_{N4}'
unset multiplot)");
}

std::string fig4(const fs::path& dir, const Recorder& mj, const Recorder& ed, const Sliding& slide,
                 const std::string& gp) {
  Table t{{"t", "omega", "omega_event"}};
  const auto ts = mj.series("t"), om = mj.series("omega");
  for (std::size_t i = 0; i < ts.size(); ++i) t.add({ts[i], om[i], value_at(ed, "omega", ts[i])});
  t.write(dir / "fig4-omega.csv");
  std::ostringstream b;
  b << "set title 'Fig. 4: angular velocity of the deck under excitation 5; shaded: the longest "
       "sliding contact (contact "
    << slide.contact << ", " << slide.start << " - " << slide.end << " s)'\n"
    << "set xlabel 't [s]'\nset ylabel 'omega_d [rad/s]'\n"
    << "set object 1 rect from " << slide.start << ", graph 0 to " << slide.end
    << ", graph 1 fc rgb '#dddddd' fs solid noborder behind\n"
    << "plot data using 't':'omega' with lines title 'Moreau-Jean', data using 't':'omega_event' "
       "with lines dt 2 title 'event-driven'";
  return plot(gp, dir, "fig4-omega", b.str(), {1200, 500});
}

std::string fig7(const fs::path& dir, const Recorder& mj,
                 const std::vector<std::pair<double, const Recorder*>>& k, double t_end,
                 const std::string& gp) {
  Table t{{"t", "theta_nonsmooth"}};
  for (const auto& [f, r] : k) t.columns.push_back("theta_k" + factor_name(f));
  const auto ts = mj.series("t"), th = mj.series("theta");
  for (std::size_t i = 0; i < ts.size() && ts[i] <= t_end; ++i) {
    std::vector<double> row{ts[i], th[i]};
    for (const auto& [f, r] : k) row.push_back(value_at(*r, "theta", ts[i]));
    t.add(row);
  }
  t.write(dir / "fig7-compliance.csv");
  std::ostringstream b;
  b << "set title 'Fig. 7: rotation under excitation 5, nonsmooth (Moreau-Jean) against the "
       "compliance method at c k'\nset xlabel 't [s]'\nset ylabel 'theta_d [rad]'\n"
    << "plot data using 't':'theta_nonsmooth' with lines lw 2 lc rgb 'black' title 'nonsmooth'";
  for (const auto& [f, r] : k) {
    b << ", data using 't':'theta_k" << factor_name(f) << "' with lines title 'compliance "
      << factor_name(f) << " k'";
  }
  return plot(gp, dir, "fig7-compliance", b.str(), {1200, 500});
}

// ---------------------------------------------------------------------------------------------
// Fig. 6 and claims C1, C2, C3.

std::string fig6(const fs::path& dir, const std::vector<Peaks>& peaks, const std::string& gp) {
  Table t{{"run", "pga_transverse_g", "pga_longitudinal_g", "peak_theta_pounding", "peak_theta_mu0",
           "peak_theta_no_pounding", "impacts"}};
  for (const auto& p : peaks) {
    t.add({double(p.run), p.pga_y, p.pga_x, p.pounding, p.mu0, p.free, double(p.impacts)});
  }
  t.write(dir / "fig6-peak-rotation.csv");
  return plot(gp, dir, "fig6-peak-rotation", R"(
set title 'Fig. 6: peak deck rotation against the transverse PGA (runs 1-7, RSN 988, Moreau-Jean)'
set xlabel 'transverse PGA of the input [g]'
set ylabel 'peak |theta_d| [rad]'
set key top left
plot data using 'pga_transverse_g':'peak_theta_pounding' with linespoints pt 7 title 'with pounding, mu = 0.5', \
     data using 'pga_transverse_g':'peak_theta_mu0' with linespoints pt 6 dt 3 title 'with pounding, mu = 0', \
     data using 'pga_transverse_g':'peak_theta_no_pounding' with linespoints pt 5 dt 2 title 'without pounding (gaps never close)')",
              {1000, 700});
}

// ---------------------------------------------------------------------------------------------
// Fig. 8 and claim C5: the first pounding under the compliance method.

struct FirstPounding {
  double factor = 0.0;
  double penetration = std::numeric_limits<double>::quiet_NaN();  // max -g_N [m]
  double duration = std::numeric_limits<double>::quiet_NaN();     // [s]
};

FirstPounding measure_first_pounding(double factor, const Recorder& r, int contact, double t0) {
  FirstPounding fp{factor};
  const auto ts = r.series("t"), g = r.series("gN" + std::to_string(contact));
  std::size_t i = 0;
  while (i < ts.size() && (ts[i] < t0 || g[i] >= 0)) ++i;
  if (i == ts.size()) return fp;
  const double start = ts[i];
  double pen = 0.0;
  for (; i < ts.size() && g[i] < 0; ++i) pen = std::max(pen, -g[i]);
  if (i == ts.size()) return fp;
  fp.penetration = pen;
  fp.duration = ts[i] - start;
  return fp;
}

std::string fig8(const fs::path& dir, const std::vector<std::pair<double, const Recorder*>>& w,
                 const Recorder& mj, int contact, double t_first, const std::string& gp) {
  const std::string g = "gN" + std::to_string(contact), l = "lambdaN" + std::to_string(contact);
  Table t{{"factor", "t", "gap", "lambda_n"}};
  for (const auto& [f, r] : w) {
    const auto ts = r->series("t"), gs = r->series(g), ls = r->series(l);
    for (std::size_t i = 0; i < ts.size(); ++i) {
      if (ts[i] >= t_first - 0.02) t.add({f, ts[i], gs[i], ls[i]});
    }
  }
  const auto ts = mj.series("t"), gs = mj.series(g), ls = mj.series(l);
  for (std::size_t i = 0; i < ts.size(); ++i) {
    if (ts[i] >= t_first - 0.02 && ts[i] <= t_first + kFirstPoundingWindow)
      t.add({0.0, ts[i], gs[i], ls[i]});
  }
  t.write(dir / "fig8-first-pounding.csv");
  std::ostringstream b;
  b << "set multiplot layout 1,2 title sprintf('Fig. 8: first pounding of excitation 5 (contact "
    << contact << ", t = %.4f s)', " << t_first << ")\n"
    << "set title 'gap at the first pounding (factor 0: nonsmooth)'\nset xlabel 't [s]'\n"
    << "set ylabel 'g_{N" << contact << "} [m]'\nset xrange [" << t_first - 0.02 << ":"
    << t_first + 0.1 << "]\nplot ";
  for (std::size_t k = 0; k < w.size(); ++k) {
    b << (k ? ", " : "") << "data using 't':(column('factor') == " << w[k].first
      << " ? column('gap') : 1/0) with lines title '" << factor_name(w[k].first) << " k'";
  }
  b << ", data using 't':(column('factor') == 0 ? column('gap') : 1/0) with lines lw 2 lc rgb "
       "'black' title 'nonsmooth'\nset autoscale x\n"
    << "set title 'force-penetration loop of the gap element'\nset xlabel 'penetration -g_N [m]'\n"
    << "set ylabel 'lambda_N [kN]'\nplot ";
  bool first = true;
  for (const auto& [f, r] : w) {
    if (f < 1.0) continue;  // the loops of the stiffer contacts, as in the paper (1e0 k, 1e2 k)
    b << (first ? "" : ", ") << "data using (column('factor') == " << f
      << " && column('gap') < 0 ? -column('gap') : 1/0):'lambda_n' with lines title '"
      << factor_name(f) << " k'";
    first = false;
  }
  if (first) b << "0 notitle";
  b << "\nunset multiplot";
  return plot(gp, dir, "fig8-first-pounding", b.str(), {1200, 500});
}

Claim claim_c5(const std::vector<FirstPounding>& fps, const std::vector<const RunOutput*>& runs) {
  Claim c{"C5", "a lower k gives deeper penetration and longer contact at the first pounding"};
  use_runs(c, runs);
  double pen = std::numeric_limits<double>::infinity(), dur = pen;
  for (std::size_t i = 0; i < fps.size(); ++i) {
    c.measured.push_back({"penetration_k" + factor_name(fps[i].factor), fps[i].penetration});
    c.measured.push_back({"duration_k" + factor_name(fps[i].factor), fps[i].duration});
    if (i + 1 < fps.size()) {  // fps ascending in k: ratio lower-k / higher-k
      pen = std::min(pen, fps[i].penetration / fps[i + 1].penetration);
      dur = std::min(dur, fps[i].duration / fps[i + 1].duration);
    }
  }
  if (fps.size() < 2) pen = dur = std::numeric_limits<double>::quiet_NaN();
  c.checks.push_back({"smallest_penetration_ratio_lower_to_higher_k", pen, ">", 1.0,
                      "every lower stiffness must penetrate strictly deeper"});
  c.checks.push_back({"smallest_duration_ratio_lower_to_higher_k", dur, ">", 1.0,
                      "every lower stiffness must stay in contact strictly longer"});
  return c;
}

Claim claim_c4(const Recorder& mj, const std::vector<std::pair<double, const Recorder*>>& k,
               double t_end, const std::vector<const RunOutput*>& runs) {
  Claim c{"C4",
          "the compliance method with a large k tracks the nonsmooth result, and with "
          "1e-4 ... 1e-2 k it underestimates the rotation"};
  use_runs(c, runs);
  const double ref = peak(mj, "theta", t_end);
  c.measured.push_back({"peak_theta_nonsmooth", ref});
  c.measured.push_back({"window_end_s", t_end});
  for (const auto& [f, r] : k) {
    const double p = peak(*r, "theta", t_end);
    c.measured.push_back({"peak_theta_k" + factor_name(f), p});
    if (f >= 1e2) {
      c.checks.push_back({"abs_peak_ratio_minus_1_k" + factor_name(f), std::abs(p / ref - 1.0), "<",
                          0.1,
                          "\"tracks\": the peak within 10 %, the agreement the paper "
                          "accepts between its analysis and the test (Fig. 6)"});
      c.checks.push_back({"normalized_rms_difference_k" + factor_name(f),
                          normalized_rms_difference(mj, *r, "theta", t_end), "<", 0.5,
                          "\"tracks\": the history differs by less than half its own RMS"});
    }
    if (f <= 1e-2) {
      c.checks.push_back(
          {"peak_ratio_k" + factor_name(f), p / ref, "<", 0.9,
           "\"underestimates\": at least 10 % below, outside the band of \"tracks\""});
    }
  }
  return c;
}

// ---------------------------------------------------------------------------------------------
// Fig. 5 and claim C6: the longest sliding contact of excitation 5.

SlidingState measure_sliding(const RunOutput& run, const Sliding& s, double mu) {
  const Recorder& r = *run.recorder;
  return paper_figures::measure_sliding(s, mu, r.series("t"),
                                        r.series("lambdaN" + std::to_string(s.contact)),
                                        r.series("lambdaT" + std::to_string(s.contact)));
}

std::string fig5(const fs::path& dir, const RunOutput& run, const SlidingState& st,
                 const std::string& gp) {
  const auto& b = dynamic_cast<const models::Bridge&>(*run.scene->system);
  const Recorder& r = *run.recorder;
  const auto ts = r.series("t");
  std::size_t row = 0;
  while (row + 1 < ts.size() && ts[row] < st.slide.start) ++row;
  const Eigen::Vector3d q(r.at(row, r.column("x")), r.at(row, r.column("y")),
                          r.at(row, r.column("theta")));
  const Eigen::Vector3d u(r.at(row, r.column("vx")), r.at(row, r.column("vy")),
                          r.at(row, r.column("omega")));
  const double t = ts[row];
  const auto corners = b.parameters().deck.corner_faces();
  // Rows: kind 0 deck outline, 1 seat faces, 2 normal force, 3 tangential force; x, y [m] and
  // the arrow components dx, dy [m] (forces at kForceScale).
  constexpr double kForceScale = 1.0 / 200.0;  // [m per kN]: 200 kN is drawn 1 m long
  Table tab{{"kind", "x", "y", "dx", "dy"}};
  const Eigen::Rotation2Dd rot(q(2));
  for (int i : {0, 2, 3, 1, 0}) {  // corners 1, 3, 4, 2, 1: the outline
    const Eigen::Vector2d p = q.head<2>() + rot * corners[static_cast<std::size_t>(i)].body_point;
    tab.add({0, p.x(), p.y(), 0, 0});
  }
  const double half = 0.75 * b.parameters().deck.width;
  for (int a = 0; a < 2; ++a) {
    const auto m = b.seat_motion(a, t);
    const auto& cf = corners[a == 0 ? 0 : 2];
    const Eigen::Vector2d n = Eigen::Rotation2Dd(m.position(2)) * cf.face_normal;
    const Eigen::Vector2d tn = models::perp(n), o = m.position.head<2>();
    tab.add(
        {1, o.x() - half * tn.x(), o.y() - half * tn.y(), 2 * half * tn.x(), 2 * half * tn.y()});
  }
  const int c = st.slide.contact;
  const auto k = models::corner_contact(corners[static_cast<std::size_t>(c - 1)], q, u,
                                        b.seat_motion(models::DeckGeometry::abutment_of(c - 1), t));
  const Eigen::Vector2d fn = st.lambda_n * kForceScale * k.normal,
                        ft = st.lambda_t * kForceScale * k.tangent;
  tab.add({2, k.point.x(), k.point.y(), fn.x(), fn.y()});
  tab.add({3, k.point.x(), k.point.y(), ft.x(), ft.y()});
  tab.write(dir / "fig5-sliding-contact.csv");
  static const std::string kPlan =
      "plot data using (column('kind') == 0 ? column('x') : 1/0):'y' with lines lw 2 title 'deck', "
      "\\\n"
      "  data using (column('kind') == 1 ? column('x') : 1/0):'y':'dx':'dy' with vectors nohead lw "
      "3 lc rgb 'gray30' title 'seat faces', \\\n"
      "  data using (column('kind') == 2 ? column('x') : 1/0):'y':'dx':'dy' with vectors lw 2 lc "
      "rgb 'red' title 'lambda_N n', \\\n"
      "  data using (column('kind') == 3 ? column('x') : 1/0):'y':'dx':'dy' with vectors lw 2 lc "
      "rgb 'blue' title 'lambda_T t'\n";
  std::ostringstream body;
  body
      << std::setprecision(4)
      << "set multiplot layout 2,1 title sprintf('Fig. 5: excitation 5 at t = %.4f s, start of the "
         "longest sliding contact (contact "
      << c << ", " << st.slide.start << " - " << st.slide.end
      << " s): lambda_N = %.1f kN, "
         "lambda_T = %.1f kN, omega = %.2e rad/s', "
      << t << ", " << st.lambda_n << ", " << st.lambda_t << ", " << u(2) << ")\n"
      << "set title 'plan (y exaggerated); forces at 1 m per 200 kN'\nset xlabel 'x [m]'\n"
      << "set ylabel 'y [m]'\nset key outside right\n"
      << kPlan << "set title 'close-up of contact " << c << " (equal axes)'\nset size ratio -1\n"
      << "set xrange [" << k.point.x() - 1.2 << ":" << k.point.x() + 1.2 << "]\n"
      << "set yrange [" << k.point.y() - 0.8 << ":" << k.point.y() + 0.8 << "]\n"
      << kPlan << "unset multiplot";
  return plot(gp, dir, "fig5-sliding-contact", body.str(), {1200, 900});
}

// ---------------------------------------------------------------------------------------------
// The eta map (skew angle against W/L).

std::string fig9(const fs::path& dir, const std::vector<EtaPoint>& pts,
                 const std::vector<RunOutput>& runs, double length, double width,
                 const std::string& gp, int& agree, int& total) {
  Table t{{"kind", "mu", "skew_deg", "w_over_l", "rotating", "predicted", "omega_after"}};
  // Contours |eta| = 1 of the derived criterion (docs/criterion.md): for alpha >= 0 the larger
  // branch is eta_+ = (L/W)(sin(2a)/2 + mu cos^2 a), so |eta| = 1 on W/L = sin(2a)/2 + mu cos^2 a.
  for (double mu : {0.0, 0.1, 0.3, 0.5, 0.8}) {
    for (int i = 0; i <= 120; ++i) {
      const double a = 0.5 * i * std::numbers::pi / 180.0;
      t.add({0, mu, 0.5 * i, std::sin(2 * a) / 2 + mu * std::cos(a) * std::cos(a), 0, 0, 0});
    }
  }
  agree = total = 0;
  for (const auto& p : pts) {
    const auto& r = find(runs, p.name);
    if (!r.ok() || impacts(*r.recorder) == 0) continue;
    // omega right after the first impact: the first sample after it.
    const double t_imp = first_impact(*r.recorder).first;
    const auto ts = r.recorder->series("t"), om = r.recorder->series("omega");
    std::size_t i = 0;
    while (i < ts.size() && ts[i] <= t_imp) ++i;
    if (i == ts.size()) continue;
    const double speed = std::hypot(kImpactNormalSpeed, kImpactSlipSpeed);
    const bool rotating = std::abs(om[i]) * 0.5 * length > kRotatingFraction * speed;
    models::analytic::CriterionInput in{p.skew_deg, p.ratio * length, length, kEtaMapFriction};
    const bool predicted = models::analytic::rotation_criterion(in).rotation;
    agree += rotating == predicted;
    ++total;
    t.add({1, kEtaMapFriction, p.skew_deg, p.ratio, double(rotating), double(predicted), om[i]});
  }
  t.add({2, 0.5, 0.0, width / length, 1, 1, 0});  // the benchmark deck
  t.write(dir / "fig9-eta-map.csv");
  std::ostringstream b;
  b << "set title sprintf('eta map: |eta| = 1 (derived criterion) for several mu; points: "
       "free-deck "
       "impacts at mu = 0.5 (%d of %d as predicted)', "
    << agree << ", " << total << ")\n"
    << "set xlabel 'skew angle alpha [deg]'\nset ylabel 'W / L [-]'\nset key outside right\n"
    << "set yrange [0:1]\n"
    << "plot for [m in '0 0.1 0.3 0.5 0.8'] data using (column('kind') == 0 && abs(column('mu') - "
       "m) "
       "< 1e-9 ? column('skew_deg') : 1/0):'w_over_l' with lines title '|eta| = 1, mu = '.m, \\\n"
    << "  data using (column('kind') == 1 && column('rotating') == 1 ? column('skew_deg') : "
       "1/0):'w_over_l' "
       "with points pt 7 ps 1.5 lc rgb 'red' title 'simulated: rotates', \\\n"
    << "  data using (column('kind') == 1 && column('rotating') == 0 ? column('skew_deg') : "
       "1/0):'w_over_l' "
       "with points pt 6 ps 1.5 lc rgb 'blue' title 'simulated: does not rotate', \\\n"
    << "  data using (column('kind') == 2 ? column('skew_deg') : 1/0):'w_over_l' with points pt 9 "
       "ps 2 lc rgb 'black' title 'benchmark deck'";
  return plot(gp, dir, "fig9-eta-map", b.str(), {1100, 700});
}

}  // namespace

double input_pga(const integrators::System& system, bool transverse) {
  const auto* b = dynamic_cast<const models::Bridge*>(&system);
  if (b == nullptr || b->excitation().bents.empty()) return 0.0;
  const auto& m =
      transverse ? b->excitation().bents[0].transverse : b->excitation().bents[0].longitudinal;
  return m ? m->pga() / 9.81 : 0.0;
}

FigureResult make_figures(const FigureOptions& options) {
  options.validate();
  const auto t0 = std::chrono::steady_clock::now();
  const fs::path scenes = options.scenes.empty() ? fs::path(NSB_SCENES_DIR) : options.scenes;
  const Setup s = setup(options.quick);
  Runner runner(scenes, options.workers);
  FigureResult res;

  // The free-deck length, for the eta map's widths.
  const double length = dynamic_cast<const models::RigidDeck&>(
                            *models::load_scene(scenes / "rigid-deck-straight.toml").system)
                            .parameters()
                            .deck.length;
  const auto pts = eta_points(s);
  std::vector<RunSpec> specs = bridge_runs(s);
  for (auto& e : eta_runs(pts, length)) specs.push_back(std::move(e));
  const std::vector<RunOutput> runs = runner.run(specs);

  // Runs that depend on excitation 5's events: every step around its first pounding
  // (compliance, Fig. 8) and around its longest sliding contact (Moreau-Jean, Fig. 5).
  const RunOutput& mj = find(runs, "exc5-moreau");
  const RunOutput& ed = find(runs, "exc5-event");
  const auto [t_first, contact_first] = first_impact(*mj.recorder);
  const Sliding longest =
      longest_sliding(sliding_contacts(mj.recorder->events(), mj.result.end_time));
  std::vector<RunSpec> late;
  const std::vector<double> windows = options.quick ? kFactorsQuick : kFactorsFull;
  if (contact_first > 0) {
    for (double f : windows) {
      late.push_back({"exc5-k" + factor_name(f) + "-first",
                      exc(kExample),
                      {"solver.method=compliance", "solver.stiffness_factor=" + factor_name(f),
                       "solver.end_time=" + factor_name(t_first + kFirstPoundingWindow),
                       "output.sample_dt=0"}});
    }
  }
  if (longest.contact > 0) {
    late.push_back(
        {"exc5-moreau-sliding",
         exc(kExample),
         {"solver.method=moreau", "solver.end_time=" + factor_name(longest.end + kSlidingLead),
          "output.sample_dt=0"}});
  }
  const std::vector<RunOutput> late_runs = runner.run(late);
  res.runs = runner.count();
  for (const auto* set : {&runs, &late_runs}) {
    for (const auto& r : *set) {
      if (!r.ok()) res.failed.push_back(status_text(r));
    }
  }

  fs::create_directories(options.out);
  const fs::path& dir = options.out;
  const std::string& gp = options.gnuplot;
  auto draw = [&](const std::string& stem, const std::string& error) {
    res.figures.push_back(stem);
    if (!error.empty()) res.plot_errors.push_back(error);
  };
  draw("fig3-response", fig3(dir, *mj.recorder, *ed.recorder, gp));
  draw("fig4-omega", fig4(dir, *mj.recorder, *ed.recorder, longest, gp));

  // Fig. 6, C1-C3: one sweep over the runs with and without pounding and with mu = 0.
  const Fig6Sweep f6 =
      fig6_sweep(scenes, dir / "fig6-sweep", s.pga_runs, s.mu0_runs, options.workers);
  res.runs += f6.runs;
  res.failed.insert(res.failed.end(), f6.failed.begin(), f6.failed.end());
  draw("fig6-peak-rotation", fig6(dir, f6.peaks, gp));
  // A claim's runs from the sweep: their names, and "not evaluated" when one did not complete.
  auto use_sweep_runs = [&](Claim& c, const std::vector<std::string>& names) {
    for (const auto& n : names) {
      c.runs.push_back("fig6-sweep/" + n);
      const auto it = f6.status.find(n);
      const std::string st = it == f6.status.end() ? "not run" : it->second;
      if (st != "completed" && st != "completed_with_fallbacks") {
        c.failure += (c.failure.empty() ? "" : "; ") + n + ": " + st;
      }
    }
  };
  std::vector<std::string> mu_runs, with_pounding, pga_runs;
  for (const auto& r : fig6_runs(s.pga_runs, s.mu0_runs)) {
    if (r.mu0) {
      mu_runs.push_back("exc" + std::to_string(r.excitation));
      mu_runs.push_back(r.name);
      continue;
    }
    pga_runs.push_back(r.name);
    if (r.pounding) with_pounding.push_back(r.name);
  }
  res.claims.push_back(claim_c1(f6.peaks));
  use_sweep_runs(res.claims.back(), mu_runs);
  res.claims.push_back(claim_c2(f6.peaks));
  use_sweep_runs(res.claims.back(), with_pounding);
  res.claims.push_back(claim_c3(f6.peaks));
  use_sweep_runs(res.claims.back(), pga_runs);

  // Fig. 7, C4.
  std::vector<std::pair<double, const Recorder*>> k;
  std::vector<const RunOutput*> c4_runs{&mj};
  for (double f : s.factors) {
    const auto& r = find(runs, "exc5-k" + factor_name(f));
    k.push_back({f, r.recorder.get()});
    c4_runs.push_back(&r);
  }
  const double t_end = s.compliance_end > 0 ? s.compliance_end : mj.result.end_time;
  draw("fig7-compliance", fig7(dir, *mj.recorder, k, t_end, gp));
  res.claims.push_back(claim_c4(*mj.recorder, k, t_end, c4_runs));

  // Fig. 8, C5.
  std::vector<std::pair<double, const Recorder*>> w;
  std::vector<FirstPounding> fps;
  std::vector<const RunOutput*> c5_runs{&mj};
  for (const auto& r : late_runs) {
    if (r.spec.name.find("-first") == std::string::npos) continue;
    const double f = std::stod(r.spec.overrides[1].substr(r.spec.overrides[1].find('=') + 1));
    w.push_back({f, r.recorder.get()});
    fps.push_back(measure_first_pounding(f, *r.recorder, contact_first, t_first - 0.02));
    c5_runs.push_back(&r);
  }
  if (contact_first > 0)
    draw("fig8-first-pounding", fig8(dir, w, *mj.recorder, contact_first, t_first, gp));
  res.claims.push_back(claim_c5(fps, c5_runs));
  if (contact_first == 0) res.claims.back().failure = "excitation 5 has no pounding";

  // Fig. 5, C6.
  const double mu = dynamic_cast<const models::Bridge&>(*mj.scene->system).parameters().friction;
  if (longest.contact > 0) {
    const auto& sr = find(late_runs, "exc5-moreau-sliding");
    const SlidingState st = measure_sliding(sr, longest, mu);
    draw("fig5-sliding-contact", fig5(dir, sr, st, gp));
    res.claims.push_back(claim_c6(st, mu));
    use_runs(res.claims.back(), {&sr});
  } else {
    Claim c{"C6", "a sliding contact carries lambda_T = mu lambda_N"};
    c.failure = "excitation 5 has no sliding contact";
    res.claims.push_back(c);
  }

  // The eta map.
  int agree = 0, total = 0;
  const double width =
      dynamic_cast<const models::Bridge&>(*mj.scene->system).parameters().deck.width;
  draw("fig9-eta-map", fig9(dir, pts, runs, length, width, gp, agree, total));

  std::ofstream(dir / "claims.json") << claims_json(res.claims);
  std::ofstream(dir / "claims.md")
      << claims_markdown(res.claims)
      << "\nHow far the verdicts depend on the assumed values: uncertainty.md (shares over a "
         "Latin hypercube, verdicts that one assumption flips, tornado chart of run 7).\n";

  // The uncertainty of the verdicts over the assumed values' ranges.
  UncertaintyOptions uo;
  uo.out = options.out;
  uo.scenes = scenes;
  uo.quick = options.quick;
  uo.workers = options.workers;
  res.uncertainty = run_uncertainty(uo);
  res.runs += res.uncertainty.runs;
  res.plot_errors.insert(res.plot_errors.end(), res.uncertainty.plot_errors.begin(),
                         res.uncertainty.plot_errors.end());
  res.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

}  // namespace nsb::paper_figures
