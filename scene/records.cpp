// Ground-motion record files: the PEER NGA .AT2, two-column and CSV readers (scene/records.hpp).
// Formats: docs/ground-motions.md.
#include "scene/records.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <istream>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace nsb::scene {

using models::kMinRecordSamples;
using models::Record;

namespace {

// Longest AT2 line 4 read ('NPTS= n, DT= dt SEC' and the filter data some files append).
constexpr std::size_t kMaxHeaderLine = 512;

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw std::invalid_argument(where + ": " + what);
}

std::string at(const std::string& file, std::size_t line) {
  return file + ":" + std::to_string(line);
}

// Strict conversion of a whole token to double: no trailing characters, finite.
// Subnormal values are read as they are; a value beyond the range of a double (1e400, or
// 1e-400, which would silently become 0) is refused by name.
double parse_number(std::string_view tok, const std::string& file, std::size_t line) {
  std::string_view s = tok;
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec == std::errc::result_out_of_range && ptr == s.data() + s.size()) {
    fail(at(file, line), "value '" + std::string(tok) + "' is outside the range of a double");
  }
  if (ec != std::errc() || ptr != s.data() + s.size() || s.empty()) {
    fail(at(file, line), "non-numeric token '" + std::string(tok) + "'");
  }
  if (!std::isfinite(v)) fail(at(file, line), "value '" + std::string(tok) + "' is not finite");
  return v;
}

std::vector<std::string_view> split_ws(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    std::size_t j = i;
    while (j < s.size() && !std::isspace(static_cast<unsigned char>(s[j]))) ++j;
    if (j > i) out.push_back(s.substr(i, j - i));
    i = j;
  }
  return out;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// Only regular files are read: a FIFO or a device could block or never end.
std::ifstream open_or_throw(const std::filesystem::path& file) {
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (ec || !std::filesystem::exists(status)) fail(file.string(), "record file does not exist");
  if (!std::filesystem::is_regular_file(status)) {
    fail(file.string(), "not a regular file; expected a record file");
  }
  std::ifstream in(file);
  if (!in) fail(file.string(), "cannot open the record file for reading");
  return in;
}

void check_unit(double unit, const std::string& file, const char* name) {
  if (!(unit > 0.0) || !std::isfinite(unit)) {
    fail(file, std::string(name) + " must be finite and > 0");
  }
}

// Appends one sample, checking that time increases strictly.
void push_sample(Record& r, double t, double a, const std::string& file,
                 std::size_t line) {
  if (!r.t.empty() && !(t > r.t.back())) {
    std::ostringstream os;
    os.precision(10);
    os << "time " << t << " is not greater than the previous time " << r.t.back()
       << " (time must increase strictly)";
    fail(at(file, line), os.str());
  }
  r.t.push_back(t);
  r.a.push_back(a);
}

void check_size(const Record& r, const std::string& file) {
  if (r.t.size() < kMinRecordSamples) {
    fail(file, "a record needs at least " + std::to_string(kMinRecordSamples) +
                            " samples, found " + std::to_string(r.t.size()));
  }
}

// The columns of a text record: fields per line and which hold t and a.
struct Columns {
  std::size_t count = 2;
  std::size_t t = 0, a = 1;
};

// How a text record is laid out: how a line splits into fields, the header that names the
// columns (nullptr: none, two columns t and a), and the message for a line of `found` fields.
struct TextFormat {
  std::vector<std::string_view> (*split)(std::string_view line);
  Columns (*header)(const std::vector<std::string_view>& fields, std::string_view line,
                    const std::string& file, std::size_t line_no);
  std::string (*wrong_count)(std::size_t expected, std::size_t found);
};

// The samples of a text record (two-column or CSV): blank lines and '#' comments are skipped,
// the first other line is the header when the format has one, every further line a sample.
Record read_text_record(std::istream& in, const std::string& file, double unit,
                        const TextFormat& format) {
  check_unit(unit, file, "unit");
  Record r;
  r.source = file;
  Columns columns;
  bool need_header = format.header != nullptr;
  std::string line;
  std::size_t line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const auto s = trim(line);
    if (s.empty() || s.front() == '#') continue;
    const auto fields = format.split(s);
    if (need_header) {
      columns = format.header(fields, s, file, line_no);
      need_header = false;
      continue;
    }
    if (fields.size() != columns.count) {
      fail(at(file, line_no), format.wrong_count(columns.count, fields.size()));
    }
    const double t = parse_number(fields[columns.t], file, line_no);
    const double a = parse_number(fields[columns.a], file, line_no);
    push_sample(r, t, a * unit, file, line_no);
  }
  if (need_header) fail(file, "empty CSV file: expected a header line 't,a'");
  check_size(r, file);
  return r;
}

