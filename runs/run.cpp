#include "runs/run.hpp"

#include "integrators/run.hpp"
#include "io/files.hpp"
#include "models/assembly.hpp"
#include "runs/estimate.hpp"
#include "runs/lcp_dump.hpp"
#include "runs/trajectory.hpp"
#include "runs/trust.hpp"

#include <algorithm>
#include <ctime>
#include <limits>
#include <memory>
#include <optional>
#include <tuple>
#include <stdexcept>
#include <utility>
#include <variant>

namespace nsb::runs {

namespace {

// The request's scene table with its overrides applied, the method's last.
scene::SceneTable scene_table(const RunRequest& request) {
  const auto* file = std::get_if<std::filesystem::path>(&request.scene);
  scene::SceneTable table = file != nullptr ? scene::read_scene_table(*file)
                                             : std::get<scene::SceneTable>(request.scene);
  scene::apply_overrides(table, request.overrides);
  scene::apply_overrides(table, request.typed_overrides);
  if (!request.method.empty()) {
    scene::apply_overrides(table, std::vector<std::string>{"solver.method=" + request.method});
  }
  return table;
}

// The family and name of each contact of an assembled model (models::Assembly, whose parts
// name them); none for another system (the test systems) or when its parts name none.
std::vector<ContactLabel> contact_labels(const integrators::System& system) {
  std::vector<ContactLabel> labels;
  const auto* assembly = dynamic_cast<const models::Assembly*>(&system);
  if (assembly == nullptr) return labels;
  bool named = false;
  const auto& contacts = assembly->parts().contacts;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const models::parts::CornerContact& c = contacts[i];
    int face = static_cast<int>(i);
    for (std::size_t j = 0; j < i; ++j) {
      const models::parts::CornerContact& o = contacts[j];
      if (o.body == c.body && o.obstacle == c.obstacle && o.obstacle_index == c.obstacle_index &&
          o.face.point == c.face.point && o.face.normal == c.face.normal) {
        face = labels[j].face;
        break;
      }
    }
    labels.push_back({c.family, c.name, face});
    named = named || !c.family.empty();
  }
  if (!named) labels.clear();
  return labels;
}

// CPU time of the calling thread [s]: a run's cost, whether or not other runs share the
// process (a sweep's threads).
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The error estimate of a run (runs/estimate.hpp): its scene built again from the same table
// (a fresh system: the run's own is at its end state) and integrated with the companion's
// step or tolerance; no rows but the first and the last are kept, the peaks being those of
// the steps. Sets digest.estimate. The companion reads the run's stop request, and reports
// its progress as the run's end, so that a caller polling for Ctrl-C in the progress callback
// still sees it; returns false when it was interrupted. trace: the run's coordinates on the
// grid of trace_interval (runs/trajectory.hpp), compared with the companion's.
bool estimate_errors(const scene::Scene& scene, const integrators::Recorder& history,
                     const CoordinateTrace& trace, const integrators::Progress& progress,
                     const integrators::RunHooks& run_hooks, Digest& digest) {
  ErrorEstimate& e = digest.estimate;
  e.enabled = true;
  const double t0 = scene.system->initial_time();
  const std::optional<CompanionPlan> plan =
      companion_plan(scene.run, integrators::end_time(scene.run) - t0);
  if (!plan) return true;
  const double start = thread_cpu_seconds();
  scene::Scene twin = scene::build_scene(scene.table);
  // The companion carries the same output groups, so that their columns' peaks get errors.
  integrators::Recorder companion_history(*twin.system, integrators::end_time(plan->config) - t0,
                                          integrators::OutputGroups::parse(twin.output.groups));
  integrators::RunHooks hooks;
  hooks.stop = run_hooks.stop;
  const double t_end = integrators::end_time(scene.run);
  integrators::Progress at_end;
  if (progress) at_end = [&progress, t_end](double) { progress(t_end); };
  TracedSystem traced(*twin.system, trace.dt, t_end - t0);
  const integrators::RunResult result =
      integrators::integrate(traced, plan->config, companion_history, at_end, hooks);
  if (result.status == integrators::RunStatus::kInterrupted) return false;
  e.companion_status = std::string(integrators::to_string(result.status));
  if (integrators::is_result(result.status)) {
    const Digest companion = make_digest(companion_history, result);
    apply_estimate(digest, history, companion, companion_history, *plan);
    bound_by_trajectories(digest, history, trace, companion, traced.trace(), *plan);
  }
  e.companion_cpu_seconds = thread_cpu_seconds() - start;
  return true;
}

// A scene integrated once, its digest and error estimate made and judged, with its CPU cost.
struct Attempt {
  integrators::RunResult result;
  integrators::Recorder history;
  Digest digest;
  double cpu_seconds = 0.0;  // the run and its companion [s]
};

Attempt integrate_once(scene::Scene& scene, const integrators::Progress& progress,
                       const integrators::RunHooks& hooks, LcpDump* dump) {
  integrators::Recorder history(*scene.system, scene.output.sample_dt,
                                integrators::OutputGroups::parse(scene.output.groups));
  // With an estimate, the run keeps its coordinates for the trajectory bound.
  std::optional<TracedSystem> traced;
  if (scene.estimate.error_estimate) {
    traced.emplace(*scene.system, trace_interval(scene.run),
                   integrators::end_time(scene.run) - scene.system->initial_time());
  }
  integrators::System& system =
      traced ? static_cast<integrators::System&>(*traced) : *scene.system;
  const double start = thread_cpu_seconds();
  integrators::RunResult result =
      integrators::integrate(system, scene.run, history, progress, hooks);
  const double run_cpu_seconds = thread_cpu_seconds() - start;
  Digest digest = make_digest(history, result, scene.system->limit_states());
  digest.input = scene.input;
  digest.contacts = contact_labels(*scene.system);
  // A run that is not a result (it failed) has no peaks worth an estimate.
  if (scene.estimate.error_estimate && integrators::is_result(result.status) &&
      !estimate_errors(scene, history, traced->trace(), progress, hooks, digest)) {
    result.status = integrators::RunStatus::kInterrupted;
  }
  // An interrupted run (or estimate) writes nothing: its dump is dropped with `dump`.
  if (dump != nullptr && result.status != integrators::RunStatus::kInterrupted) {
    dump->write_manifest();
  }
  digest.estimate.run_cpu_seconds = run_cpu_seconds;
  std::tie(digest.estimate.setting, digest.estimate.value) = accuracy_setting(scene.run);
  digest.accuracy = judge_accuracy(digest, scene.estimate.accuracy);
  const double cpu = thread_cpu_seconds() - start;
  return Attempt{std::move(result), std::move(history), std::move(digest), cpu};
}

AdaptAttempt attempt_entry(const Attempt& a) {
  AdaptAttempt e;
  e.value = a.digest.estimate.value;
  e.worst_relative = a.digest.accuracy.judged ? a.digest.accuracy.worst_relative
                                              : std::numeric_limits<double>::quiet_NaN();
  e.met = a.digest.accuracy.judged && a.digest.accuracy.met;
  e.status = std::string(integrators::to_string(a.result.status));
  e.cpu_seconds = a.cpu_seconds;
  return e;
}

// solver.adapt: the scene integrated from its own step or tolerance, then again with a
// refined one (refined_value) while the estimate exceeds solver.accuracy, at most
// kAdaptAttempts runs. Returns the last attempt; `scene` becomes its scene and `warnings` its
// step warnings. A refined value that the scene refuses (the bound on a run's work) ends the
// search with the attempt before it; so does a refined attempt that fails (stalled,
// diverged) after one that reached a result: a tighter setting would only fail again, and
// the result with its estimate is worth more than a failure. The failed attempt stays in the
// list of attempts.
Attempt adapt(scene::Scene& scene, std::vector<std::string>& warnings,
              const integrators::Progress& progress, const integrators::RunHooks& hooks,
              Adaptation& adaptation) {
  adaptation.enabled = true;
  Attempt last = integrate_once(scene, progress, hooks, nullptr);
  adaptation.attempts.push_back(attempt_entry(last));
  for (int k = 1; k < kAdaptAttempts; ++k) {
    if (last.result.status == integrators::RunStatus::kInterrupted) break;
    if (last.digest.accuracy.judged && last.digest.accuracy.met) break;
    const auto [setting, value] = accuracy_setting(scene.run);
    const double worst = integrators::is_result(last.result.status) && last.digest.accuracy.judged
                             ? last.digest.accuracy.worst_relative
                             : std::numeric_limits<double>::quiet_NaN();
    const double next = refined_value(setting, value, worst, scene.estimate.accuracy);
    scene::SceneTable table = scene.table;
    scene::apply_overrides(table, std::vector<scene::Override>{{"solver." + setting, next}});
    scene::Scene refined;
    try {
      refined = scene::build_scene(table);
    } catch (const std::invalid_argument&) {
      break;  // beyond the work a run may take: the last attempt stands
    }
    std::vector<std::string> refined_warnings =
        step_warnings(*refined.system, refined.run, refined.record_step);
    Attempt next_attempt = integrate_once(refined, progress, hooks, nullptr);
    adaptation.attempts.push_back(attempt_entry(next_attempt));
    if (next_attempt.result.status != integrators::RunStatus::kInterrupted &&
        !integrators::is_result(next_attempt.result.status) &&
        integrators::is_result(last.result.status)) {
      break;
    }
    scene = std::move(refined);
    warnings = std::move(refined_warnings);
    last = std::move(next_attempt);
  }
  for (const AdaptAttempt& a : adaptation.attempts) adaptation.cpu_seconds += a.cpu_seconds;
  return last;
}

// The cross-check (RunRequest::cross_check): the other method's run through run(), its
// progress reported as the run's end (as the companion's), compared with the run's digest.
// Returns false when it was interrupted.
bool cross_check(PreparedRun other, const std::string& run_method,
                 const integrators::Recorder& history, const integrators::Progress& progress,
                 Digest& digest, double accuracy, std::vector<std::string>& warnings) {
  const double start = thread_cpu_seconds();
  const double t_end = integrators::end_time(other.scene.run);
  integrators::Progress at_end;
  if (progress) at_end = [&progress, t_end](double) { progress(t_end); };
  const std::string method(integrators::method_name(other.scene.run));
  const RunRecord record = run(std::move(other), at_end);
  if (record.result.status == integrators::RunStatus::kInterrupted) return false;
  const std::string status(integrators::to_string(record.result.status));
  CrossCheck x;
  if (integrators::is_result(record.result.status)) {
    x = compare_runs(digest, record.digest, first_impact_time(history),
                     first_impact_time(record.history), method, status, accuracy);
  } else {
    x.method = method;
    x.status = status;
  }
  x.warnings = record.digest.warnings;
  x.cpu_seconds = thread_cpu_seconds() - start;
  digest.cross_check = std::move(x);
  for (auto& w : cross_check_warnings(digest, run_method, digest.cross_check)) {
    warnings.push_back(std::move(w));
  }
  return true;
}

}  // namespace

