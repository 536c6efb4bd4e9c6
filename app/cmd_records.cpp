// nsbridge records import DIR --out SUITE_DIR: a PEER NGA-West2 search download or a folder of
// COSMOS V1/V2 files as a record suite that sweeps read (docs/ground-motions.md, "Importing a
// record library").
#include <iostream>
#include <memory>
#include <string>

#include "app/commands.hpp"
#include "io/files.hpp"
#include "sweep/record_import.hpp"

namespace nsb::app {
namespace {

struct RecordsImportArgs {
  std::string dir;  // the downloaded folder
  std::string out;  // the suite's folder
};

void run_records_import(const RecordsImportArgs& a) {
  sweep::ImportedSuite suite;
  try {
    io::check_output_dir(a.out);
    suite = sweep::read_record_library(a.dir);
  } catch (const std::invalid_argument& e) {
    throw InputError("records import: " + std::string(e.what()));
  }
  sweep::write_suite(suite, a.out);
  std::cout << "records import: " << suite.records.size() << " records ("
            << (suite.kind == "peer" ? "PEER NGA-West2 search" : "COSMOS") << ") -> "
            << (std::filesystem::path(a.out) / "records.csv").string() << '\n';
}

}  // namespace

void add_records_command(CLI::App& app) {
  auto* records = app.add_subcommand("records", "record libraries (docs/ground-motions.md)");
  records->require_subcommand(1);
  auto args = std::make_shared<RecordsImportArgs>();
  auto* cmd = records->add_subcommand(
      "import",
      "a PEER NGA-West2 search folder (_SearchResults.csv and its .AT2 files) or a folder of "
      "COSMOS V1/V2 files as a record suite (records.csv and the record files)");
  cmd->add_option("dir", args->dir, "the downloaded folder")->required();
  cmd->add_option("--out", args->out, "the suite's folder")->required();
  cmd->callback([args] { run_records_import(*args); });
}

}  // namespace nsb::app
