#include "integrators/run.hpp"

#include <stdexcept>
#include <string>
#include <utility>

namespace nsb::integrators {

namespace {

// Calls f(Options{}) for every alternative of RunConfig, in order.
template <class F, std::size_t... I>
void for_each_method(F&& f, std::index_sequence<I...>) {
  (f(std::variant_alternative_t<I, RunConfig>{}), ...);
}
template <class F>
void for_each_method(F&& f) {
  for_each_method(std::forward<F>(f), std::make_index_sequence<std::variant_size_v<RunConfig>>{});
}

}  // namespace

std::string_view method_name(const RunConfig& config) {
  return std::visit([](const auto& o) { return std::decay_t<decltype(o)>::kMethod; }, config);
}

const std::vector<std::string_view>& method_names() {
  static const std::vector<std::string_view> names = [] {
    std::vector<std::string_view> v;
    for_each_method([&](const auto& o) { v.push_back(std::decay_t<decltype(o)>::kMethod); });
    return v;
  }();
  return names;
}

RunConfig default_config(std::string_view name) {
  RunConfig config;
  bool found = false;
  for_each_method([&](const auto& o) {
    if (std::decay_t<decltype(o)>::kMethod == name) {
      config = o;
      found = true;
    }
  });
  if (!found) {
    std::string list;
    for (auto n : method_names()) list += (list.empty() ? "\"" : ", \"") + std::string(n) + "\"";
    throw std::invalid_argument("method: must be one of " + list + " (got \"" +
                                std::string(name) + "\")");
  }
  return config;
}

double end_time(const RunConfig& config) {
  return std::visit([](const auto& o) { return o.end_time; }, config);
}

void validate(const RunConfig& config) {
  std::visit([](const auto& o) { o.validate(); }, config);
}

void require_no_restart(const RunHooks& hooks, std::string_view method) {
  if (hooks.resume != nullptr || hooks.checkpoint != nullptr) {
    throw std::invalid_argument(std::string(method) +
                                ": RunHooks::resume and checkpoint are for moreau runs only");
  }
}

RunResult integrate(System& system, const RunConfig& config, Recorder& recorder,
                    const Progress& progress, const RunHooks& hooks) {
  return std::visit(
      [&](const auto& o) { return run_method(system, o, recorder, progress, hooks); }, config);
}

}  // namespace nsb::integrators
