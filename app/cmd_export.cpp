// nsbridge export pelicun DIR [--out FILE_PREFIX] [--design FILE]: a finished sweep's demands
// and fragility curves in pelicun's CSV formats (docs/sweep.md, "Export to pelicun").
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/commands.hpp"
#include "io/files.hpp"
#include "sweep/pelicun.hpp"

namespace nsb::app {
namespace {

namespace fs = std::filesystem;

struct ExportPelicunArgs {
  std::string dir;     // the sweep's folder
  std::string out;     // prefix of the files; default DIR/pelicun
  std::string design;  // the design file; default: the one manifest.toml names
};

void run_export_pelicun(const ExportPelicunArgs& a) {
  const fs::path prefix = a.out.empty() ? fs::path(a.dir) / "pelicun" : fs::path(a.out);
  if (prefix.filename().empty() || prefix.filename() == "." || prefix.filename() == "..") {
    throw InputError("export pelicun: --out " + a.out + ": a file prefix, not a folder");
  }
  sweep::PelicunExport e;
  try {
    const fs::path parent = prefix.parent_path().empty() ? fs::path(".") : prefix.parent_path();
    io::check_output_dir(parent);
    e = sweep::pelicun_export(a.dir, a.design.empty() ? std::nullopt
                                                      : std::optional<fs::path>(a.design));
  } catch (const std::invalid_argument& ex) {
    throw InputError("export pelicun: " + std::string(ex.what()));
  }
  const std::string stem = prefix.filename().string();
  std::vector<std::pair<std::string, std::string>> files{{stem + "_demands.csv", e.demands}};
  if (!e.fragility.empty()) files.emplace_back(stem + "_fragility.csv", e.fragility);
  const fs::path parent = prefix.parent_path().empty() ? fs::path(".") : prefix.parent_path();
  io::write_file_set(parent, files);
  for (const auto& [name, text] : files) {
    std::cout << "export pelicun: " << (parent / name).string() << '\n';
  }
  std::cout << "export pelicun: " << (e.runs - e.left_out) << " of " << e.runs
            << " runs as demand samples";
  if (e.left_out > 0) std::cout << " (the others did not complete)";
  std::cout << '\n';
  for (const auto& n : e.notes) std::cout << "export pelicun: " << n << '\n';
}

}  // namespace

void add_export_command(CLI::App& app) {
  auto* exp = app.add_subcommand("export", "a sweep's results in another tool's format");
  exp->require_subcommand(1);
  auto args = std::make_shared<ExportPelicunArgs>();
  auto* cmd = exp->add_subcommand(
      "pelicun",
      "demands (pelicun's demand sample CSV) and fragility curves (pelicun's fragility CSV) of "
      "a finished sweep (docs/sweep.md)");
  cmd->add_option("dir", args->dir, "the sweep's folder (results.csv)")->required();
  cmd->add_option("--out", args->out,
                  "prefix of the files: PREFIX_demands.csv, PREFIX_fragility.csv "
                  "(default DIR/pelicun)");
  cmd->add_option("--design", args->design,
                  "the design file (default: the one DIR/manifest.toml names)");
  cmd->callback([args] { run_export_pelicun(*args); });
}

}  // namespace nsb::app
