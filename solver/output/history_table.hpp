// history.csv of a `needlefem run`: the names of its columns that are not quantities, which its
// writers (run/run_case.cpp, run/safety_report.cpp) use, and the file read back: its header and
// one row of numbers per output time (time_s is the first column).
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace needlefem::output {

// The first columns of every history.csv: the output time and the integrator's counters so far.
inline constexpr std::array<const char*, 3> kHistoryCounterColumns{"time_s", "steps", "newton_iterations"};

// ",NAME_x_mm,NAME_y_mm,NAME_z_mm": the reference position columns of a located value NAME.
std::string history_position_columns(const std::string& name);

// Whether a column holds a quantity: not the time, a counter or a position.
bool is_history_quantity(const std::string& column);

struct HistoryTable {
  std::string file;
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;  // an empty cell is NaN (a quantity not computed at that time)

  // The index of a column, if the table has it.
  std::optional<std::size_t> find_column(const std::string& name) const;
  // The index of a column; throws std::runtime_error "FILE: no column 'NAME'".
  std::size_t column(const std::string& name) const;
};

// Throws std::runtime_error "FILE: reason" when the file cannot be opened, is empty, or has a row
// of another width or a cell that is not a number.
HistoryTable read_history_table(const std::filesystem::path& csv);

}  // namespace needlefem::output
