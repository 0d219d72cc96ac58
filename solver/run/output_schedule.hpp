// When a run writes results: every output.interval_s from 0 to the end of the scene's history
// (mechanics::history_end, physics/mechanics/load_history.hpp), the end always included. IDA hits each time exactly (stop time), so outputs are never interpolated.
#pragma once

#include <vector>

#include "case/specs/loading_spec.hpp"
#include "case/specs/output_spec.hpp"

namespace needlefem::run {

// Ascending, starting at 0 and ending at mechanics::history_end of `loading`, every
// `output`.interval_s. Throws CaseError (output.interval_s) for more than 1e4 output times.
std::vector<double> output_times(const OutputSpec& output, const LoadingSpec& loading);

}  // namespace needlefem::run
