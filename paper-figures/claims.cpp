#include "paper-figures/claims.hpp"

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace nsb::paper_figures {

bool compare(double value, const std::string& op, double threshold) {
  if (!std::isfinite(value) || !std::isfinite(threshold)) {
    if (op == "<" || op == "<=" || op == ">" || op == ">=") return false;
  }
  if (op == "<") return value < threshold;
  if (op == "<=") return value <= threshold;
  if (op == ">") return value > threshold;
  if (op == ">=") return value >= threshold;
  throw std::invalid_argument("compare: unknown op \"" + op + "\" (use <, <=, > or >=)");
}

bool Check::holds() const { return compare(value, op, threshold); }

bool Claim::holds() const {
  if (!failure.empty() || checks.empty()) return false;
  for (const auto& c : checks) {
    if (!c.holds()) return false;
  }
  return true;
}

namespace {

std::string number(double v) {
  if (!std::isfinite(v)) return "null";
  std::ostringstream s;
  s << std::setprecision(17) << v;
  return s.str();
}

std::string short_number(double v) {
  std::ostringstream s;
  s << std::setprecision(4) << v;
  return s.str();
}

std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char ch : text) {
    switch (ch) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      default:
        out += ch;
    }
  }
  return out + "\"";
}

}  // namespace

std::string Claim::reason() const {
  if (!failure.empty()) return "not evaluated: " + failure;
  if (checks.empty()) return "no checks";
  std::string failed;
  for (const auto& c : checks) {
    if (!c.holds()) {
      failed += (failed.empty() ? "" : "; ") + c.quantity + " = " + short_number(c.value) +
                " is not " + c.op + " " + short_number(c.threshold);
    }
  }
  return failed.empty() ? "every check holds" : failed;
}

std::string claims_json(const std::vector<Claim>& claims) {
  std::ostringstream s;
  s << "{\"claims\": [";
  for (std::size_t i = 0; i < claims.size(); ++i) {
    const Claim& c = claims[i];
    s << (i ? ",\n" : "\n") << "  {\"id\": " << quoted(c.id)
      << ", \"statement\": " << quoted(c.statement)
      << ", \"holds\": " << (c.holds() ? "true" : "false") << ", \"reason\": " << quoted(c.reason())
      << ",\n   \"measured\": {";
    for (std::size_t k = 0; k < c.measured.size(); ++k) {
      s << (k ? ", " : "") << quoted(c.measured[k].first) << ": " << number(c.measured[k].second);
    }
    s << "},\n   \"checks\": [";
    for (std::size_t k = 0; k < c.checks.size(); ++k) {
      const Check& ck = c.checks[k];
      s << (k ? ",\n              " : "") << "{\"quantity\": " << quoted(ck.quantity)
        << ", \"value\": " << number(ck.value) << ", \"op\": " << quoted(ck.op)
        << ", \"threshold\": " << number(ck.threshold) << ", \"why\": " << quoted(ck.why) << "}";
    }
    s << "],\n   \"runs\": [";
    for (std::size_t k = 0; k < c.runs.size(); ++k) s << (k ? ", " : "") << quoted(c.runs[k]);
    s << "]}";
  }
  s << "\n]}\n";
  return s.str();
}

std::string claims_markdown(const std::vector<Claim>& claims) {
  std::ostringstream s;
  s << "# The paper's claims, checked\n\n"
    << "| claim | statement | verdict | numbers |\n|---|---|---|---|\n";
  for (const auto& c : claims) {
    std::string nums;
    for (const auto& ck : c.checks) {
      nums += (nums.empty() ? "" : "; ") + ck.quantity + " = " + short_number(ck.value) + " (" +
              ck.op + " " + short_number(ck.threshold) + ")";
    }
    if (!c.failure.empty()) nums = c.reason();
    s << "| " << c.id << " | " << c.statement << " | " << (c.holds() ? "holds" : "does not hold")
      << " | " << nums << " |\n";
  }
  for (const auto& c : claims) {
    s << "\n## " << c.id << ": " << c.statement << "\n\n"
      << "Verdict: **" << (c.holds() ? "holds" : "does not hold") << "** (" << c.reason()
      << ").\n\n";
    for (const auto& ck : c.checks) {
      s << "- `" << ck.quantity << "` = " << short_number(ck.value) << ", required " << ck.op << " "
        << short_number(ck.threshold) << ": " << (ck.holds() ? "yes" : "no") << ". " << ck.why
        << "\n";
    }
    s << "\nMeasured:";
    for (const auto& [k, v] : c.measured) s << " " << k << " = " << short_number(v) << ";";
    s << "\n\nRuns:";
    for (const auto& r : c.runs) s << " `" << r << "`";
    s << "\n";
  }
  return s.str();
}

}  // namespace nsb::paper_figures
