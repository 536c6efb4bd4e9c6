// A run read back from its outputs: history.csv and events.csv as the recorder writes them
// (shortest round-trip numbers, an empty field for a non-finite value), and the measures the
// figures and claims take of a history. Expected values are worked out by hand beside them.
#include "paper-figures/runs.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <unistd.h>

namespace fs = std::filesystem;
using nsb::paper_figures::History;
using nsb::integrators::EventKind;

namespace {

// A run folder with the given history.csv and events.csv, removed at the end of the test.
struct RunDir {
  fs::path dir;
  RunDir(const std::string& history, const std::string& events) {
    dir = fs::temp_directory_path() /
          ("nsb-runs-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter()++));
    fs::create_directories(dir);
    std::ofstream(dir / "history.csv") << history;
    std::ofstream(dir / "events.csv") << events;
  }
  ~RunDir() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  static int& counter() {
    static int n = 0;
    return n;
  }
};

const char* kEvents =
    "t,contact,kind,note\n0.15,2,impact,\n0.25,0,warning,\"a, b\"\n0.3,1,impact,\n";

}  // namespace

TEST_CASE("a history reads back the very doubles the recorder wrote") {
  // 0.1 and 5e-324 (the smallest subnormal) are written by std::to_chars as their shortest
  // round-trip text; an empty field stands for a non-finite value.
  const RunDir run("t,theta,omega\n0,0.1,5e-324\n0.1,-0.2,\n0.2,0.4,1e+300\n", kEvents);
  const History h = History::read(run.dir);
  REQUIRE(h.rows() == 3);
  CHECK(h.column("theta") == 1);
  CHECK(h.at(0, 1) == 0.1);
  CHECK(h.at(0, 2) == std::numeric_limits<double>::denorm_min());
  CHECK(std::isnan(h.at(1, 2)));
  CHECK(h.at(2, 2) == 1e300);
  CHECK(h.series("theta") == std::vector<double>{0.1, -0.2, 0.4});
  CHECK_THROWS_AS(h.column("x"), std::out_of_range);
  REQUIRE(h.events().size() == 3);
  CHECK(h.events()[0].kind == EventKind::kImpact);
  CHECK(h.events()[0].contact == 2);
  CHECK(h.events()[1].note == "a, b");
  CHECK(h.count(EventKind::kImpact) == 2);
}

TEST_CASE("a malformed history names its file and line") {
  const RunDir run("t,theta\n0,1\n0.1\n", kEvents);
  try {
    (void)History::read(run.dir);
    FAIL("no exception");
  } catch (const std::runtime_error& e) {
    const std::string m = e.what();
    CHECK(m.find("history.csv:3") != std::string::npos);
  }
}

TEST_CASE("measures of a history, by hand") {
  using namespace nsb::paper_figures;
  const RunDir a("t,theta\n0,0\n0.1,1\n0.2,-3\n0.3,2\n", kEvents);
  const RunDir b("t,theta\n0,0\n0.2,-2\n", "t,contact,kind,note\n");
  const History ha = History::read(a.dir), hb = History::read(b.dir);
  // Peak |theta| over t <= 0.2: max(0, 1, 3) = 3; over everything also 3.
  CHECK(peak(ha, "theta", 0.2) == 3.0);
  CHECK(peak(ha, "theta", 0.15) == 1.0);
  // Linear interpolation: at 0.15 halfway between 1 and -3 = -1; held beyond the ends.
  CHECK(value_at(ha, "theta", 0.15) == doctest::Approx(-1.0).epsilon(1e-15));
  CHECK(value_at(ha, "theta", -1.0) == 0.0);
  CHECK(value_at(ha, "theta", 9.0) == 2.0);
  CHECK(value_at(ha, "theta", 0.1) == 1.0);
  // b at a's samples up to 0.2: 0, -1, -2; a: 0, 1, -3. Differences 0, -2, 1: sum of squares
  // 5; a's sum of squares 10. sqrt(5 / 10).
  CHECK(normalized_rms_difference(ha, hb, "theta", 0.2) ==
        doctest::Approx(std::sqrt(0.5)).epsilon(1e-15));
  CHECK(first_impact(ha) == std::pair<double, int>{0.15, 2});
  CHECK(first_impact(hb) == std::pair<double, int>{0.0, 0});
}
