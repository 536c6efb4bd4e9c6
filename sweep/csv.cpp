#include "sweep/csv.hpp"

#include <unistd.h>

#include <fstream>
#include <stdexcept>
#include <system_error>

namespace nsb::sweep {

std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> out(1);
  std::vector<bool> was_quoted(1, false);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char ch = line[i];
    if (quoted) {
      if (ch == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        out.back() += '"';
        ++i;
      } else if (ch == '"') {
        quoted = false;
      } else {
        out.back() += ch;
      }
    } else if (ch == '"') {
      quoted = true;
      was_quoted.back() = true;
    } else if (ch == ',') {
      out.emplace_back();
      was_quoted.push_back(false);
    } else if (ch != '\r') {
      out.back() += ch;
    }
  }
  for (std::size_t k = 0; k < out.size(); ++k) {
    if (was_quoted[k]) continue;
    auto& f = out[k];
    const auto b = f.find_first_not_of(" \t");
    const auto e = f.find_last_not_of(" \t");
    f = b == std::string::npos ? std::string() : f.substr(b, e - b + 1);
  }
  return out;
}

std::string csv_quote(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + '"';
}

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

void write_file_atomically(const std::filesystem::path& file, const std::string& text) {
  std::string name = ".";
  name += file.filename().string();
  name += ".tmp";
  name += std::to_string(::getpid());
  const std::filesystem::path tmp = file.parent_path() / name;
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    out.close();
    if (!out) {
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw std::runtime_error(file.string() + ": cannot write");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, file, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw std::runtime_error(file.string() + ": cannot write (" + ec.message() + ")");
  }
}

}  // namespace nsb::sweep
