#include "lcp/siconos_format.hpp"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <new>
#include <sstream>
#include <vector>

namespace nsb::lcp {

FormatError::FormatError(const std::string& f, int l, const std::string& what)
    : std::invalid_argument(l > 0 ? f + ":" + std::to_string(l) + ": " + what : f + ": " + what),
      file(f),
      line(l) {}

namespace {

// The largest n read: M alone then takes 8 n^2 bytes = 8 GB, and min_data_bytes(n) cannot
// overflow.
constexpr long kMaxSize = 32768;

struct Line {
  int number = 0;
  std::vector<std::string> tokens;
};

// Reads the stream one non-blank line at a time, only as far as the parser asks: a file is
// never read beyond q, whatever follows it.
class Reader {
 public:
  Reader(std::istream& in, std::string name) : in_(in), name_(std::move(name)) {}

  [[noreturn]] void fail(int line, const std::string& what) const {
    throw FormatError(name_, line, what);
  }

  // The next line holding at least one token, or nullptr at the end of the stream.
  const Line* next() {
    std::string text;
    while (std::getline(in_, text)) {
      ++last_line_;
      current_.number = last_line_;
      current_.tokens.clear();
      std::istringstream s(text);
      std::string tok;
      while (s >> tok) current_.tokens.push_back(tok);
      if (!current_.tokens.empty()) return &current_;
    }
    return nullptr;
  }
  // The number of the last line read (the line count once the stream has ended).
  int last_line() const { return last_line_ > 0 ? last_line_ : 1; }

