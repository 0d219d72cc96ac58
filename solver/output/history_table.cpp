// history.csv read back; see history_table.hpp.
#include "output/history_table.hpp"

#include "output/csv.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <fmt/core.h>

namespace needlefem::output {

namespace {

constexpr std::array<const char*, 3> kPositionSuffixes{"_x_mm", "_y_mm", "_z_mm"};

}  // namespace

std::string history_position_columns(const std::string& name) {
  std::string columns;
  for (const char* suffix : kPositionSuffixes) columns += fmt::format(",{}{}", name, suffix);
  return columns;
}

bool is_history_quantity(const std::string& column) {
  for (const char* counter : kHistoryCounterColumns)
    if (column == counter) return false;
  for (const char* suffix : kPositionSuffixes)
    if (column.ends_with(suffix)) return false;
  return true;
}

std::optional<std::size_t> HistoryTable::find_column(const std::string& name) const {
  const auto it = std::find(columns.begin(), columns.end(), name);
  if (it == columns.end()) return std::nullopt;
  return static_cast<std::size_t>(it - columns.begin());
}

std::size_t HistoryTable::column(const std::string& name) const {
  const auto index = find_column(name);
  if (!index) throw std::runtime_error(fmt::format("{}: no column '{}'", file, name));
  return *index;
}

HistoryTable read_history_table(const std::filesystem::path& csv) {
  HistoryTable table;
  table.file = csv.string();
  std::ifstream in(csv);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open", table.file));
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(fmt::format("{}: empty file", table.file));
  table.columns = csv_record(line);
  for (int row = 2; std::getline(in, line); ++row) {
    if (line.empty()) continue;
    const std::vector<std::string> fields = csv_record(line);
    if (fields.size() != table.columns.size())
      throw std::runtime_error(
          fmt::format("{}: line {} has {} fields, the header {}", table.file, row, fields.size(), table.columns.size()));
    std::vector<double> values;
    values.reserve(fields.size());
    for (std::size_t i = 0; i < fields.size(); ++i) {
      const std::optional<double> value = csv_number(fields[i]);
      if (!value)
        throw std::runtime_error(fmt::format("{}: line {}: column '{}': '{}' is not a number", table.file, row,
                                             table.columns[i], fields[i]));
      values.push_back(*value);
    }
    table.rows.push_back(std::move(values));
  }
  return table;
}

}  // namespace needlefem::output
