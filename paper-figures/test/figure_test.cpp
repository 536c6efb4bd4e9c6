// The registered figures: each has a unique name, says which runs it needs and how it draws,
// and has its gnuplot script with labelled axes (a unit in brackets) in paper-figures/gnuplot.
#include "paper-figures/figure.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

using nsb::paper_figures::registered_figures;

TEST_CASE("every registered figure has a name, its runs, a draw and its script") {
  std::set<std::string> names;
  for (const auto& f : registered_figures()) {
    CAPTURE(f.name);
    CHECK(names.insert(f.name).second);
    CHECK(static_cast<bool>(f.runs));
    CHECK(static_cast<bool>(f.draw));
    std::ifstream in(nsb::paper_figures::gnuplot_dir() / (f.name + ".gp"));
    REQUIRE(in);
    std::ostringstream s;
    s << in.rdbuf();
    const std::string gp = s.str();
    for (const char* axis : {"set xlabel '", "set ylabel "}) {
      const auto at = gp.find(axis);
      REQUIRE(at != std::string::npos);
      const auto line = gp.substr(at, gp.find('\n', at) - at);
      CAPTURE(line);
      CHECK(line.find('[') != std::string::npos);
    }
    CHECK(gp.find("data") != std::string::npos);  // reads the CSV through `data`
  }
  CHECK(names.size() == 7);  // Figs. 3-8 and the eta map
}

TEST_CASE("--quick is a subset of the full set") {
  const auto quick = nsb::paper_figures::make_setup(true);
  const auto full = nsb::paper_figures::make_setup(false);
  auto subset = [](const auto& a, const auto& b) {
    for (const auto& x : a) {
      if (std::find(b.begin(), b.end(), x) == b.end()) return false;
    }
    return true;
  };
  CHECK(subset(quick.pga_runs, full.pga_runs));
  CHECK(subset(quick.mu0_runs, full.mu0_runs));
  CHECK(subset(quick.factors, full.factors));
  CHECK(subset(quick.windows, full.windows));
  CHECK(subset(quick.eta_skews, full.eta_skews));
  CHECK(subset(quick.eta_ratios, full.eta_ratios));
  CHECK(quick.compliance_end > 0);  // the strong phase only
  CHECK(full.compliance_end == 0);  // the scene's end time
}

TEST_CASE("gnuplot variables: numbers to 17 digits, strings quoted") {
  CHECK(nsb::paper_figures::gnuplot_number("t", 0.1).value == "0.10000000000000001");
  CHECK(nsb::paper_figures::gnuplot_string("f", "it's").value == "'it''s'");
  CHECK(nsb::paper_figures::factor_list({1e-4, 1e2}) == "0.0001 100");
}
