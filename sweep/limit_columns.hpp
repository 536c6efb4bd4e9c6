// The limit states of a sweep's runs as results.csv columns (docs/sweep.md, "Limit-state
// columns"): per limit state `<name>_exceeded` (0/1) and `<name>_margin` (in the limit
// state's unit, docs/limit-states.md), placed before wall_s. The runs of one sweep may watch
// different limit states (a factor that sets a seat length, a segmented scene): the columns
// are the union over the runs, in the order each name first appears in run order, and a run
// without that limit state (or a rejected run) leaves both cells empty.
#pragma once

#include "runs/digest.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace nsb::sweep {

// DIR/runs/<id>/limit_states.csv of one run: "name,exceeded,margin" and one line per limit
// state of the digest.
std::string limit_states_csv(const runs::Digest& digest);

// The header and rows of results.csv with the limit-state columns of every run's
// limit_states.csv (read from run_dirs, one per row; a missing file is a run without limit
// states) inserted before the last column (wall_s). Rows that are absent stay absent.
void add_limit_columns(std::string& header, std::vector<std::optional<std::string>>& rows,
                       const std::vector<std::filesystem::path>& run_dirs);

}  // namespace nsb::sweep
