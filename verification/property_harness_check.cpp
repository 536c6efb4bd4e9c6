// Property harness: every integrator on every scene, checked at every recorded step and
// event against the defining conditions of the nonsmooth problem (Shi & Dimitrakopoulos
// 2017, eqs. 2-7), not against a stored answer:
//   - every recorded value is finite and the run succeeds;
//   - Signorini: g_N >= -bound, lambda_N >= 0, lambda_N = 0 where the gap is open, with the
//     bound of each method derived below (kinds of Bound);
//   - Coulomb (the paper's C6): |lambda_T| <= mu lambda_N, |lambda_T| = mu lambda_N while
//     sliding, and lambda_T opposing the slip;
//   - the energy balance the integrator keeps (kinetic + stored - initial - input + losses)
//     stays within the method's bound at every row; and, recomputed here from the recorded
//     state, the mechanical energy never grows across a frictionless impact with e <= 1;
//   - for the randomised free-deck impacts, the post-impact velocity equals the exact solution
//     of eq. (6) by case enumeration (models/analytic.hpp), and every LCP solver solves that
//     problem to the same velocities.
//
// A scene is one line of scene_cases(); an integrator is one line of method_cases().
// Every recorded row (sample_dt = 0) is checked, so the bounds are stated per row.
#include "integrators/contact_stage.hpp"
#include "integrators/run.hpp"
#include "lcp/frictional.hpp"
#include "models/analytic.hpp"
#include "models/bridge_parts.hpp"
#include "scene/scene.hpp"
#include "testsupport/systems.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <variant>
#include <vector>

namespace ni = nsb::integrators;
namespace nm = nsb::models;
namespace na = nsb::models::analytic;

