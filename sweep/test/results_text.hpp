// What the sweep tests compare: results.csv without its last column (wall_s), the only one
// that depends on the machine.
#pragma once

#include "sweep/csv.hpp"

#include <filesystem>
#include <string>

namespace nsb::sweep::test {

inline std::string without_wall_time(const std::filesystem::path& results) {
  const Table t = read_csv(results);
  std::string out;
  for (const auto& row : t.rows) {
    for (std::size_t k = 0; k + 1 < row.size(); ++k) out += row[k] + ",";
    out += "\n";
  }
  return out;
}

}  // namespace nsb::sweep::test
