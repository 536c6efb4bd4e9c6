#include "sweep/csv.hpp"

#include <fstream>
#include <stdexcept>

namespace nsb::sweep {

std::size_t Table::column(const std::string& name) const {
  for (std::size_t k = 0; k < header.size(); ++k) {
    if (header[k] == name) return k;
  }
  throw std::invalid_argument("no column \"" + name + "\"");
}

Table read_csv(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::invalid_argument(file.string() + ": cannot read");
  Table t;
  std::string line;
  int lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    auto fields = csv_fields(line);
    if (t.header.empty()) {
      t.header = std::move(fields);
    } else if (fields.size() != t.header.size()) {
      throw std::invalid_argument(file.string() + ":" + std::to_string(lineno) + ": " +
                                  std::to_string(fields.size()) + " fields, the header has " +
                                  std::to_string(t.header.size()));
    } else {
      t.rows.push_back(std::move(fields));
    }
  }
  if (t.header.empty()) throw std::invalid_argument(file.string() + ": empty");
  return t;
}

}  // namespace nsb::sweep
