// The error band of every quantity of history.csv at every output time, from the same case run
// at three or more consecutive mesh.refinement_level values (`needlefem converge`, which writes
// it as converge_history.csv): grid_convergence.hpp's estimate on the three finest levels, time
// by time. The summary's bands (convergence_report.hpp) judge one number per metric, its largest
// value over the run; these say whether a curve's shape is resolved: that a value falls or rises
// between two times by more than the bands of both.
//
// A curve's shape, such as paper 001's slow case relaxing after its peak, is a change between
// two times, and is judged by the band of that change, not by comparing the two times' bands:
// each row also estimates each level's change since the quantity's peak (its value at the row's
// time less its value at the output time of the finest level's largest |value|, the same time on
// every level) with the same procedure. Where a level's error is alike at both times the change
// is better resolved than either value, and where it is not, its band says so.
//
// Quantities: every column of the finest level's history that output::is_history_quantity counts
// as one: not time_s, the step and Newton counters or the positions of located values (*_x_mm,
// *_y_mm, *_z_mm). Times: the finest level's output times; a coarser level's value at the same
// time (to 1e-9 s + 1e-7 of the time), NaN (an incomplete estimate) where it has none.
#pragma once

#include <string>
#include <vector>

#include "convergence/grid_convergence.hpp"
#include "output/history_table.hpp"

namespace needlefem::convergence {

struct HistoryBandRow {
  std::string quantity;       // a history.csv column
  double time_s = 0;
  std::vector<double> values;  // per level, coarsest first (NaN when missing)
  Estimate estimate;          // on the three finest levels
  double peak_time_s = 0;     // the finest level's time of the largest |value| (NaN when it has none)
  Estimate change;            // on the three finest levels' values less their values at peak_time_s
};

// "below" or "above" (the value at the peak time, resolved) when the change's band lies wholly
// below or above zero, "within band" when it holds zero, "" at the peak time itself and where
// the change is incomplete.
const char* change_resolution(const HistoryBandRow& row);

struct HistoryBands {
  std::vector<int> levels;
  std::vector<HistoryBandRow> rows;  // quantity by quantity, each in time order
};

// levels and histories in the same order, coarsest first, at least three.
HistoryBands history_bands(const std::vector<int>& levels, const std::vector<output::HistoryTable>& histories,
                           const Settings& settings = {});

// Columns: quantity, time_s, f_level<L> per level, observed_order, f_extrapolated, gci_fine,
// band_low, band_high, note; then peak_time_s, change_since_peak (the finest level's),
// change_band_low, change_band_high and change_resolution.
std::string history_bands_csv(const HistoryBands& bands);

}  // namespace needlefem::convergence
