// Internal to the sweep module: how the process was started, and the MPI driver.
#pragma once

#include "sweep/runner.hpp"

namespace nsb::sweep {

// The rank, the number of ranks and the ranks on this machine, as the launcher (mpirun of
// OpenMPI, or a PMI launcher) tells them in the environment; 0, 1, 1 without a launcher.
int launcher_rank();
int launcher_size();
int launcher_local_size();
// Worker threads per process when --jobs is 0: the cores shared among the local ranks.
int default_jobs(int local_ranks);

#ifdef NSB_HAVE_MPI
// The sweep over MPI ranks: rank 0 validates and prepares DIR, hands out run indices one at a
// time to whichever worker asks (its own threads and the other ranks'), gathers the rows and
// writes results.csv. Every rank reads the design itself; every run writes its own outputs.
SweepSummary run_sweep_mpi(const std::filesystem::path& design_file, const SweepOptions& options);
#endif

}  // namespace nsb::sweep
