// The run API: one typed configuration per method, one entry point, one result.
//
//   RunConfig config = MoreauJeanOptions{...};            // or EventDrivenOptions, ComplianceOptions
//   RunResult result = integrate(system, config, recorder);
//   if (!succeeded(result.status)) ...                    // a numerical outcome, never an exception
//
// integrate() throws std::invalid_argument only for a bad call (invalid options, a system
// whose sizes are inconsistent), before any integration. Everything that happens during the
// integration is a RunStatus with its counts (docs/run-api.md).
#pragma once

#include "integrators/compliance.hpp"
#include "integrators/event_driven.hpp"
#include "integrators/moreau_jean.hpp"
#include "integrators/recorder.hpp"
#include "integrators/system.hpp"

#include <string_view>
#include <variant>

namespace nsb::integrators {

// The configuration of one run: the options struct of the chosen method.
using RunConfig = std::variant<MoreauJeanOptions, EventDrivenOptions, ComplianceOptions>;

// "moreau", "event_driven" or "compliance": the name in scene files and summary.json.
std::string_view method_name(const RunConfig& config);
// The final time of the run [s].
double end_time(const RunConfig& config);
// Throws std::invalid_argument naming the field, as the method's options do.
void validate(const RunConfig& config);

// Integrates system from its initial state with the method config holds, recording into
// recorder; progress (recorder.hpp) is called by every method. Returns the result with the
// RunStatus the method set itself; throws std::invalid_argument only for a bad call.
RunResult integrate(System& system, const RunConfig& config, Recorder& recorder,
                    const Progress& progress = {});

}  // namespace nsb::integrators
