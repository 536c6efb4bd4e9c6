// The Siconos .dat reader and writer: column-major M, every malformed case reported with file:line.
#include "lcp/siconos_format.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include <sys/stat.h>
#include <unistd.h>

using namespace nsb::lcp;

namespace {
Problem parse(const std::string& text) {
  std::istringstream in(text);
  return parse_siconos_lcp(in, "t.dat");
}
}  // namespace

TEST_CASE("M is stored one column per line") {
  // Columns (1, 3) and (2, 4): M = [1 2; 3 4].
  const Problem p = parse("2\n0\n2\n2\n2 2\n1 3\n2 4\n-1 -2\n\ncomment text 5 6\n");
  REQUIRE(p.size() == 2);
  CHECK(p.M(0, 0) == 1.0);
  CHECK(p.M(1, 0) == 3.0);
  CHECK(p.M(0, 1) == 2.0);
  CHECK(p.M(1, 1) == 4.0);
  CHECK(p.q(0) == -1.0);
  CHECK(p.q(1) == -2.0);
}

TEST_CASE("the files of data/siconos-lcp read as documented") {
  // lcp_exp_murty.dat: Murty's matrix, upper triangular with 2 above the unit diagonal.
  const Problem p = read_siconos_lcp(std::filesystem::path(NSB_DATA_DIR) / "siconos-lcp" /
                                     "lcp_exp_murty.dat");
  REQUIRE(p.size() == 6);
  CHECK(p.M(0, 5) == 2.0);
  CHECK(p.M(5, 0) == 0.0);
  CHECK(p.M.diagonal().isOnes(0.0));
  CHECK(p.q.isConstant(-1.0, 0.0));
  int dense = 0;
  for (const auto& e :
       std::filesystem::directory_iterator(std::filesystem::path(NSB_DATA_DIR) / "siconos-lcp")) {
    const std::string name = e.path().filename().string();
    INFO(name);
    if (name.find("_block") != std::string::npos) {
      // Sparse-block storage is rejected on line 2 (the storage type), by name.
      CHECK_THROWS_WITH_AS(read_siconos_lcp(e.path()), doctest::Contains(":2: storage type 1"),
                           FormatError);
    } else {
      CHECK_NOTHROW(read_siconos_lcp(e.path()).validate());
      ++dense;
    }
  }
  CHECK(dense == 17);
}

TEST_CASE("malformed files name the line and what was expected") {
  struct Case {
    const char* text;
    const char* message;
  };
  const Case cases[] = {
      {"", "t.dat:1: the file is empty; expected the problem size n"},
      {"\n\n   \n", "t.dat:1: the file is empty"},
      {"x\n", "t.dat:1: found 'x'; expected the problem size n"},
      {"-2\n", "t.dat:1: n = -2; expected a size >= 0"},
      {"2\n3\n", "t.dat:2: storage type 3; expected 0 (dense)"},
      {"2\n0\n3\n", "t.dat:3: matrix size 3 differs from n = 2"},
      {"2\n0\n2\n2\n2 2 7\n", "t.dat:5: found '7' after the six header integers"},
      {"2\n0\n2\n2\n2 2\n1 3\n", "t.dat:6: unexpected end of file; expected column 2 of M"},
      {"2\n0\n2\n2\n2 2\n1 3 5\n2 4\n-1 -2\n", "t.dat:6: column 1 of M has 3 entries; expected n = 2"},
      {"2\n0\n2\n2\n2 2\n1 3\n2 4\n", "t.dat:7: unexpected end of file; expected q"},
      {"2\n0\n2\n2\n2 2\n1 3\n2 4\n-1\n", "t.dat:8: q has 1 entries; expected n = 2"},
      {"2\n0\n2\n2\n2 2\n1 nan\n2 4\n-1 -2\n", "t.dat:6: M(2, 1) is 'nan'; expected a finite number"},
      {"2\n0\n2\n2\n2 2\n1 3\n2 4\n-1 inf\n", "t.dat:8: q(2) is 'inf'; expected a finite number"},
      {"2\n0\n2\n2\n2 2\n1 3\n2 4x\n-1 -2\n", "t.dat:7: found '4x'; expected M(2, 2) (a number)"},
  };
  for (const Case& c : cases) {
    INFO("input: " << c.text);
    CHECK_THROWS_WITH_AS(parse(c.text), doctest::Contains(c.message), FormatError);
  }
  try {
    parse("2\n0\n2\n2\n2 2\n1 3\n2 4\n-1\n");
  } catch (const FormatError& e) {
    CHECK(e.file == "t.dat");
    CHECK(e.line == 8);
  }
  CHECK_THROWS_WITH_AS(read_siconos_lcp("/nonexistent/x.dat"),
                       doctest::Contains("/nonexistent/x.dat: cannot open"), FormatError);
  // n = 0 is a valid, empty problem.
  CHECK(parse("0\n0\n0 0 0 0\n").size() == 0);
}

