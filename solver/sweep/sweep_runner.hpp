// Runs a sweep's design points as child processes of the needlefem executable
//   needlefem run DIR/<point>/case.toml --out DIR/<point> [-- backend options]
// at most `jobs` at a time, each with its output in DIR/<point>/run.log.
//
// Resuming: a point whose summary.json echoes its own case and says "completed" is skipped
// (so is "failed", unless retry_failed). A point whose run was killed has a summary.json that
// still says "running" (run_case replaces it only at the end) and runs again, so a killed sweep
// restarted loses nothing. A child that exits non-zero without a summary of its own (crash,
// signal, error before the run starts) gets one written for it: status "failed" and the last
// error line of its run.log. Children are killed with the sweep (PR_SET_PDEATHSIG), so a
// restarted sweep never races an orphan of the old one.
//
// Under an MPI launcher (mpirun -n R needlefem sweep ..., srun ...) each of the R processes
// takes every R-th runnable point, found from the launcher's rank variables (OMPI_COMM_WORLD_*,
// PMI_*, PMIX_RANK, SLURM_PROCID/SLURM_NTASKS); no MPI call is made. Its children get the
// environment without the launcher's variables, so each `needlefem run` starts as an MPI
// singleton. Tables are rewritten under a file lock after every finished point.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "sweep/sweep_plan.hpp"

namespace needlefem::sweep {

struct SweepOptions {
  std::filesystem::path out_dir;
  std::filesystem::path executable;  // the needlefem binary the children run
  int jobs = 1;
  bool retry_failed = false;
  bool list_only = false;  // list the points and write the table; run nothing
  std::vector<std::string> backend_options;  // passed after "--" to every run
  std::FILE* progress = stdout;
  std::string label = "sweep";  // prefix of the progress lines
  bool write_tables = true;     // keep DIR/sweep.csv and DIR/sweep.h5 (sweep/sweep_table.hpp)
};

struct SweepOutcome {
  int rank = 0, ranks = 1;     // this process among those a launcher started
  std::size_t total = 0;       // design points of this process (valid ones)
  std::size_t already_done = 0, completed = 0, failed = 0;
  std::size_t impossible = 0;  // in the whole plan
};

SweepOutcome run_sweep(const SweepPlan& plan, const SweepOptions& options);

}  // namespace needlefem::sweep
