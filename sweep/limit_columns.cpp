#include "sweep/limit_columns.hpp"

#include "sweep/csv.hpp"

#include <algorithm>
#include <fstream>
#include <map>
#include <utility>

namespace nsb::sweep {

namespace {

// name -> (exceeded cell, margin cell) of one run.
using RunLimits = std::map<std::string, std::pair<std::string, std::string>>;

// The limit states of one run's file, and their names in file order.
RunLimits read_run(const std::filesystem::path& file, std::vector<std::string>& order) {
  RunLimits out;
  std::ifstream in(file);
  std::string line;
  if (!in || !std::getline(in, line)) return out;  // no file: no limit states
  while (std::getline(in, line)) {
    const std::vector<std::string> f = csv_fields(line);
    if (f.size() != 3) continue;
    order.push_back(f[0]);
    out[f[0]] = {f[1], f[2]};
  }
  return out;
}

// Inserts `cells` before the last field of a CSV line (wall_s, a number without commas).
void insert_before_last(std::string& line, const std::string& cells) {
  const std::size_t comma = line.rfind(',');
  if (comma == std::string::npos) return;
  line.insert(comma, cells);
}

}  // namespace

std::string limit_states_csv(const runs::Digest& digest) {
  std::string out = "name,exceeded,margin\n";
  for (const auto& v : digest.limit_states) {
    out.append(csv_quote(v.name)).append(v.exceeded ? ",1," : ",0,");
    io::append_csv_number(out, v.margin);
    out += '\n';
  }
  return out;
}

void add_limit_columns(std::string& header, std::vector<std::optional<std::string>>& rows,
                       const std::vector<std::filesystem::path>& run_dirs) {
  std::vector<std::string> names;
  std::vector<RunLimits> runs(rows.size());
  for (std::size_t i = 0; i < rows.size() && i < run_dirs.size(); ++i) {
    if (!rows[i]) continue;
    std::vector<std::string> order;
    runs[i] = read_run(run_dirs[i] / "limit_states.csv", order);
    for (const auto& n : order) {
      if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
    }
  }
  if (names.empty()) return;
  std::string columns;
  for (const auto& n : names) {
    columns.append(",").append(csv_quote(n + "_exceeded"));
    columns.append(",").append(csv_quote(n + "_margin"));
  }
  insert_before_last(header, columns);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (!rows[i]) continue;
    std::string cells;
    for (const auto& n : names) {
      const auto it = runs[i].find(n);
      if (it == runs[i].end()) {
        cells.append(",,");
      } else {
        cells.append(",").append(it->second.first).append(",").append(it->second.second);
      }
    }
    insert_before_last(*rows[i], cells);
  }
}

}  // namespace nsb::sweep
