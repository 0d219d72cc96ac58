// `needlefem converge CASE.toml [--out DIR] [--jobs N] [--levels 3] [--from 0] [--set k=v ...]
// [-- PETSc options]`: the error band of every answer (DESIGN.md §2b). Runs the case at
// consecutive values of mesh.refinement_level (each halves the element sizes near the needle)
// through the sweep machinery (sweep/sweep_plan.hpp plan_axis, sweep/sweep_runner.hpp: resumable,
// concurrent `needlefem run` children, DIR/level_<L>/run.log and summary.json), then estimates
// each summary metric's observed order, Richardson value and GCI band on the three finest levels
// (convergence/convergence_report.hpp) and writes DIR/converge.csv and DIR/converge.json, and when
// every level completed the band of every history.csv quantity at every output time
// (convergence/history_bands.hpp) in DIR/converge_history.csv. Prints
// one verdict line per run: pass, fail or undecided per safety limit, followed on a mesh coarser than
// the converged setting by the warning of case/mesh_resolution.hpp. A level that fails makes the
// command fail with one line naming it, after writing what the other levels gave.
#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include <fmt/core.h>

#include "app/commands.hpp"
#include "case/case.hpp"
#include "case/mesh_resolution.hpp"
#include "case/schema.hpp"
#include "convergence/convergence_report.hpp"
#include "convergence/history_bands.hpp"
#include "output/history_table.hpp"
#include "sweep/sweep_runner.hpp"
#include "sweep/sweep_table.hpp"

namespace needlefem::app {

namespace {

constexpr const char* kLevelKey = "mesh.refinement_level";

struct ConvergeOptions {
  CaseOptions case_options;
  int jobs = 1;
  int levels = 3;
  int from = 0;
};

void converge_command(const ConvergeOptions& options) {
  const CaseOptions& c = options.case_options;
  for (const auto& assignment : c.overrides)
    if (assignment.substr(0, assignment.find('=')) == kLevelKey)
      throw CaseError(fmt::format("--set {}: key '{}': converge sets it itself (use --from and --levels)", assignment,
                                  kLevelKey));
  const int last = options.from + options.levels - 1;
  const int highest = static_cast<int>(find_key(kLevelKey)->max);
  if (last > highest)
    throw CaseError(fmt::format("--from {} --levels {}: needs {} {}..{}, which goes up to {}", options.from, options.levels,
                                kLevelKey, options.from, last, highest));

  std::vector<sweep::AxisPoint> axis;
  for (int level = options.from; level <= last; ++level) axis.push_back({fmt::format("level_{}", level), level});
  const sweep::SweepPlan plan = sweep::plan_axis(c.case_file, c.overrides, kLevelKey, axis);
  for (const auto& point : plan.points)
    if (!point.valid())
      throw CaseError(fmt::format("{}: {}: rule '{}': {}", c.case_file, point.name, point.violations.front().rule,
                                  point.violations.front().message));

  sweep::SweepOptions run;
  run.out_dir = c.out_dir;
  run.executable = std::filesystem::read_symlink("/proc/self/exe");
  run.jobs = options.jobs;
  run.backend_options = backend_options();
  run.label = "converge";
  run.write_tables = false;
  sweep::run_sweep(plan, run);

  std::vector<convergence::LevelRun> levels;
  for (std::size_t i = 0; i < plan.points.size(); ++i) {
    const auto record = sweep::read_point(plan.points[i], run.out_dir);
    levels.push_back({options.from + static_cast<int>(i), plan.points[i].name, record.status, record.error, record.summary});
  }
  const auto report = convergence::build_report(levels);
  sweep::write_file_atomically(run.out_dir / "converge.json", convergence::report_json(report).dump(2) + "\n");
  sweep::write_file_atomically(run.out_dir / "converge.csv", convergence::report_csv(report));

  const std::filesystem::path history_bands_file = run.out_dir / "converge_history.csv";
  const auto failed = std::find_if(levels.begin(), levels.end(), [](const auto& l) { return l.status != "completed"; });
  if (failed != levels.end()) {
    // Bands over time need every level's history: none, rather than an earlier start's.
    std::filesystem::remove(history_bands_file);
    throw std::runtime_error(fmt::format("converge: level {} {}: {} (see {}); partial results in {}", failed->level,
                                         failed->status, failed->error.empty() ? "no summary" : failed->error,
                                         (run.out_dir / failed->directory / "run.log").string(),
                                         (run.out_dir / "converge.json").string()));
  }
  std::vector<int> numbers;
  std::vector<output::HistoryTable> histories;
  for (const auto& level : levels) {
    numbers.push_back(level.level);
    histories.push_back(output::read_history_table(run.out_dir / level.directory / "history.csv"));
  }
  sweep::write_file_atomically(history_bands_file,
                               convergence::history_bands_csv(convergence::history_bands(numbers, histories)));
  for (const auto& warning : report.warnings) fmt::print("converge: warning: {}\n", warning);
  if (const std::string line = convergence::coarser_band_line(report); !line.empty()) fmt::print("{}\n", line);
  // Refinement halves the sizes near the needle only: a coarse core stays coarse at every level.
  const std::string mesh_warning = coarse_mesh_warning(plan.points.front().coarse_mesh);
  fmt::print("{}{}\n", convergence::verdict_line(report), mesh_warning.empty() ? "" : "; " + mesh_warning);
}

}  // namespace

void add_converge_command(CLI::App& app) {
  auto* command = app.add_subcommand(
      "converge",
      "Error band of every answer: run a case at three consecutive mesh.refinement_level values (each halves the "
      "element sizes near the needle), then per summary metric the observed order, Richardson value and grid "
      "convergence index (GCI, Celik et al. 2008); converge.csv + converge.json and a pass/fail/undecided verdict "
      "per safety limit (decided by the critical-distance value when the run reports one); converge_history.csv, "
      "the band of every history.csv quantity at every output time and of its change since its peak. Resumes: finished "
      "levels are not run again; each level's run is in OUT/level_<L>/, and postprocess/plot_convergence.py OUT draws "
      "the bands. Options after `--` go to every run.");
  auto options = std::make_shared<ConvergeOptions>();
  options->case_options.add_to(*command, "out/converge");
  command->add_option("--jobs", options->jobs, "Levels run at the same time")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  command->add_option("--levels", options->levels,
                      "Number of refinement levels (the estimate uses the finest three; with four or more, the band "
                      "of the three below the finest is checked against the finest value)")
      ->check(CLI::Range(3, 5))
      ->capture_default_str();
  command->add_option("--from", options->from, "Coarsest refinement level")->check(CLI::Range(0, 4))->capture_default_str();
  command->callback([options] { converge_command(*options); });
}

}  // namespace needlefem::app
