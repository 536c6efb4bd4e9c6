// A sweep's results in the input formats of pelicun (NHERI SimCenter's damage and loss
// assessment; docs/sweep.md, "Export to pelicun"):
//   - demands: pelicun's demand sample CSV. Row 1: an empty cell, then one column per demand
//     named "<event>-<type>-<location>-<direction>"; row 2: "Units", then each column's unit;
//     then one row per run (the run id, then its values). Types are pelicun's EDP types
//     (pelicun/base.py, EDP_to_demand_type): PGA and SA for the IM factors
//     model.excitation.target_pga and target_sa (g, location 0, direction 2: the transverse
//     record), PFD for the deck's peak_x and peak_y (m, location 1, directions 1 and 2), LR
//     for its peak_theta (rad, location 1, direction 0), RID for |residual_theta| (rad,
//     location 1, direction 0) and PID for a bent's drift |peak_bent<i>_u<x|y>| / H_i (rad,
//     location i, directions 1 and 2; H_i = model.bents[i-1].height of the run's scene).
//     Event 1 throughout: every run is one realization of the one event a sweep describes.
//   - fragility: pelicun's fragility database CSV (ID, Incomplete, Demand-Type, Demand-Unit,
//     Demand-Offset, Demand-Directional, LS1-Family, LS1-Theta_0, LS1-Theta_1): one row per
//     limit state of the design's [fragility], its lognormal maximum likelihood fit (theta the
//     median, beta the dispersion) as a function of the IM (Peak Ground Acceleration or
//     Spectral Acceleration, g); Incomplete = 1 and empty parameters without an estimate.
// Only runs whose status is completed, completed_with_fallbacks or unseated are demands: the
// others have no complete response.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace nsb::sweep {

struct PelicunExport {
  std::string demands;          // the demand sample CSV
  std::string fragility;        // the fragility CSV; "" when the sweep has no fragility.json
  std::size_t runs = 0;         // rows of results.csv
  std::size_t left_out = 0;     // runs not exported (status not completed or unseated)
  std::vector<std::string> notes;  // what was not exported and why
};

// The export of the finished sweep in dir (results.csv; fragility.json when present). The
// design (for the bent heights and the fragility section) is `design` when given, else the
// file manifest.toml names (as written, then relative to dir's parent). Throws
// std::invalid_argument naming the file, line and column for a results.csv that cannot be
// read, a missing design, or a bent height it needs and does not find.
PelicunExport pelicun_export(const std::filesystem::path& dir,
                             const std::optional<std::filesystem::path>& design = std::nullopt);

// The demand types of pelicun's EDP list (pelicun/base.py, EDP_to_demand_type, v3) that the
// export uses, with their full names.
struct PelicunType {
  const char* code;
  const char* name;
};
const std::vector<PelicunType>& pelicun_types();

}  // namespace nsb::sweep
