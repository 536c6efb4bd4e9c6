// The typed results of a sweep: one Row per run, as runs::execute's record says it, and the
// table of rows (Results) whose columns are those of results.csv (docs/sweep.md). results.csv,
// fragility.json, the plots, the count of failed runs, the figures' runs and Python's
// nsbridge.sweep are all made from these values in memory. A row becomes text only at the
// edges: results.csv, and the run's resume files DIR/runs/<id>/row.csv and limit_states.csv,
// which a sweep reads back only when it resumes (or rank 0 receives from another MPI rank).
//
//   Row row = make_row(design, index, record, wall);     // typed, from the digest
//   Results r = results_of(design, rows);                 // the table of every row
//   io::write_file_atomically(dir / "results.csv", r.csv());
#pragma once

#include "runs/digest.hpp"
#include "runs/run.hpp"
#include "sweep/csv.hpp"
#include "sweep/design.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace nsb::sweep {

inline constexpr double kNotANumber = std::numeric_limits<double>::quiet_NaN();

// A limit state of one run (System::limit_states(), docs/limit-states.md).
struct LimitCell {
  std::string name;
  bool exceeded = false;
  double margin = kNotANumber;  // [unit of the limit state]; NaN when unknown
};

// One run's row of results.csv. A real that is not finite, or that the run does not have,
// is NaN (an empty field); a count of a rejected run is absent (an empty field too).
struct Row {
  std::string run;                  // the run id, zero padded ("0007")
  std::vector<std::string> labels;  // one per factor of the design; empty: the base value
  std::string status;               // integrators::RunStatus name, or "rejected"
  std::vector<double> peaks;        // max |q| per coordinate of Results::coordinates
  std::vector<double> peak_errors;  // the estimated absolute error of each peak (runs::
                                    //   CoordinatePeak::error); NaN: not estimated
  double residual = kNotANumber;    // the last coordinate's value at the end
  std::optional<std::int64_t> impacts;  // impact events
  double max_penetration = kNotANumber;  // max over samples and contacts of -gN, >= 0 [m]
  double energy_error = kNotANumber;     // relative energy-balance error at the end
  double end_time = kNotANumber;         // simulated time reached [s]
  std::optional<std::int64_t> steps, lcp_solves, lcp_fallbacks, lcp_unsolved;
  double failure_time = kNotANumber;  // [s]; NaN for a run that succeeded
  std::string message;                // why the run stopped early or was rejected
  std::vector<LimitCell> limit_states;  // the run's, in the system's order
  double wall_s = kNotANumber;          // wall time of the run [s]
  // The design's cross-check (Design::cross_check), empty without one: the other method's
  // status, its peak and peak error per coordinate, its impacts, and whether every peak agrees
  // within the estimates (runs::CrossCheck).
  std::string cross_status;
  std::vector<double> cross_peaks, cross_peak_errors;
  std::optional<std::int64_t> cross_impacts;
  std::optional<bool> cross_agrees;
};

// The row of a finished run: the design's labels of run `index`, and the record's status,
// digest and limit states; wall: the run's wall time [s].
Row make_row(const Design& design, std::size_t index, const runs::RunRecord& record, double wall);
// The row of a run whose combination of values the scene refused (status "rejected").
Row rejected_row(const Design& design, std::size_t index, const std::string& message,
                 double wall);
// True when the row's status is a result (integrators::is_result): completed, with fallbacks,
// or unseated. "rejected" is none.
bool is_result(const Row& row);

std::string_view to_string(ValueKind kind);

// The columns of results.csv after `run` and the factor columns, for a system whose
// generalized coordinates are `coordinates` (base_coordinates of the design), without the
// limit states': status, peak_<q> and peak_<q>_error for every coordinate q, residual_<q> for
// the last, then
// impacts through message, and wall_s.
std::vector<std::string> result_columns(const std::vector<std::string>& coordinates);

// What a column of results.csv holds: which field of a Row (and, for a factor, a coordinate's
// peak or a limit state, which one: `index`).
enum class Field {
  kRun, kFactor, kStatus, kPeak, kPeakError, kResidual, kImpacts, kMaxPenetration, kEnergyError, kEndTime,
  kSteps, kLcpSolves, kLcpFallbacks, kLcpUnsolved, kFailureTime, kMessage, kExceeded, kMargin,
  kWall, kCrossStatus, kCrossPeak, kCrossPeakError, kCrossImpacts, kCrossAgrees,
};

struct Column {
  std::string name;  // the header of results.csv
  Field field = Field::kRun;
  std::size_t index = 0;  // kFactor: the factor; kPeak, kPeakError: the coordinate; kExceeded, kMargin:
                          //   the limit state in Results::limit_states
  ValueKind kind = ValueKind::kText;  // the type of its values (Python's dtype)
};

// The type of a factor's column: the kinds of its levels combined (integers with reals are
// reals; anything else mixed is text). A level of a TOML `values` entry or a range has the
// kind it was written with; a level that is a name (records, named levels, a list design's
// cells) has the kind its text has as a TOML value: "3" integer, "0.17" real, "true" boolean.
ValueKind factor_kind(const Factor& factor);

// The rows of a sweep in run order, and results.csv's columns: run, the factors, status,
// peak_<q> and peak_<q>_error for every coordinate q, residual_<q> of the last, impacts through
// message, then
// with a cross-check (Design::cross_check) cross_check_status, cross_check_peak_<q> and
// cross_check_peak_<q>_error for every coordinate, cross_check_impacts and cross_check_agrees,
// then <name>_exceeded and <name>_margin for every limit state some run has (in the order each
// first appears in run order), and wall_s last.
struct Results {
  std::vector<std::string> factors;       // factor keys, in the design's order
  std::vector<std::string> coordinates;   // the base scene's generalized coordinates
  std::vector<std::string> limit_states;  // union over the rows, by first appearance
  std::vector<Column> columns;
  std::vector<Row> rows;

  // Index of a column; throws std::invalid_argument naming it when absent.
  std::size_t column(const std::string& name) const;
  // The column's value in a row as a number: NaN and empty fields (an absent limit state, a
  // rejected run's count) are std::nullopt, as is a text (a factor level that is a name).
  std::optional<double> number(const Row& row, std::size_t column) const;
  // The column's field of results.csv, unquoted.
  std::string cell(const Row& row, std::size_t column) const;
  // The whole of results.csv: header and one line per row.
  std::string csv() const;
};

// The results of a design from the rows of its runs (absent rows: runs not made) in run order.
Results results_of(const Design& design, const std::vector<std::optional<Row>>& rows);

// A results.csv read back as a table (`nsbridge sweep --plot-only`, a figure's subset): the
// columns named by its header (the factors are those between run and status), each row's
// fields parsed into a Row. Throws std::invalid_argument for a header without "run" and
// "status" or with a column results.csv does not have.
Results results_of(const Table& table);

// A run's resume files: DIR/runs/<id>/row.csv (the row's results.csv line without the limit-
// state columns) and limit_states.csv ("name,exceeded,margin" and a line per limit state).
std::string row_line(const Design& design, const Row& row);
std::string limit_states_csv(const std::vector<LimitCell>& limit_states);
// The row of run `index` from those two texts; std::nullopt when the line is not that run's
// (another id, too few fields).
std::optional<Row> parse_row(const Design& design, std::size_t index, const std::string& line,
                             const std::string& limit_states_csv);

}  // namespace nsb::sweep
