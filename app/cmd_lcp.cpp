#include "app/commands.hpp"

namespace nsb::app {

void add_lcp_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("lcp", "(not yet available)");
  cmd->callback([] { throw InputError("'lcp' is not available yet"); });
}

}  // namespace nsb::app