namespace {

// ------------------------------------------------------------------------------------------
// Scenes

// The solver of one run: the typed configuration of the method, and the scene's Moreau–Jean
// step h (the step of the bounds).
struct Solver {
  ni::RunConfig config;
  double step = 0.0;
};

struct SceneCase {
  std::string name;
  // Builds the system and fills the scene's configuration for the named method (one fresh
  // system per run).
  std::function<std::unique_ptr<ni::System>(const std::string& method, Solver&)> make;
  bool conservative = false;   // no input, no viscous damping, mu = 0: energy can only drop
  bool driven = false;         // moving supports or obstacles feed work in: the bridge (Takeda
                               //   bents, support motion), the moving wall
                               //   (MethodCase::energy_bound_driven)
  double normal_load = 0.0;    // largest smooth normal force on one contact [kN], for the
                               //   compliance penetration bound (Bound::kHertz)
};

// A scene file with the window [0, end_time] and the Moreau–Jean step h.
SceneCase from_file(std::string file, double end_time, double h, bool conservative,
                    double normal_load, std::vector<std::string> extra = {}) {
  SceneCase c;
  c.name = file;
  c.conservative = conservative;
  c.normal_load = normal_load;
  c.driven = file.rfind("bridge", 0) == 0;
  c.make = [file, end_time, h, extra](const std::string& method, Solver& solver) {
    std::vector<std::string> o = extra;
    o.push_back("solver.end_time=" + std::to_string(end_time));
    o.push_back("solver.step=" + std::to_string(h));
    o.push_back("solver.method=" + method);
    auto scene = nsb::scene::load_scene(std::filesystem::path(NSB_SCENES_DIR) / file, o);
    solver.config = scene.run;
    solver.step = std::stod(std::to_string(h));  // the value solver.step was read as
    return std::move(scene.system);
  };
  return c;
}

// The bridge windows: [0, 4 s] of each excitation holds the first pounding of excitations 5
// and 7 and the strong-motion onset of the others. Step 1e-4 s as in the scenes. The normal
// load bounds the seat force without impact: deck mass 140.5 t times 1 g plus the three bents'
// yield forces (under 300 kN together, docs/bridge.md), rounded up to 2000 kN.
constexpr double kBridgeWindow = 4.0;
constexpr double kBridgeNormalLoad = 2000.0;

// A block pressed with P = 10 kN towards a wall that accelerates into it at a = 1 m/s^2
// (testsupport::WallBlock, m = 1 t), from 1 mm away: an impact with e = 0.5, then a persistent
// contact with a moving obstacle whose force is P + m a = 11 kN and whose work on the block is
// positive (the wall pushes it). The compliance method's Hertz stiffness is scaled to the
// block, 1e5 kN/m^1.5 (times the harness's factor 1e2): the bridge's 2.747e7 on a 1 t block
// only shortens the contact's period below what the window needs to resolve.
std::vector<SceneCase> moving_obstacle_scenes() {
  SceneCase c;
  c.name = "wall-block (moving wall)";
  c.normal_load = 11.0;
  c.driven = true;
  c.make = [](const std::string& method, Solver& solver) -> std::unique_ptr<ni::System> {
    solver.config = ni::default_config(method);
    solver.step = 1e-4;
    std::visit([](auto& o) { o.end_time = 1.0; }, solver.config);
    if (auto* o = std::get_if<ni::MoreauJeanOptions>(&solver.config)) o->step = solver.step;
    if (auto* o = std::get_if<ni::ComplianceOptions>(&solver.config)) o->stiffness = 1e5;
    nsb::testsupport::WallBlock::Parameters p;
    p.initial_gap = 1e-3;
    p.restitution = 0.5;
    return std::make_unique<nsb::testsupport::WallBlock>(p);
  };
  return {c};
}

std::vector<SceneCase> scene_cases() {
  // Normal loads: ball and block m g = 9.81 kN; oscillator k (gap + A) < 1 kN; free deck 0.
  std::vector<SceneCase> s{
      from_file("bouncing-ball.toml", 4.0, 1e-3, true, 9.81),
      from_file("impact-oscillator.toml", 20.0, 1e-3, true, 1.0),
      from_file("sliding-block.toml", 1.0, 1e-4, false, 9.81),
      from_file("rigid-deck-straight.toml", 0.5, 1e-4, false, 0.0),
      from_file("rigid-deck-skew.toml", 0.5, 1e-4, true, 0.0),
  };
  for (int exc = 1; exc <= 7; ++exc) {
    s.push_back(from_file("bridge-exc" + std::to_string(exc) + ".toml", kBridgeWindow, 1e-4,
                          false, kBridgeNormalLoad));
  }
  // Bridges in parts (the same window, step and load bound as the one-deck benchmark: the
  // deck's mass and bents are shared among the frames) and the free two-deck chain (no
  // smooth force on a contact: load 0).
  // With connectors (docs/bridge.md, "Connectors"): backfill abutments (backwall bodies on
  // the hyperbolic backfill), a restrainer across the two-frame bridge's hinge, and
  // lead-rubber bearings (bilinear) under the deck ends.
  for (const char* file : {"bridge-two-frame.toml", "bridge-skew-three-span.toml",
                           "bridge-backfill.toml", "bridge-two-frame-restrainers.toml",
                           "bridge-bearings.toml"}) {
    s.push_back(from_file(file, kBridgeWindow, 1e-4, false, kBridgeNormalLoad));
  }
  s.push_back(from_file("deck-chain-two.toml", 1.0, 1e-4, false, 0.0));
  // The bridge with shear keys: unbreakable, and breaking (its window covers the first
  // breaks under Moreau–Jean and event-driven, 3.7 s to 4.3 s, so that rows after a removal
  // are run and skipped for that contact).
  s.push_back(from_file("bridge-shear-keys.toml", kBridgeWindow, 1e-4, false, kBridgeNormalLoad));
  s.push_back(from_file("bridge-shear-keys-capacity.toml", 5.0, 1e-4, false, kBridgeNormalLoad));
  // Seats short enough to be lost: every method stops unseated before 5 s (3.94 s under
  // Moreau–Jean).
  s.push_back(from_file("bridge-unseating.toml", 5.0, 1e-4, false, kBridgeNormalLoad));
  for (auto& c : moving_obstacle_scenes()) s.push_back(std::move(c));
  return s;
}

// ------------------------------------------------------------------------------------------
// Integrators

// How far a method may let a gap penetrate, and how far open a gap may be while it carries a
// force. Derivations:
//  - kStep (Moreau–Jean, velocity-level law): a contact enters the index set when
//    g_k + (h/2) gdot_k <= 0; it was not in at t_k-1, so g_k >= -(h/2) V with V the largest
//    normal speed. Inside, gdot_k+1 >= -e gdot_k >= 0, and q_k+1 = q_k + h ((1-theta) u_k +
//    theta u_k+1) gives g_k+1 >= g_k - (1-theta) h V >= -h V. While closed, g drifts by the
//    second-order term of the gap, at most (h^2/2) A per step, A the largest |gddot_N|: over
//    the window T that is (h T / 2) A. Bound: h (V + T A). A carried force needs the contact
//    in the index set: g_k <= (h/2) V, and g_k+1 <= g_k + h V: open bound 1.5 h V + drift.
//  - kTolerance (event-driven): impacts are located on g_N = 0 and closed contacts are
//    projected back to g_N = 0 within gap_tolerance (1e-9 m); between projections the dense
//    output carries the local error tolerance * (1 + |q|). Bound: 1e-9 m + 10 tol (1 + |q|).
//  - kHertz (compliance): energy at the deepest point of an impact with approach speed V,
//    effective mass m* = 1 / (W_N^T M^-1 W_N) and a constant load F,
//      m* V^2 / 2 + F delta = (2/5) k delta^2.5 (damping only lowers delta),
//    so one of the two left terms is at least half the right side:
//      delta <= max((5 m* V^2 / (2 k))^0.4, (5 F / k)^(2/3)).
//    The force vanishes exactly for g_N >= 0 (eq. 9).
enum class Bound { kStep, kTolerance, kHertz };

struct MethodCase {
  std::string name;
  Bound bound;
  std::string method;  // solver.method of the runs
  // Applied to the scene's configuration of that method.
  std::function<void(ni::RunConfig&)> configure;
  // Largest relative energy-balance error of a row (EnergyBalance::error) on the simple
  // scenes and on the driven ones (the bridge; the moving wall, whose worst rows are MJ
  // theta = 0.5 3.1e-15, theta = 1 2.1e-4, event-driven 2e-16, compliance 1.8e-3: the
  // trapezoidal quadrature of the wall's work, 1.8e-4 at tolerance 1e-10, so O(h^2)).
  // Measured worst rows, h and tolerances as below:
  //   MJ theta = 0.5: simple 1e-13 (impulse work booked exactly, trapezoidal work exact for
  //     the linear and constant forces), bridge 1.4e-3 (O(h) work lost at each Takeda branch
  //     change inside a step; 3e-7 on the windows where the bents stay elastic);
  //   MJ theta = 1: simple 2.2e-3, bridge 1.9e-2 (the theta-method's numerical dissipation,
  //     (theta - 1/2) |u_k+1 - u_k|_M^2 per step, is not booked: O(h));
  //   event-driven: simple 6.5e-9, bridge 3.7e-6 (tolerance 1e-8 on the state);
  //   compliance: simple 3.8e-4, bridge 4.5e-3 (trapezoidal quadrature of the powers over
  //     steps up to max_step = 1e-3 s, and of the Hertz force across a closure).
  // Bounds: 2-3 times the measured worst, round-off for MJ 0.5 on the simple scenes.
  double energy_bound;
  double energy_bound_driven;
};

// Compliance at 100 times the scene's Hertz stiffness: stiff enough that its penetration is
// small against the gaps, soft enough for Rosenbrock to take steps of a few microseconds.
constexpr double kStiffnessFactor = 1e2;

std::vector<MethodCase> method_cases() {
  return {
      {"moreau theta=0.5", Bound::kStep, "moreau",
       [](ni::RunConfig& c) { std::get<ni::MoreauJeanOptions>(c).theta = 0.5; }, 1e-10, 4e-3},
      {"moreau theta=1", Bound::kStep, "moreau",
       [](ni::RunConfig& c) { std::get<ni::MoreauJeanOptions>(c).theta = 1.0; }, 5e-3, 5e-2},
      {"event_driven", Bound::kTolerance, "event_driven",
       [](ni::RunConfig& c) { std::get<ni::EventDrivenOptions>(c).tolerance = 1e-8; }, 2e-8,
       1e-5},
      {"compliance 1e2 k", Bound::kHertz, "compliance",
       [](ni::RunConfig& c) {
         auto& o = std::get<ni::ComplianceOptions>(c);
         o.tolerance = 1e-8;
         o.stiffness_factor = kStiffnessFactor;
       },
       1e-3, 1e-2},
  };
}

// ------------------------------------------------------------------------------------------
// Row checks

// Round-off allowances, scaled to the data: impulses and velocities from an LCP solved to
// 1e-12 relative, and a few ulps of O(1) quantities.
constexpr double kRelRoundOff = 1e-8;

struct Row {
  double t = 0.0;
  ni::Vector q, u;
  std::vector<double> gap, lambda_n, lambda_t;
  double energy_error = 0.0;
};

std::vector<Row> rows_of(const ni::Recorder& r, int n, int m) {
  std::vector<Row> out(r.rows());
  const std::size_t e = r.column("energy_error");
  for (std::size_t i = 0; i < r.rows(); ++i) {
    Row& w = out[i];
    w.t = r.at(i, 0);
    w.q.resize(n);
    w.u.resize(n);
    for (int k = 0; k < n; ++k) {
      w.q[k] = r.at(i, 1 + static_cast<std::size_t>(k));
      w.u[k] = r.at(i, 1 + static_cast<std::size_t>(n + k));
    }
    for (int c = 0; c < m; ++c) {
      const std::size_t base =
          1 + 2 * static_cast<std::size_t>(n) + 3 * static_cast<std::size_t>(c);
      w.gap.push_back(r.at(i, base));
      w.lambda_n.push_back(r.at(i, base + 1));
      w.lambda_t.push_back(r.at(i, base + 2));
    }
    w.energy_error = r.at(i, e);
  }
  return out;
}

struct Tally {
  std::size_t rows = 0, checks = 0, failures = 0;
  double worst_penetration_ratio = 0.0;  // max penetration / bound
  double worst_energy_error = 0.0;
  double worst_cone = 0.0;               // max (|lambda_T| - mu lambda_N) / scale
  std::string first_failure;
  // Counts one check; the message (time, 1-based contact or 0, what, a value) is formatted
  // only for the first failure, so that a million passing rows cost no strings.
  void expect(bool ok, const char* what, double t = 0.0, int contact = -1,
              double value = std::nan("")) {
    ++checks;
    if (ok || failures++ > 0) return;
    char buf[200];
    if (std::isnan(value)) {
      std::snprintf(buf, sizeof buf, "t = %.9g, contact %d: %s", t, contact + 1, what);
    } else {
      std::snprintf(buf, sizeof buf, "t = %.9g, contact %d: %s (%.6g)", t, contact + 1, what,
                    value);
    }
    first_failure = buf;
  }
  void expect(bool ok, const std::string& what) { expect(ok, what.c_str()); }
};

struct RunData {
  const SceneCase* scene = nullptr;
  const MethodCase* method = nullptr;
  Solver solver;
  ni::System* system = nullptr;
  std::vector<Row> rows;
  std::vector<ni::Event> events;
  ni::RunResult result;
  // Per contact, the time the system removed it (a broken shear key; +inf: never). Its rows
  // after that time are no contact's and are not checked.
  std::vector<double> removed_at;
  bool removed(int c, double t) const { return t > removed_at[static_cast<std::size_t>(c)]; }
};

double mechanical_energy(ni::System& s, const Row& r) {
  return 0.5 * r.u.dot(s.mass() * r.u) + s.energy(r.t, r.q).stored;
}

void check_run(const RunData& d, Tally& tally) {
  ni::System& sys = *d.system;
  const int m = sys.contacts();
  const auto& rows = d.rows;
  const double h = d.solver.step;
  const double T = ni::end_time(d.solver.config);
  const ni::Matrix minv = sys.mass().inverse();

  // An unseated run is a result (docs/limit-states.md): it stops at the lost seat, and its
  // rows up to there must hold every property as any other run's.
  const bool unseated = d.result.status == ni::RunStatus::kUnseated;
  tally.expect(ni::is_result(d.result.status), "run status " +
                                                   std::string(ni::to_string(d.result.status)) +
                                                   ": " + d.result.message);
  tally.expect(!rows.empty() && rows.back().t >= (unseated ? d.result.end_time : T) - 1e-9,
               "the run reached end_time (or its unseating time)");

  // Contact data along the run (the W of each recorded state) and the scales of the bounds.
  std::vector<std::vector<ni::ContactData>> cd(rows.size(), sys.make_contact_buffer());
  double v_max = 0.0, a_max = 0.0, q_max = 1.0, lambda_scale = 1e-12, slip_scale = 1e-12;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    sys.contact_data(rows[i].t, rows[i].q, rows[i].u, cd[i]);
    q_max = std::max(q_max, rows[i].q.cwiseAbs().maxCoeff());
    for (int c = 0; c < m; ++c) {
      if (d.removed(c, rows[i].t)) continue;
      const auto& k = cd[i][static_cast<std::size_t>(c)];
      if (!k.far) v_max = std::max(v_max, std::abs(k.gap_rate(rows[i].u)));
      slip_scale = std::max(slip_scale, std::abs(k.slip_rate(rows[i].u)));
      lambda_scale =
          std::max(lambda_scale, std::abs(rows[i].lambda_n[static_cast<std::size_t>(c)]));
      // |gddot_N| from consecutive rows that carry no contact force (smooth motion only).
      if (i > 0 && rows[i].lambda_n[static_cast<std::size_t>(c)] == 0.0 &&
          rows[i - 1].lambda_n[static_cast<std::size_t>(c)] == 0.0 && rows[i].t > rows[i - 1].t) {
        const double a = std::abs(k.gap_rate(rows[i].u) -
                                  cd[i - 1][static_cast<std::size_t>(c)].gap_rate(rows[i - 1].u)) /
                         (rows[i].t - rows[i - 1].t);
        if (!k.far && std::isfinite(a)) a_max = std::max(a_max, a);
      }
    }
  }

