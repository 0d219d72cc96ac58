// The error band of every history.csv quantity at every output time; see history_bands.hpp.
#include "convergence/history_bands.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "output/csv.hpp"

namespace needlefem::convergence {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The row of a history at time t (to 1e-9 s + 1e-7 t), or nullptr.
const std::vector<double>* row_at(const output::HistoryTable& history, std::size_t time_column, double t) {
  for (const auto& row : history.rows)
    if (std::abs(row[time_column] - t) <= 1e-9 + 1e-7 * std::abs(t)) return &row;
  return nullptr;
}

// The row of a quantity's largest finite |value| on the finest level, or rows.size() if none.
std::size_t peak_row(const std::vector<HistoryBandRow>& rows) {
  std::size_t peak = rows.size();
  double largest = -1.0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const double value = std::abs(rows[i].values.back());
    if (std::isfinite(value) && value > largest) largest = value, peak = i;
  }
  return peak;
}

}  // namespace

const char* change_resolution(const HistoryBandRow& row) {
  if (row.time_s == row.peak_time_s || row.change.behaviour == Behaviour::incomplete) return "";
  if (row.change.band_high < 0.0) return "below";
  if (row.change.band_low > 0.0) return "above";
  return "within band";
}

HistoryBands history_bands(const std::vector<int>& levels, const std::vector<output::HistoryTable>& histories,
                           const Settings& settings) {
  if (histories.size() < 3 || levels.size() != histories.size())
    throw std::invalid_argument("history bands need three levels, each with its history");
  HistoryBands bands;
  bands.levels = levels;
  const std::size_t n = histories.size();
  const output::HistoryTable& finest = histories.back();
  const std::size_t finest_time = finest.column("time_s");
  // Each level's row at each of the finest level's times (nullptr where it has none).
  std::vector<std::vector<const std::vector<double>*>> rows_at(n);
  for (std::size_t l = 0; l < n; ++l) {
    const std::size_t time_column = histories[l].column("time_s");
    for (const auto& finest_row : finest.rows)
      rows_at[l].push_back(row_at(histories[l], time_column, finest_row[finest_time]));
  }

  for (const std::string& quantity : finest.columns) {
    if (!output::is_history_quantity(quantity)) continue;
    std::vector<std::optional<std::size_t>> columns;
    for (const auto& history : histories) columns.push_back(history.find_column(quantity));
    std::vector<HistoryBandRow> rows;
    for (std::size_t t = 0; t < finest.rows.size(); ++t) {
      HistoryBandRow row;
      row.quantity = quantity;
      row.time_s = finest.rows[t][finest_time];
      for (std::size_t l = 0; l < n; ++l)
        row.values.push_back(columns[l] && rows_at[l][t] ? (*rows_at[l][t])[*columns[l]] : kNaN);
      row.estimate = estimate(row.values[n - 3], row.values[n - 2], row.values[n - 1], settings);
      rows.push_back(std::move(row));
    }
    const std::size_t peak = peak_row(rows);
    const double peak_time = peak < rows.size() ? rows[peak].time_s : kNaN;
    const std::vector<double> peak_values = peak < rows.size() ? rows[peak].values : std::vector<double>(n, kNaN);
    const auto change = [&](const HistoryBandRow& row, std::size_t l) { return row.values[l] - peak_values[l]; };
    for (auto& row : rows) {
      row.peak_time_s = peak_time;
      row.change = estimate(change(row, n - 3), change(row, n - 2), change(row, n - 1), settings);
      bands.rows.push_back(std::move(row));
    }
  }
  return bands;
}

std::string history_bands_csv(const HistoryBands& bands) {
  std::vector<std::string> header{"quantity", "time_s"};
  for (int level : bands.levels) header.push_back(fmt::format("f_level{}", level));
  for (const char* column : {"observed_order", "f_extrapolated", "gci_fine", "band_low", "band_high", "note",
                             "peak_time_s", "change_since_peak", "change_band_low", "change_band_high",
                             "change_resolution"})
    header.emplace_back(column);
  std::string text = fmt::format("{}\n", fmt::join(header, ","));
  for (const auto& row : bands.rows) {
    std::vector<std::string> fields{row.quantity, number_text(row.time_s)};
    for (double v : row.values) fields.push_back(number_text(v));
    const auto cells = estimate_cells(row.estimate);
    fields.insert(fields.end(), cells.begin(), cells.end());
    fields.push_back(row.estimate.note);
    for (double v : {row.peak_time_s, row.change.fine, row.change.band_low, row.change.band_high})
      fields.push_back(number_text(v));
    fields.emplace_back(change_resolution(row));
    for (auto& field : fields) field = output::csv_field(field);
    text += fmt::format("{}\n", fmt::join(fields, ","));
  }
  return text;
}

}  // namespace needlefem::convergence