 private:
  std::istream& in_;
  std::string name_;
  Line current_;
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

// Every token strtod reads whole is either a finite double (subnormal numbers included, and
// numbers that underflow to zero) or refused with a message: NaN, infinity and overflow.
double parse_number(const Reader& r, int line, const std::string& tok, const std::string& what) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(tok.c_str(), &end);
  if (end == tok.c_str() || *end != '\0')
    r.fail(line, "found '" + tok + "'; expected " + what + " (a number)");
  if (!std::isfinite(v)) r.fail(line, what + " is '" + tok + "'; expected a finite number");
  return v;
}

// The fewest bytes a dense file of size n can have after its header: n (n + 1) numbers of at
// least one character, each followed by a separator.
std::uintmax_t min_data_bytes(std::uintmax_t n) { return 2 * n * (n + 1); }

}  // namespace

namespace {

// Header: six integers n, storage, n, n, n, n, possibly over several lines, starting at the
// first non-blank line l. Returns n.
long read_header(Reader& r, const Line* l) {
  static const char* const kHeader[] = {"the problem size n", "the storage type (0 = dense)",
                                        "the number of rows n", "the number of columns n",
                                        "the number of rows n", "the number of columns n"};
  long header[6] = {0, 0, 0, 0, 0, 0};
  std::size_t ti = 0;
  for (int k = 0; k < 6; ++k) {
    if (l == nullptr)
      r.fail(r.last_line(), std::string("unexpected end of file; expected ") + kHeader[k]);
    header[k] = parse_integer(r, l->number, l->tokens[ti], kHeader[k]);
    if (k == 0 && header[0] < 0)
      r.fail(l->number, "n = " + l->tokens[ti] + "; expected a size >= 0");
    if (k == 0 && header[0] > kMaxSize)
      r.fail(l->number, "n = " + l->tokens[ti] + "; expected a size <= " +
                            std::to_string(kMaxSize));
    if (k == 1 && header[1] != 0) {
      if (header[1] == 1)
        r.fail(l->number, "storage type 1 (sparse block) is not supported; expected 0 (dense): "
                          "use the dense file of the same problem");
      r.fail(l->number, "storage type " + l->tokens[ti] + "; expected 0 (dense)");
    }
    if (k >= 2 && header[k] != header[0])
      r.fail(l->number, "matrix size " + l->tokens[ti] + " differs from n = " +
                            std::to_string(header[0]) + "; expected " + kHeader[k] + " = " +
                            std::to_string(header[0]));
    if (++ti == l->tokens.size()) {
      ti = 0;
      if (k < 5) l = r.next();
    }
  }
  if (ti != 0)
    r.fail(l->number, "found '" + l->tokens[ti] +
                          "' after the six header integers; expected the end of the line");
  return header[0];
}

// An n x n M and q of size n, refused before allocation when the file cannot hold them.
Problem allocate(const Reader& r, Eigen::Index n, std::uintmax_t size) {
  const std::uintmax_t need = min_data_bytes(static_cast<std::uintmax_t>(n));
  if (n > 0 && size < need)
    r.fail(r.last_line(), "n = " + std::to_string(n) + " needs at least " + std::to_string(need) +
                              " bytes for M and q, but the file has " + std::to_string(size) +
                              "; expected n to match the data that follows");
  Problem p;
  try {
    p.M.resize(n, n);
    p.q.resize(n);
  } catch (const std::bad_alloc&) {
    r.fail(r.last_line(), "n = " + std::to_string(n) + " does not fit in memory; expected a "
                          "smaller problem");
  }
  return p;
}

// The next non-blank line, which must hold n numbers: `what` (its description in messages)
// is a column of M or q.
const Line& read_row(Reader& r, Eigen::Index n, const std::string& what) {
  const Line* l = r.next();
  if (l == nullptr)
    r.fail(r.last_line(), "unexpected end of file; expected " + what + " (" + std::to_string(n) +
                              " numbers on one line)");
  if (static_cast<Eigen::Index>(l->tokens.size()) != n)
    r.fail(l->number, what + " has " + std::to_string(l->tokens.size()) +
                          " entries; expected n = " + std::to_string(n));
  return *l;
}

}  // namespace

Problem parse_siconos_lcp(std::istream& in, const std::string& name, std::uintmax_t size) {
  Reader r(in, name);
  const Line* first = r.next();
  if (first == nullptr)
    r.fail(1, "the file is empty; expected the problem size n on the first line");
  const auto n = static_cast<Eigen::Index>(read_header(r, first));
  Problem p = allocate(r, n, size);
  // M, one column per line.
  for (Eigen::Index j = 0; j < n; ++j) {
    const Line& l = read_row(r, n, "column " + std::to_string(j + 1) + " of M");
    for (Eigen::Index i = 0; i < n; ++i)
      p.M(i, j) = parse_number(r, l.number, l.tokens[static_cast<std::size_t>(i)],
                               "M(" + std::to_string(i + 1) + ", " + std::to_string(j + 1) + ")");
  }
  if (n > 0) {
    const Line& l = read_row(r, n, "q");
    for (Eigen::Index i = 0; i < n; ++i)
      p.q(i) = parse_number(r, l.number, l.tokens[static_cast<std::size_t>(i)],
                            "q(" + std::to_string(i + 1) + ")");
  }
  return p;
}

Problem read_siconos_lcp(const std::filesystem::path& file) {
  // A FIFO, a device or a directory could block or never end: only regular files are read.
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (ec || !std::filesystem::exists(status))
    throw FormatError(file.string(), 0, "cannot open the file for reading (no such file)");
  if (!std::filesystem::is_regular_file(status))
    throw FormatError(file.string(), 0, "not a regular file; expected a .dat file");
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  std::ifstream in(file);
  if (!in || ec) throw FormatError(file.string(), 0, "cannot open the file for reading");
  return parse_siconos_lcp(in, file.string(), size);
}

void write_siconos_lcp(std::ostream& out, const Problem& p, const std::string& comment) {
  p.validate();
  const Eigen::Index n = p.size();
  out << n << "\n0\n" << n << '\n' << n << '\n' << n << ' ' << n << '\n';
  // %.17g: 17 significant digits identify every double (IEEE 754-2008, §5.12.2).
  char buf[32];
  const auto number = [&](double v) {
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
  };
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index i = 0; i < n; ++i) out << (i > 0 ? " " : "") << number(p.M(i, j));
    out << '\n';
  }
  for (Eigen::Index i = 0; i < n; ++i) out << (i > 0 ? " " : "") << number(p.q(i));
  if (n > 0) out << '\n';
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) out << "# " << line << '\n';
}

}  // namespace nsb::lcp