  double penetration_bound = 0.0, open_bound = 0.0;
  switch (d.method->bound) {
    case Bound::kStep:
      // Plus the round-off of a computed gap (ContactTolerances::gap), the whole bound when
      // a contact rests from the start (V = A = 0).
      penetration_bound =
          h * (v_max + T * a_max) + ni::ContactTolerances::kRoundOff * (1.0 + q_max);
      open_bound = 1.5 * h * v_max + 0.5 * h * T * a_max;
      break;
    case Bound::kTolerance:
      penetration_bound = 1e-9 + 10.0 * std::get<ni::EventDrivenOptions>(d.solver.config).tolerance * q_max;
      open_bound = penetration_bound;
      break;
    case Bound::kHertz: {
      const auto& o = std::get<ni::ComplianceOptions>(d.solver.config);
      const double k = o.stiffness * o.stiffness_factor;
      double m_eff = 0.0;
      for (int c = 0; c < m; ++c) {
        const auto& w = cd[0][static_cast<std::size_t>(c)].w_normal;
        m_eff = std::max(m_eff, 1.0 / w.dot(minv * w));
      }
      penetration_bound = std::max(std::pow(5.0 * m_eff * v_max * v_max / (2.0 * k), 0.4),
                                   std::pow(5.0 * d.scene->normal_load / k, 2.0 / 3.0));
      open_bound = 0.0;
      break;
    }
  }

