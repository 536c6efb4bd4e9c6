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

namespace {

using nsb::scene::RecordKeys;

// Standard gravity and the inch, exact by definition (NIST SP 811, 2008, B.8).
constexpr double kGn = 9.80665;
constexpr double kInch = 0.0254;

RecordKeys keys(double unit, std::string unit_key, double dt = 0.0, bool angular = false) {
  RecordKeys k;
  k.unit = unit;
  k.unit_key = std::move(unit_key);
  k.dt = dt;
  k.dt_key = "record_dt";
  k.angular = angular;
  return k;
}

}  // namespace

TEST_CASE("CSV headers give the units of the time and acceleration columns") {
  TempDir dir;
  // 0.5 g = 0.5 * 9.80665 m/s^2; the default unit 1 (not given) gives way to the header's.
  {
    const auto p = dir.write("g.csv", "t [s],a [g]\n0,0\n0.01,0.5\n0.02,-0.25\n");
    const Record r = nsb::scene::read_csv(p);
    REQUIRE(r.a.size() == 3);
    CHECK(r.a[1] == doctest::Approx(0.5 * kGn).epsilon(1e-15));
    CHECK(r.a[2] == doctest::Approx(-0.25 * kGn).epsilon(1e-15));
  }
  // Milliseconds and gal: t = 10 ms = 0.01 s; 50 gal = 0.5 m/s^2.
  {
    const auto p = dir.write("gal.csv", "time [ms],acceleration [gal]\n0,0\n10,50\n20,-100\n");
    const Record r = nsb::scene::read_csv(p);
    CHECK(r.t[1] == doctest::Approx(0.01).epsilon(1e-15));
    CHECK(r.a[1] == doctest::Approx(0.5).epsilon(1e-15));
    CHECK(r.a[2] == doctest::Approx(-1.0).epsilon(1e-15));
  }
  // Round brackets, spaces, "²", in/s^2: 10 in/s^2 = 0.254 m/s^2.
  for (const char* head : {"t (s), a (in/s^2)", "t [ s ], a [in/s²]", "t,a [IN/S2]"}) {
    const auto p = dir.write("in.csv", std::string(head) + "\n0,0\n0.01,10\n0.02,0\n");
    const Record r = nsb::scene::read_csv(p);
    CAPTURE(head);
    CHECK(r.a[1] == doctest::Approx(10 * kInch).epsilon(1e-15));
  }
  CHECK(nsb::scene::acceleration_unit("cm/s^2") == 0.01);
  CHECK(nsb::scene::acceleration_unit("ft/s^2") == doctest::Approx(12 * kInch).epsilon(1e-15));
  CHECK(nsb::scene::acceleration_unit("furlong") == 0.0);
  // A unit the scene gives must agree with the header's; 9.81 agrees with g (3.4e-4 apart)
  // and is then used as given.
  {
    const auto p = dir.write("agree.csv", "t [s],a [g]\n0,0\n0.01,1\n0.02,0\n");
    CHECK(nsb::scene::read_csv(p, keys(9.81, "model.excitation.record_unit")).a[1] == 9.81);
    expect_error([&] { nsb::scene::read_csv(p, keys(1.0, "model.excitation.record_unit")); },
                 {"agree.csv:1:", "[g]", "conflicts with model.excitation.record_unit = 1"});
  }
  // Unknown units, of either column, name the file, the line and the unit.
  {
    const auto p = dir.write("unknown.csv", "# comment\nt [s],a [furlong/s^2]\n0,0\n0.01,1\n0.02,0\n");
    expect_error([&] { nsb::scene::read_csv(p); }, {"unknown.csv:2:", "[furlong/s^2]", "known: g"});
    const auto q = dir.write("unknown_t.csv", "t [min],a [g]\n0,0\n0.01,1\n0.02,0\n");
    expect_error([&] { nsb::scene::read_csv(q); }, {"unknown_t.csv:1:", "time unit [min]"});
  }
  // A rotation record takes rad/s^2 and refuses a linear unit; a ground record the reverse.
  {
    const auto p = dir.write("rot.csv", "t [s],a [rad/s^2]\n0,0\n0.01,1\n0.02,0\n");
    CHECK(nsb::scene::read_csv(p, keys(1.0, "", 0.0, true)).a[1] == 1.0);
    expect_error([&] { nsb::scene::read_csv(p); }, {"rot.csv:1:", "angular"});
    const auto q = dir.write("lin.csv", "t [s],a [g]\n0,0\n0.01,1\n0.02,0\n");
    expect_error([&] { nsb::scene::read_csv(q, keys(1.0, "", 0.0, true)); }, {"lin.csv:1:", "linear"});
  }
}

