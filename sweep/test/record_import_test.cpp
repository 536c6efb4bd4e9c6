// Record libraries imported as suites: a PEER NGA-West2 search folder and a folder of COSMOS
// V2 files (test/data/records-import, synthetic files written from the published layouts:
// PEER's _SearchResults.csv table and the COSMOS Strong Motion Data Format v1.20). Expected
// values are the numbers written in those files, converted by hand: an .AT2 value times the
// g = 9.81 m/s^2 that scenes pass to the AT2 reader, a COSMOS value in cm/s^2 (unit code 4)
// times 0.01, one in g (code 2) times the standard 9.80665 m/s^2.
#include "sweep/record_import.hpp"

#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "scene/cosmos.hpp"
#include "scene/records.hpp"
#include "sweep/csv.hpp"
#include "sweep/suites.hpp"

namespace fs = std::filesystem;
using namespace nsb::sweep;

namespace {

// NSB_DATA_DIR is the source tree's data/ folder; the fixtures are beside this file.
const fs::path kData =
    fs::path(NSB_DATA_DIR).parent_path() / "sweep" / "test" / "data" / "records-import";

fs::path scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("nsb_record_import_test_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir.parent_path());
  return dir;
}

fs::path copy_of(const std::string& kind, const std::string& name) {
  const fs::path dir = scratch(name);
  fs::copy(kData / kind, dir, fs::copy_options::recursive);
  return dir;
}

std::string bytes(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

std::size_t column(const ImportedSuite& s, const std::string& name) {
  for (std::size_t k = 0; k < s.header.size(); ++k) {
    if (s.header[k] == name) return k;
  }
  FAIL("no column " << name);
  return 0;
}

// Replaces the first occurrence of from in file by to.
void edit(const fs::path& file, const std::string& from, const std::string& to) {
  std::string text = bytes(file);
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  text.replace(at, from.size(), to);
  std::ofstream(file, std::ios::binary) << text;
}

}  // namespace

TEST_CASE("a PEER search folder: components paired per RSN, scale factor and metadata kept") {
  const ImportedSuite s = read_record_library(kData / "peer");
  CHECK(s.kind == "peer");
  REQUIRE(s.records.size() == 2);
  const auto& r0 = s.records[0].cells;
  const auto& r1 = s.records[1].cells;
  CHECK(r0[column(s, "rsn")] == "101");
  CHECK(r0[column(s, "file_1")] == "RSN101_SYN_A000.AT2");
  CHECK(r0[column(s, "file_2")] == "RSN101_SYN_A090.AT2");
  CHECK(r1[column(s, "rsn")] == "202");
  CHECK(r1[column(s, "file_1")] == "RSN202_SYN_B180.AT2");
  CHECK(r1[column(s, "file_2")] == "RSN202_SYN_B270.AT2");
  // PEER's factors as the table writes them, kept and not applied.
  CHECK(r0[column(s, "scale_factor")] == "1.2500");
  CHECK(r1[column(s, "scale_factor")] == "0.8000");
  CHECK(r1[column(s, "earthquake_name")] == "Synthetic-02, aftershock");
  CHECK(r0[column(s, "rjb_km")] == "10.00");
  CHECK(r1[column(s, "vs30_m_sec")] == "760.00");
  CHECK(r0[column(s, "magnitude")] == "6.50");
  CHECK(r0[column(s, "npts_1")] == "50");
  CHECK(r0[column(s, "dt_1_s")] == "0.01");
  CHECK(r1[column(s, "npts_2")] == "40");
  CHECK(r1[column(s, "dt_2_s")] == "0.02");
  // The vertical component's column is not metadata.
  for (const auto& h : s.header) CHECK(h != "vertical_acc_filename");

  const fs::path out = scratch("peer-suite");
  write_suite(s, out);
  CHECK(bytes(out / "RSN101_SYN_A000.AT2") == bytes(kData / "peer" / "RSN101_SYN_A000.AT2"));
  const auto suite = read_suite(out / "records.csv", {"file_1", "file_2"});
  REQUIRE(suite.size() == 2);
  CHECK(suite[0].name == "RSN101");
  CHECK(suite[1].name == "RSN202");
  // Second sample of RSN101_SYN_A000.AT2: 3.96e-03 g.
  const nsb::models::Record r = nsb::scene::read_at2(suite[0].files[0], 9.81);
  CHECK(r.a[1] == doctest::Approx(3.96e-3 * 9.81).epsilon(1e-15));
  CHECK(r.t[1] == doctest::Approx(0.01));
}

TEST_CASE("COSMOS V2 channels: units to m/s^2, dt from real parameter 62, verticals marked") {
  const auto cm = nsb::scene::read_cosmos(kData / "cosmos" / "SYN01.V2c");
  REQUIRE(cm.size() == 3);
  CHECK(cm[0].azimuth == 360);
  CHECK(cm[0].horizontal);
  CHECK(cm[1].azimuth == 90);
  CHECK(!cm[2].horizontal);  // azimuth 400: up
  CHECK(cm[0].station == "CE24278");
  CHECK(cm[0].station_name == "Synthetic Station One");
  CHECK(cm[0].start == "1999-09-21T17:47");
  CHECK(cm[0].dt == doctest::Approx(0.01).epsilon(1e-15));
  REQUIRE(cm[0].record.a.size() == 60);
  CHECK(cm[0].record.a[1] == 2.467 * 0.01);  // 2.46700 cm/s^2
  CHECK(cm[0].record.t[59] == doctest::Approx(0.59));

  const auto g = nsb::scene::read_cosmos(kData / "cosmos" / "SYN02_000.V2");
  REQUIRE(g.size() == 1);
  CHECK(g[0].azimuth == 700);
  CHECK(g[0].unit == nsb::scene::kStandardGravity);
  CHECK(g[0].record.a[2] == 0.01442 * 9.80665);  // 0.01442 g
  CHECK(g[0].dt == doctest::Approx(0.02).epsilon(1e-15));
}

TEST_CASE("a COSMOS folder: horizontal channels of one station and start paired, written in m/s^2") {
  const ImportedSuite s = read_record_library(kData / "cosmos");
  CHECK(s.kind == "cosmos");
  REQUIRE(s.records.size() == 2);
  const auto& a = s.records[0].cells;  // groups sorted by station
  const auto& b = s.records[1].cells;
  CHECK(a[column(s, "name")] == "CE24278_19990921T1747");
  CHECK(a[column(s, "file_1")] == "SYN01_c1.csv");
  CHECK(a[column(s, "file_2")] == "SYN01_c2.csv");
  CHECK(a[column(s, "azimuth_2")] == "90");
  CHECK(b[column(s, "name")] == "NP00125_19990921T1747");
  CHECK(b[column(s, "file_1")] == "SYN02_000_c1.csv");
  CHECK(b[column(s, "file_2")] == "SYN02_090_c1.csv");
  CHECK(b[column(s, "unit_code_1")] == "2");

  const fs::path out = scratch("cosmos-suite");
  write_suite(s, out);
  const auto suite = read_suite(out / "records.csv", {"file_1", "file_2"});
  REQUIRE(suite.size() == 2);
  const nsb::models::Record r = nsb::scene::read_csv(suite[0].files[0]);
  REQUIRE(r.a.size() == 60);
  CHECK(r.a[1] == 2.467 * 0.01);  // the CSV's shortest round-trip text reads back exactly
  CHECK(r.t[1] == 0.01);
}

TEST_CASE("bad libraries are refused naming the file, the line and the column") {
  SUBCASE("a missing AT2 file") {
    const fs::path dir = copy_of("peer", "missing");
    fs::remove(dir / "RSN101_SYN_A090.AT2");
    const std::string e = error_of([&] { (void)read_record_library(dir); });
    CHECK(e.find("_SearchResults.csv:8: RSN 101: column Horizontal-2 Acc. Filename: no such file") !=
          std::string::npos);
    CHECK(e.find("RSN101_SYN_A090.AT2") != std::string::npos);
  }
  SUBCASE("a record with one horizontal component") {
    const fs::path dir = copy_of("peer", "one");
    edit(dir / "_SearchResults.csv", "RSN202_SYN_B270.AT2", "---");
    const std::string e = error_of([&] { (void)read_record_library(dir); });
    CHECK(e.find("_SearchResults.csv:9: RSN 202: column Horizontal-2 Acc. Filename is empty") !=
          std::string::npos);
  }
  SUBCASE("a scale factor that is not a number") {
    const fs::path dir = copy_of("peer", "scale");
    edit(dir / "_SearchResults.csv", "1.2500", "x");
    CHECK(error_of([&] { (void)read_record_library(dir); })
              .find("_SearchResults.csv:8: column Scale Factor: 'x'") != std::string::npos);
  }
  SUBCASE("a malformed integer header") {
    const fs::path dir = copy_of("cosmos", "header");
    edit(dir / "SYN01.V2c", "Integer-header values follow", "Integer values follow");
    CHECK(error_of([&] { (void)read_record_library(dir); })
              .find("SYN01.V2c:14: expected \"<n> Integer-header values") != std::string::npos);
  }
  SUBCASE("a unit that is not an acceleration") {
    const fs::path dir = copy_of("cosmos", "unit");
    edit(dir / "SYN02_090.V2", "       2       1       2", "       2       1       6");
    CHECK(error_of([&] { (void)read_record_library(dir); })
              .find("SYN02_090.V2:14: integer parameter 3 (physical unit) is 6") !=
          std::string::npos);
  }
  SUBCASE("a non-numeric acceleration value") {
    const fs::path dir = copy_of("cosmos", "value");
    edit(dir / "SYN01.V2c", "   2.46700", "   2.4x700");
    CHECK(error_of([&] { (void)read_record_library(dir); })
              .find("SYN01.V2c:46: the acceleration values: field 2 (columns 11-20)") !=
          std::string::npos);
  }
  SUBCASE("a station with one horizontal channel") {
    const fs::path dir = copy_of("cosmos", "single");
    fs::remove(dir / "SYN02_090.V2");
    CHECK(error_of([&] { (void)read_record_library(dir); })
              .find("station 'NP00125', start '1999-09-21T17:47': 1 horizontal channels") !=
          std::string::npos);
  }
}