  const double energy_bound =
      d.scene->driven ? d.method->energy_bound_driven : d.method->energy_bound;
  double e_ref = rows.empty() ? 0.0 : mechanical_energy(sys, rows[0]);
  const double e_scale = std::max(1.0, std::abs(e_ref));
  std::vector<ni::ContactData> at_law = sys.make_contact_buffer();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    ++tally.rows;
    bool finite = r.q.allFinite() && r.u.allFinite() && std::isfinite(r.energy_error);
    for (int c = 0; c < m; ++c) {
      const auto ci = static_cast<std::size_t>(c);
      finite = finite && std::isfinite(r.gap[ci]) && std::isfinite(r.lambda_n[ci]) &&
               std::isfinite(r.lambda_t[ci]);
    }
    tally.expect(finite, "a non-finite value", r.t, -1);
    if (!finite) continue;

    bool any_force = false;
    for (int c = 0; c < m; ++c) {
      if (d.removed(c, r.t)) continue;
      const auto ci = static_cast<std::size_t>(c);
      const ni::ContactData& k = cd[i][ci];
      const double ln = r.lambda_n[ci], lt = r.lambda_t[ci];
      any_force = any_force || ln != 0.0;
      // Signorini.
      if (penetration_bound > 0.0) {
        tally.worst_penetration_ratio =
            std::max(tally.worst_penetration_ratio, -r.gap[ci] / penetration_bound);
      }
      tally.expect(r.gap[ci] >= -penetration_bound, "gap below -bound", r.t, c, r.gap[ci]);
      tally.expect(ln >= -kRelRoundOff * lambda_scale, "lambda_N < 0", r.t, c, ln);
      tally.expect(ln <= kRelRoundOff * lambda_scale || r.gap[ci] <= open_bound,
                   "lambda_N > 0 on an open gap", r.t, c, r.gap[ci]);
      // Coulomb.
      const double mu = k.friction;
      const double cone = std::abs(lt) - mu * ln;
      const double tol = kRelRoundOff * lambda_scale;
      tally.worst_cone = std::max(tally.worst_cone, cone / lambda_scale);
      tally.expect(cone <= tol, "|lambda_T| > mu lambda_N", r.t, c, cone);
      if (mu == 0.0 || ln <= tol) continue;
      // The slip the force law sees: for Moreau–Jean the end-of-step velocity with the
      // W of the step's start (the previous row), the rheonomic term at either end of the
      // step (its time of imposition differs between versions of the contact stage); for the
      // others the recorded state.
      double slip = k.slip_rate(r.u), slip_alt = slip, sliding = 0.0;
      switch (d.method->bound) {
        case Bound::kStep:
          if (i == 0) continue;
          slip = cd[i - 1][ci].w_tangent.dot(r.u) + cd[i - 1][ci].what_tangent;
          slip_alt = cd[i - 1][ci].w_tangent.dot(r.u) + k.what_tangent;
          sliding = 1e-9 * (1.0 + slip_scale);  // exact at velocity level, to LCP round-off
          break;
        case Bound::kTolerance:
          // EventDrivenOptions::stick_velocity default
          sliding = 10.0 * std::get<ni::EventDrivenOptions>(d.solver.config).tolerance;
          break;
        case Bound::kHertz:
          // eq. (10): saturated beyond eps_v
          sliding = std::get<ni::ComplianceOptions>(d.solver.config).stick_slip_velocity;
          break;
      }
      const bool slides = std::min(std::abs(slip), std::abs(slip_alt)) > sliding &&
                          slip * slip_alt > 0.0;
      if (slides) {
        tally.expect(std::abs(cone) <= 1e-6 * mu * ln + tol,
                     "sliding with |lambda_T| != mu lambda_N", r.t, c, cone);
        tally.expect(lt * slip <= 0.0, "friction does not oppose the slip", r.t, c, lt * slip);
      }
      if (d.method->bound == Bound::kHertz) {
        tally.expect(lt * slip <= tol * std::abs(slip), "friction does not oppose the slip", r.t,
                     c, lt * slip);
      }
    }
    // Moreau–Jean's velocity-level Signorini condition (eqs. 3, 7), exact to LCP round-off:
    // for a contact of the step's index set (g_k + (h/2) gdot_k <= 0 at the previous row),
    //   gdot_N0 = gdot_N,k+1 + e gdot_N,k >= 0 and lambda_N gdot_N0 = 0,
    // with gdot_N,k+1 = W(t_k+1, q_k)^T u_k+1 + what(t_k+1, q_k), where the contact stage
    // imposes the law, and gdot_N,k = W(t_k, q_k)^T u_k + what(t_k, q_k), the approach
    // velocity (docs/moreau-jean.md, "The contact law at t_k+1").
    if (d.method->bound == Bound::kStep && i > 0 && rows[i].t - rows[i - 1].t > 0.5 * h) {
      sys.contact_data(r.t, rows[i - 1].q, rows[i - 1].u, at_law);
      for (int c = 0; c < m; ++c) {
        const auto ci = static_cast<std::size_t>(c);
        const ni::ContactData& k0 = cd[i - 1][ci];
        if (d.removed(c, r.t) || k0.far || k0.gap_normal + 0.5 * h * k0.gap_rate(rows[i - 1].u) > 0.0) continue;
        const double g0 =
            at_law[ci].gap_rate(r.u) + k0.restitution * k0.gap_rate(rows[i - 1].u);
        const double vtol = 1e-9 * (1.0 + v_max);
        const bool closed = r.lambda_n[ci] > kRelRoundOff * lambda_scale;
        tally.expect(g0 >= -vtol && (!closed || std::abs(g0) <= vtol),
                     "Moreau–Jean: velocity-level Signorini violated, gdot_N0 [m/s]", r.t, c, g0);
      }
    }
    // Energy balance as the integrator keeps it.
    tally.worst_energy_error = std::max(tally.worst_energy_error, r.energy_error);
    tally.expect(r.energy_error <= energy_bound, "energy balance error", r.t, -1, r.energy_error);
    // No growth of the mechanical energy, recomputed from the state: against the last row
    // with every contact force zero (during a compliance impact the Hertz spring holds
    // energy that kinetic + stored does not count, so only a drop can be seen there).
    if (d.scene->conservative) {
      const double e = mechanical_energy(sys, r);
      const double growth_tol = (d.method->bound == Bound::kStep ? 1e-10 : 1e-7) * e_scale;
      tally.expect(e <= e_ref + growth_tol, "mechanical energy grows", r.t, -1, e - e_ref);
      if (!any_force) e_ref = e;
    }
  }

  // Events: within the run, a known contact, and an impact or closure where a gap is closed.
  for (const auto& ev : d.events) {
    tally.expect(ev.t >= sys.initial_time() - 1e-12 && ev.t <= T + 1e-9 && ev.contact >= 0 &&
                     ev.contact <= m,
                 "event outside the run or of an unknown contact");
    if (ev.kind != ni::EventKind::kImpact && ev.kind != ni::EventKind::kClose) continue;
    if (ev.contact == 0) continue;
    const auto it = std::lower_bound(rows.begin(), rows.end(), ev.t,
                                     [](const Row& r, double t) { return r.t < t; });
    double g = 1e300;
    for (auto j = (it == rows.begin() ? it : it - 1); j != rows.end() && j <= it; ++j) {
      g = std::min(g, j->gap[static_cast<std::size_t>(ev.contact - 1)]);
    }
    const double near = std::max(open_bound, penetration_bound) + v_max * (h + 1e-9);
    char buf[120];
    std::snprintf(buf, sizeof buf, "t = %.9g: %s event at contact %d with gap %.3g", ev.t,
                  std::string(ni::to_string(ev.kind)).c_str(), ev.contact, g);
    tally.expect(g <= near, buf);
  }
}

