// The bound on the work of a run (integrators/work_bounds.hpp): the count before the run and
// the pace check during an adaptive one, with the counts derived by hand.
#include "integrators/work_bounds.hpp"

#include <doctest/doctest.h>

#include <string>

namespace ni = nsb::integrators;

namespace {

bool contains(const std::string& s, const std::string& part) {
  const bool ok = s.find(part) != std::string::npos;
  if (!ok) MESSAGE("'" << s << "' does not contain '" << part << "'");
  return ok;
}

}  // namespace

TEST_CASE("work_misfit counts the fewest steps and the rows, and names the key") {
  ni::MoreauJeanOptions m;
  m.end_time = 1.0;
  m.step = 1e-8;  // 1e8 steps: exactly the bound, accepted
  CHECK(ni::work_misfit(m, 0.0, 1e-3).empty());
  m.step = 0.99e-8;  // 1.0101e8 steps
  CHECK(contains(ni::work_misfit(m, 0.0, 1e-3),
                 "step: end_time 1 s with step 9.9e-09 s takes at least 1.01e+08 steps"));
  // The step at its default while end_time is given: end_time is named.
  m.step = 1e-4;
  m.end_time = 2e4;  // 2e8 steps of the default step
  CHECK(contains(ni::work_misfit(m, 0.0, 0.01, false, true), "end_time: end_time 2e+04 s"));
  // Rows: 10 s every 1e-6 s is 1e7 + 1 rows, one more than kMaxRows.
  m.end_time = 10.0;
  CHECK(contains(ni::work_misfit(m, 0.0, 1e-6), "sample_dt: end_time 10 s with output.sample_dt "
                                                "1e-06 s gives 1e+07 history rows"));
  CHECK(ni::work_misfit(m, 0.0, 1.000001e-6).empty());  // 9999991 rows
  // The duration counts from the initial time.
  CHECK(ni::work_misfit(m, 9.9, 1e-6).empty());
  // Event-driven without max_step has no step bound; its rows still count.
  ni::EventDrivenOptions e;
  e.end_time = 1e308;
  CHECK(ni::work_misfit(e, 0.0, 0.0).empty());
  CHECK(contains(ni::work_misfit(e, 0.0, 0.005), "end_time: end_time 1e+308 s"));
  ni::ComplianceOptions c;
  c.end_time = 1e6;  // 1e9 steps of max_step = 1e-3 s
  CHECK(contains(ni::work_misfit(c, 0.0, 0.0, true, false),
                 "end_time: end_time 1e+06 s with max_step 0.001 s takes at least 1e+09 steps"));
}

TEST_CASE("PaceWatch stops a run whose step collapsed, looking every kPaceBlock steps") {
  const auto b = ni::kPaceBlock;  // 8192
  ni::PaceWatch pace(0.0, 10.0);
  // Between two looks nothing is said, whatever the time.
  CHECK(pace.collapsed(b - 1, 0.0).empty());
  // 8192 steps over 1e-3 s: 10 s at 1.22e-7 s a step is 8.2e7 steps, within 1e8 - 8192.
  CHECK(pace.collapsed(b, 1e-3).empty());
  // The next 8192 steps advance 1e-6 s: the 9.999 s left would take 8.2e10 steps.
  const std::string why = pace.collapsed(2 * b, 1e-3 + 1e-6);
  CHECK(contains(why, "step size collapsed at t = 0.001 s: the last 8192 steps averaged "
                      "1.22e-10 s"));
  CHECK(contains(why, "more than the 1e+08 a run may take"));
  // A block that does not advance at all (a stuck step) is a collapse too.
  ni::PaceWatch stuck(0.0, 1.0);
  CHECK_FALSE(stuck.collapsed(b, 0.0).empty());
}
