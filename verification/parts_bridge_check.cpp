// The benchmark bridge assembled from parts (models/bridge_parts.hpp) against models::Bridge:
// built from the same Bridge::Parameters and Excitation (those of scenes/bridge-exc5.toml and
// bridge-exc7.toml), Moreau–Jean and the event-driven integrator give the same history,
// column by column, to 1e-12 of each column's peak, the same events and the same statistics.
#include "integrators/event_driven.hpp"
#include "integrators/moreau_jean.hpp"
#include "models/bridge_parts.hpp"
#include "scene/scene.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace ni = nsb::integrators;
namespace nm = nsb::models;

namespace {

// Ten seconds hold the strong phase of both records: pounding at both abutments, yielding
// bents (excitation 7 reaches the abutments within the first 12 s).
constexpr double kEnd = 10.0;
// The assembly performs the bridge's operations in the same order (models/assembly.hpp), so
// the histories agree to round-off of the peak; 1e-12 leaves room for a reordered sum.
constexpr double kRelative = 1e-12;

struct Pair {
  nsb::scene::Scene scene;      // owns the models::Bridge
  nm::Assembly parts;   // built from its parameters and excitation
};

Pair load(const std::string& name) {
  nsb::scene::Scene scene = nsb::scene::load_scene(std::string(NSB_SCENES_DIR) + "/" + name,
                                   {"solver.end_time=" + std::to_string(kEnd)});
  const auto* bridge = dynamic_cast<const nm::Bridge*>(scene.system.get());
  REQUIRE(bridge != nullptr);
  nm::Assembly parts(nm::bridge_parts(bridge->parameters(), bridge->excitation()));
  return {std::move(scene), std::move(parts)};
}

// Largest difference of every column, relative to the column's peak |value| in the bridge's
// history (absolute for a column that stays zero). Returns the worst one.
double compare(const ni::Recorder& bridge, const ni::Recorder& parts) {
  REQUIRE(bridge.columns() == parts.columns());
  REQUIRE(bridge.rows() == parts.rows());
  double worst = 0.0;
  for (std::size_t c = 0; c < bridge.columns().size(); ++c) {
    double peak = 0.0, diff = 0.0;
    for (std::size_t r = 0; r < bridge.rows(); ++r) {
      peak = std::max(peak, std::abs(bridge.at(r, c)));
      diff = std::max(diff, std::abs(bridge.at(r, c) - parts.at(r, c)));
    }
    const double relative = peak > 0.0 ? diff / peak : diff;
    INFO("column ", bridge.columns()[c], ": max |difference| ", diff, ", peak ", peak);
    CHECK(relative <= kRelative);
    worst = std::max(worst, relative);
  }
  return worst;
}

void same_run(const ni::RunResult& a, const ni::RunResult& b, const ni::Recorder& ra,
              const ni::Recorder& rb) {
  CHECK(a.completed);
  CHECK(b.completed);
  CHECK(a.steps == b.steps);
  CHECK(a.steps_with_lcp == b.steps_with_lcp);
  CHECK(a.lcp_status == b.lcp_status);
  REQUIRE(ra.events().size() == rb.events().size());
  for (std::size_t i = 0; i < ra.events().size(); ++i) {
    CHECK(ra.events()[i].kind == rb.events()[i].kind);
    CHECK(ra.events()[i].contact == rb.events()[i].contact);
    CHECK(std::abs(ra.events()[i].t - rb.events()[i].t) <= kRelative * kEnd);
  }
}

void check_scene(const std::string& name) {
  Pair p = load(name);
  ni::System& bridge = *p.scene.system;
  const double dt = p.scene.output.sample_dt;
  {
    ni::MoreauJeanOptions o;
    o.end_time = kEnd;
    const auto& scene_mj = std::get<ni::MoreauJeanOptions>(p.scene.run);  // [solver] moreau
    o.step = scene_mj.step;
    o.theta = scene_mj.theta;
    ni::Recorder rb(bridge, dt), rp(p.parts, dt);
    const auto a = ni::moreau_jean(bridge, o, rb);
    const auto b = ni::moreau_jean(p.parts, o, rp);
    same_run(a, b, rb, rp);
    CHECK(a.steps_with_lcp > 0);  // it pounds
    MESSAGE(name, ", Moreau–Jean h = ", o.step, ": largest difference ", compare(rb, rp),
            " of the column's peak over ", rb.rows(), " rows");
  }
  Pair q = load(name);  // fresh springs
  ni::System& bridge2 = *q.scene.system;
  {
    ni::EventDrivenOptions o;
    o.end_time = kEnd;
    // The scenes set no tolerance: the event-driven method's default.
    o.tolerance = ni::EventDrivenOptions{}.tolerance;
    ni::Recorder rb(bridge2, dt), rp(q.parts, dt);
    const auto a = ni::event_driven(bridge2, o, rb);
    const auto b = ni::event_driven(q.parts, o, rp);
    same_run(a, b, rb, rp);
    MESSAGE(name, ", event-driven tol = ", o.tolerance, ": largest difference ",
            compare(rb, rp), " of the column's peak over ", rb.rows(), " rows, ",
            rb.events().size(), " events");
  }
}

}  // namespace

TEST_CASE("parts bridge = models::Bridge: excitation 5") { check_scene("bridge-exc5.toml"); }

TEST_CASE("parts bridge = models::Bridge: excitation 7") { check_scene("bridge-exc7.toml"); }