RunData run(const SceneCase& s, const MethodCase& m, std::unique_ptr<ni::System>& holder) {
  RunData d;
  d.scene = &s;
  d.method = &m;
  holder = s.make(m.method, d.solver);
  m.configure(d.solver.config);
  ni::validate(d.solver.config);
  d.system = holder.get();
  ni::Recorder rec(*holder, 0.0);
  d.result = ni::integrate(*holder, d.solver.config, rec);
  d.rows = rows_of(rec, holder->dofs(), holder->contacts());
  d.events = rec.events();
  for (int c = 0; c < holder->contacts(); ++c) d.removed_at.push_back(rec.removed_at(c));
  return d;
}

}  // namespace

TEST_CASE("every integrator on every scene: finiteness, Signorini, Coulomb, energy") {
  const auto scenes = scene_cases();
  const auto methods = method_cases();
  for (const auto& s : scenes) {
    for (const auto& m : methods) {
      std::unique_ptr<ni::System> holder;
      const RunData d = run(s, m, holder);
      Tally tally;
      check_run(d, tally);
      std::printf("%-26s %-18s rows %7zu  steps %7lld  impacts %4zu  pen/bound %.2e  "
                  "energy %.1e  cone %.1e  wall %.2f s\n",
                  s.name.c_str(), m.name.c_str(), tally.rows,
                  static_cast<long long>(d.result.steps),
                  static_cast<std::size_t>(std::count_if(
                      d.events.begin(), d.events.end(),
                      [](const ni::Event& e) { return e.kind == ni::EventKind::kImpact; })),
                  tally.worst_penetration_ratio, tally.worst_energy_error, tally.worst_cone,
                  d.result.wall_time);
      INFO(s.name << " / " << m.name << ": " << tally.failures << " of " << tally.checks
                  << " checks failed; first: " << tally.first_failure);
      CHECK(tally.failures == 0);
      CHECK(tally.checks > tally.rows);
    }
  }
}

