// When a run writes results: every output.interval_s from 0 to the end of the scene's history
// (brain-tip: motion.duration_s; block: loading.ramp_s + loading.hold_s), the end always
// included. IDA hits each time exactly (stop time), so outputs are never interpolated.
#pragma once

#include <vector>

namespace needlefem {
class Case;
}

namespace needlefem::run {

double history_end(const Case& c);
// Ascending, starting at 0 and ending at history_end(c). Throws CaseError (output.interval_s)
// for more than 1e4 output times.
std::vector<double> output_times(const Case& c);

}  // namespace needlefem::run
