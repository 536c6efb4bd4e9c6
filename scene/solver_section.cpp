// The [solver] table read straight into integrators::RunConfig with the methods' own fields
// (integrators/options.cpp): one declaration of every key, its unit and its range.
#include "scene/scene_builders.hpp"
#include "scene/scene_schema.hpp"

#include "integrators/work_bounds.hpp"

#include <algorithm>
#include <type_traits>
#include <variant>

namespace nsb::scene {

namespace {

using integrators::RunConfig;

// solver.adapt = true under Moreau–Jean: solver.min_step when the scene gives none, as a
// multiple of solver.accuracy [s] (docs/moreau-jean.md, "The smallest step"). A switch
// localised to within min_step moves the state after it by up to min_step |u|, relative to a
// peak min_step |u|max / |q|max; |u|max / |q|max is 3.5–36 /s on the bridges, so
// 0.01 s × accuracy keeps that below 0.36 × accuracy. Measured at accuracy 1e-2 (1e-4 s
// against 1 µs): the deck peaks move by less than 0.06 %, the cost falls 4–21 times. It is
// never coarser than the scene's solver.step, the resolution its author chose for its
// switches: the two-frame bridges' hinge impact at 11.55 s takes the converged branch only at
// steps up to 4.5e-5 s, and with 1e-4 s both adapted to |theta1| 16 % low while claiming 1 %.
constexpr double kMinStepOfAccuracy = 0.01;

// solver.adapt = true under Moreau–Jean: solver.max_step when the scene gives none, as a
// multiple of solver.accuracy [s], 1 ms at 1e-2. A run asked for an accuracy takes nothing
// from the scene's solver.step (without adapt the largest step is 10 solver.step), so two
// scenes of one bridge with different steps adapt alike. Measured at accuracy 1e-2 on every
// shipped bridge (docs/error-estimates.md, "Measured on every bridge"): 1 ms keeps every deck
// peak within 1 % of event-driven at 1e-10 (the largest 0.91 %, bridge-backfill's theta2 at
// its accuracy 0.1); 2.5e-4 s, ten times the two-frame bridges' step, ended them 16 % off on
// theta1, a pounding of frame 1 missed, and 5 ms ends bridge-backfill 1.56 % off.
constexpr double kMaxStepOfAccuracy = 0.1;

// solver.adapt = true under event-driven: the loosest tolerance a run starts from, whatever
// the scene's (docs/error-estimates.md, "Choosing the step"). The tolerance bounds the
// position error per step in metres; where the error exceeds the clearance of a near miss,
// the run takes the near miss for a pounding, a change of the response that its companion at
// a looser tolerance shares and so cannot show. On excitation 7 a near miss of 13.5 µm is a
// pounding at every tolerance down to 1e-5 (|theta| 33 % high); at 1e-6 it is 9.1 µm, 4.5 µm
// off. Started at 1e-7, two of the 24 bridge runs still end 1.2–1.4 % off while claiming
// 1 %; at 1e-8, the method's default, every one ends within 0.46 %.
constexpr double kAdaptLoosestTolerance = 1e-8;

// Calls fn.template operator()<O>() for every options type O registered in RunConfig.
template <class Fn>
void for_each_method(Fn&& fn) {
  [&]<class... O>(std::type_identity<std::variant<O...>>) {
    (fn.template operator()<O>(), ...);
  }(std::type_identity<RunConfig>{});
}

// Every [solver] key: method, then each method's keys in their order of declaration, once,
// then the error estimate's (EstimateSettings).
std::vector<std::string_view> solver_keys() {
  std::vector<std::string_view> keys = keys_of(MethodSetting::fields());
  for_each_method([&]<class O>() {
    for (const auto& f : O::fields()) {
      if (std::find(keys.begin(), keys.end(), f.key) == keys.end()) keys.push_back(f.key);
    }
  });
  for (const auto key : keys_of(EstimateSettings::fields())) keys.push_back(key);
  return keys;
}

// A key the chosen method does not declare: accepted when a method that declares it accepts
// its value, else an error with the rule of the first method that declares it.
void check_other_method_key(const Section& s, std::string_view key) {
  std::string why;
  bool accepted = false;
  for_each_method([&]<class O>() {
    const auto* f = config::find_field(O::fields(), key);
    if (f == nullptr || accepted) return;
    const std::string misfit = config::misfit(*f, *s.value(key, f->kind));
    if (misfit.empty()) {
      accepted = true;
    } else if (why.empty()) {
      why = "for " + std::string(O::kMethod) + ", " + misfit;
    }
  });
  if (!accepted) s.fail(key, why);
}

}  // namespace

RunConfig read_solver(Section& s, EstimateSettings& estimate) {
  s.only(solver_keys());
  MethodSetting chosen;
  s.read_all(MethodSetting::fields(), chosen);
  s.read_all(EstimateSettings::fields(), estimate);
  if (estimate.adapt && !estimate.error_estimate) {
    s.fail("adapt", "needs solver.error_estimate = true: the estimate decides each refinement");
  }
  RunConfig config = integrators::default_config(chosen.method);
  std::visit(
      [&s](auto& options) {
        const auto fields = options.fields();
        s.read_all(fields, options);
        for (auto&& [k, v] : s.table()) {
          const std::string_view key = k.str();
          if (config::find_field(MethodSetting::fields(), key) != nullptr) continue;
          if (config::find_field(EstimateSettings::fields(), key) != nullptr) continue;
          if (config::find_field(fields, key) == nullptr) check_other_method_key(s, key);
        }
      },
      config);
  // solver.adapt under Moreau–Jean: adaptive steps at a local tolerance from the accuracy,
  // unless the scene gives its own (docs/moreau-jean.md, "Adaptive steps").
  // Its smallest step from the accuracy too: a switch need not be localised beyond what moves
  // a peak by a fraction of the target, nor more coarsely than the scene's step
  // (kMinStepOfAccuracy).
  auto* moreau = std::get_if<integrators::MoreauJeanOptions>(&config);
  if (estimate.adapt && moreau != nullptr && moreau->local_tolerance == 0.0) {
    moreau->local_tolerance = integrators::kLocalToleranceOfAccuracy * estimate.accuracy;
  }
  if (estimate.adapt && moreau != nullptr && !s.has("min_step")) {
    moreau->min_step = std::min(kMinStepOfAccuracy * estimate.accuracy, moreau->step);
  }
  if (estimate.adapt && moreau != nullptr && !s.has("max_step")) {
    moreau->max_step = kMaxStepOfAccuracy * estimate.accuracy;
  }
  // solver.adapt under event-driven: a start no looser than kAdaptLoosestTolerance, below
  // which a near miss is no longer taken for a pounding.
  auto* event = std::get_if<integrators::EventDrivenOptions>(&config);
  if (estimate.adapt && event != nullptr) {
    event->tolerance = std::min(event->tolerance, kAdaptLoosestTolerance);
  }
  return config;
}

void check_work(const Section& solver, const Section& output, const RunConfig& config,
                double t0, double sample_dt) {
  const std::string_view step_key =
      std::holds_alternative<integrators::MoreauJeanOptions>(config) ? "step" : "max_step";
  const std::string why = integrators::work_misfit(config, t0, sample_dt, solver.has(step_key),
                                                   output.has("sample_dt"));
  if (why.empty()) return;
  const auto colon = why.find(": ");
  const std::string key = why.substr(0, colon);
  const std::string what = why.substr(colon + 2);
  if (key == "sample_dt") output.fail(key, what);
  solver.fail(key, what);
}

void check_solver(const Section& s, const RunConfig& config) {
  try {
    integrators::validate(config);
  } catch (const std::invalid_argument& e) {
    s.rethrow(e);
  }
}

}  // namespace nsb::scene
