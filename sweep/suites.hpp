// Record suites as the levels of a sweep factor (docs/sweep.md, "Record suites"): the rows of
// a CSV file that names each record's component files, or the ground-motion files of a
// folder. Each record becomes one level of a `key = "record"` factor, its components the
// scene keys model.excitation.transverse_record and longitudinal_record.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace nsb::sweep {

// One record of a suite: its name (the level's label) and its component files, in the order
// of the factor's components (transverse, then longitudinal); "" for a component left out.
struct SuiteRecord {
  std::string name;
  std::vector<std::string> files;  // paths as found: the CSV's folder joined to its cell
};

// The rows of a suite CSV (e.g. data/ground-motions/asce7-suite/records.csv): columns[i] names
// the column that holds component i's file, relative to the CSV's folder. The name is the
// `name` column when there is one, else "RSN" followed by the `rsn` column, else the stem of
// the first component's file. Throws std::invalid_argument naming the file, the row and the
// column for an unreadable file, a missing column, an empty cell, a file that does not exist
// or a name that appears twice.
std::vector<SuiteRecord> read_suite(const std::filesystem::path& csv,
                                    const std::vector<std::string>& columns);

// Every .AT2 file (any case) directly in folder, sorted by file name, one component each;
// named by its stem. Throws std::invalid_argument when the folder cannot be read or holds none.
std::vector<SuiteRecord> read_folder(const std::filesystem::path& folder);

}  // namespace nsb::sweep
