// history.csv of a `needlefem run` read back: its header and one row of numbers per output time
// (run/run_case.cpp writes it; time_s is the first column).
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace needlefem::output {

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
