// `needlefem run CASE.toml [--out DIR] [--set k=v] [-- PETSc/SUNDIALS options]`: solves the
// case's tissue mechanics over its history (run/run_case.hpp) and writes
//   DIR/mesh.msh, DIR/result.h5 + result.xdmf (fields per output time), DIR/history.csv,
//   DIR/summary.json (verdict, maxima with time and position, reactions, solver statistics,
//   material, resolved case). The last line printed is the run's safety verdict.
#include <fmt/core.h>

#include "app/commands.hpp"
#include "case/case.hpp"
#include "interrupt/interrupt_guard.hpp"
#include "run/run_case.hpp"
#include "run/safety_report.hpp"

namespace needlefem::app {

namespace {

void run_command(const CaseOptions& options) {
  const Case c = Case::load(options.case_file, options.overrides);
  run::RunOptions run_options;
  run_options.out_dir = options.out_dir;
  run_options.petsc_options = backend_options();
  // Ctrl-C (or a scheduler's SIGTERM) ends the run cleanly after the step in progress; a second
  // Ctrl-C kills it at once.
  const InterruptGuard interrupt(true);
  run_options.stop = &InterruptGuard::stop_flag();
  const auto summary = run::run_case(c, run_options);
  const auto& solver = summary["solver"];
  fmt::print("run: {} output times to t = {} s in {:.2f} s ({} steps, {} Newton its, {} Jacobians, {} dofs); "
             "written {}\n",
             summary["output_times"].get<std::size_t>(), summary["time_reached_s"].get<double>(),
             solver["wall_s"].get<double>(), solver["steps"].get<long>(), solver["newton_iterations"].get<long>(),
             solver["jacobian_setups"].get<long>(), solver["dofs"].get<long>(),
             (run_options.out_dir / "summary.json").string());
  const std::string verdict = run::verdict_line(summary);
  if (!verdict.empty()) fmt::print("{}\n", verdict);
}

}  // namespace

void add_run_command(CLI::App& app) {
  add_case_command(app, "run",
                   "Solve a case's tissue mechanics with IDA to every output.interval_s. Writes into OUT:\n"
                   "  result.h5 + result.xdmf  fields: displacement, velocity, Cauchy stress, von Mises, max principal\n"
                   "                           stress and log strain, strain rate, pressure, their running maxima;\n"
                   "                           brain-tip: contact_pressure, contact_slip on the cavity\n"
                   "  history.csv              per output time: the maxima with their positions, reactions per surface,\n"
                   "                           energies; brain-tip: force, moment and lateral force on the needle, contact area\n"
                   "  summary.json             verdict (pass, or fail when any limit fails; also the last line printed),\n"
                   "                           maxima, safety metrics with a verdict per limit, needle loads, software\n"
                   "                           versions; status 'running' until the run ends\n"
                   "A run holds OUT for its lifetime; a second run into it is refused.\n"
                   "Options after `--` go to PETSc and SUNDIALS unchanged. Ctrl-C or SIGTERM stops the run after the\n"
                   "step in progress, keeping the output times it has written (a second Ctrl-C stops it at once).",
                   "out/run", run_command);
}

}  // namespace needlefem::app
