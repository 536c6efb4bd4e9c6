#include "lcp/siconos_format.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

namespace nsb::lcp {

FormatError::FormatError(const std::string& f, int l, const std::string& what)
    : std::invalid_argument(l > 0 ? f + ":" + std::to_string(l) + ": " + what : f + ": " + what),
      file(f),
      line(l) {}

namespace {

struct Line {
  int number = 0;
  std::vector<std::string> tokens;
};

class Reader {
 public:
  Reader(std::istream& in, std::string name) : name_(std::move(name)) {
    std::string text;
    int number = 0;
    while (std::getline(in, text)) {
      ++number;
      Line l;
      l.number = number;
      std::istringstream s(text);
      std::string tok;
      while (s >> tok) l.tokens.push_back(tok);
      if (!l.tokens.empty()) lines_.push_back(std::move(l));
    }
    last_line_ = number;
  }

  [[noreturn]] void fail(int line, const std::string& what) const {
    throw FormatError(name_, line, what);
  }

  bool empty() const { return lines_.empty(); }
  std::size_t line_count() const { return lines_.size(); }
  const Line& line(std::size_t i) const { return lines_[i]; }
  int last_line() const { return last_line_; }

 private:
  std::string name_;
  std::vector<Line> lines_;
  int last_line_ = 0;
};

long parse_integer(const Reader& r, int line, const std::string& tok, const std::string& what) {
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(tok.c_str(), &end, 10);
  if (end == tok.c_str() || *end != '\0' || errno != 0)
    r.fail(line, "found '" + tok + "'; expected " + what + " (an integer)");
  return v;
}

double parse_number(const Reader& r, int line, const std::string& tok, const std::string& what) {
  char* end = nullptr;
  const double v = std::strtod(tok.c_str(), &end);
  if (end == tok.c_str() || *end != '\0')
    r.fail(line, "found '" + tok + "'; expected " + what + " (a number)");
  if (!std::isfinite(v)) r.fail(line, what + " is '" + tok + "'; expected a finite number");
  return v;
}

}  // namespace

Problem parse_siconos_lcp(std::istream& in, const std::string& name) {
  const Reader r(in, name);
  if (r.empty()) r.fail(1, "the file is empty; expected the problem size n on the first line");

  // Header: six integers n, storage, n, n, n, n, possibly over several lines.
  static const char* const kHeader[] = {"the problem size n", "the storage type (0 = dense)",
                                        "the number of rows n", "the number of columns n",
                                        "the number of rows n", "the number of columns n"};
  long header[6] = {0, 0, 0, 0, 0, 0};
  std::size_t li = 0;
  std::size_t ti = 0;
  for (int k = 0; k < 6; ++k) {
    if (li >= r.line_count())
      r.fail(r.last_line(), std::string("unexpected end of file; expected ") + kHeader[k]);
    const Line& l = r.line(li);
    header[k] = parse_integer(r, l.number, l.tokens[ti], kHeader[k]);
    if (k == 0 && header[0] < 0)
      r.fail(l.number, "n = " + l.tokens[ti] + "; expected a size >= 0");
    if (k == 1 && header[1] != 0) {
      if (header[1] == 1)
        r.fail(l.number, "storage type 1 (sparse block) is not supported; expected 0 (dense): "
                         "use the dense file of the same problem");
      r.fail(l.number, "storage type " + l.tokens[ti] + "; expected 0 (dense)");
    }
    if (k >= 2 && header[k] != header[0])
      r.fail(l.number, "matrix size " + l.tokens[ti] + " differs from n = " +
                           std::to_string(header[0]) + "; expected " + kHeader[k] + " = " +
                           std::to_string(header[0]));
    if (++ti == l.tokens.size()) {
      ti = 0;
      ++li;
    }
  }
  if (ti != 0)
    r.fail(r.line(li).number, "found '" + r.line(li).tokens[ti] +
                                  "' after the six header integers; expected the end of the line");

  const auto n = static_cast<Eigen::Index>(header[0]);
  Problem p;
  p.M.resize(n, n);
  p.q.resize(n);
  const auto row_count = [&](const Line& l, const std::string& what) {
    if (static_cast<Eigen::Index>(l.tokens.size()) != n)
      r.fail(l.number, what + " has " + std::to_string(l.tokens.size()) + " entries; expected n = " +
                           std::to_string(n));
  };
  for (Eigen::Index j = 0; j < n; ++j, ++li) {
    const std::string what = "column " + std::to_string(j + 1) + " of M";
    if (li >= r.line_count())
      r.fail(r.last_line(), "unexpected end of file; expected " + what + " (" +
                                std::to_string(n) + " numbers on one line)");
    const Line& l = r.line(li);
    row_count(l, what);
    for (Eigen::Index i = 0; i < n; ++i)
      p.M(i, j) = parse_number(r, l.number, l.tokens[static_cast<std::size_t>(i)],
                               "M(" + std::to_string(i + 1) + ", " + std::to_string(j + 1) + ")");
  }
  if (n > 0) {
    if (li >= r.line_count())
      r.fail(r.last_line(),
             "unexpected end of file; expected q (" + std::to_string(n) + " numbers on one line)");
    const Line& l = r.line(li);
    row_count(l, "q");
    for (Eigen::Index i = 0; i < n; ++i)
      p.q(i) = parse_number(r, l.number, l.tokens[static_cast<std::size_t>(i)],
                            "q(" + std::to_string(i + 1) + ")");
  }
  return p;
}

Problem read_siconos_lcp(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw FormatError(file.string(), 0, "cannot open the file for reading");
  return parse_siconos_lcp(in, file.string());
}

}  // namespace nsb::lcp