PreparedRun prepare(const RunRequest& request) {
  PreparedRun p{scene::build_scene(scene_table(request)), {}};
  const std::string file = p.scene.table.origin.name;
  if (!p.scene.system) throw std::invalid_argument(file + ": the scene built no system");
  try {
    check_initial_state(*p.scene.system);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(file + ": " + e.what());
  }
  p.warnings = step_warnings(*p.scene.system, p.scene.run, p.scene.record_step);
  if (!request.dump_lcp.empty()) {
    if (p.scene.estimate.adapt) {
      throw std::invalid_argument("dump_lcp " + request.dump_lcp.string() +
                                  ": not with solver.adapt = true, whose run is several runs");
    }
    try {
      io::check_output_dir(request.dump_lcp);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("dump_lcp " + request.dump_lcp.string() + ": " + e.what());
    }
    p.dump_lcp = request.dump_lcp;
  }
  p.stop = request.stop;
  if (!request.cross_check.empty()) {
    const auto& names = integrators::method_names();
    if (std::find(names.begin(), names.end(), request.cross_check) == names.end()) {
      std::string choices;
      for (const auto n : names) choices += (choices.empty() ? "" : ", ") + std::string(n);
      throw std::invalid_argument("cross_check: unknown method \"" + request.cross_check +
                                  "\"; expected one of " + choices);
    }
    RunRequest other;
    other.scene = p.scene.table;
    other.method = request.cross_check;
    other.stop = request.stop;
    p.cross_check = std::make_shared<PreparedRun>(prepare(other));
  }
  return p;
}

