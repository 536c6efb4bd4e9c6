#include "sweep/suites.hpp"

#include <algorithm>
#include <cctype>
#include <set>
#include <stdexcept>

#include "sweep/csv.hpp"

namespace nsb::sweep {

namespace fs = std::filesystem;

namespace {

// The index of a column, or header.size() when absent.
std::size_t find_column(const Table& t, const std::string& name) {
  const auto it = std::find(t.header.begin(), t.header.end(), name);
  return static_cast<std::size_t>(it - t.header.begin());
}

}  // namespace

std::vector<SuiteRecord> read_suite(const fs::path& csv, const std::vector<std::string>& columns) {
  const Table t = read_csv(csv);
  std::vector<std::size_t> index;
  for (const auto& c : columns) {
    const std::size_t k = find_column(t, c);
    if (k == t.header.size()) {
      throw std::invalid_argument(csv.string() + ": no column \"" + c +
                                  "\" (components name "
                                  "the columns that hold the record files)");
    }
    index.push_back(k);
  }
  const std::size_t name = find_column(t, "name"), rsn = find_column(t, "rsn");
  const fs::path dir = csv.parent_path();
  std::vector<SuiteRecord> out;
  std::set<std::string> names;
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    const auto& row = t.rows[r];
    const std::string where = csv.string() + ": row " + std::to_string(r + 1);
    SuiteRecord rec;
    for (std::size_t i = 0; i < index.size(); ++i) {
      const std::string& cell = row[index[i]];
      if (cell.empty()) throw std::invalid_argument(where + ": column " + columns[i] + " is empty");
      const fs::path file = (dir / cell).lexically_normal();
      std::error_code ec;
      if (!fs::is_regular_file(file, ec)) {
        throw std::invalid_argument(where + ": column " + columns[i] + ": no such file " +
                                    file.string());
      }
      rec.files.push_back(file.string());
    }
    rec.name = name < t.header.size()  ? row[name]
               : rsn < t.header.size() ? "RSN" + row[rsn]
                                       : fs::path(rec.files.front()).stem().string();
    if (rec.name.empty() || !names.insert(rec.name).second) {
      throw std::invalid_argument(where + ": record name \"" + rec.name +
                                  "\" is empty or appears twice");
    }
    out.push_back(std::move(rec));
  }
  if (out.empty()) throw std::invalid_argument(csv.string() + ": holds no record");
  return out;
}

std::vector<SuiteRecord> read_folder(const fs::path& folder) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) {
    throw std::invalid_argument(folder.string() + ": not a folder");
  }
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(folder, ec)) {
    std::string ext = e.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    if (ext == ".at2" && e.is_regular_file()) files.push_back(e.path());
  }
  if (ec) throw std::invalid_argument(folder.string() + ": cannot read: " + ec.message());
  if (files.empty()) throw std::invalid_argument(folder.string() + ": holds no .AT2 file");
  std::sort(files.begin(), files.end(),
            [](const fs::path& a, const fs::path& b) { return a.filename() < b.filename(); });
  std::vector<SuiteRecord> out;
  for (const auto& f : files) {
    out.push_back({f.stem().string(), {f.lexically_normal().string()}});
  }
  return out;
}

}  // namespace nsb::sweep
