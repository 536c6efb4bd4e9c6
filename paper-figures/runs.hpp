// The runs behind the figures: each is a scene of scenes/ with overrides, made by the sweep
// module's runner (sweep::run_threaded: an ordinary runs::execute call whose outputs go to
// runs/<id>/). Its status comes from the run's typed row, its history from the record in
// memory, as history.csv and events.csv hold it: a value that is not finite (an empty field
// there) is NaN.
#pragma once

#include "integrators/recorder.hpp"

#include <cstddef>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace nsb::paper_figures {

struct RunSpec {
  std::string name;                    // unique in a study, e.g. "exc5-moreau"
  std::string scene;                   // scene file stem under the scenes folder
  std::vector<std::string> overrides;  // scene overrides "key=value", as `nsbridge run --set`
};

// A run's history.csv (columns by name, one row per recorded sample; an empty field, which
// the recorder writes for a non-finite value, reads as NaN) and its events.csv.
class History {
 public:
  History() = default;
  // The history a recorder holds, as its history.csv and events.csv say it.
  explicit History(const integrators::Recorder& recorder);
  // Reads <dir>/history.csv and <dir>/events.csv. Throws std::runtime_error naming the file
  // when one cannot be read or a row's width differs from the header's.
  static History read(const std::filesystem::path& dir);
  std::size_t rows() const { return columns_.empty() ? 0 : data_.size() / columns_.size(); }
  double at(std::size_t row, std::size_t col) const { return data_[row * columns_.size() + col]; }
  // Index of a column by name; throws std::out_of_range naming it when absent.
  std::size_t column(std::string_view name) const;
  std::vector<double> series(std::string_view name) const;
  const std::vector<integrators::Event>& events() const { return events_; }
  std::size_t count(integrators::EventKind kind) const;

 private:
  std::vector<std::string> columns_;
  std::vector<double> data_;  // row-major
  std::vector<integrators::Event> events_;
};

// One run made for a figure: what was asked, how it ended (its row of results.csv) and what
// it recorded.
struct FigureRun {
  RunSpec spec;
  std::string status;  // integrators::RunStatus name, or "rejected" (the scene refused the run)
  double end_time = 0.0;                                            // [s] reached
  double failure_time = std::numeric_limits<double>::quiet_NaN();  // [s], NaN when completed
  History history;  // empty unless the run produced outputs
  bool ok() const;  // a completed status (integrators::succeeded)
  std::string status_text() const;  // "<name>: <status> at t = <failure_time> s"
};

// The runs of a study by name, in the order they were made.
class RunSet {
 public:
  void add(FigureRun r);  // throws std::logic_error for a name already present
  const FigureRun* find(const std::string& name) const;
  const FigureRun& at(const std::string& name) const;  // throws std::logic_error when absent
  const std::vector<FigureRun>& all() const { return runs_; }

 private:
  std::vector<FigureRun> runs_;
};

// Makes the runs on `workers` threads: one list design per scene (a factor "run" labelled with
// the run's name) in dir/<scene>/, which keeps the design's results.csv and manifest.toml; the
// runs' own folders are removed once read back. Every scene is loaded with its run's overrides
// before any run, so bad input throws std::invalid_argument before anything is written.
std::vector<FigureRun> make_runs(const std::vector<RunSpec>& specs,
                                 const std::filesystem::path& scenes,
                                 const std::filesystem::path& dir, int workers);

// ---------------------------------------------------------------------------------------------
// Measures of one history.

// Largest |column| over the samples with t <= t_end.
double peak(const History& h, std::string_view column,
            double t_end = std::numeric_limits<double>::infinity());
// Linear interpolation of a column at time t (held beyond the ends; NaN without samples).
double value_at(const History& h, std::string_view column, double t);
// RMS of (b - a) over a's samples up to t_end, b interpolated at a's times, divided by the RMS
// of a; NaN when a is zero throughout.
double normalized_rms_difference(const History& a, const History& b, std::string_view column,
                                 double t_end);
// The first impact: its time [s] and 1-based contact; {0, 0} when there is none.
std::pair<double, int> first_impact(const History& h);

}  // namespace nsb::paper_figures
