#include "runs/run.hpp"

#include "integrators/run.hpp"
#include "io/files.hpp"
#include "runs/lcp_dump.hpp"
#include "runs/trust.hpp"

#include <optional>
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
  integrators::Recorder history(*scene.system, scene.output.sample_dt);
  std::optional<LcpDump> dump;
  if (!prepared.dump_lcp.empty()) dump.emplace(prepared.dump_lcp);
  integrators::RunHooks hooks;
  if (dump) hooks.contact_observer = &*dump;
  hooks.stop = prepared.stop;
  integrators::RunResult result =
      integrators::integrate(*scene.system, scene.run, history, progress, hooks);
  // An interrupted run writes nothing: its dump is dropped with `dump`.
  if (dump && result.status != integrators::RunStatus::kInterrupted) dump->write_manifest();
  Digest digest = make_digest(history, result, scene.system->limit_states());
  digest.input = scene.input;
  std::vector<std::string> warnings = std::move(prepared.warnings);
  for (auto& w : result_warnings(history, digest, result)) warnings.push_back(std::move(w));
  result.warnings.insert(result.warnings.end(), warnings.begin(), warnings.end());
  digest.warnings.insert(digest.warnings.end(), warnings.begin(), warnings.end());
  return RunRecord{scene.name, scene.kind, std::move(result), std::move(history),
                   std::move(digest)};
}

RunRecord execute(const RunRequest& request) { return run(prepare(request), request.progress); }

}  // namespace nsb::runs
