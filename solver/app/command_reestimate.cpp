// `needlefem reestimate TABLE.csv [--out FILE.csv]`: a converge table's bands and verdicts again,
// from its level values, under this version's estimator (convergence/convergence_report.hpp
// report_from_table): for committed tables whose runs are gone, so that a change of the rules
// reaches them without the runs. Writes the table in converge.csv's form to FILE.csv (stdout
// without --out) and prints converge's lines: the bands held one level up (four or more levels)
// and the verdict.
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fmt/core.h>

#include "app/commands.hpp"
#include "convergence/convergence_report.hpp"
#include "sweep/sweep_table.hpp"

namespace needlefem::app {

namespace {

struct ReestimateOptions {
  std::string table;
  std::string out;
};

void reestimate_command(const ReestimateOptions& options) {
  std::ifstream in(options.table);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot be read", options.table));
  std::ostringstream text;
  text << in.rdbuf();
  const convergence::Report report = convergence::report_from_table(text.str(), options.table);
  const std::string table = convergence::report_csv(report);
  if (options.out.empty()) {
    fmt::print("{}", table);
    return;
  }
  sweep::write_file_atomically(options.out, table);
  if (const std::string line = convergence::coarser_band_line(report); !line.empty()) fmt::print("{}\n", line);
  fmt::print("{}\n", convergence::verdict_line(report));
}

}  // namespace

void add_reestimate_command(CLI::App& app) {
  auto* command = app.add_subcommand(
      "reestimate",
      "A converge table's bands and verdicts again from its level values (f_level0, f_level1, ...), under this "
      "version's rules: for a committed table whose runs are gone. Writes the table in converge.csv's form.");
  auto options = std::make_shared<ReestimateOptions>();
  command->add_option("table", options->table, "A converge.csv written by `needlefem converge`")->required();
  command->add_option("--out", options->out, "The re-estimated table (stdout when not given); may be TABLE itself");
  command->callback([options] { reestimate_command(*options); });
}

}  // namespace needlefem::app
