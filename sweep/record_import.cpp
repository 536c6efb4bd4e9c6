#include "sweep/record_import.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "io/csv.hpp"
#include "io/files.hpp"
#include "scene/cosmos.hpp"
#include "scene/records.hpp"

namespace nsb::sweep {

namespace fs = std::filesystem;

namespace {

const char* const kSearchResults = "_SearchResults.csv";
const char* const kRsn = "Record Sequence Number";
const char* const kScale = "Scale Factor";
const char* const kH1 = "Horizontal-1 Acc. Filename";
const char* const kH2 = "Horizontal-2 Acc. Filename";
const char* const kVertical = "Vertical Acc. Filename";

std::string trimmed(std::string s) {
  const auto space = [](unsigned char c) { return std::isspace(c) != 0; };
  s.erase(s.begin(), std::find_if_not(s.begin(), s.end(), space));
  s.erase(std::find_if_not(s.rbegin(), s.rend(), space).base(), s.end());
  return s;
}

// A column name as a records.csv column: lower case, each run of other characters one '_'.
std::string slug(const std::string& name) {
  std::string out;
  for (const char ch : name) {
    const auto c = static_cast<unsigned char>(ch);
    if (std::isalnum(c)) {
      out += static_cast<char>(std::tolower(c));
    } else if (!out.empty() && out.back() != '_') {
      out += '_';
    }
  }
  while (!out.empty() && out.back() == '_') out.pop_back();
  return out;
}

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  if (!in && !in.eof()) throw std::invalid_argument(file.string() + ": cannot read");
  return s.str();
}

// A column name that does not clash with those already taken: name, name_2, name_3, ...
std::string unique_name(const std::string& name, std::set<std::string>& taken) {
  std::string out = name.empty() ? "column" : name;
  for (int k = 2; !taken.insert(out).second; ++k) out = name + "_" + std::to_string(k);
  return out;
}

std::string lower_ext(const fs::path& p) {
  std::string e = p.extension().string();
  std::transform(e.begin(), e.end(), e.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}

}  // namespace

ImportedSuite read_peer_search(const fs::path& dir) {
  const fs::path csv = dir / kSearchResults;
  std::error_code ec;
  if (!fs::is_regular_file(csv, ec)) {
    throw std::invalid_argument(csv.string() + ": no such file (a PEER search folder holds it)");
  }
  std::ifstream in(csv);
  if (!in) throw std::invalid_argument(csv.string() + ": cannot open for reading");
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) {
    if (!l.empty() && l.back() == '\r') l.pop_back();
    lines.push_back(std::move(l));
  }
  // The table's header: the first line whose fields name the RSN and the first component.
  std::size_t head = lines.size();
  std::vector<std::string> names;
  for (std::size_t i = 0; i < lines.size() && head == lines.size(); ++i) {
    names = io::csv_fields(lines[i]);
    for (auto& n : names) n = trimmed(n);
    if (std::find(names.begin(), names.end(), kRsn) != names.end() &&
        std::find(names.begin(), names.end(), kH1) != names.end()) {
      head = i;
    }
  }
  if (head == lines.size()) {
    throw std::invalid_argument(csv.string() + ": no table of records (a line naming the columns \"" +
                                kRsn + "\" and \"" + kH1 + "\")");
  }
  const std::string at_head = csv.string() + ":" + std::to_string(head + 1);
  auto column = [&](const char* name) {
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end()) {
      throw std::invalid_argument(at_head + ": no column \"" + std::string(name) + "\"");
    }
    return static_cast<std::size_t>(it - names.begin());
  };
  const std::size_t c_rsn = column(kRsn), c_scale = column(kScale), c_h1 = column(kH1),
                    c_h2 = column(kH2);

  ImportedSuite suite;
  suite.kind = "peer";
  std::set<std::string> taken{"rsn", "file_1", "file_2", "npts_1", "dt_1_s", "npts_2", "dt_2_s"};
  suite.header = {"rsn", "file_1", "file_2", "npts_1", "dt_1_s", "npts_2", "dt_2_s"};
  std::vector<std::size_t> kept;  // the metadata columns, in the table's order
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (k == c_rsn || k == c_h1 || k == c_h2 || names[k] == kVertical || names[k].empty()) continue;
    kept.push_back(k);
    suite.header.push_back(unique_name(slug(names[k]), taken));
  }

  std::set<long> seen;
  std::set<std::string> files_taken;
  for (std::size_t i = head + 1; i < lines.size(); ++i) {
    if (trimmed(lines[i]).empty()) break;  // the table ends at its first blank line
    const std::string where = csv.string() + ":" + std::to_string(i + 1);
    std::vector<std::string> row = io::csv_fields(lines[i]);
    for (auto& cell : row) cell = trimmed(cell);
    if (row.size() < names.size()) {
      throw std::invalid_argument(where + ": " + std::to_string(row.size()) + " fields, the header has " +
                                  std::to_string(names.size()));
    }
    const std::string& rsn_text = row[c_rsn];
    char* end = nullptr;
    const long rsn = std::strtol(rsn_text.c_str(), &end, 10);
    if (rsn_text.empty() || *end != '\0' || rsn <= 0) {
      throw std::invalid_argument(where + ": column " + kRsn + ": '" + rsn_text +
                                  "' is not a positive integer");
    }
    if (!seen.insert(rsn).second) {
      throw std::invalid_argument(where + ": RSN " + rsn_text + " appears twice");
    }
    const std::string& scale_text = row[c_scale];
    const double scale = std::strtod(scale_text.c_str(), &end);
    if (scale_text.empty() || *end != '\0' || !std::isfinite(scale) || scale <= 0) {
      throw std::invalid_argument(where + ": column " + kScale + ": '" + scale_text +
                                  "' is not a number > 0");
    }
    ImportedRecord rec;
    rec.cells = {rsn_text};
    std::vector<std::string> stats;
    for (const std::size_t c : {c_h1, c_h2}) {
      const std::string& name = row[c];
      const std::string col = names[c];
      if (name.empty() || name.find_first_not_of('-') == std::string::npos) {
        throw std::invalid_argument(where + ": RSN " + rsn_text + ": column " + col +
                                    " is empty: a suite record pairs two horizontal components");
      }
      if (fs::path(name).has_parent_path() || name == "." || name == "..") {
        throw std::invalid_argument(where + ": RSN " + rsn_text + ": column " + col + ": '" + name +
                                    "' is not a file name in the search folder");
      }
      const fs::path file = dir / name;
      if (!fs::is_regular_file(file, ec)) {
        throw std::invalid_argument(where + ": RSN " + rsn_text + ": column " + col +
                                    ": no such file " + file.string());
      }
      if (!files_taken.insert(name).second) {
        throw std::invalid_argument(where + ": RSN " + rsn_text + ": column " + col + ": " + name +
                                    " is named twice");
      }
      models::Record r;
      try {
        r = scene::read_at2(file);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(where + ": RSN " + rsn_text + ": " + e.what());
      }
      rec.cells.push_back(name);
      stats.push_back(std::to_string(r.t.size()));
      stats.push_back(io::csv_number(r.t[1] - r.t[0]));
      rec.files.emplace_back(name, read_bytes(file));
    }
    rec.cells.insert(rec.cells.end(), stats.begin(), stats.end());
    for (const std::size_t k : kept) rec.cells.push_back(row[k]);
    suite.records.push_back(std::move(rec));
  }
  if (suite.records.empty()) {
    throw std::invalid_argument(at_head + ": the table holds no record");
  }
  return suite;
}

