// Record libraries as they are downloaded, turned into record suites (docs/ground-motions.md,
// "Importing a record library"; the suite format: docs/sweep.md, "Record suites"):
//   - a PEER NGA-West2 search download: `_SearchResults.csv` and the `.AT2` files it names.
//     The table of selected records follows a preamble: a line of column names, among them
//     "Record Sequence Number", "Scale Factor", "Horizontal-1 Acc. Filename" and
//     "Horizontal-2 Acc. Filename" (the names may carry leading spaces), one row per record,
//     ended by a blank line; later sections (the spectra) are not read. Each record's two
//     horizontal components become file_1 and file_2, copied byte for byte; every other
//     column is kept under its name in lower case with non-alphanumerics as '_'
//     ("Rjb (km)" -> rjb_km), PEER's scale factor as scale_factor (kept, not applied).
//   - a folder of COSMOS V1/V2 files (scene/cosmos.hpp): the horizontal channels of one
//     station and one start time form a record, written as CSV files "t [s],a [m/s^2]".
// The suite is a folder: records.csv (rsn or name, file_1, file_2, then the metadata) and the
// record files, written as one set (io::FileSet): a failed import leaves nothing behind.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace nsb::sweep {

// One record of an imported suite.
struct ImportedRecord {
  std::vector<std::string> cells;                // the row of records.csv
  std::vector<std::pair<std::string, std::string>> files;  // (name in the suite, contents)
};

struct ImportedSuite {
  std::string kind;                  // "peer" or "cosmos"
  std::vector<std::string> header;   // the columns of records.csv
  std::vector<ImportedRecord> records;
};

// The records of a PEER search folder (dir holds _SearchResults.csv). Throws
// std::invalid_argument naming the file, line and column for a missing column, a bad cell, a
// missing or unreadable .AT2 file, a record without two horizontal components or an RSN that
// appears twice.
ImportedSuite read_peer_search(const std::filesystem::path& dir);

// The records of a folder of COSMOS files (.V1, .V2, .V1c, .V2c, any case), grouped by station
// and start time. Throws std::invalid_argument naming the file and line for a malformed file,
// and the station for one without exactly two horizontal channels.
ImportedSuite read_cosmos_folder(const std::filesystem::path& dir);

// read_peer_search when dir holds _SearchResults.csv, else read_cosmos_folder.
ImportedSuite read_record_library(const std::filesystem::path& dir);

// records.csv of a suite.
std::string suite_csv(const ImportedSuite&);

// Writes the suite into out (records.csv and the record files) as one set.
void write_suite(const ImportedSuite&, const std::filesystem::path& out);

}  // namespace nsb::sweep
