// Claims: a verdict is the conjunction of its checks, a failed run makes it "not evaluated",
// and claims.json carries the numbers the verdict came from. Expected values are written by
// hand from the definitions in paper-figures/claims.hpp.
#include "paper-figures/claims.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

using nsb::paper_figures::Check;
using nsb::paper_figures::Claim;

namespace {
bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}
}  // namespace

TEST_CASE("a check compares its value with its threshold") {
  CHECK(Check{"r", 0.4, "<", 0.5, ""}.holds());
  CHECK_FALSE(Check{"r", 0.5, "<", 0.5, ""}.holds());
  CHECK(Check{"r", 0.5, "<=", 0.5, ""}.holds());
  CHECK(Check{"b", 1.3, ">", 1.0, ""}.holds());
  CHECK_FALSE(Check{"b", 1.0, ">", 1.0, ""}.holds());
  CHECK(Check{"n", 1.0, ">=", 1.0, ""}.holds());
  // A missing measurement never satisfies a check, whichever the direction.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK_FALSE(Check{"r", nan, "<", 0.5, ""}.holds());
  CHECK_FALSE(Check{"r", nan, ">", 0.5, ""}.holds());
  CHECK_THROWS_AS((void)Check({"r", 1.0, "==", 1.0, ""}).holds(), std::invalid_argument);
}

TEST_CASE("a claim holds when every check holds, and says which do not") {
  Claim c{"C1", "friction makes the deck rotate"};
  CHECK_FALSE(c.holds());  // no checks: nothing shown
  c.checks.push_back({"ratio_a", 0.42, "<", 0.5, "half"});
  c.checks.push_back({"ratio_b", 0.3, "<", 0.5, "half"});
  CHECK(c.holds());
  CHECK(c.reason() == "every check holds");
  c.checks.push_back({"ratio_c", 0.7, "<", 0.5, "half"});
  CHECK_FALSE(c.holds());
  CHECK(c.reason() == "ratio_c = 0.7 is not < 0.5");
  c.checks.pop_back();
  c.failure = "exc5-mu0: diverged at t = 3 s";
  CHECK_FALSE(c.holds());
  CHECK(contains(c.reason(), "not evaluated: exc5-mu0"));
}

TEST_CASE("claims.json and claims.md carry the verdict and its numbers") {
  Claim c{"C2", "grows \"faster\" than linearly"};
  c.measured = {{"peak", 1.5e-3}, {"missing", std::numeric_limits<double>::infinity()}};
  c.checks.push_back({"exponent", 1.25, ">", 1.0, "b > 1"});
  c.runs = {"exc1-moreau", "exc7-moreau"};
  const std::string json = nsb::paper_figures::claims_json({c});
  CHECK(contains(json, "{\"claims\": ["));
  CHECK(contains(json, "\"id\": \"C2\""));
  CHECK(contains(json, "grows \\\"faster\\\" than"));  // quotes escaped
  CHECK(contains(json, "\"holds\": true"));
  CHECK(contains(json, "\"peak\": 0.0015"));
  CHECK(contains(json, "\"missing\": null"));  // non-finite: null, never inf
  CHECK(contains(json, "\"value\": 1.25, \"op\": \">\", \"threshold\": 1"));
  CHECK(contains(json, "\"runs\": [\"exc1-moreau\", \"exc7-moreau\"]"));
  const std::string md = nsb::paper_figures::claims_markdown({c});
  CHECK(contains(md, "| C2 |"));
  CHECK(contains(md, "| holds |"));
  CHECK(contains(md, "exponent = 1.25 (> 1)"));
}

TEST_CASE("a compliance claim carries its damping law; the others carry none") {
  Claim c{"C4'", "tracks"};
  c.checks.push_back({"abs_peak_ratio_minus_1_k100", 0.005, "<", 0.1, "10 %"});
  c.runs = {"exc5-k100-hunt_crossley_exact"};
  c.law = {"hunt_crossley_exact", 1000.0, 0.001, 0.0};
  const std::string json = nsb::paper_figures::claims_json({c});
  CHECK(contains(json, "\"id\": \"C4'\""));
  CHECK(contains(json, "\"law\": {\"name\": \"hunt_crossley_exact\", \"chi\": 1000, "
                       "\"effective_restitution\": 0.001, \"nonsmooth_restitution\": 0}"));
  const std::string md = nsb::paper_figures::claims_markdown({c});
  CHECK(contains(md, "tracks (law hunt_crossley_exact, effective restitution 0.001; "
                     "nonsmooth eps = 0)"));
  CHECK(contains(md, "Damping law of eq. (9): `hunt_crossley_exact`, chi = 1000"));
  Claim plain{"C2", "grows"};
  plain.checks.push_back({"exponent", 1.25, ">", 1.0, "b > 1"});
  CHECK_FALSE(contains(nsb::paper_figures::claims_json({plain}), "\"law\""));
  CHECK_FALSE(contains(nsb::paper_figures::claims_markdown({plain}), "Damping law"));
}

