// The runs of the grid, one-factor-at-a-time and latin designs, from the factors that
// load_design has read (sweep/design.hpp; the list mode reads its runs from a CSV file there).
// Each appends to Design::runs, in id order, the design's `set` first in every run's overrides.
#pragma once

#include "sweep/design.hpp"

namespace nsb::sweep {

// Full factorial: every combination of every factor's levels, first factor slowest.
void expand_grid(Design& d);
// The base scene (every label empty), then each level of each factor alone.
void expand_oat(Design& d);
// Design::samples runs of a Latin hypercube over the factors (latin_hypercube).
void expand_latin(Design& d);

}  // namespace nsb::sweep
