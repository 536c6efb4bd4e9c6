// The eta map: the contours |eta| = 1 of the derived rotation criterion (docs/criterion.md) in
// the plane of skew angle and W/L, with free-deck impacts simulated at points of that plane
// (scenes/rigid-deck-straight.toml with the geometry set) and the benchmark deck.
#include "paper-figures/figure.hpp"

#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>

#include "models/analytic.hpp"

namespace nsb::paper_figures {

namespace {

// Free-deck impacts of the eta map, event-driven: the criterion assumes that both corners of
// an end strike at once, which the event-driven method resolves as one impact; Moreau-Jean may
// take them one step apart when round-off makes one gap smaller (seen at 60 deg, W/L = 0.9).
// The deck approaches the right abutment with a normal contact velocity of -0.2 m/s and a
// tangential one of +0.5 m/s (ratio 2.5 > mu (1 + eps) for every mu <= 1 with eps = 0: both
// corners slide, friction fully mobilised, docs/criterion.md).
constexpr double kImpactNormalSpeed = 0.2, kImpactSlipSpeed = 0.5;  // [m/s]
constexpr double kEtaMapFriction = 0.5;  // the paper's mu for the simulated points
// "Rotating": the post-impact angular velocity moves a deck end by more than 1e-6 of the
// impact speed, far above round-off (1e-12 relative) and far below any rotation that counts.
constexpr double kRotatingFraction = 1e-6;
constexpr const char* kFreeDeck = "rigid-deck-straight";

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

double free_deck_length(const Study& s) {
  const scene::Scene scene = load_run_scene(s, {"", kFreeDeck, {}});
  return scene.design.value().deck.length;
}

std::vector<RunSpec> eta_runs(const Study& s) {
  const double length = free_deck_length(s);
  std::vector<RunSpec> v;
  for (const auto& p : eta_points(s.setup)) {
    const double a = p.skew_deg * std::numbers::pi / 180.0, c = std::cos(a), sn = std::sin(a);
    // Right abutment: n = (-c, s), t = (-s, -c) (docs/criterion.md); v = gN n + gT t.
    const double gn = -kImpactNormalSpeed, gt = kImpactSlipSpeed;
    const double vx = gn * -c + gt * -sn, vy = gn * sn + gt * -c;
    std::ostringstream vel;
    vel << std::setprecision(17) << "model.initial_velocity=[" << vx << ", " << vy << ", 0.0]";
    v.push_back({p.name,
                 kFreeDeck,
                 {"model.skew_deg=" + factor_name(p.skew_deg),
                  "model.width=" + factor_name(p.ratio * length),
                  "model.friction=" + factor_name(kEtaMapFriction), vel.str(),
                  "model.gap_left=0.0127", "model.gap_right=0.0127", "solver.end_time=0.2",
                  "solver.method=event_driven", "output.sample_dt=0"}});
  }
  return v;
}

// Contours |eta| = 1 of the derived criterion (docs/criterion.md): for alpha >= 0 the larger
// branch is eta_+ = (L/W)(sin(2a)/2 + mu cos^2 a), so |eta| = 1 on W/L = sin(2a)/2 + mu cos^2 a.
void add_contours(Table& t) {
  for (double mu : {0.0, 0.1, 0.3, 0.5, 0.8}) {
    for (int i = 0; i <= 120; ++i) {
      const double a = 0.5 * i * std::numbers::pi / 180.0;
      t.add({0, mu, 0.5 * i, std::sin(2 * a) / 2 + mu * std::cos(a) * std::cos(a), 0, 0, 0});
    }
  }
}

Drawing draw_eta_map(const std::string& name, const Study& s, const Canvas& canvas) {
  const double length = free_deck_length(s);
  Table t{{"kind", "mu", "skew_deg", "w_over_l", "rotating", "predicted", "omega_after"}};
  add_contours(t);
  int agree = 0, total = 0;
  for (const auto& p : eta_points(s.setup)) {
    const FigureRun& r = s.runs.at(p.name);
    if (!r.ok() || r.history.count(integrators::EventKind::kImpact) == 0) continue;
    // omega right after the first impact: the first sample after it.
    const double t_imp = first_impact(r.history).first;
    const auto ts = r.history.series("t"), om = r.history.series("omega");
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
  // The benchmark deck.
  const scene::Scene bridge = load_run_scene(s, exc5_moreau());
  const double width = bridge.design.value().deck.width;
  t.add({2, 0.5, 0.0, width / length, 1, 1, 0});
  return draw_table(canvas, name, t,
                    {gnuplot_number("agree", agree), gnuplot_number("total", total)}, {1100, 700});
}

}  // namespace

Figure fig9_eta_map() {
  Figure f;
  f.name = "fig9-eta-map";
  f.runs = eta_runs;
  f.draw = [name = f.name](const Study& s, const Canvas& canvas) {
    return draw_eta_map(name, s, canvas);
  };
  return f;
}

}  // namespace nsb::paper_figures