std::vector<std::string_view> split_csv(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = s.find(',', start);
    out.push_back(trim(s.substr(start, comma == std::string_view::npos ? comma : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

// CSV header: columns named t (or time) and a (or acceleration); with exactly two columns of
// other names, the first is time and the second acceleration.
Columns csv_header(const std::vector<std::string_view>& fields, std::string_view line,
                   const std::string& file, std::size_t line_no) {
  Columns c;
  c.count = fields.size();
  bool found_t = false, found_a = false;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    std::string name(fields[i]);
    std::transform(name.begin(), name.end(), name.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    if (name == "t" || name == "time") { c.t = i; found_t = true; }
    if (name == "a" || name == "acceleration") { c.a = i; found_a = true; }
  }
  if (!(found_t && found_a) && c.count != 2) {
    fail(at(file, line_no), "header must name the columns 't' and 'a', found '" +
                                std::string(line) + "'");
  }
  if (!(found_t && found_a)) { c.t = 0; c.a = 1; }
  return c;
}

}  // namespace

Record read_at2(const std::filesystem::path& file, double g) {
  check_unit(g, file.string(), "g");
  std::ifstream in = open_or_throw(file);
  return read_at2(in, file.string(), g);
}

Record read_at2(std::istream& in, const std::string& file, double g) {
  check_unit(g, file, "g");
  std::string line;
  std::size_t line_no = 0;
  // Lines 1-3: free text (database, event and station, units).
  for (int i = 0; i < 3; ++i) {
    if (!std::getline(in, line)) fail(at(file, line_no + 1), "missing AT2 header line");
    ++line_no;
  }
  if (!std::getline(in, line)) fail(at(file, 4), "missing the 'NPTS= n, DT= dt SEC' line");
  ++line_no;
  // Line 4 in both PEER forms: "NPTS=  1559, DT= .02000 SEC" and
  // "NPTS=   8773, DT=   .0050 SEC,   4 POLE @ ..." (filter data may follow).
  // PEER header lines are about 80 characters; a longer line is not one, and std::regex's
  // recursive matcher is kept away from unbounded input.
  if (line.size() > kMaxHeaderLine) {
    fail(at(file, 4), "line 4 has " + std::to_string(line.size()) + " characters; expected "
                      "'NPTS= <count>, DT= <step> SEC' (at most " +
                      std::to_string(kMaxHeaderLine) + ")");
  }
  static const std::regex header(R"(NPTS\s*=\s*([0-9]+)\s*,\s*DT\s*=\s*([-+0-9.eE]+))",
                                 std::regex::icase);
  std::smatch m;
  if (!std::regex_search(line, m, header)) {
    fail(at(file, 4), "expected 'NPTS= <count>, DT= <step> SEC', found '" +
                          std::string(trim(line)) + "'");
  }
  const std::string npts_s = m[1].str();
  const std::string dt_s = m[2].str();
  // At most 9 digits: far more samples than any record, and no overflow in the conversion.
  if (npts_s.size() > 9) fail(at(file, 4), "NPTS = " + npts_s + " is too large");
  const long npts = std::stol(npts_s);
  const double dt = parse_number(dt_s, file, 4);
  if (npts < static_cast<long>(kMinRecordSamples)) {
    fail(at(file, 4), "NPTS must be >= " + std::to_string(kMinRecordSamples));
  }
  if (!(dt > 0.0)) fail(at(file, 4), "DT must be > 0");
  Record r;
  r.source = file;
  std::size_t last_data_line = 4;
  while (std::getline(in, line)) {
    ++line_no;
    for (auto tok : split_ws(line)) {
      const double v = parse_number(tok, file, line_no);
      if (static_cast<long>(r.a.size()) >= npts) {
        fail(at(file, line_no), "more values than NPTS = " + npts_s + " (line 4)");
      }
      r.a.push_back(v * g);
      last_data_line = line_no;
    }
  }
  if (static_cast<long>(r.a.size()) != npts) {
    fail(at(file, last_data_line), "NPTS = " + npts_s + " (line 4) but " +
                                       std::to_string(r.a.size()) + " values found");
  }
  r.t.resize(r.a.size());
  for (std::size_t i = 0; i < r.t.size(); ++i) r.t[i] = static_cast<double>(i) * dt;
  return r;
}

Record read_two_column(const std::filesystem::path& file, double unit) {
  check_unit(unit, file.string(), "unit");
  std::ifstream in = open_or_throw(file);
  return read_two_column(in, file.string(), unit);
}

Record read_two_column(std::istream& in, const std::string& file, double unit) {
  static const TextFormat format{
      split_ws, nullptr, [](std::size_t, std::size_t found) {
        return "expected two numbers 't a', found " + std::to_string(found) + " fields";
      }};
  return read_text_record(in, file, unit, format);
}

Record read_csv(const std::filesystem::path& file, double unit) {
  check_unit(unit, file.string(), "unit");
  std::ifstream in = open_or_throw(file);
  return read_csv(in, file.string(), unit);
}

Record read_csv(std::istream& in, const std::string& file, double unit) {
  static const TextFormat format{
      split_csv, csv_header, [](std::size_t expected, std::size_t found) {
        return "expected " + std::to_string(expected) + " comma-separated fields, found " +
               std::to_string(found);
      }};
  return read_text_record(in, file, unit, format);
}

}  // namespace nsb::scene
