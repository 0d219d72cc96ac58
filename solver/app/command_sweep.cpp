// `needlefem sweep SWEEP.toml [--out DIR] [--jobs N] [--retry-failed] [--list] [-- PETSc options]`:
// a design study. Expands the sweep file (sweep/sweep_plan.hpp) into design points, lists the
// geometrically impossible ones with their rule, runs the others as `needlefem run` child
// processes, at most N at a time, resuming where an earlier sweep into DIR stopped
// (sweep/sweep_runner.hpp), and keeps DIR/sweep.csv and DIR/sweep.h5 up to date
// (sweep/sweep_table.hpp). Under mpirun each rank runs its share of the points.
#include <filesystem>

#include "app/commands.hpp"
#include "sweep/sweep_runner.hpp"

namespace needlefem::app {

namespace {

struct SweepCommandOptions {
  std::string sweep_file;
  std::string out_dir = "out/sweep";
  int jobs = 1;
  bool retry_failed = false;
  bool list_only = false;
};

void sweep_command(const SweepCommandOptions& options) {
  const sweep::SweepPlan plan = sweep::load_sweep(options.sweep_file);
  sweep::SweepOptions run;
  run.out_dir = options.out_dir;
  run.executable = std::filesystem::read_symlink("/proc/self/exe");
  run.jobs = options.jobs;
  run.retry_failed = options.retry_failed;
  run.list_only = options.list_only;
  run.backend_options = backend_options();
  sweep::run_sweep(plan, run);
}

}  // namespace

void add_sweep_command(CLI::App& app) {
  auto* command = app.add_subcommand(
      "sweep", "Design study: run a base case over grids of case-key values, resumably and concurrently; "
               "summary table sweep.csv + sweep.h5");
  auto options = std::make_shared<SweepCommandOptions>();
  command->add_option("sweep", options->sweep_file, "Sweep file (TOML): base case, [set], [axes], [linked], [[grid]]")
      ->required();
  command->add_option("--out", options->out_dir, "Output directory (one sub-directory per design point)")
      ->capture_default_str();
  command->add_option("--jobs", options->jobs, "Runs at the same time (per process when started by mpirun)")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  command->add_flag("--retry-failed", options->retry_failed, "Run failed points again (finished ones are skipped)");
  command->add_flag("--list", options->list_only,
                    "List the design points (impossible ones with their rule), write the table, run nothing");
  command->footer(
      "A point's folder is named by its values after short labels of the swept keys (r0.5_b20_f0.25: the sweep "
      "prints what each label stands for); sweep.csv has every value in a column. A restarted sweep skips every "
      "point whose summary.json says completed for the same case. Under `mpirun -n R` each rank runs every R-th "
      "point; the table is shared.");
  command->callback([options] { sweep_command(*options); });
}

}  // namespace needlefem::app
