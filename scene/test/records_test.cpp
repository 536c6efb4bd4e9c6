// The ground-motion record files (scene/records.hpp): the PEER NGA .AT2 file in both header
// forms, the two-column and CSV files, and errors that name the file and the line.
#include "scene/records.hpp"

#include <doctest/doctest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using nsb::models::Record;

namespace {

const fs::path kMotions = fs::path(NSB_DATA_DIR) / "ground-motions";
constexpr double kG = 9.81;
// Values printed with 5-7 significant digits in the files, compared after parsing.
constexpr double kParseTolerance = 1e-12;

// A scratch directory for files written by the tests, removed at the end.
struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() /
           ("nsb_records_test_" + std::to_string(std::random_device{}()));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path p = path / name;
    std::ofstream(p) << text;
    return p;
  }
};

// Asserts that f throws std::invalid_argument whose message contains every fragment.
template <class F>
void expect_error(F&& f, std::initializer_list<std::string> fragments) {
  try {
    f();
    FAIL("expected std::invalid_argument");
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    for (const auto& frag : fragments) {
      INFO("message: " << msg);
      CHECK(msg.find(frag) != std::string::npos);
    }
  }
}

// Index and value of the largest |a|.
std::pair<std::size_t, double> peak_of(const std::vector<double>& a) {
  std::size_t k = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::abs(a[i]) > std::abs(a[k])) k = i;
  }
  return {k, std::abs(a[k])};
}

}  // namespace

TEST_CASE("ground motion: PEER AT2 files in both header forms") {
  SUBCASE("NPTS=  1559, DT= .02000 SEC (Peknold El Centro)") {
    const Record r = nsb::scene::read_at2(kMotions / "elCentro_NS_1940_Peknold.AT2");
    REQUIRE(r.a.size() == 1559);
    CHECK(r.t[1] == doctest::Approx(0.02));
    CHECK(r.t.back() == doctest::Approx(1558 * 0.02));
    // First and last values of the file, in g.
    CHECK(r.a.front() == doctest::Approx(0.00630 * kG).epsilon(kParseTolerance));
    CHECK(r.a.back() == doctest::Approx(0.0).scale(1.0));
    // Chopra's PGA of this version: 0.319 g.
    CHECK(peak_of(r.a).second / kG == doctest::Approx(0.319).epsilon(0.002));
  }
  SUBCASE("NPTS=   8773, DT=   .0050 SEC, ... (Northridge, Sylmar)") {
    // bridge-parameters: component 142 has 0.923 g at t = 7.0 s, 052 has 0.623 g at 4.7 s.
    for (const auto& [file, pga, time] :
         {std::tuple{"RSN1084_NORTHR_SCS142.AT2", 0.923, 7.0},
          std::tuple{"RSN1084_NORTHR_SCS052.AT2", 0.623, 4.7}}) {
      const Record r = nsb::scene::read_at2(kMotions / file, kG);
      REQUIRE(r.a.size() == 8773);
      CHECK(r.t[1] == doctest::Approx(0.005));
      const auto [k, peak] = peak_of(r.a);
      CHECK(peak / kG == doctest::Approx(pga).epsilon(1e-3));
      CHECK(r.t[k] == doctest::Approx(time).epsilon(0.01));
    }
    const Record first = nsb::scene::read_at2(kMotions / "RSN1084_NORTHR_SCS052.AT2", 1.0);
    CHECK(first.a.front() == doctest::Approx(-0.4981725e-2).epsilon(kParseTolerance));
  }
}

