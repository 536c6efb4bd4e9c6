#include "integrators/run_bookkeeping.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace {

using nsb::integrators::ContactStageCounts;
using nsb::integrators::EnergyBalance;
using nsb::integrators::Progress;
using nsb::integrators::RunBookkeeping;
using nsb::integrators::RunStatus;

// A balance whose error is finite (zero: nothing happened).
EnergyBalance closed_balance() {
  EnergyBalance e;
  e.close();
  return e;
}

}  // namespace

TEST_CASE("a run that reaches its end is completed, counts its steps and reports progress") {
  std::vector<double> calls;
  const Progress progress = [&calls](double t) { calls.push_back(t); };
  RunBookkeeping book("moreau", progress, 2);
  for (int k = 1; k <= 5; ++k) {
    book.count_step();
    book.progress_at_interval(0.1 * k);
  }
  const auto r = book.finish(0.5, true, closed_balance(), nullptr);
  CHECK(r.method == "moreau");
  CHECK(r.status == RunStatus::kCompleted);
  CHECK(r.completed);
  CHECK(r.steps == 5);
  CHECK(r.end_time == 0.5);
  CHECK(r.wall_time >= 0.0);
  // Every second step (steps 2 and 4), then once at the end.
  CHECK(calls == std::vector<double>{0.1 * 2, 0.1 * 4, 0.5});
}

TEST_CASE("an empty progress callback is never called") {
  const Progress none;
  RunBookkeeping book("compliance", none, 1);
  book.count_step();
  book.progress_at_interval(0.1);
  CHECK(book.finish(0.1, true, closed_balance(), nullptr).status == RunStatus::kCompleted);
}

TEST_CASE("the contact stage's counts set the status and the lcp_status table") {
  const Progress none;
  ContactStageCounts counts;
  counts.solves = 3;
  counts.fallbacks = 1;
  counts.by_status[static_cast<int>(nsb::lcp::Status::kSolved)] = 3;
  RunBookkeeping book("event_driven", none, 1);
  const auto r = book.finish(1.0, true, closed_balance(), &counts);
  CHECK(r.status == RunStatus::kCompletedWithFallbacks);
  CHECK(r.lcp_solves == 3);
  CHECK(r.lcp_fallbacks == 1);
  CHECK(r.lcp_status.size() == 1);
  CHECK(r.lcp_status.at(std::string(nsb::lcp::to_string(nsb::lcp::Status::kSolved))) == 3);
}

TEST_CASE("failure_time is the first unsolved problem for contact_unsolved") {
  const Progress none;
  ContactStageCounts counts;
  counts.solves = 2;
  counts.unsolved = 2;
  RunBookkeeping book("moreau", none, 1);
  book.note_unsolved(0.25);
  book.note_unsolved(0.75);
  const auto r = book.finish(1.0, true, closed_balance(), &counts);
  CHECK(r.status == RunStatus::kContactUnsolved);
  CHECK(r.failure_time == 0.25);
}

TEST_CASE("failure_time is where the run stopped for diverged and stalled") {
  const Progress none;
  SUBCASE("divergence") {
    // Moreau–Jean diverges on its step to t_k+1 = 0.4 and ends at t_k = 0.3.
    RunBookkeeping book("moreau", none, 1);
    book.diverge(0.4);
    CHECK(book.diverged());
    const auto r = book.finish(0.3, false, closed_balance(), nullptr);
    CHECK(r.status == RunStatus::kDiverged);
    CHECK(r.failure_time == 0.4);
  }
  SUBCASE("a stall") {
    RunBookkeeping book("event_driven", none, 1);
    book.stall(0.6);
    const auto r = book.finish(0.6, false, closed_balance(), nullptr);
    CHECK(r.status == RunStatus::kStalled);
    CHECK(r.failure_time == 0.6);
  }
  SUBCASE("a run that stops short without a reason given has stalled at its end") {
    RunBookkeeping book("compliance", none, 1);
    const auto r = book.finish(0.7, false, closed_balance(), nullptr);
    CHECK(r.status == RunStatus::kStalled);
    CHECK(r.failure_time == 0.7);
  }
  SUBCASE("a non-finite energy balance is divergence at the end") {
    RunBookkeeping book("compliance", none, 1);
    EnergyBalance e;
    e.error = std::numeric_limits<double>::quiet_NaN();
    const auto r = book.finish(0.8, true, e, nullptr);
    CHECK(r.status == RunStatus::kDiverged);
    CHECK(r.failure_time == 0.8);
    CHECK(std::isnan(r.energy.error));
  }
}

TEST_CASE("a progress interval that is not a power of two is a caller's mistake") {
  const Progress none;
  CHECK_THROWS_AS(RunBookkeeping("moreau", none, 3), std::invalid_argument);
  CHECK_THROWS_AS(RunBookkeeping("moreau", none, 0), std::invalid_argument);
  CHECK_NOTHROW(RunBookkeeping("moreau", none, 1));
}
