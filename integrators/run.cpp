#include "integrators/run.hpp"

#include <type_traits>

namespace nsb::integrators {

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
  return std::visit(
      [&](const auto& o) -> RunResult {
        using T = std::decay_t<decltype(o)>;
        if constexpr (std::is_same_v<T, MoreauJeanOptions>) {
          return moreau_jean(system, o, recorder, progress);
        } else if constexpr (std::is_same_v<T, EventDrivenOptions>) {
          return event_driven(system, o, recorder, progress);
        } else {
          return compliance(system, o, recorder, progress);
        }
      },
      config);
}

}  // namespace nsb::integrators
