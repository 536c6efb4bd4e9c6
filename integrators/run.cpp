#include "integrators/run.hpp"

#include <type_traits>

namespace nsb::integrators {

namespace {

// The status a result's counts imply, for integrators that report only counts.
RunStatus status_from_counts(const RunResult& r) {
  if (!r.completed) {
    return r.message.find("non-finite") != std::string::npos ? RunStatus::kDiverged
                                                             : RunStatus::kStalled;
  }
  if (r.lcp_unsolved > 0) return RunStatus::kContactUnsolved;
  if (r.lcp_fallbacks > 0) return RunStatus::kCompletedWithFallbacks;
  return RunStatus::kCompleted;
}

}  // namespace

std::string_view method_name(const RunConfig& config) {
  return std::visit(
      [](const auto& o) -> std::string_view {
        using T = std::decay_t<decltype(o)>;
        if constexpr (std::is_same_v<T, MoreauJeanOptions>) return "moreau";
        else if constexpr (std::is_same_v<T, EventDrivenOptions>) return "event_driven";
        else return "compliance";
      },
      config);
}

double end_time(const RunConfig& config) {
  return std::visit([](const auto& o) { return o.end_time; }, config);
}

void validate(const RunConfig& config) {
  std::visit([](const auto& o) { o.validate(); }, config);
}

RunResult integrate(System& system, const RunConfig& config, Recorder& recorder,
                    const Progress& progress) {
  RunResult result = std::visit(
      [&](const auto& o) -> RunResult {
        using T = std::decay_t<decltype(o)>;
        if constexpr (std::is_same_v<T, MoreauJeanOptions>) {
          if (!progress) return moreau_jean(system, o, recorder);
          MoreauJeanOptions with_progress = o;
          with_progress.progress = progress;
          return moreau_jean(system, with_progress, recorder);
        } else if constexpr (std::is_same_v<T, EventDrivenOptions>) {
          return event_driven(system, o, recorder);
        } else {
          return compliance(system, o, recorder);
        }
      },
      config);
  for (const auto& [name, count] : result.lcp_status) {
    if (name != "solved") result.lcp_unsolved += count;
  }
  result.status = status_from_counts(result);
  if (!succeeded(result.status)) result.failure_time = result.end_time;
  return result;
}

}  // namespace nsb::integrators