RunRecord run(PreparedRun prepared, const integrators::Progress& progress) {
  scene::Scene& scene = prepared.scene;
  std::optional<LcpDump> dump;
  if (!prepared.dump_lcp.empty()) dump.emplace(prepared.dump_lcp);
  integrators::RunHooks hooks;
  if (dump) hooks.contact_observer = &*dump;
  hooks.stop = prepared.stop;
  std::vector<std::string> warnings = std::move(prepared.warnings);
  Adaptation adaptation;
  Attempt a = scene.estimate.adapt
                  ? adapt(scene, warnings, progress, hooks, adaptation)
                  : integrate_once(scene, progress, hooks, dump ? &*dump : nullptr);
  integrators::RunResult& result = a.result;
  Digest& digest = a.digest;
  digest.adaptation = std::move(adaptation);
  for (auto& w : result_warnings(a.history, digest, result)) warnings.push_back(std::move(w));
  if (prepared.cross_check && result.status != integrators::RunStatus::kInterrupted &&
      !cross_check(std::move(*prepared.cross_check), result.method, a.history, progress, digest,
                   scene.estimate.accuracy, warnings)) {
    result.status = integrators::RunStatus::kInterrupted;
  }
  result.warnings.insert(result.warnings.end(), warnings.begin(), warnings.end());
  digest.warnings.insert(digest.warnings.end(), warnings.begin(), warnings.end());
  return RunRecord{scene.name, scene.kind, std::move(result), std::move(a.history),
                   std::move(digest)};
}

RunRecord execute(const RunRequest& request) { return run(prepare(request), request.progress); }

}  // namespace nsb::runs
