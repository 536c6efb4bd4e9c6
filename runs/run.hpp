// The one way to run a scene: request -> record -> files. `nsbridge run`, every run of a
// sweep, the figures and the Python module call it, so a run means the same thing everywhere
// (docs/run-api.md, "The run pipeline").
//
//   RunRequest ──prepare──► PreparedRun ──run──► RunRecord ──write_record──► history.csv,
//   (scene file or value,   (scene built,         (result, history,          events.csv,
//    overrides, method,      checked, step         digest with every          summary.json
//    progress)               warnings)             warning)
//
// execute() is prepare() then run(). A caller that must know the scene before it integrates
// (`nsbridge run`: its default output folder is named after the scene) calls the two steps.
// A caller that runs one scene many times (Python, a sweep's base scene) reads it once
// (scene::read_scene_table, or a table built in code) and passes the value: prepare then reads
// no scene file, only the scene's record files.
#pragma once

#include "integrators/recorder.hpp"
#include "runs/digest.hpp"
#include "scene/scene.hpp"

#include <atomic>
#include <filesystem>
#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace nsb::runs {

struct RunRequest {
  // The scene file (TOML, docs/scenes.md), or a scene value: its table, origin and overridden
  // keys (scene/scene.hpp), checked by prepare exactly as the file's would be.
  std::variant<std::filesystem::path, scene::SceneTable> scene;
  std::vector<std::string> overrides;  // "section.key=value", applied in order
  std::string method;                  // an integrators::method_names() entry; empty: the
                                       //   scene's solver.method
  integrators::Progress progress;      // called with the simulated time reached; may be empty
  std::filesystem::path dump_lcp{};    // a folder that receives every contact problem of the
                                       //   run and manifest.csv (runs/lcp_dump.hpp); empty:
                                       //   none
  std::vector<scene::Override> typed_overrides{};  // applied after `overrides`, in order
  const std::atomic<bool>* stop = nullptr;  // a stop request (integrators::RunHooks::stop):
                                            //   once true, the run ends as interrupted;
                                            //   not owned; nullptr: never stopped
  std::string cross_check{};  // an integrators::method_names() entry: the same scene is run
                              //   again under it and compared (Digest::cross_check); empty:
                              //   none
};

struct RunRecord {
  std::string scene_name, kind;   // the scene's name (file stem) and [model] kind
  integrators::RunResult result;  // status and statistics; result.warnings holds every warning
  integrators::Recorder history;  // the sampled history and the events
  Digest digest;                  // peaks, event counts, energy and warnings, computed once
};

// A scene loaded and checked, ready to integrate.
struct PreparedRun {
  scene::Scene scene;
  std::vector<std::string> warnings;  // step warnings (runs/trust.hpp), found before the run
  std::filesystem::path dump_lcp{};    // RunRequest::dump_lcp, checked writable (not created)
  const std::atomic<bool>* stop = nullptr;  // RunRequest::stop
  // The cross-check's run (RunRequest::cross_check), prepared from the same scene table with
  // solver.method set to the other method; null without a cross-check.
  std::shared_ptr<PreparedRun> cross_check{};
};

// Reads the scene file (or copies the scene value), applies the overrides, then the typed
// overrides (and "solver.method=<method>" last when a method is given), builds and checks the
// scene (scene::build_scene), checks its initial state and finds the step warnings, and
// checks that the dump_lcp folder, when one is asked for, can be written (io::check_output_dir;
// nothing is created before the run), and prepares the cross-check's run, when one is asked
// for, from the same table under the other method (an unknown method throws naming
// cross_check). A scene value gives the scene its file
// gives, bit for bit. Throws std::invalid_argument for bad input, naming the file (a value's
// origin name) and key ("<file>:<line>:<col>: <key>: ...") or the folder, before any
// integration.
PreparedRun prepare(const RunRequest& request);

// Integrates a prepared scene and digests the run: the trust checks' warnings follow the
// integrator's own in result.warnings and digest.warnings. With solver.adapt the scene is
// integrated again with a finer step or tighter tolerance while its estimate exceeds
// solver.accuracy (runs/estimate.hpp, refined_value), and the record is the last attempt's,
// with every attempt in digest.adaptation. With a cross-check, the other method's run follows
// (through this same function) and digest.cross_check compares the two, its warnings last. A numerical failure is the
// record's result.status, never an exception; a stop request (prepared.stop) ends it as
// RunStatus::kInterrupted. With prepared.dump_lcp, every contact problem is written beside
// that folder as it is solved, and the problems with manifest.csv move into it as one set
// (io::FileSet) when the run was not interrupted; throws io::WriteError naming the file when
// they cannot be written, and leaves nothing of them.
RunRecord run(PreparedRun prepared, const integrators::Progress& progress = {});

// prepare(request), then run(..., request.progress).
RunRecord execute(const RunRequest& request);

}  // namespace nsb::runs
