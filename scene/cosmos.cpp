#include "scene/cosmos.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string_view>

namespace nsb::scene {

namespace {

namespace fs = std::filesystem;

// The specification's value for an unknown integer or real header entry.
constexpr int kUnknown = -999;

// 1-based parameter numbers of the COSMOS v1.20 integer and real headers.
constexpr std::size_t kIntStage = 1, kIntSeries = 2, kIntUnit = 3, kIntYear = 40,
                      kIntMonth = 42, kIntDay = 43, kIntHour = 44, kIntMinute = 45,
                      kIntAzimuth = 54;
constexpr std::size_t kRealDtMs = 62;

// The file's lines, read once; messages count lines from 1.
struct Lines {
  std::string file;
  std::vector<std::string> text;
  std::size_t next = 0;  // index of the next line to read

  bool done() const { return next >= text.size(); }
  std::size_t number() const { return next + 1; }  // line number of the next line
  [[noreturn]] void fail(std::size_t line, const std::string& what) const {
    throw std::invalid_argument(file + ":" + std::to_string(line) + ": " + what);
  }
  const std::string& take(const std::string& what) {
    if (done()) fail(text.size() + 1, "the file ends before " + what);
    return text[next++];
  }
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

// A whole token as a number; nullopt when it is not one (or not finite).
std::optional<double> number(std::string_view s) {
  s = trim(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || ptr != s.data() + s.size() || !std::isfinite(v)) {
    return std::nullopt;
  }
  return v;
}

// The leading integer of a line ("  100 Integer-header values follow ...").
std::optional<long> leading_count(std::string_view line) {
  line = trim(line);
  const std::size_t end = line.find_first_of(" \t");
  const auto v = number(line.substr(0, end));
  if (!v || *v < 0 || *v != std::floor(*v) || *v > 1e8) return std::nullopt;
  return static_cast<long>(*v);
}

// A Fortran edit descriptor of a header or data block, "(10I8)", "(6F13.6)", "(8(1PE10.3))":
// values per line and field width.
struct FieldFormat {
  std::size_t per_line = 0, width = 0;
};

std::optional<FieldFormat> field_format(std::string_view line) {
  const std::string l = lower(line);
  const std::size_t f = l.find("format");
  if (f == std::string::npos) return std::nullopt;
  std::size_t i = l.find('(', f);
  if (i == std::string::npos) return std::nullopt;
  auto skip_spaces = [&] {
    while (i < l.size() && l[i] == ' ') ++i;
  };
  auto digits = [&]() -> std::size_t {
    std::size_t v = 0, n = 0;
    while (i < l.size() && std::isdigit(static_cast<unsigned char>(l[i])) && n < 6) {
      v = 10 * v + static_cast<std::size_t>(l[i] - '0');
      ++i;
      ++n;
    }
    return v;
  };
  ++i;
  skip_spaces();
  FieldFormat out;
  out.per_line = digits();
  if (out.per_line == 0) out.per_line = 1;
  skip_spaces();
  if (i < l.size() && l[i] == '(') ++i;
  if (l.compare(i, 2, "1p") == 0) i += 2;
  if (i >= l.size() || std::string_view("fegid").find(l[i]) == std::string_view::npos) {
    return std::nullopt;
  }
  ++i;
  out.width = digits();
  if (out.width == 0) return std::nullopt;
  return out;
}

// count values in fixed fields of the given format, from the lines that follow.
std::vector<double> read_fields(Lines& in, std::size_t count, const FieldFormat& fmt,
                                const std::string& what) {
  std::vector<double> out;
  out.reserve(count);
  while (out.size() < count) {
    const std::size_t line = in.number();
    const std::string& text = in.take(what + " (" + std::to_string(out.size()) + " of " +
                                      std::to_string(count) + " values read)");
    const std::size_t here = std::min(fmt.per_line, count - out.size());
    for (std::size_t k = 0; k < here; ++k) {
      const std::size_t from = k * fmt.width;
      const std::string_view field =
          from < text.size() ? std::string_view(text).substr(from, fmt.width) : "";
      const auto v = number(field);
      if (!v) {
        in.fail(line, what + ": field " + std::to_string(k + 1) + " (columns " +
                          std::to_string(from + 1) + "-" + std::to_string(from + fmt.width) +
                          ") is not a number: '" + std::string(trim(field)) + "'");
      }
      out.push_back(*v);
    }
  }
  return out;
}

// A header block: "<n> <what> values follow on <m> lines, Format= (...)", then the values.
std::vector<double> read_header_block(Lines& in, const std::string& what) {
  const std::size_t line = in.number();
  const std::string& head = in.take("the " + what + " header");
  const auto n = leading_count(head);
  const auto fmt = field_format(head);
  if (!n || lower(head).find(lower(what)) == std::string::npos || !fmt) {
    in.fail(line, "expected \"<n> " + what + " values follow on <m> lines, Format= (...)\", got '" +
                      std::string(trim(head)) + "'");
  }
  return read_fields(in, static_cast<std::size_t>(*n), *fmt, "the " + what + " values");
}

double param(const std::vector<double>& values, std::size_t number) {
  return number <= values.size() ? values[number - 1] : kUnknown;
}

bool horizontal_azimuth(int az) {
  return (az >= 0 && az <= 360) || az == 500 || az == 501 || az == 600 || az == 601 ||
         az == 700 || az == 701;
}

bool vertical_azimuth(int az) { return az >= 400 && az <= 402; }

// "(Format v01.20 with 13 text lines)" on line 1: the number of text lines.
std::optional<std::size_t> text_lines(std::string_view first) {
  const std::string l = lower(first);
  if (l.find("(format v") == std::string::npos) return std::nullopt;
  const std::size_t with = l.find("with");
  if (with == std::string::npos) return std::nullopt;
  const auto n = leading_count(std::string_view(l).substr(with + 4));
  if (!n || *n < 5 || l.find("text line", with) == std::string::npos) return std::nullopt;
  return static_cast<std::size_t>(*n);
}

std::string two(int v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%02d", v);
  return buf;
}

CosmosChannel read_channel(Lines& in) {
  CosmosChannel ch;
  ch.line = in.number();
  const std::string first = in.take("the text header");
  const auto n_text = text_lines(first);
  if (!n_text) {
    in.fail(ch.line, "not a COSMOS v1.20 channel: line 1 of a channel says \"(Format v01.20 "
                     "with <n> text lines)\"");
  }
  std::vector<std::string> text{first};
  for (std::size_t k = 1; k < *n_text; ++k) text.push_back(in.take("the text header"));
  if (text[4].size() > 25) {
    ch.station = std::string(trim(std::string_view(text[4]).substr(25, 9)));
    std::string code;
    for (const char c : ch.station) {
      if (!std::isspace(static_cast<unsigned char>(c))) code += c;
    }
    ch.station = code;
  }
  if (text[4].size() > 40) ch.station_name = std::string(trim(std::string_view(text[4]).substr(40)));

  const std::size_t int_line = in.number();
  const std::vector<double> ints = read_header_block(in, "Integer-header");
  const std::size_t real_line = in.number();
  const std::vector<double> reals = read_header_block(in, "Real-header");

  const int stage = static_cast<int>(param(ints, kIntStage));
  if (stage != 1 && stage != 2) {
    in.fail(int_line, "integer parameter 1 (processing stage) is " + std::to_string(stage) +
                          "; only V1 and V2 data (1, 2: acceleration in physical units) are read");
  }
  const int series = static_cast<int>(param(ints, kIntSeries));
  if (series != 1 && series != kUnknown) {
    in.fail(int_line, "integer parameter 2 (kind of series) is " + std::to_string(series) +
                          ", not 1 (acceleration)");
  }
  ch.unit_code = static_cast<int>(param(ints, kIntUnit));
  ch.unit = cosmos_acceleration_unit(ch.unit_code);
  if (ch.unit <= 0) {
    in.fail(int_line, "integer parameter 3 (physical unit) is " + std::to_string(ch.unit_code) +
                          ", not a unit of acceleration (2 g, 4 cm/s^2, 7 in/s^2, 10 gal, 11 "
                          "milli-g)");
  }
  ch.azimuth = static_cast<int>(param(ints, kIntAzimuth));
  ch.horizontal = horizontal_azimuth(ch.azimuth);
  if (!ch.horizontal && !vertical_azimuth(ch.azimuth)) {
    in.fail(int_line, "integer parameter 54 (sensor azimuth) is " + std::to_string(ch.azimuth) +
                          ": neither horizontal (0-360, 500, 501, 600, 601, 700, 701) nor "
                          "vertical (400-402)");
  }
  const int year = static_cast<int>(param(ints, kIntYear)),
            month = static_cast<int>(param(ints, kIntMonth)),
            day = static_cast<int>(param(ints, kIntDay)),
            hour = static_cast<int>(param(ints, kIntHour)),
            minute = static_cast<int>(param(ints, kIntMinute));
  if (year > 0 && month > 0 && day > 0 && hour >= 0 && minute >= 0) {
    ch.start = std::to_string(year) + "-" + two(month) + "-" + two(day) + "T" + two(hour) + ":" +
               two(minute);
  }
  const double dt_ms = param(reals, kRealDtMs);
  if (!(dt_ms > 0) || dt_ms == kUnknown) {
    in.fail(real_line, "real parameter 62 (sampling interval, ms) is " + std::to_string(dt_ms) +
                           ", not > 0");
  }
  ch.dt = dt_ms / 1000.0;

  const std::size_t comment_line = in.number();
  const std::string& comments = in.take("the comment count line");
  const auto n_comments = leading_count(comments);
  if (!n_comments || lower(comments).find("comment") == std::string::npos) {
    in.fail(comment_line, "expected \"<k> Comment line(s) follow ...\", got '" +
                              std::string(trim(comments)) + "'");
  }
  for (long k = 0; k < *n_comments; ++k) in.take("the comment lines");

  const std::size_t data_line = in.number();
  const std::string& data = in.take("the acceleration block");
  const auto npts = leading_count(data);
  const auto fmt = field_format(data);
  if (!npts || lower(data).find("acceleration") == std::string::npos || !fmt) {
    in.fail(data_line, "expected \"<npts> acceleration pts, ... Format=(...)\", got '" +
                           std::string(trim(data)) + "'");
  }
  if (*npts < static_cast<long>(models::kMinRecordSamples)) {
    in.fail(data_line, std::to_string(*npts) + " acceleration points; a record needs at least " +
                           std::to_string(models::kMinRecordSamples));
  }
  const std::vector<double> values =
      read_fields(in, static_cast<std::size_t>(*npts), *fmt, "the acceleration values");
  ch.record.source = in.file;
  ch.record.t.reserve(values.size());
  ch.record.a.reserve(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    ch.record.t.push_back(static_cast<double>(i) * ch.dt);
    ch.record.a.push_back(values[i] * ch.unit);
  }
  // The velocity and displacement blocks and the end-of-data line, up to the next channel.
  while (!in.done() && !text_lines(in.text[in.next])) ++in.next;
  return ch;
}

}  // namespace

double cosmos_acceleration_unit(int code) {
  switch (code) {
    case 2: return kStandardGravity;           // g
    case 4: return 0.01;                       // cm/s^2
    case 7: return 0.0254;                     // in/s^2 (1 in = 0.0254 m exactly)
    case 10: return 0.01;                      // gal = 1 cm/s^2
    case 11: return 1e-3 * kStandardGravity;   // milli-g
    default: return 0.0;
  }
}

bool is_cosmos_file(const fs::path& file) {
  std::ifstream in(file);
  std::string first;
  return in && std::getline(in, first) && lower(first).find("(format v") != std::string::npos;
}

std::vector<CosmosChannel> read_cosmos(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) {
    throw std::invalid_argument(file.string() + ": not a regular file; expected a COSMOS file");
  }
  std::ifstream stream(file);
  if (!stream) throw std::invalid_argument(file.string() + ": cannot open for reading");
  Lines in{file.string(), {}, 0};
  for (std::string line; std::getline(stream, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    in.text.push_back(std::move(line));
  }
  while (!in.text.empty() && trim(in.text.back()).empty()) in.text.pop_back();
  if (in.text.empty()) in.fail(1, "empty file");
  std::vector<CosmosChannel> out;
  while (!in.done()) out.push_back(read_channel(in));
  for (const auto& ch : out) models::validate_record(ch.record);
  return out;
}

}  // namespace nsb::scene
