// How long and how a scene is loaded, parsed: [loading] and displacement.translation*
// (physics/mechanics/load_history.hpp). Read as given: the history table's rules are checked
// where a mesh scene builds its history (LoadHistory::from_spec), the only scene that uses it.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "case/specs/scene_kind.hpp"

namespace needlefem {

struct LoadingSpec {
  std::string origin;  // the case's, for the CaseErrors of the history table's rules
  SceneKind scene_kind;
  double motion_duration_s;  // motion.duration_s: a brain-tip scene is loaded while the needle moves
  double ramp_s;
  double hold_s;
  std::optional<std::vector<double>> history_time_s;
  std::optional<std::vector<double>> history_factor;
  std::array<double, 3> translation_mm;  // displacement.translation_mm
  bool translation_mm_given;             // rather than the schema's default
  std::optional<std::vector<double>> translation_history_mm;  // displacement.translation_history_mm
};

// scene_kind: the mesh spec's (parse_mesh_spec parses scene.kind).
LoadingSpec parse_loading_spec(const Case& c, SceneKind scene_kind);

}  // namespace needlefem
