// Claims: a verdict is the conjunction of its checks, a failed run makes it "not evaluated",
// and claims.json carries the numbers the verdict came from. Expected values are written by
// hand from the definitions in paper-figures/claims.hpp.
#include "paper-figures/claims.hpp"

#include <doctest/doctest.h>

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
