// The plot tables drawn from results.csv, on a small hand-made table whose expected curves,
// shares and bars are worked out in the comments.
#include "sweep/plots.hpp"

#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

using namespace nsb::sweep;

namespace {

// Two records x two PGAs, one failed run (left out), and one row without a PGA value.
Table ida_table() {
  Table t;
  t.header = {"run", "record", "model.excitation.target_pga", "status", "peak_theta", "wall_s"};
  t.rows = {{"0000", "a", "0.5", "completed", "0.004", "1"},
            {"0001", "a", "1", "completed", "0.02", "1"},
            {"0002", "b", "0.5", "completed_with_fallbacks", "0.012", "1"},
            {"0003", "b", "1", "diverged", "", "1"},
            {"0004", "b", "1.5", "completed", "0.03", "1"}};
  return t;
}

}  // namespace

TEST_CASE("IDA: one curve per other factor, completed runs only, sorted by PGA") {
  const auto p = ida_points(results_of(ida_table()), PlotOptions{});
  REQUIRE(p.size() == 4);
  CHECK(p[0].curve == "record=a");
  CHECK(p[0].pga == 0.5);
  CHECK(p[1].response == 0.02);
  CHECK(p[2].curve == "record=b");
  CHECK(p[3].pga == 1.5);  // the diverged run at 1 g is not a point
}

TEST_CASE("exceedance: share of the completed runs above the limit at each PGA") {
  PlotOptions o;
  o.limit = 0.01;
  const auto e = exceedance_points(results_of(ida_table()), o);
  // 0.5 g: 0.004 and 0.012 -> 1 of 2; 1 g: 0.02 -> 1 of 1; 1.5 g: 0.03 -> 1 of 1.
  REQUIRE(e.size() == 3);
  CHECK(e[0].runs == 2);
  CHECK(e[0].exceeding == 1);
  CHECK(e[0].share == 0.5);
  CHECK(e[1].share == 1.0);
  o.limit = 0.025;
  CHECK(exceedance_points(results_of(ida_table()), o)[1].share == 0.0);
  CHECK(exceedance_points(results_of(ida_table()), o)[2].share == 1.0);
}

TEST_CASE("tornado: swing about the base run, largest first") {
  Table t;
  t.header = {"run", "mu", "gap", "status", "peak_theta", "wall_s"};
  t.rows = {{"0000", "", "", "completed", "0.010", "1"},  // base
            {"0001", "0.2", "", "completed", "0.008", "1"},
            {"0002", "0.8", "", "completed", "0.013", "1"},  // mu: [0.008, 0.013], swing 0.005
            {"0003", "", "0.5", "completed", "0.011", "1"},  // gap: [0.010, 0.011] with the base
            {"0004", "", "0.9", "stalled", "0.5", "1"}};     // failed: left out
  const auto bars = tornado_bars(results_of(t), PlotOptions{});
  REQUIRE(bars.size() == 2);
  CHECK(bars[0].factor == "mu");
  CHECK(bars[0].low == 0.008);
  CHECK(bars[0].high == 0.013);
  CHECK(bars[0].low_level == "0.2");
  CHECK(bars[0].base == 0.010);
  CHECK(bars[1].factor == "gap");
  CHECK(bars[1].low == 0.010);  // the base is lower than the only level
  CHECK(bars[1].high == 0.011);
  t.rows.erase(t.rows.begin());
  CHECK(tornado_bars(results_of(t), PlotOptions{}).empty());  // no base run, no tornado
}

TEST_CASE("draw_plots writes PNG and SVG beside their CSV") {
  const auto dir =
      std::filesystem::temp_directory_path() / ("nsb_plots_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "results.csv")
      << "run,record,model.excitation.target_pga,status,peak_theta,wall_s\n"
         "0000,a,0.5,completed,0.004,1\n0001,a,1,completed,0.02,1\n";
  const auto files = draw_plots(results_of(read_csv(dir / "results.csv")), dir / "plots", PlotOptions{});
  for (const char* f :
       {"ida.csv", "ida.png", "ida.svg", "exceedance.csv", "exceedance.png", "exceedance.svg"}) {
    INFO(f);
    CHECK(std::filesystem::file_size(dir / "plots" / f) > 0);
  }
  CHECK(!std::filesystem::exists(dir / "plots" / "tornado.csv"));
  PlotOptions bad;
  bad.response = "peak_omega";
  CHECK_THROWS_AS(draw_plots(results_of(read_csv(dir / "results.csv")), dir / "plots", bad), std::invalid_argument);
  std::filesystem::remove_all(dir);
}

TEST_CASE("an unseated run: its own IDA point, exceeding in the exceedance plot") {
  Table t = ida_table();
  // Record b at 1 g lost a seat at a response below every limit.
  t.rows[3] = {"0003", "b", "1", "unseated", "0.001", "1"};
  const auto p = ida_points(results_of(t), PlotOptions{});
  REQUIRE(p.size() == 5);
  CHECK((p[3].curve == "record=b" && p[3].pga == 1.0 && p[3].unseated));
  CHECK_FALSE(p[2].unseated);
  PlotOptions o;
  o.limit = 0.01;
  const auto e = exceedance_points(results_of(t), o);
  // 1 g: a's 0.02 exceeds, b is unseated: 2 of 2, one unseated.
  CHECK((e[1].runs == 2 && e[1].exceeding == 2 && e[1].unseated == 1));
  CHECK((e[0].unseated == 0 && e[0].exceeding == 1));

  const auto dir = std::filesystem::temp_directory_path() /
                   ("nsb_plots_unseated_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "results.csv")
      << "run,record,model.excitation.target_pga,status,peak_theta,wall_s\n"
         "0000,a,0.5,completed,0.004,1\n0001,a,1,unseated,0.002,1\n";
  (void)draw_plots(results_of(read_csv(dir / "results.csv")), dir / "plots", o);
  std::ifstream ida(dir / "plots" / "ida.csv"), lost(dir / "plots" / "ida-unseated.csv");
  const std::string ida_text((std::istreambuf_iterator<char>(ida)), {});
  const std::string lost_text((std::istreambuf_iterator<char>(lost)), {});
  CHECK(ida_text.find(",1,") == std::string::npos);  // not joined to the curve
  CHECK(lost_text.find("record=a,1,0.002") != std::string::npos);
  std::ifstream ex(dir / "plots" / "exceedance.csv");
  const std::string ex_text((std::istreambuf_iterator<char>(ex)), {});
  CHECK(ex_text.find("runs,exceeding,share,unseated\n0.5,1,0,0,0\n1,1,1,1,1\n") !=
        std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST_CASE("a bridge in segments: the default response is frame 1's peak rotation") {
  // results.csv of a segmented bridge has peak_theta1, peak_theta2 and no peak_theta; the
  // default options plot peak_theta1 (the IDA table's last column), not an error.
  const auto dir = std::filesystem::temp_directory_path() /
                   ("nsb_plots_segments_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "results.csv")
      << "run,record,model.excitation.target_pga,status,peak_theta1,peak_theta2,wall_s\n"
         "0000,a,0.5,completed,0.004,0.005,1\n0001,a,1,completed,0.02,0.03,1\n";
  (void)draw_plots(results_of(read_csv(dir / "results.csv")), dir / "plots", PlotOptions{});
  std::ifstream ida(dir / "plots" / "ida.csv");
  std::string header;
  std::getline(ida, header);
  CHECK(header == "curve,model.excitation.target_pga,peak_theta1");
  std::filesystem::remove_all(dir);
}