TEST_CASE("ground motion: reader errors name the file and the line") {
  TempDir dir;
  const std::string head = "PEER\nevent\nUNITS OF G\n";
  {
    const auto p = dir.write("bad_token.AT2", head + "NPTS=  4, DT= .01 SEC\n 0.1 0.2\n 0.3 x4\n");
    expect_error([&] { nsb::scene::read_at2(p); }, {"bad_token.AT2:6:", "non-numeric", "x4"});
  }
  {
    const auto p = dir.write("short.AT2", head + "NPTS=  5, DT= .01 SEC\n 0.1 0.2\n 0.3 0.4\n");
    expect_error([&] { nsb::scene::read_at2(p); }, {"short.AT2:6:", "NPTS = 5", "4 values"});
  }
  {
    const auto p = dir.write("long.AT2", head + "NPTS=  3, DT= .01 SEC\n 0.1 0.2\n 0.3 0.4\n");
    expect_error([&] { nsb::scene::read_at2(p); }, {"long.AT2:6:", "more values than NPTS"});
  }
  {
    const auto p = dir.write("header.AT2", head + "POINTS 3 STEP 0.01\n 0.1 0.2 0.3\n");
    expect_error([&] { nsb::scene::read_at2(p); }, {"header.AT2:4:", "NPTS="});
  }
  {
    const auto p = dir.write("nan.AT2", head + "NPTS=  3, DT= .01 SEC\n 0.1 nan 0.3\n");
    expect_error([&] { nsb::scene::read_at2(p); }, {"nan.AT2:5:", "not finite"});
  }
  {
    const auto p = dir.write("dt.AT2", head + "NPTS=  3, DT= 0 SEC\n 0.1 0.2 0.3\n");
    expect_error([&] { nsb::scene::read_at2(p); }, {"dt.AT2:4:", "DT"});
  }
  expect_error([&] { nsb::scene::read_at2(dir.path / "missing.AT2"); },
               {"missing.AT2", "does not exist"});
  {
    const auto p = dir.write("time.txt", "# t a\n0 0.1\n0.01 0.2\n\n0.01 0.3\n0.03 0.1\n");
    expect_error([&] { nsb::scene::read_two_column(p); },
                 {"time.txt:5:", "not greater than the previous"});
  }
  {
    const auto p = dir.write("fields.txt", "0 0.1\n0.01 0.2 7\n");
    expect_error([&] { nsb::scene::read_two_column(p); }, {"fields.txt:2:", "two numbers"});
  }
  {
    const auto p = dir.write("csvbad.csv", "t,a\n0,0.1\n0.01,abc\n0.02,0\n");
    expect_error([&] { nsb::scene::read_csv(p); }, {"csvbad.csv:3:", "non-numeric", "abc"});
  }
  {
    const auto p = dir.write("csvhead.csv", "time,x,y\n0,1,2\n");
    expect_error([&] { nsb::scene::read_csv(p); }, {"csvhead.csv:1:", "'t' and 'a'"});
  }
  {
    const auto p = dir.write("csvfields.csv", "t,a\n0,1\n0.1\n");
    expect_error([&] { nsb::scene::read_csv(p); }, {"csvfields.csv:3:", "2 comma-separated"});
  }
  {
    const auto p = dir.write("two.txt", "0 0.1\n0.01 0.2\n");
    expect_error([&] { nsb::scene::read_two_column(p); }, {"two.txt", "at least 3"});
  }
}

TEST_CASE("ground motion: readers refuse what is not a regular file, and name out-of-range numbers") {
  TempDir dir;
  // A FIFO would block the reader for ever (no writer), a directory is no record.
  const auto fifo = dir.path / "fifo.AT2";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  expect_error([&] { nsb::scene::read_at2(fifo); }, {"fifo.AT2", "not a regular file"});
  expect_error([&] { nsb::scene::read_csv(dir.path); }, {"not a regular file"});
  // Subnormal values are values; 1e-400 and 1e400 are beyond a double and refused by name.
  const std::string head = "PEER\nevent\nUNITS OF G\n";
  {
    std::istringstream in(head + "NPTS=  3, DT= .01 SEC\n 1e-310 -4.9e-324 0.3\n");
    const Record r = nsb::scene::read_at2(in, "sub.AT2", 1.0);
    CHECK(r.a[0] == 1e-310);
    CHECK(r.a[1] == -4.9e-324);
  }
  for (const char* v : {"1e-400", "1e400"}) {
    std::istringstream in(head + "NPTS=  3, DT= .01 SEC\n 0.1 " + v + " 0.3\n");
    expect_error([&] { nsb::scene::read_at2(in, "range.AT2", 1.0); },
                 {"range.AT2:5:", "outside the range of a double", v});
  }
  // A header line far longer than any PEER line is refused before the regular expression.
  {
    std::istringstream in(head + "NPTS= " + std::string(100000, ' ') + "3, DT= .01\n0 0 0\n");
    expect_error([&] { nsb::scene::read_at2(in, "long.AT2", 1.0); },
                 {"long.AT2:4:", "100016 characters"});
  }
}

TEST_CASE("ground motion: two-column and CSV readers") {
  TempDir dir;
  const auto p2 = dir.write("rec.txt", "# time [s]  acc [g]\n0.0 0.0\n0.5 +1.5e-1\n1.25 -0.25\n2 0\n");
  const Record r2 = nsb::scene::read_two_column(p2, kG);
  REQUIRE(r2.t.size() == 4);
  CHECK(r2.t[2] == 1.25);
  CHECK(r2.a[1] == doctest::Approx(0.15 * kG));
  CHECK(r2.source == p2.string());
  const auto pc = dir.write("rec.csv", "a, t ,note\n0.0,0.0,x\n1.0,0.1,y\n-2.0,0.2,z\n");
  const Record rc = nsb::scene::read_csv(pc, 0.5);
  REQUIRE(rc.t.size() == 3);
  CHECK(rc.t[2] == doctest::Approx(0.2));
  CHECK(rc.a[2] == doctest::Approx(-1.0));
}
