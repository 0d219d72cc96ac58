#include "convergence/convergence_report.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "output/csv.hpp"

namespace needlefem::convergence {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
using json = nlohmann::json;

// Safety metrics in the limit's own unit (a field value), which get a verdict; the others
// (volume above the limit, its region fraction) are converged but not compared.
constexpr const char* kComparedSafetyMetrics[] = {"point_max", "critical_distance", "percentile"};
constexpr const char* kNeedleLoads[] = {"max_axial_force_n", "max_torque_n_m"};

double number(const json& j, const json::json_pointer& pointer) {
  if (!j.is_object() || !j.contains(pointer)) return kNaN;
  const json& v = j.at(pointer);
  return v.is_number() ? v.get<double>() : kNaN;
}

json number_json(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

// A summary's number as it was written (a count stays an integer), null when absent.
json summary_number(const json& summary, const char* pointer) {
  const json::json_pointer at(pointer);
  return summary.is_object() && summary.contains(at) && summary.at(at).is_number() ? summary.at(at) : json(nullptr);
}

struct MetricKey {
  std::string metric, pointer, limit_name;
  bool compared = false;
};

// The limits of a summary's "safety": each limit's name and entry.
std::vector<std::pair<std::string, const json*>> safety_limits(const json& summary) {
  std::vector<std::pair<std::string, const json*>> out;
  if (!summary.is_object() || !summary.contains("safety") || !summary["safety"].is_object()) return out;
  for (const auto& [limit, entry] : summary["safety"].items())
    if (limit != "settings" && entry.is_object()) out.emplace_back(limit, &entry);
  return out;
}

// The limit whose point maximum is summary "max".<name> (thresholds.<limit>.max_key), or "".
std::string limit_of_maximum(const json& summary, const std::string& name) {
  if (!summary.is_object() || !summary.contains("thresholds") || !summary["thresholds"].is_object()) return "";
  for (const auto& [limit, entry] : summary["thresholds"].items())
    if (entry.is_object() && entry.value("max_key", "") == name) return limit;
  return "";
}

// The metrics one summary reports, in the order of the header comment.
std::vector<MetricKey> metrics_of(const json& summary) {
  std::vector<MetricKey> out;
  if (!summary.is_object()) return out;
  for (const auto& [limit, entry] : safety_limits(summary))
    for (const auto& [name, metric] : entry->items()) {
      if (!metric.is_object() || !metric.contains("value") || !metric["value"].is_number()) continue;
      const bool compared = std::find(std::begin(kComparedSafetyMetrics), std::end(kComparedSafetyMetrics), name) !=
                            std::end(kComparedSafetyMetrics);
      out.push_back({fmt::format("safety.{}.{}", limit, name), fmt::format("/safety/{}/{}/value", limit, name), limit,
                     compared});
    }
  if (summary.contains("max") && summary["max"].is_object())
    for (const auto& [name, maximum] : summary["max"].items()) {
      if (!maximum.is_object() || !maximum.contains("value") || !maximum["value"].is_number()) continue;
      const std::string limit = limit_of_maximum(summary, name);
      out.push_back({"max." + name, fmt::format("/max/{}/value", name), limit, !limit.empty()});
    }
  for (const char* load : kNeedleLoads)
    if (!std::isnan(number(summary, json::json_pointer(fmt::format("/needle/{}", load)))))
      out.push_back({fmt::format("needle.{}", load), fmt::format("/needle/{}", load), "", false});
  return out;
}

// A limit's value: safety.<limit>.limit, else thresholds.<limit>.limit, from the finest level
// that gives it.
double limit_value(const std::vector<LevelRun>& levels, const std::string& name) {
  for (auto level = levels.rbegin(); level != levels.rend(); ++level)
    for (const char* section : {"safety", "thresholds"}) {
      const double limit = number(level->summary, json::json_pointer(fmt::format("/{}/{}/limit", section, name)));
      if (!std::isnan(limit)) return limit;
    }
  return kNaN;
}

void estimate_rows(Report& report);
void decide_limits(Report& report);

}  // namespace

Report build_report(std::vector<LevelRun> levels, const Settings& settings) {
  if (levels.size() < 3) throw std::invalid_argument("grid convergence needs three levels");
  Report report;
  report.settings = settings;
  report.levels = std::move(levels);
  const auto& runs = report.levels;
  const std::size_t n = runs.size();

  std::vector<MetricKey> keys;
  for (const auto& run : runs)
    for (auto& key : metrics_of(run.status == "completed" ? run.summary : json()))
      if (std::none_of(keys.begin(), keys.end(), [&](const MetricKey& k) { return k.metric == key.metric; }))
        keys.push_back(std::move(key));

  for (const auto& key : keys) {
    MetricRow row;
    row.metric = key.metric;
    row.limit_name = key.limit_name;
    row.limit = key.limit_name.empty() ? kNaN : limit_value(runs, key.limit_name);
    row.compared = key.compared && !std::isnan(row.limit);
    for (const auto& run : runs)
      row.values.push_back(run.status == "completed" ? number(run.summary, json::json_pointer(key.pointer)) : kNaN);
    report.rows.push_back(std::move(row));
  }
  estimate_rows(report);

  std::vector<double> tets;
  for (const auto& run : runs) tets.push_back(number(run.summary, json::json_pointer("/mesh/tets")));
  if (std::none_of(tets.begin(), tets.end(), [](double t) { return std::isnan(t); })) {
    if (std::all_of(tets.begin(), tets.end(), [&](double t) { return t == tets.front(); }))
      report.warnings.push_back(fmt::format("all levels have the same mesh ({} tets): mesh.refinement_level does not "
                                            "refine this case, so the bands hold no discretisation error", tets.front()));
    else
      for (std::size_t i = 1; i < n; ++i) {
        const double ratio = std::cbrt(tets[i] / tets[i - 1]);
        if (std::abs(ratio / settings.ratio - 1.0) > 0.25)
          report.warnings.push_back(fmt::format("level {}: effective refinement ratio (N/N_previous)^(1/3) = {:.3g}, "
                                                "not the nominal {:g} the orders assume", runs[i].level, ratio, settings.ratio));
      }
  }

  decide_limits(report);
  // Each limit's history.csv columns, from the finest level that names them.
  for (LimitVerdict& limit : report.limits) {
    const json::json_pointer at(fmt::format("/safety/{}/history_columns", limit.limit_name));
    for (auto run = runs.rbegin(); run != runs.rend() && limit.history_columns.empty(); ++run)
      if (run->status == "completed" && run->summary.contains(at) && run->summary.at(at).is_object())
        limit.history_columns = run->summary.at(at);
  }
  return report;
}

namespace {

// Each row's estimate on the three finest levels, its verdict, and with four or more levels the
// check of the band one level up.
void estimate_rows(Report& report) {
  const std::size_t n = report.levels.size();
  for (MetricRow& row : report.rows) {
    row.estimate = estimate(row.values[n - 3], row.values[n - 2], row.values[n - 1], report.settings);
    if (row.compared) row.verdict = verdict(row.estimate, row.limit);
    if (n < 4) continue;
    const Estimate coarser = estimate(row.values[n - 4], row.values[n - 3], row.values[n - 2], report.settings);
    if (coarser.behaviour != Behaviour::incomplete) row.coarser_estimate = coarser;
    const double finest = row.values[n - 1];
    if (row.coarser_estimate && !std::isnan(finest)) {
      row.finest_in_coarser_band = finest >= coarser.band_low && finest <= coarser.band_high;
      ++report.coarser_bands_checked;
      report.coarser_bands_held += *row.finest_in_coarser_band ? 1 : 0;
    }
  }
}

// Each limit's verdict from its most objective compared metric.
void decide_limits(Report& report) {
  std::vector<std::string> names;
  for (const auto& row : report.rows)
    if (row.compared && std::find(names.begin(), names.end(), row.limit_name) == names.end()) names.push_back(row.limit_name);
  for (const auto& name : names) {
    const MetricRow* decider = nullptr;
    for (const std::string& metric :
         {"safety." + name + ".critical_distance", "safety." + name + ".point_max", std::string()}) {
      for (const auto& row : report.rows)
        if (row.compared && row.limit_name == name && (metric.empty() ? row.metric.starts_with("max.") : row.metric == metric)) {
          decider = &row;
          break;
        }
      if (decider) break;
    }
    if (!decider) continue;
    report.limits.push_back({name, decider->limit, decider->metric, *decider->verdict, json::object()});
  }
}

}  // namespace

Report report_from_table(const std::string& text, const std::string& file, const Settings& settings) {
  const auto refuse = [&](const std::string& reason) {
    return std::invalid_argument(fmt::format("{}: {}", file, reason));
  };
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line)) throw refuse("empty: not a converge table");
  const std::vector<std::string> header = output::csv_record(line);
  const auto column = [&](const char* name) {
    const auto at = std::find(header.begin(), header.end(), name);
    if (at == header.end()) throw refuse(fmt::format("no column {} (not a converge table)", name));
    return static_cast<std::size_t>(at - header.begin());
  };
  const std::size_t metric_column = column("metric"), limit_column = column("limit"),
                    limit_value_column = column("limit_value"), verdict_column = column("verdict");
  Report report;
  report.settings = settings;
  std::vector<std::size_t> level_columns;
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i].starts_with("f_level") && header[i].size() > 7 &&
        header[i].find_first_not_of("0123456789", 7) == std::string::npos) {
      level_columns.push_back(i);
      report.levels.push_back({std::stoi(header[i].substr(7)), "", "completed", "", json()});
    }
  if (report.levels.size() < 3)
    throw refuse(fmt::format("{} level columns f_levelK: grid convergence needs three", report.levels.size()));
  for (int row_number = 2; std::getline(in, line); ++row_number) {
    if (line.empty()) continue;
    const std::vector<std::string> fields = output::csv_record(line);
    if (fields.size() != header.size())
      throw refuse(fmt::format("row {}: {} fields, the header has {}", row_number, fields.size(), header.size()));
    const auto cell_number = [&](std::size_t i) {
      if (const auto x = output::csv_number(fields[i])) return *x;
      throw refuse(fmt::format("metric {}: column {}: '{}' is not a number", fields[metric_column], header[i], fields[i]));
    };
    MetricRow row;
    row.metric = fields[metric_column];
    row.limit_name = fields[limit_column];
    row.limit = cell_number(limit_value_column);
    // The table gives a verdict to the rows compared with their limit, and to no other.
    row.compared = !fields[verdict_column].empty() && !std::isnan(row.limit);
    for (std::size_t i : level_columns) row.values.push_back(cell_number(i));
    report.rows.push_back(std::move(row));
  }
  estimate_rows(report);
  decide_limits(report);
  return report;
}

