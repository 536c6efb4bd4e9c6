#include "app/commands.hpp"

namespace nsb::app {

void add_criterion_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("criterion", "(not yet available)");
  cmd->callback([] { throw InputError("'criterion' is not available yet"); });
}

}  // namespace nsb::app