TEST_CASE("a CSV file whose first line is numbers has no header: that line is a sample") {
  TempDir dir;
  const auto p = dir.write("nohead.csv", "0,0.125\n0.01,0.25\n0.02,-0.5\n");
  const Record r = nsb::scene::read_csv(p);
  REQUIRE(r.t.size() == 3);
  CHECK(r.t[0] == 0.0);
  CHECK(r.a[0] == 0.125);
  // A first line with a number among words is a bad cell, not a header.
  const auto q = dir.write("mixed.csv", "0,abc\n0.01,0.25\n0.02,-0.5\n");
  expect_error([&] { nsb::scene::read_csv(q); }, {"mixed.csv:1:", "non-numeric", "abc"});
  // More than two columns without a header cannot be told apart.
  const auto w = dir.write("wide.csv", "0,1,2\n0.01,1,2\n0.02,1,2\n");
  expect_error([&] { nsb::scene::read_csv(w); }, {"wide.csv:1:", "no header"});
}

TEST_CASE("a file of acceleration values only takes its step from dt") {
  TempDir dir;
  // One value per line, or several (the OpenSees Path -dt habit): t_i = i dt.
  const auto p = dir.write("values.txt", "0.1\n0.2\n0.3\n");
  const Record r = nsb::scene::read_two_column(p, keys(kG, "", 0.02));
  REQUIRE(r.t.size() == 3);
  CHECK(r.t[2] == doctest::Approx(0.04).epsilon(1e-15));
  CHECK(r.a[2] == doctest::Approx(0.3 * kG).epsilon(1e-15));
  const auto q = dir.write("rows.txt", "0.1 0.2 0.3\n-0.4\n0.5 0.6\n");
  const Record rq = nsb::scene::read_two_column(q, keys(1.0, "", 0.01));
  REQUIRE(rq.a.size() == 6);
  CHECK(rq.a[3] == -0.4);
  CHECK(rq.t[5] == doctest::Approx(0.05).epsilon(1e-15));
  // The same as CSV, with or without a header naming the unit.
  const auto c = dir.write("values.csv", "a [g]\n0.1\n0.2\n0.3\n");
  CHECK(nsb::scene::read_csv(c, keys(1.0, "", 0.01)).a[0] == doctest::Approx(0.1 * kGn).epsilon(1e-15));
  const auto c2 = dir.write("values2.csv", "0.1\n0.2\n0.3\n");
  CHECK(nsb::scene::read_csv(c2, keys(1.0, "", 0.01)).t[2] == doctest::Approx(0.02).epsilon(1e-15));
  // Without dt, a single column is refused naming the key to add.
  expect_error([&] { nsb::scene::read_two_column(p, keys(1.0, "")); },
               {"values.txt:1:", "record_dt"});
  expect_error([&] { nsb::scene::read_csv(c2, keys(1.0, "")); }, {"values2.csv:1:", "record_dt"});
  expect_error([&] { nsb::scene::read_csv(c, keys(1.0, "")); }, {"values.csv:1:", "record_dt"});
  // A "t a" file read with dt is refused: its first column increases strictly.
  const auto ta = dir.write("ta.txt", "0 0.1\n0.01 -0.2\n0.02 0.3\n0.03 0\n");
  expect_error([&] { nsb::scene::read_two_column(ta, keys(1.0, "", 0.01)); },
               {"ta.txt:1:", "'t a'", "remove record_dt"});
  // A file with a time column keeps it; a dt that disagrees with its step is refused.
  const auto tc = dir.write("tc.csv", "t,a\n0,0.1\n0.01,0.2\n0.03,0.3\n");
  expect_error([&] { nsb::scene::read_csv(tc, keys(1.0, "", 0.01)); },
               {"tc.csv:4:", "time step 0.02 s differs from record_dt = 0.01 s"});
}