std::string report_csv(const Report& report) {
  std::vector<std::string> header{"metric", "limit", "limit_value"};
  for (const auto& run : report.levels) header.push_back(fmt::format("f_level{}", run.level));
  for (const char* column : {"observed_order", "f_extrapolated", "gci_fine", "band_low", "band_high", "verdict", "note"})
    header.emplace_back(column);
  const bool checked_one_level_up = report.levels.size() >= 4;
  if (checked_one_level_up)
    for (const char* column : {"coarser_band_low", "coarser_band_high", "finest_in_coarser_band"}) header.emplace_back(column);
  std::string text = fmt::format("{}\n", fmt::join(header, ","));
  for (const auto& row : report.rows) {
    const Estimate& e = row.estimate;
    std::vector<std::string> fields{row.metric, row.limit_name, number_text(row.limit)};
    for (double v : row.values) fields.push_back(number_text(v));
    const auto cells = estimate_cells(e);
    fields.insert(fields.end(), cells.begin(), cells.end());
    fields.insert(fields.end(), {row.verdict ? to_string(*row.verdict) : "", e.note});
    if (checked_one_level_up) {
      const auto& coarser = row.coarser_estimate;
      fields.insert(fields.end(), {coarser ? number_text(coarser->band_low) : "",
                                   coarser ? number_text(coarser->band_high) : "",
                                   row.finest_in_coarser_band ? (*row.finest_in_coarser_band ? "yes" : "no") : ""});
    }
    for (auto& field : fields) field = output::csv_field(field);
    text += fmt::format("{}\n", fmt::join(fields, ","));
  }
  return text;
}

