// The error band of every metric a run reports, from the summary.json of the same case run at
// three or more consecutive mesh.refinement_level values (`needlefem converge`), and the
// verdict per safety limit. The estimates are grid_convergence.hpp's, on the three finest levels;
// with four or more levels each band is also checked one level up: the band of the three levels
// below the finest against the finest value, a test of the band itself.
//
// Metrics (every part optional; what a summary lacks is skipped, what a level lacks is empty):
//   safety.<limit>.<metric>.value  every object with a numeric "value" (point_max,
//                                  critical_distance, volume_above_limit_mm3, ...), limit
//                                  safety.<limit>.limit; compared with the limit when the
//                                  metric is in the limit's unit (point_max, critical_distance,
//                                  percentile)
//   max.<quantity>.value           point maxima; the one a limit names (thresholds.<limit>.max_key)
//                                  is compared with thresholds.<limit>.limit
//   needle.max_axial_force_n, needle.max_torque_n_m
// The verdict of a limit is that of safety.<limit>.critical_distance, else of
// safety.<limit>.point_max, else of the point maximum under "max" (DESIGN.md §2b: point maxima
// at a needle edge do not converge; the critical-distance value does).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "convergence/grid_convergence.hpp"

namespace needlefem::convergence {

struct LevelRun {
  int level = 0;
  std::string directory;   // relative to the converge folder
  std::string status;      // completed, failed or pending
  std::string error;
  nlohmann::json summary;  // the run's summary.json (null when there is none)
};

struct MetricRow {
  std::string metric;            // "safety.log_strain.critical_distance", "max.von_mises_pa", ...
  std::string limit_name;        // "" when the metric belongs to no limit
  double limit = 0;              // NaN when none
  bool compared = false;         // in the limit's unit: gets a verdict
  std::vector<double> values;    // per level (NaN when missing)
  Estimate estimate;             // on the three finest levels
  std::optional<Verdict> verdict;
  // With four or more levels, the check of the band one level up: the estimate on the three
  // levels below the finest (empty when one of them lacks the value), and whether the finest
  // value fell inside its band (empty when either is missing).
  std::optional<Estimate> coarser_estimate;
  std::optional<bool> finest_in_coarser_band;
};

struct LimitVerdict {
  std::string limit_name;
  double limit = 0;
  std::string metric;  // the row that decided
  Verdict verdict = Verdict::undecided;
  // safety.<limit>.history_columns: its history.csv columns by role ({} when no level names them)
  nlohmann::json history_columns = nlohmann::json::object();
};

struct Report {
  std::vector<LevelRun> levels;
  std::vector<MetricRow> rows;
  std::vector<LimitVerdict> limits;
  Settings settings;
  // The meshes do not refine as assumed: all levels have the same tet count (the estimates then
  // hold no discretisation error), or a level's effective ratio (N_l / N_{l-1})^(1/3) is off the
  // nominal r by more than 25 %.
  std::vector<std::string> warnings;
  // With four or more levels: how many rows' finest value fell inside the band of the three
  // levels below it, of those where both exist ("the band held one level up").
  int coarser_bands_held = 0, coarser_bands_checked = 0;
};

// Needs at least three levels, in increasing order.
Report build_report(std::vector<LevelRun> levels, const Settings& settings = {});
// The same report from a converge table's text (report_csv's columns: metric, limit,
// limit_value, f_level<K> per level, verdict; the other columns are recomputed), for a table whose
// runs are gone: its bands and verdicts under these settings and this version's rules. A row is
// compared with its limit where the table gave it a verdict. Without the runs' summaries there
// are no refinement-ratio warnings and no history columns. A text that is not such a table
// (no such column, fewer than three levels, a row of another length, a cell that is not a
// number) is refused in one line naming `file` (and the metric and column).
Report report_from_table(const std::string& text, const std::string& file, const Settings& settings = {});

std::string report_csv(const Report& report);
nlohmann::json report_json(const Report& report);
// With four or more levels, one line: how many bands of the three levels below the finest held
// the finest value, naming the rows that did not ("" with fewer levels).
std::string coarser_band_line(const Report& report);
// One line: the overall verdict (fail if any limit fails, else undecided if any is, else pass)
// and each limit's deciding metric with its band.
std::string verdict_line(const Report& report);

}  // namespace needlefem::convergence