TEST_CASE("PEER .AT2: the older header form, the unit on line 3, and printable messages") {
  // Both forms as PEER describes its files: three text lines (database, event and station,
  // "... IN UNITS OF G"), then NPTS and DT, then the values in g, several per line. The NGA
  // form writes "NPTS=   5, DT=   .0100 SEC"; the older database wrote the numbers first,
  // "   5   .0100   NPTS, DT".
  const std::string head =
      "PEER STRONG MOTION DATABASE RECORD\nSYNTHETIC 1/1/2000, STATION, 090\n"
      "ACCELERATION TIME HISTORY IN UNITS OF G\n";
  const std::string values = "  .1000E+00  -.2000E+00   .3000E+00\n  -.4000E+00   .5000E+00\n";
  for (const char* line4 : {"NPTS=      5, DT=   .0100 SEC\n", "    5    .0100    NPTS, DT\n",
                            "5 0.0100 NPTS, DT\n", "  5,  .0100  NPTS, DT, SEC\n"}) {
    std::istringstream in(head + line4 + values);
    const Record r = nsb::scene::read_at2(in, "form.AT2", kG);
    CAPTURE(line4);
    REQUIRE(r.a.size() == 5);
    CHECK(r.t[4] == doctest::Approx(0.04).epsilon(1e-15));
    CHECK(r.a[1] == doctest::Approx(-0.2 * kG).epsilon(1e-15));
  }
  {
    std::istringstream in("A\nB\nACCELERATION IN UNITS OF CM/SEC/SEC\nNPTS= 5, DT= .01\n" + values);
    expect_error([&] { nsb::scene::read_at2(in, "cm.AT2", kG); }, {"cm.AT2:3:", "CM/SEC/SEC", "in g"});
  }
  {
    std::istringstream in(head + "NPTS= 5, DT= .01\n" + values);
    expect_error([&] { nsb::scene::read_at2(in, "unit.AT2", kG, keys(1.0, "model.excitation.record_unit")); },
                 {"unit.AT2:3:", "in g", "conflicts with model.excitation.record_unit = 1"});
  }
  {
    std::istringstream in(head + "NPTS= 5, DT= .01\n" + values);
    expect_error([&] { nsb::scene::read_at2(in, "dt.AT2", kG, keys(1.0, "", 0.02)); },
                 {"dt.AT2:4:", "DT = 0.01 s differs from record_dt = 0.02 s"});
  }
  // Binary bytes are escaped, never echoed raw.
  {
    std::istringstream in(head + std::string("NPTS\x00\x01\xff", 7) + "\n" + values);
    try {
      nsb::scene::read_at2(in, "bin.AT2", kG);
      FAIL("expected std::invalid_argument");
    } catch (const std::invalid_argument& e) {
      const std::string msg = e.what();
      CHECK(msg.find("bin.AT2:4:") != std::string::npos);
      CHECK(msg.find("\\x00\\x01\\xff") != std::string::npos);
      for (const char ch : msg) CHECK((static_cast<unsigned char>(ch) >= 0x20 && ch != 0x7f));
    }
  }
  // A huge DT is written with a few digits, not 300.
  {
    std::istringstream in(head + "NPTS= 5, DT= -1e300\n" + values);
    try {
      nsb::scene::read_at2(in, "huge.AT2", kG);
      FAIL("expected std::invalid_argument");
    } catch (const std::invalid_argument& e) {
      const std::string msg = e.what();
      CHECK(msg.find("-1e+300") != std::string::npos);
      CHECK(msg.size() < 120);
    }
  }
}