// ------------------------------------------------------------------------------------------
// Randomised free-deck impacts against the enumeration oracle of eq. (6)

namespace {

struct RandomDeck {
  nm::BridgeDesign p = nm::BridgeDesign::free_deck();
  double t_impact = 0.0;  // closed-form time of the first (two-corner) impact [s]
};

// A deck at theta = 0, not rotating, moving towards the right abutment: both right corners
// lie on the abutment face, so they strike together (corners 3 and 4) and the impact is the
// two-contact problem of eq. (6) with the columns of analytic::deck_contact_columns.
RandomDeck random_deck(std::mt19937& rng) {
  std::uniform_real_distribution<double> U(0.0, 1.0);
  RandomDeck d;
  auto& p = d.p;
  p.mass = 50.0 + 150.0 * U(rng);
  p.deck.length = 10.0 + 30.0 * U(rng);
  p.deck.width = 2.0 + 8.0 * U(rng);
  p.inertia = p.mass * (p.deck.length * p.deck.length + p.deck.width * p.deck.width) / 12.0 *
              (0.8 + 0.4 * U(rng));
  p.deck.skew_deg = -45.0 + 90.0 * U(rng);
  p.deck.gap_right = 0.002 + 0.01 * U(rng);
  p.deck.gap_left = 1.0;  // far: only the right end is struck within the run
  p.restitution = U(rng);
  p.friction = U(rng) < 0.25 ? 0.0 : 0.8 * U(rng);
  const double a = p.deck.skew_deg * std::acos(-1.0) / 180.0;
  // The closing speed vx cos a - vy sin a is kept above 0.1 m/s.
  double vx = 0.0, vy = 0.0, closing = 0.0;
  do {
    vx = 0.1 + 0.9 * U(rng);
    vy = -0.5 + U(rng);
    closing = vx * std::cos(a) - vy * std::sin(a);
  } while (closing < 0.1);
  p.initial_velocity = Eigen::Vector3d(vx, vy, 0.0);
  d.t_impact = p.deck.gap_right * std::cos(a) / closing;
  return d;
}

// Velocity after the first impact: the first recorded row whose velocity differs from the
// initial one (the deck moves freely, so the velocity is constant between impacts).
Eigen::Vector3d first_change(const ni::Recorder& rec, const Eigen::Vector3d& u0) {
  const std::size_t c = rec.column("vx");
  for (std::size_t i = 0; i < rec.rows(); ++i) {
    const Eigen::Vector3d u(rec.at(i, c), rec.at(i, c + 1), rec.at(i, c + 2));
    if ((u - u0).norm() > 1e-12 * (1.0 + u0.norm())) return u;
  }
  return u0;
}

// Velocities of two exact solutions of the same impact agree to LCP round-off (1e-12
// relative residual on O(1) data); 1e-9 leaves three decades for the conditioning of G.
constexpr double kOracleAgreement = 1e-9;
constexpr int kRandomDecks = 24;

}  // namespace

