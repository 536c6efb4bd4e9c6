// The paper's claims (Shi & Dimitrakopoulos 2017) as checks with numbers and a verdict.
//
// A claim holds when every one of its checks holds; a check compares one measured quantity
// with a stated threshold. A claim whose runs did not succeed is not evaluated: it does not
// hold, and its reason says why. The thresholds and their reasons: docs/paper-figures.md.
#pragma once

#include <string>
#include <utility>
#include <vector>

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
  bool holds() const;       // failure.empty() and every check holds (false without checks)
  std::string reason() const;  // one line: which checks fail, or the failure
};

// The comparison itself, shared by Check::holds and the checker of claims.json.
// Throws std::invalid_argument for an unknown op.
bool compare(double value, const std::string& op, double threshold);

// claims.json: {"claims": [{"id", "statement", "holds", "reason", "measured": {...},
// "checks": [{"quantity", "value", "op", "threshold", "why"}], "runs": [...]}]}.
// Numbers are written with 17 significant digits; a non-finite number is written as null.
std::string claims_json(const std::vector<Claim>& claims);
// claims.md: a table (claim, verdict, key numbers) and each claim's checks.
std::string claims_markdown(const std::vector<Claim>& claims);

}  // namespace nsb::paper_figures
