// nsbridge: nonsmooth seismic response of bridges with deck-abutment pounding.
#include "app/commands.hpp"
#include "io/files.hpp"

#include <cstdio>
#include <exception>
#include <iostream>

namespace nsb::app {
int& exit_code() {
  static int code = 0;
  return code;
}
}  // namespace nsb::app

int main(int argc, char** argv) {
  CLI::App app{"nsbridge: nonsmooth seismic response of bridges with deck-abutment pounding"};
  app.set_version_flag("--version", nsb::app::version_text());
  app.require_subcommand(1);
  nsb::app::add_lcp_command(app);
  nsb::app::add_criterion_command(app);
  nsb::app::add_run_command(app);
  nsb::app::add_figures_command(app);
  nsb::app::add_sweep_command(app);
  nsb::app::add_spectrum_command(app);
  nsb::app::add_suite_spectra_command(app);
  nsb::app::add_records_command(app);
  nsb::app::add_export_command(app);
  nsb::app::add_plot_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11 exits 0 for --help; every other parse error is a usage error (exit 2).
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  } catch (const nsb::app::InputError& e) {
    std::cerr << "nsbridge: " << e.what() << '\n';
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "nsbridge: " << e.what() << '\n';
    return 2;
  } catch (const nsb::io::WriteError& e) {
    // An output that could not be written (a full disk) is met as an unwritable place.
    std::cerr << "nsbridge: " << e.what() << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "nsbridge: internal error: " << e.what() << '\n';
    return 1;
  }
  return nsb::app::exit_code();
}