TEST_CASE("JSON numbers and strings") {
  using nsb::paper_figures::json_number;
  using nsb::paper_figures::json_string;
  // JSON (RFC 8259) has no NaN or infinity: they are written as null.
  CHECK(json_number(std::numeric_limits<double>::quiet_NaN()) == "null");
  CHECK(json_number(std::numeric_limits<double>::infinity()) == "null");
  // The shortest text that reads back to the same double (summary.json's form): 0.1 is
  // 0.1000000000000000055..., and "0.1" is the shortest text that reads back to it.
  CHECK(json_number(0.1) == "0.1");
  CHECK(std::stod(json_number(0.1 + 0.2)) == 0.1 + 0.2);
  CHECK(json_number(-2.0) == "-2");
  // A quote, a backslash and a newline are escaped (RFC 8259, section 7), and so is every
  // other control character.
  CHECK(json_string("a\"b\\c\nd") == "\"a\\\"b\\\\c\\nd\"");
  CHECK(json_string("\x01\t") == "\"\\u0001\\t\"");
}

TEST_CASE("C4 from hand-made peaks: a stiff contact tracks, a soft one underestimates") {
  using nsb::paper_figures::claim_c4;
  // Nonsmooth peak 0.01 rad. 1e-4 k: 0.005 (ratio 0.5 < 0.9). 1e0 k: no check. 1e2 k: 0.0105,
  // |1.05 - 1| = 0.05 < 0.1, RMS difference 0.2 < 0.5.
  const auto c = claim_c4(0.01, 12.0, {{1e-4, 0.005, 0.7}, {1.0, 0.009, 0.3}, {1e2, 0.0105, 0.2}});
  REQUIRE(c.checks.size() == 3);
  CHECK(c.checks[0].quantity == "peak_ratio_k0.0001");
  CHECK(c.checks[0].value == doctest::Approx(0.5));
  CHECK(c.checks[1].quantity == "abs_peak_ratio_minus_1_k100");
  CHECK(c.checks[1].value == doctest::Approx(0.05));
  CHECK(c.checks[2].value == 0.2);
  CHECK(c.holds());
  // 1e2 k off by 20 %: it no longer tracks.
  CHECK_FALSE(claim_c4(0.01, 12.0, {{1e2, 0.012, 0.2}}).holds());
}

TEST_CASE("C5 and the first pounding, by hand") {
  using nsb::paper_figures::claim_c5;
  using nsb::paper_figures::measure_first_pounding;
  // g closes at t = 1 (first g < 0 after t0 = 0), reaches -3 at t = 2 and opens at t = 4:
  // penetration 3, duration 4 - 1 = 3.
  const auto fp = measure_first_pounding(1.0, {0, 1, 2, 3, 4}, {1, -1, -3, -2, 0.5}, 0.0);
  CHECK(fp.penetration == 3.0);
  CHECK(fp.duration == 3.0);
  // Still closed at the end of the history: not measured.
  CHECK(std::isnan(measure_first_pounding(1.0, {0, 1}, {1, -1}, 0.0).duration));
  // Ascending factors; the lower one deeper (2x) and longer (2.5x): holds.
  CHECK(claim_c5({{1e-4, 0.002, 0.05}, {1.0, 0.001, 0.02}}).holds());
  // Equal penetrations: "strictly deeper" fails.
  CHECK_FALSE(claim_c5({{1e-4, 0.001, 0.05}, {1.0, 0.001, 0.02}}).holds());
  // One factor: no ratio, the checks are NaN and fail.
  CHECK_FALSE(claim_c5({{1.0, 0.001, 0.02}}).holds());
}
