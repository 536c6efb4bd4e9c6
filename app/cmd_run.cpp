#include "app/commands.hpp"

namespace nsb::app {

void add_run_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("run", "(not yet available)");
  cmd->callback([] { throw InputError("'run' is not available yet"); });
}

}  // namespace nsb::app
