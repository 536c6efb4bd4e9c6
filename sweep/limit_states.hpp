// The `[fragility]` section of a sweep design (docs/fragility.md, "Fragility from a sweep"):
// the factor whose levels are the intensity stripes and the limit states, each a results.csv
// column compared with a threshold. Read and checked with the design (sweep/fragility_sweep.hpp).
#pragma once

#include <string>
#include <vector>

namespace nsb::sweep {

// A limit state: a run reaches it when its `response` (a results.csv column, in that column's
// unit: rad for peak_theta and residual_theta) is >= `threshold` (in the same unit), or, with
// `absolute`, when |response| >= threshold (for signed columns such as residual_theta), or,
// with `below`, when response <= threshold (a margin of docs/limit-states.md, which shrinks as
// the demand grows: <name>_margin <= 0 is the watched limit state reached).
struct LimitState {
  std::string name;      // key of the limit state in fragility.json, unique in the design
  std::string response;  // a results.csv column of the design, or a limit-state column
                         //   (<name>_exceeded, <name>_margin) the runs write
  double threshold = 0.0;
  bool absolute = false;
  bool below = false;
};

struct FragilitySpec {
  std::string im;                       // a factor key of the design: its levels are the stripes
  std::vector<LimitState> limit_states;  // in file order, at least one
};

}  // namespace nsb::sweep
