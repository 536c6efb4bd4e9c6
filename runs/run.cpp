#include "runs/run.hpp"

#include "integrators/run.hpp"
#include "io/files.hpp"
#include "runs/estimate.hpp"
#include "runs/lcp_dump.hpp"
#include "runs/trust.hpp"

#include <ctime>
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
// still sees it; returns false when it was interrupted.
bool estimate_errors(const scene::Scene& scene, const integrators::Recorder& history,
                     const integrators::Progress& progress, const integrators::RunHooks& run_hooks,
                     Digest& digest) {
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
  const integrators::RunResult result =
      integrators::integrate(*twin.system, plan->config, companion_history, at_end, hooks);
  if (result.status == integrators::RunStatus::kInterrupted) return false;
  e.companion_status = std::string(integrators::to_string(result.status));
  if (integrators::is_result(result.status)) {
    const Digest companion = make_digest(companion_history, result);
    apply_estimate(digest, history, companion, companion_history, *plan);
  }
  e.companion_cpu_seconds = thread_cpu_seconds() - start;
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
    try {
      io::check_output_dir(request.dump_lcp);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("dump_lcp " + request.dump_lcp.string() + ": " + e.what());
    }
    p.dump_lcp = request.dump_lcp;
  }
  p.stop = request.stop;
  return p;
}

RunRecord run(PreparedRun prepared, const integrators::Progress& progress) {
  scene::Scene& scene = prepared.scene;
  integrators::Recorder history(*scene.system, scene.output.sample_dt,
                                integrators::OutputGroups::parse(scene.output.groups));
  std::optional<LcpDump> dump;
  if (!prepared.dump_lcp.empty()) dump.emplace(prepared.dump_lcp);
  integrators::RunHooks hooks;
  if (dump) hooks.contact_observer = &*dump;
  hooks.stop = prepared.stop;
  const double start = thread_cpu_seconds();
  integrators::RunResult result =
      integrators::integrate(*scene.system, scene.run, history, progress, hooks);
  const double run_cpu_seconds = thread_cpu_seconds() - start;
  Digest digest = make_digest(history, result, scene.system->limit_states());
  digest.input = scene.input;
  // A run that is not a result (it failed) has no peaks worth an estimate.
  if (scene.estimate.error_estimate && integrators::is_result(result.status) &&
      !estimate_errors(scene, history, progress, hooks, digest)) {
    result.status = integrators::RunStatus::kInterrupted;
  }
  // An interrupted run (or estimate) writes nothing: its dump is dropped with `dump`.
  if (dump && result.status != integrators::RunStatus::kInterrupted) dump->write_manifest();
  digest.estimate.run_cpu_seconds = run_cpu_seconds;
  std::tie(digest.estimate.setting, digest.estimate.value) = accuracy_setting(scene.run);
  digest.accuracy = judge_accuracy(digest, scene.estimate.accuracy);
  std::vector<std::string> warnings = std::move(prepared.warnings);
  for (auto& w : result_warnings(history, digest, result)) warnings.push_back(std::move(w));
  result.warnings.insert(result.warnings.end(), warnings.begin(), warnings.end());
  digest.warnings.insert(digest.warnings.end(), warnings.begin(), warnings.end());
  return RunRecord{scene.name, scene.kind, std::move(result), std::move(history),
                   std::move(digest)};
}

RunRecord execute(const RunRequest& request) { return run(prepare(request), request.progress); }

}  // namespace nsb::runs
