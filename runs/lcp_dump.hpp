// The contact problems of one run as files (`nsbridge run --dump-lcp DIR`, docs/outputs.md):
// every problem the contact stage solves, as the LCP of eq. (6) of Shi & Dimitrakopoulos
// (2017) that it stands for (lcp::build_eq6: 3m x 3m, or m x m when frictionless), in Siconos
// Numerics' dense .dat format (lcp/siconos_format.hpp), so that `nsbridge lcp`, the LCP
// solvers and Siconos itself read them; and DIR/manifest.csv, one row per problem:
//
//   file          lcp-000001.dat, ... in the order solved; empty when the data were not finite
//   t             the time at which the contact law is imposed [s]
//   step          the integrator's accepted steps before the problem
//   kind          impact | continuous (event-driven) | step (Moreau–Jean)
//   contacts      m, the contacts of the index set
//   size          n, the size of the LCP in the file (3m, or m when frictionless)
//   solver        the solver whose answer the stage kept (lemke, pgs, nfb, enum), closed_form
//                 for one frictionless contact (max(0, -b / G), no solver), none when the data
//                 were not finite
//   status        that solver's lcp::Status (solved, ray_termination, ...)
//   stage_status  solved | solved_by_fallback | unsolved | non_finite_input
//   residual      the frictional residual of the answer (lcp::frictional_residual)
//
// Each .dat file is written when its problem is solved, so a run holds at most one problem in
// memory, into a staging folder beside DIR (io::FileSet); the manifest (a short row per
// problem) is written at the end, and the files with it move into DIR as one set. A run that
// fails to write, or is interrupted, leaves nothing: no partial .dat file, no partial set.
#pragma once

#include "integrators/contact_stage.hpp"
#include "io/files.hpp"
#include "lcp/lcp.hpp"

#include <cstdint>
#include <filesystem>
#include <string>

namespace nsb::runs {

class LcpDump final : public integrators::ContactObserver {
 public:
  // dir is checked by io::check_output_dir before; nothing is created before the first
  // problem. An earlier dump in dir is replaced as a set, and manifest.csv lists exactly the
  // files of this run.
  explicit LcpDump(std::filesystem::path dir);

  // Writes the problem's file and notes its manifest row. Never throws: the first I/O
  // failure is kept and reported by write_manifest(), and nothing more is written.
  void solved(const integrators::SolvedProblem& problem) override;

  // Writes manifest.csv and moves the set into dir (io::FileSet::commit). Throws
  // io::WriteError naming the file when a problem's file or the manifest could not be
  // written; the staged files are then removed.
  void write_manifest();

  std::int64_t problems() const { return problems_; }  // problems seen so far
  static constexpr const char* kManifestHeader =
      "file,t,step,kind,contacts,size,solver,status,stage_status,residual";

 private:
  io::FileSet files_;
  std::string manifest_;  // the rows so far (about 80 bytes each)
  std::string failure_;   // the first I/O failure, empty if none
  std::int64_t problems_ = 0;
};

}  // namespace nsb::runs
