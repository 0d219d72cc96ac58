// The CSV that needlefem writes and reads back (history.csv, sweep.csv, converge.csv): a field
// quoted only when it must be, and one strict number per cell.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace needlefem::output {

// A CSV field, quoted when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& text);
// The fields of one CSV line as csv_field writes them (quoted fields unquoted, "" read as ").
std::vector<std::string> csv_record(const std::string& line);
// A cell's number: NaN for an empty cell, nothing when the cell is not wholly a number. strtod,
// not stod: a subnormal value is a number too.
std::optional<double> csv_number(const std::string& cell);

}  // namespace needlefem::output
