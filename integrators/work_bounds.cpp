#include "integrators/work_bounds.hpp"

#include "io/csv.hpp"

#include <cmath>
#include <variant>

namespace nsb::integrators {

namespace {

// A count for messages: 3 significant digits, one beyond a double as "more than 1e308".
std::string count(double n) {
  return std::isfinite(n) ? io::three_digits(n) : std::string("more than 1e308");
}

// "at least 1e+09", or "more than 1e308".
std::string at_least(double n) {
  return std::isfinite(n) ? "at least " + io::three_digits(n) : count(n);
}

// The largest step [s] the options allow and its key; 0 when the method has none.
struct LargestStep {
  double h = 0.0;
  const char* key = "";
  bool below_default = false;  // the step is smaller than the method's default
};

LargestStep largest_step(const RunConfig& config) {
  struct Visitor {
    LargestStep operator()(const MoreauJeanOptions& o) const {
      return {o.step, "step", o.step < MoreauJeanOptions{}.step};
    }
    LargestStep operator()(const ComplianceOptions& o) const {
      return {o.max_step, "max_step", o.max_step < ComplianceOptions{}.max_step};
    }
    LargestStep operator()(const EventDrivenOptions& o) const {
      return {o.max_step, "max_step", o.max_step > 0.0};
    }
  };
  return std::visit(Visitor{}, config);
}

}  // namespace

std::string work_misfit(const RunConfig& config, double t0, double sample_dt, bool step_given,
                        bool sample_given) {
  const double end = end_time(config);
  const double duration = end - t0;
  if (!(duration > 0.0)) return {};
  const std::string span = "end_time " + io::three_digits(end) + " s";
  // The key named: the short interval (step or sample_dt) unless it is at its default while
  // end_time is given, or end_time alone is longer than any run (kLongRun).
  const auto blame = [&](const std::string& key, bool key_given) {
    return (!key_given || duration > kLongRun) ? std::string("end_time") : key;
  };
  const LargestStep h = largest_step(config);
  if (h.h > 0.0) {
    const double steps = duration / h.h;
    if (!(steps <= kMaxSteps)) {
      return blame(h.key, step_given && h.below_default) + ": " + span + " with " + h.key +
             " " + io::three_digits(h.h) + " s takes " + at_least(steps) +
             " steps, more than the " + count(kMaxSteps) +
             " a run may take (docs/scenes.md, \"The work of a run\")";
    }
  }
  if (sample_dt > 0.0) {
    const double rows = duration / sample_dt + 1.0;
    if (!(rows <= kMaxRows)) {
      return blame("sample_dt", sample_given) + ": " + span + " with output.sample_dt " +
             io::three_digits(sample_dt) + " s gives " + count(rows) +
             " history rows, more than the " + count(kMaxRows) +
             " a run may write (docs/scenes.md, \"The work of a run\")";
    }
  } else if (std::holds_alternative<MoreauJeanOptions>(config)) {
    // Every step is a row.
    const double rows = duration / h.h + 1.0;
    if (!(rows <= kMaxRows)) {
      return blame(h.key, step_given && h.below_default) + ": " + span + " with " + h.key +
             " " + io::three_digits(h.h) + " s and output.sample_dt = 0 (a row per step) gives " +
             count(rows) + " history rows, more than the " + count(kMaxRows) +
             " a run may write; set output.sample_dt (docs/scenes.md, \"The work of a run\")";
    }
  }
  return {};
}

std::string PaceWatch::look(std::int64_t steps, double t) {
  const double advanced = t - block_start_;
  block_start_ = t;
  const double left = end_time_ - t;
  const double budget = kMaxSteps - static_cast<double>(steps);
  // At the block's average step advanced / kPaceBlock, the rest takes
  // left / advanced * kPaceBlock steps.
  if (!(left * static_cast<double>(kPaceBlock) > budget * advanced)) return {};
  const double pace = advanced / static_cast<double>(kPaceBlock);
  return "step size collapsed at t = " + io::three_digits(t) + " s: the last " +
         std::to_string(kPaceBlock) + " steps averaged " + io::three_digits(pace) +
         " s, so the " + io::three_digits(left) + " s left would take " +
         count(pace > 0.0 ? left / pace : INFINITY) + " steps, more than the " +
         count(kMaxSteps) + " a run may take";
}

}  // namespace nsb::integrators