json report_json(const Report& report) {
  const Settings& s = report.settings;
  json out;
  out["format"] = "needlefem-converge";
  out["settings"] = {{"refinement_ratio", s.ratio},
                     {"safety_factor", s.safety_factor},
                     {"oscillatory_safety_factor", s.oscillatory_safety_factor},
                     {"formal_order", s.max_order},
                     {"asymptotic_order_min", s.min_order},
                     {"data_range_order", s.data_range_order},
                     {"mesh_independent_tolerance", s.mesh_independent_tolerance},
                     {"band", "f_fine +- gci_fine |f_fine|; estimates on the three finest levels"},
                     {"method", "Celik et al. 2008, J. Fluids Eng. 130:078001; Roache 1998; from data_range_order on, "
                                "at least safety_factor x the levels' range (Eca & Hoekstra 2014, J. Comput. Phys. 262:104)"}};
  json levels = json::array();
  for (std::size_t i = 0; i < report.levels.size(); ++i) {
    const LevelRun& run = report.levels[i];
    const json& summary = run.summary;
    json level = {{"level", run.level},
                  {"directory", run.directory},
                  {"status", run.status},
                  {"relative_size", std::ldexp(1.0, -(run.level - report.levels.front().level))},
                  {"tets", summary_number(summary, "/mesh/tets")},
                  {"nodes", summary_number(summary, "/mesh/nodes")},
                  {"dofs", summary_number(summary, "/solver/dofs")},
                  {"wall_s", summary_number(summary, "/solver/wall_s")}};
    if (!run.error.empty()) level["error"] = run.error;
    // (N_this / N_previous)^(1/3): the size ratio the mesher actually achieved, for information.
    if (i > 0) {
      const double ratio = std::cbrt(number(summary, json::json_pointer("/mesh/tets")) /
                                     number(report.levels[i - 1].summary, json::json_pointer("/mesh/tets")));
      level["effective_ratio_to_previous"] = number_json(ratio);
    }
    levels.push_back(level);
  }
  out["levels"] = levels;
  json rows = json::array();
  for (const auto& row : report.rows) {
    const Estimate& e = row.estimate;
    json values = json::array();
    for (double v : row.values) values.push_back(number_json(v));
    json r = {{"metric", row.metric},
              {"values", values},
              {"behaviour", to_string(e.behaviour)},
              {"observed_order", number_json(e.observed_order)},
              {"order_used", number_json(e.order)},
              {"order", e.behaviour == Behaviour::incomplete ? "" : order_text(e)},
              {"f_extrapolated", number_json(e.extrapolated)},
              {"gci_fine", number_json(e.gci_fine)},
              {"band", {number_json(e.band_low), number_json(e.band_high)}},
              {"note", e.note}};
    if (!row.limit_name.empty()) {
      r["limit"] = row.limit_name;
      r["limit_value"] = number_json(row.limit);
    }
    if (row.verdict) r["verdict"] = to_string(*row.verdict);
    if (row.coarser_estimate)
      r["coarser_band"] = {number_json(row.coarser_estimate->band_low), number_json(row.coarser_estimate->band_high)};
    if (row.finest_in_coarser_band) r["finest_in_coarser_band"] = *row.finest_in_coarser_band;
    rows.push_back(r);
  }
  out["metrics"] = rows;
  json verdicts = json::object();
  for (const auto& limit : report.limits)
    verdicts[limit.limit_name] = {{"verdict", to_string(limit.verdict)},
                                  {"metric", limit.metric},
                                  {"limit", limit.limit},
                                  {"history_columns", limit.history_columns}};
  out["verdicts"] = verdicts;
  out["warnings"] = report.warnings;
  if (report.levels.size() >= 4)
    out["coarser_bands"] = {{"checked", report.coarser_bands_checked}, {"held", report.coarser_bands_held}};
  return out;
}

