// The subcommands of `nsbridge`. Each adds itself to the CLI11 app and sets its callback.
//
// Exit codes (docs/cli.md): 0 success; 1 the computation ran but did not succeed (e.g. an
// LCP solver status other than solved, a run that stopped early, or a warning with
// `run --strict`); 2 bad input (file, key, option, number, path).
#pragma once

#include <CLI/CLI.hpp>

#include <stdexcept>
#include <string>

namespace nsb::app {

// Thrown by a command for bad input; main prints "nsbridge: <what>" and exits with 2.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A command's callback stores its exit code here (0 unless it sets it).
int& exit_code();

void add_lcp_command(CLI::App& app);        // nsbridge lcp FILE ...
void add_criterion_command(CLI::App& app);  // nsbridge criterion ...
void add_run_command(CLI::App& app);        // nsbridge run SCENE.toml ...
void add_figures_command(CLI::App& app);    // nsbridge figures --out DIR [--quick]
void add_sweep_command(CLI::App& app);      // nsbridge sweep DESIGN.toml --out DIR ...
void add_spectrum_command(CLI::App& app);   // nsbridge spectrum RECORD... [--periods ...]
void add_suite_spectra_command(CLI::App& app);  // nsbridge suite-spectra SUITE.csv --out DIR
void add_records_command(CLI::App& app);        // nsbridge records import DIR --out SUITE_DIR
void add_export_command(CLI::App& app);         // nsbridge export pelicun DIR [--out PREFIX]
void add_plot_command(CLI::App& app);           // nsbridge plot RUN_DIR [--what ...] [--out FILE]

// nsbridge --version: version, git revision (at build time), build type, compiler and the
// versions of the libraries linked.
std::string version_text();

}  // namespace nsb::app
