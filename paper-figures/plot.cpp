#include "paper-figures/plot.hpp"

#include "io/files.hpp"
#include "io/gnuplot.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace nsb::paper_figures {

void Table::add(std::vector<double> row) {
  if (row.size() != columns.size()) {
    throw std::logic_error("Table::add: " + std::to_string(row.size()) + " values for " +
                           std::to_string(columns.size()) + " columns");
  }
  rows.push_back(std::move(row));
}

void Table::write(const std::filesystem::path& file) const {
  std::ostringstream out;
  for (std::size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << columns[c];
  out << '\n' << std::setprecision(10);
  for (const auto& r : rows) {
    for (std::size_t c = 0; c < r.size(); ++c) {
      if (c) out << ',';
      if (std::isfinite(r[c])) out << r[c];
    }
    out << '\n';
  }
  io::write_file_atomically(file, out.str());
}

std::string plot(const std::string& gnuplot, const std::filesystem::path& dir,
                 const std::string& stem, const std::string& body, PlotSize size) {
  const auto script = dir / (stem + ".gp");
  {
    std::ostringstream gp;
    gp << "# Draws " << stem << ".png / .svg from " << stem << ".csv (nsbridge figures).\n"
       << "data = '" << stem << ".csv'\n"
       << "set datafile separator ','\nset datafile columnheaders\nset grid\n"
       << body << '\n';
    io::write_file_atomically(script, gp.str());
  }
  return io::render_gnuplot(gnuplot, dir, stem, {size.width, size.height, ",10"});
}

}  // namespace nsb::paper_figures
