// Writing a figure: its CSV, and its gnuplot script drawn twice, as PNG and as SVG.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace nsb::paper_figures {

// A table with named columns, written as CSV (a header line, then one row per line). A
// non-finite value is written as an empty field, which gnuplot skips.
struct Table {
  explicit Table(std::vector<std::string> names) : columns(std::move(names)) {}
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  void add(std::vector<double> row);  // throws std::logic_error on a wrong row size
  void write(const std::filesystem::path& file) const;  // atomically; throws io::WriteError
};

struct PlotSize {
  int width = 1200, height = 800;  // [px] of the PNG; the SVG gets the same size
};

// Writes <dir>/<stem>.gp from `body` (gnuplot commands that read '<stem>.csv' through the
// variable `data`) and runs gnuplot in dir for <stem>.png and <stem>.svg. Returns an empty
// string on success, else what went wrong with gnuplot; a script that cannot be written
// throws io::WriteError.
std::string plot(const std::string& gnuplot, const std::filesystem::path& dir,
                 const std::string& stem, const std::string& body, PlotSize size = {});

}  // namespace nsb::paper_figures
