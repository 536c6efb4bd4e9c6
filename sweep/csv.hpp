// The small CSV and file helpers of the sweep: RFC 4180 fields, and files written under a
// temporary name and renamed, so that a reader never sees a partial file.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace nsb::sweep {

// The fields of one CSV line; quoted fields may hold commas and doubled quotes. Unquoted
// fields are trimmed of spaces and tabs.
std::vector<std::string> csv_fields(const std::string& line);

// s as a CSV field: quoted (RFC 4180) when it holds a comma, a quote or a line break.
std::string csv_quote(const std::string& s);

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

// Writes text to file via "<file>.tmp<pid>" and rename. Throws std::runtime_error naming the
// path on failure, after removing the temporary.
void write_file_atomically(const std::filesystem::path& file, const std::string& text);

}  // namespace nsb::sweep
