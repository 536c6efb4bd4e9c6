// Reading a sweep's CSV files (results.csv, a list design's runs). Fields, quoting and files
// written through a temporary name are io's (io/csv.hpp, io/files.hpp).
#pragma once

#include "io/csv.hpp"
#include "io/files.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace nsb::sweep {

using io::csv_fields;
using io::csv_quote;
using io::write_file_atomically;

// A CSV file: its header and its rows, each split into fields. Blank lines and lines that
// start with '#' are skipped. Throws std::invalid_argument naming the file (and line) when it
// cannot be read or a row's width differs from the header's.
struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  // Index of a column; throws std::invalid_argument naming it when absent.
  std::size_t column(const std::string& name) const;
};
Table read_csv(const std::filesystem::path& file);

}  // namespace nsb::sweep