TEST_CASE("randomised free-deck impacts equal the enumeration oracle of eq. (6)") {
  std::mt19937 rng(20170611);
  const std::vector<nsb::lcp::Solver> solvers{nsb::lcp::Solver::kLemke, nsb::lcp::Solver::kPgs,
                                              nsb::lcp::Solver::kNewtonFb,
                                              nsb::lcp::Solver::kEnumeration};
  int energy_gains = 0;
  double worst = 0.0;
  std::array<int, 4> attempts{}, solved{};
  for (int n = 0; n < kRandomDecks; ++n) {
    const RandomDeck rd = random_deck(rng);
    const auto& p = rd.p;
    const na::DeckBody g{p.mass, p.inertia, p.deck};
    const Eigen::Vector3d u0 = p.initial_velocity;
    const auto oracle = na::deck_impact(g, {3, 4}, u0, p.restitution, p.friction);
    REQUIRE(oracle.solutions == 1);
    const Eigen::Vector3d M(p.mass, p.mass, p.inertia);
    const double e_before = 0.5 * u0.dot(M.cwiseProduct(u0));
    const double e_after = 0.5 * oracle.velocity_after.dot(M.cwiseProduct(oracle.velocity_after));
    INFO("deck " << n << ": skew " << p.deck.skew_deg << " deg, e = " << p.restitution
                 << ", mu = " << p.friction << ", u- = " << u0.transpose());
    // Energy at the impact: never a gain without friction. With friction, Newton's law can
    // gain energy (Kane's example); the count of such draws is printed.
    if (p.friction == 0.0) CHECK(e_after <= e_before * (1.0 + 1e-12));
    if (e_after > e_before * (1.0 + 1e-12)) ++energy_gains;

    // Every LCP solver on the oracle's problem, through the eq. (6) solver interface.
    nsb::lcp::FrictionalProblem fp;
    fp.delassus = oracle.problem.delassus;
    fp.gdot_free = oracle.problem.gdot_minus;
    fp.gdot_n_minus = oracle.problem.gdot_minus.head(2);
    fp.restitution = oracle.problem.restitution;
    fp.friction = oracle.problem.friction;
    Eigen::Matrix<double, 3, 4> w;
    for (int k = 0; k < 2; ++k) {
      const auto cols = na::deck_contact_columns(g.deck, 3 + k);
      w.col(k) = cols.w_normal;
      w.col(2 + k) = cols.w_tangent;
    }
    for (auto solver : solvers) {
      const auto r = nsb::lcp::solve_frictional(fp, solver);
      INFO("solver " << nsb::lcp::to_string(solver));
      // Lemke and enumeration are exact pivoting methods and must solve; PGS and Newton–FB
      // may stop short of 1e-12 on the singular G of two corners sharing W_T (counted).
      if (solver == nsb::lcp::Solver::kLemke || solver == nsb::lcp::Solver::kEnumeration) {
        REQUIRE(r.ok());
      }
      ++attempts[static_cast<std::size_t>(solver)];
      if (!r.ok()) continue;
      ++solved[static_cast<std::size_t>(solver)];
      Eigen::Vector4d lambda;
      lambda << r.lambda_n, r.lambda_t;
      const Eigen::Vector3d u_after = u0 + (w * lambda).cwiseQuotient(M);
      const double err = (u_after - oracle.velocity_after).norm() / (1.0 + u0.norm());
      worst = std::max(worst, err);
      CHECK(err <= kOracleAgreement);
    }

    // The integrators: Moreau–Jean (each theta, each LCP solver) and event-driven.
    std::vector<ni::RunConfig> configs;
    for (double theta : {0.5, 1.0}) {
      for (auto solver : solvers) {
        ni::MoreauJeanOptions o;
        o.end_time = rd.t_impact + 1e-3;
        o.step = 1e-4;
        o.theta = theta;
        o.solver = solver;
        configs.emplace_back(o);
      }
    }
    ni::EventDrivenOptions e;
    e.end_time = rd.t_impact + 1e-3;
    configs.emplace_back(e);
    for (const auto& config : configs) {
      nm::Assembly deck(nm::bridge_parts(p));
      ni::Recorder rec(deck, 0.0);
      const auto result = ni::integrate(deck, config, rec);
      std::string label(ni::method_name(config));
      if (const auto* mj = std::get_if<ni::MoreauJeanOptions>(&config)) {
        label += " theta " + std::to_string(mj->theta) + " " +
                 std::string(nsb::lcp::to_string(mj->solver));
      }
      INFO(label);
      REQUIRE(ni::succeeded(result.status));
      const Eigen::Vector3d u_after = first_change(rec, u0);
      const double err = (u_after - oracle.velocity_after).norm() / (1.0 + u0.norm());
      worst = std::max(worst, err);
      CHECK(err <= kOracleAgreement);
    }
  }
  std::printf("random decks: %d draws, worst |u+ - u+_oracle| / (1 + |u-|) = %.2e; "
              "frictional draws gaining energy at the impact: %d\n",
              kRandomDecks, worst, energy_gains);
  for (auto solver : solvers) {
    const auto k = static_cast<std::size_t>(solver);
    std::printf("  %s solved %d of %d oracle problems\n",
                std::string(nsb::lcp::to_string(solver)).c_str(), solved[k], attempts[k]);
  }
}