ImportedSuite read_cosmos_folder(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw std::invalid_argument(dir.string() + ": not a folder");
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string ext = lower_ext(e.path());
    if ((ext == ".v1" || ext == ".v2" || ext == ".v1c" || ext == ".v2c") && e.is_regular_file()) {
      files.push_back(e.path());
    }
  }
  if (ec) throw std::invalid_argument(dir.string() + ": cannot read: " + ec.message());
  if (files.empty()) {
    throw std::invalid_argument(dir.string() + ": holds neither " + kSearchResults +
                                " (a PEER search) nor COSMOS files (.V1, .V2, .V1c, .V2c)");
  }
  std::sort(files.begin(), files.end());

  // A channel with where it came from: the file and its channel number in the file.
  struct Channel {
    scene::CosmosChannel data;
    fs::path file;
    std::size_t index = 0;
  };
  std::map<std::string, std::vector<Channel>> groups;  // by station and start
  for (const auto& f : files) {
    std::vector<scene::CosmosChannel> channels = scene::read_cosmos(f);
    for (std::size_t k = 0; k < channels.size(); ++k) {
      if (!channels[k].horizontal) continue;
      const std::string key = channels[k].station + "|" + channels[k].start;
      groups[key].push_back({std::move(channels[k]), f, k + 1});
    }
  }
  if (groups.empty()) {
    throw std::invalid_argument(dir.string() + ": the COSMOS files hold no horizontal channel");
  }

  ImportedSuite suite;
  suite.kind = "cosmos";
  suite.header = {"name",       "file_1",    "file_2",    "station",   "station_name",
                  "start",      "azimuth_1", "azimuth_2", "source_1",  "source_2",
                  "unit_code_1", "unit_code_2", "npts_1",  "dt_1_s",    "npts_2",
                  "dt_2_s"};
  std::set<std::string> names;
  for (auto& [key, channels] : groups) {
    const scene::CosmosChannel& first = channels.front().data;
    const std::string who = "station '" + first.station + "', start '" + first.start + "'";
    if (channels.size() != 2) {
      std::string where;
      for (const auto& c : channels) {
        where += " " + c.file.string() + ":" + std::to_string(c.data.line);
      }
      throw std::invalid_argument(dir.string() + ": " + who + ": " +
                                  std::to_string(channels.size()) +
                                  " horizontal channels (a suite record pairs two):" + where);
    }
    std::string name = first.station.empty() ? channels.front().file.stem().string() : first.station;
    std::string stamp;
    for (const char c : first.start) {
      if (std::isdigit(static_cast<unsigned char>(c)) || c == 'T') stamp += c;
    }
    if (!stamp.empty()) name += "_" + stamp;
    if (!names.insert(name).second) {
      throw std::invalid_argument(dir.string() + ": two records are named " + name);
    }
    ImportedRecord rec;
    rec.cells = {name};
    std::vector<std::string> files_of;
    for (const auto& c : channels) {
      const std::string file = c.file.stem().string() + "_c" + std::to_string(c.index) + ".csv";
      std::string text = "t [s],a [m/s^2]\n";
      for (std::size_t i = 0; i < c.data.record.t.size(); ++i) {
        text += io::csv_number(c.data.record.t[i]) + "," + io::csv_number(c.data.record.a[i]) + "\n";
      }
      rec.cells.push_back(file);
      rec.files.emplace_back(file, std::move(text));
    }
    const scene::CosmosChannel& second = channels.back().data;
    rec.cells.insert(rec.cells.end(),
                     {first.station, first.station_name, first.start, std::to_string(first.azimuth),
                      std::to_string(second.azimuth), channels.front().file.filename().string(),
                      channels.back().file.filename().string(), std::to_string(first.unit_code),
                      std::to_string(second.unit_code), std::to_string(first.record.t.size()),
                      io::csv_number(first.dt), std::to_string(second.record.t.size()),
                      io::csv_number(second.dt)});
    suite.records.push_back(std::move(rec));
  }
  return suite;
}

ImportedSuite read_record_library(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw std::invalid_argument(dir.string() + ": not a folder");
  if (fs::exists(dir / kSearchResults, ec)) return read_peer_search(dir);
  return read_cosmos_folder(dir);
}

std::string suite_csv(const ImportedSuite& suite) {
  std::string out;
  auto row = [&](const std::vector<std::string>& cells) {
    for (std::size_t k = 0; k < cells.size(); ++k) {
      if (k > 0) out += ',';
      out += io::csv_quote(cells[k]);
    }
    out += '\n';
  };
  row(suite.header);
  for (const auto& r : suite.records) row(r.cells);
  return out;
}

void write_suite(const ImportedSuite& suite, const fs::path& out) {
  io::FileSet set(out);
  for (const auto& r : suite.records) {
    for (const auto& [name, text] : r.files) set.add(name, text);
  }
  set.add("records.csv", suite_csv(suite));
  set.commit();
}

}  // namespace nsb::sweep
