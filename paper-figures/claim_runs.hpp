// The runs the claims are judged on, at a point of the benchmark's assumed values. The figures
// (Fig. 6 and claims C1-C3, at the nominal point) and the uncertainty study (studies/, at
// points over the assumptions' plausible ranges) share them:
//   - the assumed values of the benchmark (docs/bridge.md, "Assumed") with their ranges, and a
//     point giving each a value;
//   - a claim run (an excitation with or without pounding, with mu = 0, or under the compliance
//     method) and the scene overrides that make it at a point;
//   - the sweep design of a set of points and runs, run through the sweep runner, and its rows
//     read back typed;
//   - Fig. 6's peaks from the rows of one point.
#pragma once

#include "integrators/compliance.hpp"
#include "paper-figures/claims.hpp"
#include "sweep/design.hpp"

#include <array>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace nsb::paper_figures {

// One assumed value with its plausible range. A point gives every assumption a value;
// point_overrides() turns it into scene overrides.
struct Assumption {
  std::string key;               // column name in the CSV files, e.g. "deck_width"
  std::string name;              // in words, e.g. "deck width W"
  std::string unit;              // "m", "-", "s"
  double nominal = 0.0;          // the benchmark's value (scenes/bridge-exc*.toml)
  double low = 0.0, high = 0.0;  // the plausible range, low < high
  bool two_values = false;       // only the two ends are plausible (the Latin hypercube picks one)
  std::string reason;            // why this range: source or derivation
};
// The assumptions, in the order of the CSV columns.
const std::vector<Assumption>& assumptions();
// Every assumption at its nominal value.
std::vector<double> nominal_point();
// The column of an assumption in a point's values, by key; throws std::logic_error for an
// unknown key.
std::size_t assumption_index(const std::string& key);
// The override "key=value" with the value as the sweep writes numbers.
std::string override_text(const std::string& key, double v);

// One run of the claims' set at a point: an excitation with or without pounding, or with
// mu = 0, or excitation 5 under the compliance method.
struct ClaimRun {
  std::string name;      // "exc7", "exc7-no-pounding", "exc7-mu0", "exc5-k100"
  int excitation = 7;    // the scene bridge-exc<n>.toml
  bool pounding = true;  // false: gaps of 1 m that never close
  bool mu0 = false;      // true: mu = 0
  double factor = 0.0;   // > 0: the compliance method at c k with c = factor; 0: the scene's
  integrators::DampingLaw law = integrators::DampingLaw::kHertzDamp;  // of eq. (9), if factor > 0
  double tolerance = 0.0;  // > 0: the compliance method's tolerance; 0: the scene's
};
// The runs of Fig. 6: each excitation of pga_runs with and without pounding ("exc<n>",
// "exc<n>-no-pounding"), then each of mu0_runs with mu = 0 ("exc<n>-mu0").
std::vector<ClaimRun> fig6_runs(const std::vector<int>& pga_runs, const std::vector<int>& mu0_runs);

// The base scene of every claim run: the excitations differ only in their target PGAs.
inline constexpr int kBaseExcitation = 7;

// What point_overrides needs from the scenes: each excitation's target PGAs as the scene
// states them, and the longitudinal record's own PGA.
struct SceneTargets {
  std::map<int, double> transverse_pga, longitudinal_pga;  // [g] by excitation
  std::string longitudinal_record;       // the base scene's longitudinal record file
  std::filesystem::path longitudinal_record_file;  // where the scene loader found it
  double longitudinal_record_pga = 0.0;  // [g], the record as recorded (seat rotation's scale)
  // The seats' angular acceleration record of the seat-rotation assumption
  // (write_rotation_record); empty: no point may ask for a seat rotation.
  std::filesystem::path rotation_record;
};
// The targets of the excitations of `runs` and of the base scene, read from the scenes folder.
// Throws std::invalid_argument for a scene without them.
SceneTargets scene_targets(const std::filesystem::path& scenes, const std::vector<ClaimRun>& runs);

// Writes the longitudinal record's ground acceleration [m/s^2], read as the seats' angular
// acceleration [rad/s^2] of the seat-rotation assumption (phi = c u_x / W), as a two-column
// text file into `dir`, and returns its path: a rotation record is a file in rad/s^2, never
// an .AT2 file in g (scene/bridge_scene.cpp). Throws std::invalid_argument when targets has
// no record file or it cannot be read.
std::filesystem::path write_rotation_record(const SceneTargets& targets,
                                            const std::filesystem::path& dir);

// The overrides of the base scene (bridge-exc7.toml) that give claim run `run` at the point
// `values` (one per assumption, in assumptions() order). Throws std::invalid_argument for a
// wrong number of values or an excitation missing from targets.
std::vector<std::string> point_overrides(const std::vector<double>& values, const ClaimRun& run,
                                         const SceneTargets& targets);

// A point of a design: its name (the "point" column) and one value per assumption; `labels`
// gives the assumption columns (empty: the nominal value, as the sweep's oat mode writes it).
struct Point {
  std::string name;
  std::vector<double> values;
  std::vector<std::string> labels;
  std::string assumption, end;  // one-at-a-time points
};

// The sweep design of a set of points: every point with the claim runs it needs. Factor
// columns: point, claim_run, then one per assumption. The hash only names the design: the
// folder is rewritten every time (restart).
sweep::Design make_design(const std::string& name, const std::filesystem::path& base_scene,
                          const std::vector<Point>& points, const SceneTargets& targets,
                          double end_time, const std::vector<ClaimRun>& claim_set,
                          const std::function<bool(const Point&, const ClaimRun&)>& wanted);

// The results of one design, by point and run: the row's fields, and the run's folder.
struct RunRow {
  std::string status;
  double peak_theta = std::numeric_limits<double>::quiet_NaN();
  std::size_t impacts = 0;
  double end_time = 0.0;
  std::filesystem::path dir;
  bool ok() const;  // a completed status (integrators::succeeded)
};
using Rows = std::map<std::string, std::map<std::string, RunRow>>;  // point -> run -> row

// Runs a design into dir (restarting it) and reads its results back; failed runs are added to
// `failed`, the runs made to `runs`.
Rows run_design(const sweep::Design& d, const std::filesystem::path& dir, int workers, int& runs,
                std::vector<std::string>& failed);

// The input PGAs [g] of an excitation, transverse and longitudinal, as the nominal scene's
// motions have them (Fig. 6's abscissa and C2's).
using InputPga = std::map<int, std::array<double, 2>>;
InputPga input_pgas(const std::filesystem::path& scenes, const std::vector<int>& excitations);

// The peaks of Fig. 6 at one point, from the rows of its runs (runs that were not made leave
// their numbers at the defaults; the claims then say which run is missing).
std::vector<Peaks> peaks_of(const std::map<std::string, RunRow>& runs,
                            const std::vector<int>& excitations, const InputPga& pga);

// Fig. 6's data as one sweep at the nominal point: the runs of fig6_runs(pga_runs, mu0_runs),
// run through the sweep runner into dir (dir/results.csv; the runs' own outputs are removed).
struct Fig6Sweep {
  std::vector<Peaks> peaks;                   // one per excitation of pga_runs, in order
  std::map<std::string, std::string> status;  // by run name: "completed", "diverged", ...
  int runs = 0;                               // integrations
  std::vector<std::string> failed;            // runs that did not complete
};
Fig6Sweep fig6_sweep(const std::filesystem::path& scenes, const std::filesystem::path& dir,
                     const std::vector<int>& pga_runs, const std::vector<int>& mu0_runs,
                     int workers);

}  // namespace nsb::paper_figures
