// The `[fragility]` section of a sweep design (docs/fragility.md, "Fragility from a sweep"):
// the factor whose levels are the intensity stripes and the limit states, each a results.csv
// column compared with a threshold. Read and checked with the design (sweep/fragility_sweep.hpp).
#pragma once

#include <string>
#include <vector>

namespace nsb::sweep {

// How a run stopped by the loss of a seat (status "unseated", docs/limit-states.md) counts
// for a limit state. The deck has fallen: its response after that instant is unknown and
// unbounded, so by default the run reaches every limit state (the collapse convention of
// incremental dynamic analysis, Vamvatsikos & Cornell 2002, Earthquake Eng. Struct. Dyn.
// 31(3); of FEMA P-58: a collapsed structure is in every damage state). kResponse compares its
// response up to the loss of seat instead (a lower bound of the response to the whole record).
enum class UnseatedRuns { kExceed, kResponse };

// A limit state: a run reaches it when its `response` (a results.csv column, in that column's
// unit: rad for peak_theta and residual_theta) is >= `threshold` (in the same unit), or, with
// `absolute`, when |response| >= threshold (for signed columns such as residual_theta), or,
// with `below`, when response <= threshold (a margin of docs/limit-states.md, which shrinks as
// the demand grows: <name>_margin <= 0 is the watched limit state reached). A limit state
// given as `limit_state = "<watched name>"` is response <name>_exceeded, threshold 1.
struct LimitState {
  std::string name;      // key of the limit state in fragility.json, unique in the design
  std::string response;  // a results.csv column of the design, or a limit-state column
                         //   (<name>_exceeded, <name>_margin) the runs write
  double threshold = 0.0;
  bool absolute = false;
  bool below = false;
  std::string watched{};  // the watched limit state named by `limit_state`, else empty
  UnseatedRuns unseated = UnseatedRuns::kExceed;
};

struct FragilitySpec {
  std::string im;                       // a factor key of the design: its levels are the stripes
  std::vector<LimitState> limit_states;  // in file order, at least one
};

}  // namespace nsb::sweep
