// output/history_table.hpp: history.csv's columns that are not quantities, the file read back,
// and its one-line errors naming file, line and column.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "output/history_table.hpp"

namespace needlefem::output {
namespace {

std::filesystem::path write(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::path(::testing::TempDir()) / name;
  std::ofstream(path) << text;
  return path;
}

std::string error_of(const std::filesystem::path& path) {
  try {
    read_history_table(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(HistoryTable, ReadsColumnsAndRows) {
  const auto path = write("history_ok.csv", "time_s,steps,critical_distance_log_strain,volume_mm3\n"
                                            "0,0,0,\n0.01,12,0.0134,4.9e-320\n");
  const HistoryTable table = read_history_table(path);
  ASSERT_EQ(table.columns.size(), 4u);
  ASSERT_EQ(table.rows.size(), 2u);
  EXPECT_EQ(table.column("critical_distance_log_strain"), 2u);
  EXPECT_DOUBLE_EQ(table.rows[1][0], 0.01);
  EXPECT_DOUBLE_EQ(table.rows[1][2], 0.0134);
  EXPECT_TRUE(std::isnan(table.rows[0][3])) << "an empty cell is NaN";
  EXPECT_GT(table.rows[1][3], 0.0) << "a subnormal value is read, not refused";
  EXPECT_EQ(table.file, path.string());
  EXPECT_THROW(table.column("max_log_strain"), std::runtime_error);
}

TEST(HistoryTable, CountersAndPositionsAreNotQuantities) {
  EXPECT_EQ(history_position_columns("max_log_strain"), ",max_log_strain_x_mm,max_log_strain_y_mm,max_log_strain_z_mm");
  for (const char* column : {"time_s", "steps", "newton_iterations", "max_log_strain_x_mm", "max_log_strain_y_mm",
                             "critical_distance_von_mises_z_mm"})
    EXPECT_FALSE(is_history_quantity(column)) << column;
  for (const char* column : {"max_log_strain", "critical_distance_von_mises", "volume_above_log_strain_mm3",
                             "needle_force_x_n", "elastic_energy_j"})
    EXPECT_TRUE(is_history_quantity(column)) << column;
}

TEST(HistoryTable, BadFilesGiveOneLineNamingTheFault) {
  const auto missing = std::filesystem::path(::testing::TempDir()) / "no_such_history.csv";
  EXPECT_EQ(error_of(missing), missing.string() + ": cannot open");
  const auto empty = write("history_empty.csv", "");
  EXPECT_EQ(error_of(empty), empty.string() + ": empty file");
  const auto short_row = write("history_short.csv", "time_s,a,b\n0,1,2\n0.1,1\n");
  EXPECT_EQ(error_of(short_row), short_row.string() + ": line 3 has 2 fields, the header 3");
  const auto text = write("history_text.csv", "time_s,a\n0,1\n0.1,1.5x\n");
  EXPECT_EQ(error_of(text), text.string() + ": line 3: column 'a': '1.5x' is not a number");
}

}  // namespace
}  // namespace needlefem::output
