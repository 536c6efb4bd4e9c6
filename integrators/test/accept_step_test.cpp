// System::accept_step under every integrator: a system that removes its contact or stops the
// run at a known time, a ball of mass 1 resting under gravity on a floor.
#include "integrators/compliance.hpp"
#include "integrators/event_driven.hpp"
#include "integrators/moreau_jean.hpp"
#include "integrators/run_bookkeeping.hpp"
#include "io/csv.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace nsb::integrators {
namespace {

constexpr double kGravity = 9.81;  // [m/s^2]
constexpr double kNever = std::numeric_limits<double>::infinity();

// A unit mass at y = 0 on the floor y >= 0 (restitution 0, no friction), under gravity. At the
// first accepted step ending at or after remove_at, accept_step removes the contact (far from
// then on, its gap still y); at the first one ending at or after stop_at, it stops the run.
// It records what the integrator handed it.
class Breakable final : public SystemBase {
 public:
  Breakable(double remove_at, double stop_at)
      : SystemBase({"y"}, {"v"}), remove_at_(remove_at), stop_at_(stop_at) {}

  void forces(double, const Vector&, const Vector&, Vector& f) override { f[0] = -kGravity; }
  int contacts() const override { return 1; }
  void contact_data(double, const Vector& q, const Vector&,
                    std::vector<ContactData>& out) const override {
    set_fixed_contact(out[0], q[0], Vector::Ones(1), Vector::Zero(1), 0.0, 0.0);
    out[0].far = removed_;
  }

  StepVerdict accept_step(const AcceptedStep& step) override {
    ++calls;
    if (stopped) ++calls_after_stop;
    last_t = step.t;
    CHECK(step.h > 0.0);
    CHECK(step.q->size() == 1);
    const double impulse = (*step.normal_impulse)[0];
    if (removed_) {
      impulse_after_removal = std::max(impulse_after_removal, std::abs(impulse));
    } else {
      impulse_before_removal += impulse;
    }
    if (!removed_ && step.t >= remove_at_) {
      removed_ = true;
      removed_at = step.t;
      return StepVerdict::kContactsRemoved;
    }
    if (step.t >= stop_at_) {
      stopped = true;
      return StepVerdict::kUnseated;
    }
    return StepVerdict::kContinue;
  }

  std::vector<LimitStateValue> limit_states() const override {
    std::vector<LimitStateValue> out(1);
    out[0].name = "floor";
    out[0].unit = "kN";
    out[0].exceeded = removed_;
    out[0].time = removed_at;
    out[0].removes_contact = 1;
    return out;
  }

  int calls = 0, calls_after_stop = 0;
  bool stopped = false;
  double last_t = 0.0, removed_at = kNever;
  double impulse_before_removal = 0.0;  // sum of the normal impulses up to the removal [kN s]
  double impulse_after_removal = 0.0;   // largest |normal impulse| of a step after it [kN s]

 private:
  double remove_at_, stop_at_;
  bool removed_ = false;
};

// One run of `method` ("moreau", "event_driven", "compliance") to end_time.
RunResult run(const std::string& method, Breakable& s, Recorder& rec, double end_time) {
  if (method == "moreau") {
    MoreauJeanOptions o;
    o.end_time = end_time;
    o.step = 1e-3;
    return moreau_jean(s, o, rec);
  }
  if (method == "event_driven") {
    EventDrivenOptions o;
    o.end_time = end_time;
    return event_driven(s, o, rec);
  }
  ComplianceOptions o;
  o.end_time = end_time;
  o.stiffness = 1e6;
  o.max_step = 1e-3;
  return compliance(s, o, rec);
}

TEST_CASE("every method stops at the first accepted step at or after the unseating time") {
  for (const std::string method : {"moreau", "event_driven", "compliance"}) {
    CAPTURE(method);
    Breakable s(kNever, 0.25);
    Recorder rec(s, 0.0);
    const RunResult r = run(method, s, rec, 1.0);
    CHECK(r.status == RunStatus::kUnseated);
    CHECK(is_result(r.status));
    CHECK_FALSE(succeeded(r.status));
    CHECK(s.stopped);
    CHECK(s.calls_after_stop == 0);
    CHECK(s.last_t >= 0.25);
    CHECK(r.end_time == s.last_t);
    CHECK(r.failure_time == s.last_t);
    CHECK(rec.at(rec.rows() - 1, 0) == s.last_t);
    CHECK(r.message == "unseated at t = " + io::three_digits(s.last_t) + " s");
    if (method == "moreau") {
      CHECK(s.last_t < 0.25 + 1e-3 + 1e-12);
      CHECK(s.calls == r.steps);
    }
    if (method == "compliance") CHECK(s.calls == r.steps);
  }
}

TEST_CASE("a removed contact is never active again, and the impulses before are the step's") {
  for (const std::string method : {"moreau", "event_driven", "compliance"}) {
    CAPTURE(method);
    Breakable s(0.2, kNever);
    Recorder rec(s, 0.0);
    const double end_time = 0.5;
    const RunResult r = run(method, s, rec, end_time);
    CHECK(succeeded(r.status));
    REQUIRE(s.removed_at >= 0.2);
    // Resting, the floor carries the weight: the impulses up to the removal sum to m g t.
    CHECK(s.impulse_before_removal == doctest::Approx(kGravity * s.removed_at).epsilon(2e-2));
    CHECK(s.impulse_after_removal == 0.0);
    // The removal is an event on the contact, at its time.
    int removals = 0;
    for (const Event& e : rec.events()) {
      if (e.kind != EventKind::kWarning) continue;
      ++removals;
      CHECK(e.t == s.removed_at);
      CHECK(e.contact == 1);
      CHECK(e.note == "floor exceeded: contact removed");
    }
    CHECK(removals == 1);
    // Free fall from the removal on.
    const double fall = 0.5 * kGravity * (end_time - s.removed_at) * (end_time - s.removed_at);
    const std::size_t y = rec.column("y"), lambda = rec.column("lambdaN1");
    CHECK(rec.at(rec.rows() - 1, y) == doctest::Approx(-fall).epsilon(2e-2));
    for (std::size_t k = 0; k < rec.rows(); ++k) {
      if (rec.at(k, 0) > s.removed_at + 1e-12) CHECK(rec.at(k, lambda) == 0.0);
    }
  }
}

TEST_CASE("RunBookkeeping: an unseated run is a result with the stop as failure_time") {
  const Progress none;
  RunBookkeeping book("moreau", none, 1);
  book.unseat(0.3);
  EnergyBalance e;
  e.close();
  const RunResult r = book.finish(0.3, false, e, nullptr);
  CHECK(r.status == RunStatus::kUnseated);
  CHECK(r.failure_time == 0.3);
  CHECK(to_string(r.status) == "unseated");
  CHECK(parse_run_status("unseated") == RunStatus::kUnseated);
}

}  // namespace
}  // namespace nsb::integrators
