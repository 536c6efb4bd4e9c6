// The paper's claims (Shi & Dimitrakopoulos 2017) as checks with numbers and a verdict.
//
// A claim holds when every one of its checks holds; a check compares one measured quantity
// with a stated threshold. A claim whose runs did not succeed is not evaluated: it does not
// hold, and its reason says why. The thresholds and their reasons: docs/paper-figures.md.
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "integrators/recorder.hpp"
#include "io/json.hpp"

namespace nsb::paper_figures {

// One comparison "quantity op threshold", e.g. "peak_ratio < 0.5".
struct Check {
  std::string quantity;    // name of the measured quantity it compares
  double value = 0.0;      // the measured value
  std::string op;          // "<", "<=", ">" or ">="
  double threshold = 0.0;  // the stated threshold
  std::string why;         // one sentence: why this threshold
  bool holds() const;      // value op threshold; false for a non-finite value
};

// The damping law of eq. (9) behind a compliance claim: its name, its factor chi at the
// nonsmooth runs' restitution, the effective restitution of a single impact under it
// (integrators::hunt_crossley_restitution(chi)) and that nonsmooth restitution eps.
struct LawRestitution {
  std::string name;  // integrators::kDampingLawNames
  double chi = std::numeric_limits<double>::quiet_NaN();
  double effective_restitution = std::numeric_limits<double>::quiet_NaN();
  double nonsmooth_restitution = std::numeric_limits<double>::quiet_NaN();
};

struct Claim {
  Claim() = default;
  Claim(std::string id_, std::string statement_)
      : id(std::move(id_)), statement(std::move(statement_)) {}
  std::string id;           // "C1" ... "C6"
  std::string statement;    // the claim in the paper's words
  std::vector<Check> checks;                              // all must hold
  std::vector<std::pair<std::string, double>> measured;   // every number behind the checks
  std::vector<std::string> runs;                          // the runs it used
  std::string failure;      // non-empty: a run failed and the claim was not evaluated
  LawRestitution law;       // the compliance claims' damping law; empty name for the others
  bool holds() const;       // failure.empty() and every check holds (false without checks)
  std::string reason() const;  // one line: which checks fail, or the failure
};

// The comparison itself, shared by Check::holds and the checker of claims.json.
// Throws std::invalid_argument for an unknown op.
bool compare(double value, const std::string& op, double threshold);

// JSON text of a number (shortest round-trip; null when not finite) and of a string (every
// control character escaped): io's, as in summary.json. Used by claims.json and
// uncertainty.json.
using io::json_number;
using io::json_string;

// claims.json: {"claims": [{"id", "statement", "holds", "reason", "measured": {...},
// "checks": [{"quantity", "value", "op", "threshold", "why"}], "runs": [...]}]}; a compliance
// claim also has "law": {"name", "chi", "effective_restitution", "nonsmooth_restitution"}.
// Numbers are written with 17 significant digits; a non-finite number is written as null.
std::string claims_json(const std::vector<Claim>& claims);
// claims.md: a table (claim, verdict, key numbers) and each claim's checks.
std::string claims_markdown(const std::vector<Claim>& claims);

// ---------------------------------------------------------------------------------------------
// The claims from their numbers. The nominal figures and the uncertainty study call the same
// functions; the caller adds the runs it used (Claim::runs, Claim::failure).

// The runs the verdict of C1 rests on, in --quick, in the full set and in the uncertainty
// study alike: the paper's example (excitation 5) and the strongest run (7).
inline constexpr int kExampleRun = 5;
inline constexpr int kStrongestRun = 7;

// One run of Fig. 6: the peak rotations with pounding (mu as in the scene), with mu = 0 (NaN
// when not run) and without pounding (gaps that never close), and the impacts of the runs with
// and without pounding.
struct Peaks {
  int run = 0;                      // excitation number, 1..7
  double pga_y = 0.0, pga_x = 0.0;  // transverse and longitudinal PGA of the input [g]
  double pounding = 0.0;            // peak |theta| with pounding [rad]
  double mu0 = std::numeric_limits<double>::quiet_NaN();  // peak |theta| with mu = 0 [rad]
  double free = 0.0;                // peak |theta| without pounding [rad]
  std::size_t impacts = 0, impacts_free = 0;
};

// C1: peak |theta|(mu = 0) / peak |theta|(mu) < 0.5 under excitations 5 and 7; every run with a
// finite mu0 is reported.
Claim claim_c1(const std::vector<Peaks>& peaks);
// C2: exponent b of the least-squares fit theta = a PGA^b over the distinct PGAs, b > 1.
Claim claim_c2(const std::vector<Peaks>& peaks);
// C3: largest peak ratio without / with pounding over the runs that pound < 0.5, and no impact
// in the runs without pounding.
Claim claim_c3(const std::vector<Peaks>& peaks);

// One compliance run of C4 against the nonsmooth (Moreau-Jean) run, over the window of C4.
struct CompliancePeak {
  double factor = 0.0;          // contact stiffness c of c k
  double peak = 0.0;            // peak |theta| [rad]
  double rms_difference = 0.0;  // RMS of the difference from the nonsmooth theta / its RMS
};
// C4: for c >= 1e2 the peak within 10 % of the nonsmooth one and the normalized RMS difference
// below 0.5; for c <= 1e-2 the peak at least 10 % below. window_end [s]: end of the window.
Claim claim_c4(double peak_nonsmooth, double window_end, const std::vector<CompliancePeak>& runs);

// The first pounding of a compliance run: the deepest penetration and the time in contact.
struct FirstPounding {
  double factor = 0.0;                                            // c of c k
  double penetration = std::numeric_limits<double>::quiet_NaN();  // max -g_N [m]
  double duration = std::numeric_limits<double>::quiet_NaN();     // [s]
};
// The first closing of the gap g after t0 (t ascending, g of the first pounding's contact);
// NaN penetration and duration when the gap does not close and open again in the history.
FirstPounding measure_first_pounding(double factor, const std::vector<double>& t,
                                     const std::vector<double>& g, double t0);
// C5: for factors in ascending order, each lower stiffness penetrates strictly deeper and
// stays in contact strictly longer than the next higher one.
Claim claim_c5(const std::vector<FirstPounding>& fps);

// A sliding contact of a Moreau-Jean run: from a slip event to the next change of state of the
// same contact (open, stick, or slip in the other direction).
struct Sliding {
  int contact = 0;                // 1-based; 0: none
  double start = 0.0, end = 0.0;  // [s]
};
// Every sliding contact of a run, from its events; a slide still open at t_final ends there.
std::vector<Sliding> sliding_contacts(const std::vector<integrators::Event>& events,
                                      double t_final);
// The longest of them (contact 0 when there is none; the first of equal lengths).
Sliding longest_sliding(const std::vector<Sliding>& slides);

// Coulomb's law over a sliding contact: the largest ||lambda_T| - mu lambda_N| / (mu lambda_N)
// over the recorded samples in [start, end) with lambda_N > 0.
struct SlidingState {
  Sliding slide;
  double lambda_n = 0.0, lambda_t = 0.0;  // [kN] at the first sample of the slide
  double max_deviation = std::numeric_limits<double>::quiet_NaN();
  std::size_t samples = 0;                // samples examined
};
// t, lambda_n, lambda_t: the history of the sliding contact (equal lengths, t ascending).
SlidingState measure_sliding(const Sliding& slide, double mu, const std::vector<double>& t,
                             const std::vector<double>& lambda_n,
                             const std::vector<double>& lambda_t);
// C6: at least one slipping sample, and the largest deviation below 1e-6.
Claim claim_c6(const SlidingState& state, double mu);

}  // namespace nsb::paper_figures