std::string coarser_band_line(const Report& report) {
  if (report.levels.size() < 4) return "";
  const int coarse = report.levels[report.levels.size() - 4].level, finest = report.levels.back().level;
  std::vector<std::string> missed;
  for (const auto& row : report.rows)
    if (row.finest_in_coarser_band && !*row.finest_in_coarser_band)
      missed.push_back(fmt::format("{} {:.4g} outside [{:.4g}, {:.4g}]", row.metric, row.values.back(),
                                   row.coarser_estimate->band_low, row.coarser_estimate->band_high));
  return fmt::format("converge: the bands of levels {}-{} hold level {}'s value for {} of {} metrics{}{}", coarse,
                     finest - 1, finest, report.coarser_bands_held, report.coarser_bands_checked,
                     missed.empty() ? "" : ": not ", fmt::join(missed, "; "));
}

std::string verdict_line(const Report& report) {
  if (report.limits.empty()) return "converge: no safety limit reported: no verdict";
  bool any_fail = false, any_undecided = false;
  std::vector<std::string> parts;
  for (const auto& limit : report.limits) {
    any_fail = any_fail || limit.verdict == Verdict::fail;
    any_undecided = any_undecided || limit.verdict == Verdict::undecided;
    const auto row = std::find_if(report.rows.begin(), report.rows.end(), [&](const MetricRow& r) { return r.metric == limit.metric; });
    parts.push_back(fmt::format("{} {} ({} {:.4g} in [{:.4g}, {:.4g}], limit {:.4g})", limit.limit_name,
                                to_string(limit.verdict), limit.metric, row->estimate.fine, row->estimate.band_low,
                                row->estimate.band_high, limit.limit));
  }
  const char* overall = any_fail ? "FAIL" : any_undecided ? "UNDECIDED" : "PASS";
  return fmt::format("converge: {}: {}", overall, fmt::join(parts, "; "));
}

}  // namespace needlefem::convergence