// Energy can grow at a frictional impact with Newton's restitution (Kane's example, discussed
// by Stronge, Impact Mechanics, 2000): a rotating deck striking the seat with one corner at
// e = 0.95, mu = 0.7 gains kinetic energy under eq. (6). The harness does not assert
// "no growth" for frictional impacts; this case shows why, and that Moreau–Jean and the
// event-driven integrator reproduce the gain of the exact solution.
TEST_CASE("frictional impact with an energy gain (Kane's example): integrators follow eq. (6)") {
  nm::BridgeDesign p = nm::BridgeDesign::free_deck();
  p.mass = 100.0;
  p.inertia = 3000.0;
  p.deck.length = 20.0;
  p.deck.width = 5.0;
  p.deck.skew_deg = 20.0;
  p.deck.gap_right = 0.0;  // the right corners touch the seat at t0, theta = 0
  p.deck.gap_left = 1.0;
  p.restitution = 0.95;
  p.friction = 0.7;
  p.initial_velocity = Eigen::Vector3d(0.65, 0.3, -0.2);
  const na::DeckBody g{p.mass, p.inertia, p.deck};
  const Eigen::Vector3d u0 = p.initial_velocity;
  // The corners that approach the seat take part in the impact.
  std::vector<int> corners;
  for (int c : {3, 4}) {
    if (na::deck_contact_columns(g.deck, c).w_normal.dot(u0) < 0.0) corners.push_back(c);
  }
  REQUIRE(!corners.empty());
  const auto oracle = na::deck_impact(g, corners, u0, p.restitution, p.friction);
  REQUIRE(oracle.solutions == 1);
  const Eigen::Vector3d M(p.mass, p.mass, p.inertia);
  const double e_before = 0.5 * u0.dot(M.cwiseProduct(u0));
  const double e_after = 0.5 * oracle.velocity_after.dot(M.cwiseProduct(oracle.velocity_after));
  std::printf("Kane-type impact at corners %zu: kinetic energy %.4f -> %.4f kJ (%+.1f %%)\n",
              corners.size(), e_before, e_after, 100.0 * (e_after / e_before - 1.0));
  CHECK(e_after > e_before);
  std::vector<ni::RunConfig> configs;
  ni::MoreauJeanOptions mj;
  mj.end_time = 1e-3;
  mj.step = 1e-4;
  configs.emplace_back(mj);
  ni::EventDrivenOptions ed;
  ed.end_time = 1e-3;
  configs.emplace_back(ed);
  for (const auto& config : configs) {
    nm::Assembly deck(nm::bridge_parts(p));
    ni::Recorder rec(deck, 0.0);
    REQUIRE(ni::succeeded(ni::integrate(deck, config, rec).status));
    const Eigen::Vector3d u_after = first_change(rec, u0);
    INFO(ni::method_name(config) << ": u+ = " << u_after.transpose() << ", oracle "
                                 << oracle.velocity_after.transpose());
    CHECK((u_after - oracle.velocity_after).norm() <= kOracleAgreement * (1.0 + u0.norm()));
  }
}
