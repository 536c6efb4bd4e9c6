#include "paper-figures/plot.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
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
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write " + file.string());
  for (std::size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << columns[c];
  out << '\n' << std::setprecision(10);
  for (const auto& r : rows) {
    for (std::size_t c = 0; c < r.size(); ++c) {
      if (c) out << ',';
      if (std::isfinite(r[c])) out << r[c];
    }
    out << '\n';
  }
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

namespace {

// Quotes a path for the POSIX shell.
std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char ch : s) out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return out + "'";
}

}  // namespace

std::string plot(const std::string& gnuplot, const std::filesystem::path& dir,
                 const std::string& stem, const std::string& body, PlotSize size) {
  const auto script = dir / (stem + ".gp");
  {
    std::ofstream gp(script);
    gp << "# Draws " << stem << ".png / .svg from " << stem << ".csv (nsbridge figures).\n"
       << "data = '" << stem << ".csv'\n"
       << "set datafile separator ','\nset datafile columnheaders\nset grid\n"
       << body << '\n';
    if (!gp) return "cannot write " + script.string();
  }
  const struct {
    const char* terminal;
    const char* ext;
  } outputs[2] = {{"pngcairo", "png"}, {"svg", "svg"}};
  for (const auto& o : outputs) {
    std::ostringstream cmd;
    cmd << "cd " << shell_quote(dir.string()) << " && " << shell_quote(gnuplot) << " -e "
        << shell_quote(std::string("set terminal ") + o.terminal + " size " +
                       std::to_string(size.width) + "," + std::to_string(size.height) +
                       " font ',10'; set output '" + stem + "." + o.ext + "'")
        << ' ' << shell_quote(stem + ".gp") << " > " << shell_quote(stem + "." + o.ext + ".log")
        << " 2>&1";
    if (std::system(cmd.str().c_str()) != 0) {
      return stem + "." + o.ext + ": gnuplot failed (see " + stem + "." + o.ext + ".log)";
    }
    std::error_code ec;
    std::filesystem::remove(dir / (stem + "." + o.ext + ".log"), ec);
  }
  return {};
}

}  // namespace nsb::paper_figures