TEST_CASE("numbers: subnormal values are read, overflow is refused") {
  // strtod reads 1e-310 and -4.9e-324 as subnormal doubles, and 1e-400 as 0 (underflow):
  // all are finite numbers. 1e400 overflows to infinity and is refused by name.
  const Problem p = parse("2\n0\n2\n2\n2 2\n1 1e-310\n0 1e-400\n-1 -4.9e-324\n");
  CHECK(p.M(1, 0) == 1e-310);
  CHECK(p.M(1, 1) == 0.0);
  CHECK(p.q(1) == -4.9e-324);
  CHECK_THROWS_WITH_AS(parse("1\n0\n1\n1\n1 1\n1\n1e400\n"),
                       doctest::Contains("t.dat:7: q(1) is '1e400'; expected a finite number"),
                       FormatError);
}

TEST_CASE("n is checked against the file's length before anything is allocated") {
  // n = 1e9 would need 8e18 bytes for M: refused by the size bound on line 1.
  std::istringstream huge("1000000000 0 1000000000 1000000000 1000000000 1000000000\n");
  CHECK_THROWS_WITH_AS(parse_siconos_lcp(huge, "t.dat"),
                       doctest::Contains("t.dat:1: n = 1000000000; expected a size <= 32768"),
                       FormatError);
  // n = 100 needs 2 n (n + 1) = 20200 bytes at least; a 40-byte file cannot hold it.
  const std::string text = "100 0 100 100 100 100\n1 2 3\n";
  std::istringstream in(text);
  CHECK_THROWS_WITH_AS(parse_siconos_lcp(in, "t.dat", text.size()),
                       doctest::Contains("t.dat:1: n = 100 needs at least 20200 bytes"),
                       FormatError);
}

TEST_CASE("only regular files are read: a FIFO or a device is refused, never read") {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("nsb-siconos-" + std::to_string(static_cast<long>(::getpid())));
  std::filesystem::create_directories(dir);
  const auto fifo = dir / "fifo.dat";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  CHECK_THROWS_WITH_AS(read_siconos_lcp(fifo), doctest::Contains("fifo.dat: not a regular file"),
                       FormatError);
  CHECK_THROWS_WITH_AS(read_siconos_lcp("/dev/urandom"),
                       doctest::Contains("/dev/urandom: not a regular file"), FormatError);
  std::filesystem::remove_all(dir);
}

TEST_CASE("write_siconos_lcp: what it writes reads back bit for bit, the comment is not read") {
  // Entries that a short decimal form would change: 0.1 + 0.2, 1/3, a subnormal, -0.0.
  Problem p;
  p.M.resize(3, 3);
  p.M << 0.1 + 0.2, 1.0 / 3.0, -2.5e-310, 7.0, -0.0, 1e300, 2.0 / 3.0, 4.0, 5e-324;
  p.q = Eigen::Vector3d(-1.0 / 7.0, 0.0, 123456789.123456789);
  std::ostringstream out;
  write_siconos_lcp(out, p, "t = 0.25\nkind = step");
  const Problem back = parse(out.str());
  REQUIRE(back.size() == 3);
  for (Eigen::Index j = 0; j < 3; ++j) {
    for (Eigen::Index i = 0; i < 3; ++i) CHECK(back.M(i, j) == p.M(i, j));
    CHECK(back.q(j) == p.q(j));
  }
  CHECK(out.str().find("# t = 0.25\n# kind = step\n") != std::string::npos);
  // The one data set of the collection that is read and written again is unchanged.
  const Problem cps = read_siconos_lcp(std::filesystem::path(NSB_DATA_DIR) / "siconos-lcp" /
                                       "lcp_CPS_1.dat");
  std::ostringstream again;
  write_siconos_lcp(again, cps);
  const Problem cps_back = parse(again.str());
  CHECK(cps_back.M == cps.M);
  CHECK(cps_back.q == cps.q);
  // n = 0 is a valid problem, and reads back as one.
  std::ostringstream empty;
  write_siconos_lcp(empty, Problem{});
  CHECK(parse(empty.str()).size() == 0);
}

TEST_CASE("write_siconos_lcp refuses what the reader could not read back") {
  Problem p;
  p.M = Eigen::Matrix2d::Identity();
  p.q = Eigen::Vector2d(1.0, std::nan(""));
  std::ostringstream out;
  CHECK_THROWS_WITH_AS(write_siconos_lcp(out, p), doctest::Contains("q("), std::invalid_argument);
  p.q = Eigen::Vector3d::Zero();
  CHECK_THROWS_AS(write_siconos_lcp(out, p), std::invalid_argument);
}
