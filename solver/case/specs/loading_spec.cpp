#include "case/specs/loading_spec.hpp"

#include "case/case.hpp"

namespace needlefem {

LoadingSpec parse_loading_spec(const Case& c, SceneKind scene_kind) {
  const std::vector<double> translation = c.reals("displacement.translation_mm");  // three entries (schema)
  return {.origin = c.origin(),
          .scene_kind = scene_kind,
          .motion_duration_s = c.real("motion.duration_s"),
          .ramp_s = c.real("loading.ramp_s"),
          .hold_s = c.real("loading.hold_s"),
          .history_time_s = c.maybe_reals("loading.history_time_s"),
          .history_factor = c.maybe_reals("loading.history_factor"),
          .translation_mm = {translation[0], translation[1], translation[2]},
          .translation_mm_given = c.given("displacement.translation_mm"),
          .translation_history_mm = c.maybe_reals("displacement.translation_history_mm")};
}

}  // namespace needlefem
