#include "runs/lcp_dump.hpp"

#include "io/csv.hpp"
#include "io/files.hpp"
#include "lcp/frictional.hpp"
#include "lcp/siconos_format.hpp"

#include <array>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <utility>

namespace nsb::runs {

namespace {

// "lcp-000001.dat": six digits keep the files of a 40 s run (< 1e6 problems) in order.
std::string file_name(std::int64_t index) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "lcp-%06lld.dat", static_cast<long long>(index));
  return buf;
}

std::string solver_name(const integrators::SolvedProblem& s) {
  if (s.status == integrators::ContactStatus::kNonFiniteInput) return "none";
  if (s.closed_form) return "closed_form";
  return std::string(lcp::to_string(s.result.solver_used));
}

// The lines after q in a problem's file (the reader ignores them): where it comes from.
std::string comment(const integrators::SolvedProblem& s, std::int64_t index,
                    const std::string& solver) {
  return "nsbridge contact problem " + std::to_string(index) + ": " +
         std::string(config::name_of(integrators::kProblemKindNames, s.origin.kind)) + " at t = " +
         io::csv_number(s.origin.t) + " s, step " + std::to_string(s.origin.step) + ", " +
         std::to_string(s.problem.contacts()) + " contacts\n" +
         "LCP of eq. (6), Shi & Dimitrakopoulos 2017 (lcp::build_eq6)\n" + "solved by " +
         solver + ": " + std::string(lcp::to_string(s.result.status)) + " (" +
         std::string(config::name_of(integrators::kContactStatusNames, s.status)) + ")";
}

}  // namespace

LcpDump::LcpDump(std::filesystem::path dir) : files_(std::move(dir)) {
  manifest_ = std::string(kManifestHeader) + '\n';
}

void LcpDump::solved(const integrators::SolvedProblem& s) {
  ++problems_;
  const lcp::FrictionalProblem& fp = s.problem;
  const bool finite = s.status != integrators::ContactStatus::kNonFiniteInput;
  const std::string file = finite ? file_name(problems_) : std::string();
  const std::string_view kind = config::name_of(integrators::kProblemKindNames, s.origin.kind);
  const std::string solver = solver_name(s);
  const std::string_view status = lcp::to_string(s.result.status);
  const std::string_view stage = config::name_of(integrators::kContactStatusNames, s.status);
  const auto size = finite ? lcp::eq6_size(fp) : Eigen::Index{0};
  if (finite && failure_.empty()) {
    try {
      std::ostringstream text;
      write_siconos_lcp(text, lcp::build_eq6(fp), comment(s, problems_, solver));
      files_.add(file, text.str());
    } catch (const io::WriteError& e) {
      failure_ = e.what();
    } catch (const std::exception& e) {
      failure_ = (files_.target() / file).string() + ": " + e.what();
    }
  }
  std::string& m = manifest_;
  m += file;
  m += ',';
  io::append_csv_number(m, s.origin.t);
  m += ',' + std::to_string(s.origin.step) + ',';
  m += kind;
  m += ',' + std::to_string(fp.contacts()) + ',' + std::to_string(size) + ',' + solver + ',';
  m += status;
  m += ',';
  m += stage;
  m += ',';
  io::append_csv_number(m, s.result.residual);
  m += '\n';
}

void LcpDump::write_manifest() {
  if (!failure_.empty()) throw io::WriteError(failure_);
  files_.add("manifest.csv", manifest_);
  files_.commit();
}

}  // namespace nsb::runs
