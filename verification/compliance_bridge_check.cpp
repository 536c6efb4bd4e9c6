// The compliance method on the benchmark bridge (scenes/bridge-exc5.toml with the earlier
// input set: the Sylmar record at 0.65 g transverse, time compressed by 0.5, the 33.35 m deck),
// over the first seconds that contain the first pounding:
//  - theta(t) converges to the nonsmooth (Moreau–Jean) history computed with eps =
//    e_effective of the damping law as the stiffness grows from 1e-4 k0 to 1e2 k0;
//  - the first pounding's penetration depth and contact duration grow as k falls (the
//    paper's Figure 8 trend).
// The full 22 s study is benchmarks/compliance_bench.cpp (docs/benchmarks/compliance.md).
// Release only: the eight bridge runs take a few seconds optimised but minutes under ASan.
#include "integrators/compliance.hpp"
#include "integrators/moreau_jean.hpp"
#include "scene/scene.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

namespace {

using nsb::integrators::EventKind;
using nsb::integrators::Recorder;

// The first pounding (contact 2, near t = 2.29 s with the Sylmar input set) and 1.7 s of the
// response after it. With the test's record (RSN 988) the first pounding comes at 3.97 s, so a
// window that contains it and the response after it would cost twice the run time; the check
// is about the method, not the record, so it keeps the earlier input set, written out below
// (the override lines of docs/bridge.md).
constexpr double kEndTime = 4.0;  // [s]
constexpr double kReferenceStep = 1e-4;  // Moreau–Jean h of the reference [s]

std::string scene_file() { return std::string(NSB_SCENES_DIR) + "/bridge-exc5.toml"; }

std::string number(double v) {
  std::ostringstream os;
  os.precision(12);
  os << v;
  return os.str();
}

double interpolate(const std::vector<double>& t, const std::vector<double>& y, double x) {
  auto it = std::lower_bound(t.begin(), t.end(), x);
  if (it == t.begin()) return y.front();
  if (it == t.end()) return y.back();
  const auto i = static_cast<std::size_t>(it - t.begin());
  const double s = (x - t[i - 1]) / (t[i] - t[i - 1]);
  return (1 - s) * y[i - 1] + s * y[i];
}

struct Run {
  double error = 0.0;        // RMS of theta - theta_ref over the reference samples
  double penetration = 0.0;  // first pounding: largest penetration [m]
  double duration = 0.0;     // first pounding: close -> open [s]
  int contact = 0;
};

// Runs the study for one damping law at the paper's eps_N = 0; returns the RMS errors.
void convergence(nsb::integrators::DampingLaw law) {
  std::printf("# %s\n", std::string(nsb::integrators::to_string(law)).c_str());
  const double e_set = 0.0;  // the paper's eps_N
  const double e_eff = nsb::integrators::hunt_crossley_restitution(
      nsb::integrators::damping_factor(law, e_set));
  const std::vector<std::string> common{
      "solver.end_time=" + number(kEndTime),
      "model.deck.length=33.35",
      "model.bents.0.position=-8.34",
      "model.bents.2.position=8.34",
      "model.excitation.transverse_record=ground-motions/RSN1084_NORTHR_SCS142.AT2",
      "model.excitation.longitudinal_record=ground-motions/RSN1084_NORTHR_SCS052.AT2",
      "model.excitation.target_pga=0.65",
      "model.excitation.longitudinal_pga=0",
      "model.excitation.time_scale=0.5"};

  // Reference: Moreau–Jean with eps = e_effective.
  auto ref_overrides = common;
  ref_overrides.push_back("model.seats.restitution=" + number(e_eff));
  auto ref_scene = nsb::scene::load_scene(scene_file(), ref_overrides);
  nsb::integrators::MoreauJeanOptions mo;
  mo.end_time = kEndTime;
  mo.step = kReferenceStep;
  Recorder ref(*ref_scene.system, 0.0);
  REQUIRE(nsb::integrators::moreau_jean(*ref_scene.system, mo, ref).completed);
  const auto t_ref = ref.series("t"), th_ref = ref.series("theta");
  double peak_ref = 0.0;
  for (double v : th_ref) peak_ref = std::max(peak_ref, std::abs(v));
  REQUIRE(peak_ref > 0.0);

  std::vector<double> factors{1e-4, 1e-2, 1.0, 1e2};
  std::vector<Run> runs;
  for (double factor : factors) {
    auto overrides = common;
    overrides.push_back("model.seats.restitution=" + number(e_set));
    overrides.push_back("solver.method=compliance");
    auto sc = nsb::scene::load_scene(scene_file(), overrides);
    const auto& read = std::get<nsb::integrators::ComplianceOptions>(sc.run);
    nsb::integrators::ComplianceOptions o;
    o.end_time = kEndTime;
    o.tolerance = read.tolerance;
    o.stiffness = read.stiffness * factor;
    o.stick_slip_velocity = read.stick_slip_velocity;
    o.law = law;
    Recorder rec(*sc.system, 0.0);
    const auto st = nsb::integrators::compliance(*sc.system, o, rec);
    REQUIRE(st.completed);
    const auto t = rec.series("t"), th = rec.series("theta");
    Run r;
    double sum = 0.0;
    for (std::size_t i = 0; i < t_ref.size(); ++i) {
      const double d = interpolate(t, th, t_ref[i]) - th_ref[i];
      sum += d * d;
    }
    r.error = std::sqrt(sum / static_cast<double>(t_ref.size())) / peak_ref;
    double t_close = 0.0;
    for (const auto& ev : rec.events()) {
      if (r.contact == 0 && ev.kind == EventKind::kClose) {
        r.contact = ev.contact;
        t_close = ev.t;
      } else if (r.contact != 0 && ev.contact == r.contact && ev.kind == EventKind::kOpen) {
        r.duration = ev.t - t_close;
        break;
      }
    }
    REQUIRE(r.contact > 0);
    const auto g = rec.series("gN" + std::to_string(r.contact));
    for (std::size_t i = 0; i < t.size(); ++i) {
      if (t[i] >= t_close && t[i] <= t_close + r.duration) {
        r.penetration = std::max(r.penetration, -g[i]);
      }
    }
    std::printf("k = %6.0e k0: theta RMS error / peak %.4e; first pounding contact %d at %.4f s, "
                "penetration %.4e m, duration %.4e s; %lld steps\n",
                factor, r.error, r.contact, t_close, r.penetration, r.duration,
                static_cast<long long>(st.steps));
    runs.push_back(r);
  }
  for (std::size_t i = 1; i < runs.size(); ++i) {
    CAPTURE(factors[i]);
    // Convergence: the error falls as k grows.
    CHECK(runs[i].error < runs[i - 1].error);
    // Figure 8: a softer gap element penetrates deeper and stays closed longer.
    CHECK(runs[i].penetration < runs[i - 1].penetration);
    CHECK(runs[i].duration < runs[i - 1].duration);
  }
  // At 1e2 k0 the compliance history is close to the nonsmooth one.
  CHECK(runs.back().error < 0.05);
}

}  // namespace

TEST_CASE("compliance: bridge theta(t) converges to the nonsmooth history as k grows") {
#ifndef NDEBUG
  MESSAGE("compliance_bridge_check runs in optimised (NDEBUG) builds only");
#else
  convergence(nsb::integrators::DampingLaw::kHertzDamp);
  convergence(nsb::integrators::DampingLaw::kHuntCrossleyExact);
#endif
}
