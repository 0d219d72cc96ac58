// The loading history of the block and mesh scenes (scene.kind = "block", "mesh"): a load
// factor s(t) that scales the applied displacement gradient and the pressure, and the
// translation d(t) of the displaced groups (mesh scene).
//
//   without loading.history_time_s:  s(t) = ramp_then_hold(t, loading.ramp_s),
//                                    d(t) = s(t) displacement.translation_mm;
//   with it (times t_k from 0, strictly increasing): s and d piecewise linear through
//     (t_k, loading.history_factor[k]) and (t_k, displacement.translation_history_mm[3k..3k+2])
//     (d from s(t) displacement.translation_mm when no translation history is given),
//     held after the last time.
// The history lasts until loading.ramp_s (or the last history time) + loading.hold_s
// (brain-tip: motion.duration_s).
#pragma once

#include <vector>

#include "case/specs/loading_spec.hpp"
#include "model/tet_mesh.hpp"

namespace needlefem::mechanics {

// Load factor of the block scene: linear ramp to 1 over ramp_s, then hold.
double ramp_then_hold(double t, double ramp_s);

// How long the case's scene is loaded (s): its output history ends there.
double history_end(const LoadingSpec& spec);

class LoadHistory {
 public:
  // Throws CaseError for a history table that is not increasing from 0 or whose lists differ
  // in length, or a translation history given without history times or with
  // displacement.translation_mm.
  static LoadHistory from_spec(const LoadingSpec& spec);

  double factor(double t) const;
  Point3 translation(double t) const;  // metres

 private:
  std::vector<double> times_, factors_;
  std::vector<Point3> translations_;
};

}  // namespace needlefem::mechanics
