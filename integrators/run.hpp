// The run API: one typed configuration per method, one entry point, one result.
//
//   RunConfig config = MoreauJeanOptions{...};            // or EventDrivenOptions, ComplianceOptions
//   RunResult result = integrate(system, config, recorder);
//   if (!succeeded(result.status)) ...                    // a numerical outcome, never an exception
//
// integrate() throws std::invalid_argument only for a bad call (invalid options, a system
// whose sizes are inconsistent), before any integration. Everything that happens during the
// integration is a RunStatus with its counts (docs/run-api.md).
//
// Adding a method: its own files, with an options struct that has
//   static constexpr std::string_view kMethod = "<name>";     // the scene's solver.method
//   static std::span<const config::Field<Options>> fields();  // its [solver] keys
//   void validate() const;
// and an overload
//   RunResult run_method(System&, const Options&, Recorder&, const Progress&, const RunHooks&);
// then one registration: its options type in RunConfig below.
#pragma once

#include "integrators/compliance.hpp"
#include "integrators/event_driven.hpp"
#include "integrators/moreau_jean.hpp"
#include "integrators/recorder.hpp"
#include "integrators/run_hooks.hpp"
#include "integrators/system.hpp"

#include <string_view>
#include <variant>
#include <vector>

namespace nsb::integrators {

// The registered methods: the configuration of one run is the options struct of one of them.
using RunConfig = std::variant<MoreauJeanOptions, EventDrivenOptions, ComplianceOptions>;

// "moreau", "event_driven" or "compliance": the name in scene files and summary.json.
std::string_view method_name(const RunConfig& config);
// The names of every registered method, in the order of RunConfig.
const std::vector<std::string_view>& method_names();
// The options of the method named `name` with their defaults; throws std::invalid_argument
// naming the registered methods for an unknown name.
RunConfig default_config(std::string_view name);
// The final time of the run [s].
double end_time(const RunConfig& config);
// Throws std::invalid_argument naming the field, as the method's options do.
void validate(const RunConfig& config);
// Integrates system from its initial state with the method config holds, recording into
// recorder; progress (recorder.hpp) is called by every method; hooks (run_hooks.hpp) hold the
// run's contact observer and restart, which are not part of a scene. Returns the result with
// the RunStatus the method set itself; throws std::invalid_argument only for a bad call
// (a restart asked of a method other than moreau among them).
RunResult integrate(System& system, const RunConfig& config, Recorder& recorder,
                    const Progress& progress = {}, const RunHooks& hooks = {});

}  // namespace nsb::integrators
