#include "case/specs/needle_tip_spec.hpp"

#include <array>
#include <utility>

#include "case/specs/choice.hpp"

namespace needlefem {

namespace {

// needle.kind's choices (schema.cpp) with their enumerators.
const std::array kNeedleKinds{std::pair{"bevel", NeedleKind::bevel}, std::pair{"compliant", NeedleKind::compliant},
                              std::pair{"cad", NeedleKind::cad}};

}  // namespace

NeedleTipSpec parse_needle_tip_spec(const Case& c) {
  return {.origin = c.origin(),
          .kind = parse_choice(c, "needle.kind", kNeedleKinds),
          .radius_mm = c.real("needle.radius_mm"),
          .bevel_deg = c.real("needle.bevel_deg"),
          .fillet_mm = c.real("needle.fillet_mm"),
          .shaft_mm = c.real("needle.shaft_mm"),
          .head_length_mm = c.real("needle.head_length_mm"),
          .neck_length_mm = c.real("needle.neck_length_mm"),
          .neck_diameter_mm = c.real("needle.neck_diameter_mm"),
          .point_length_mm = c.real("needle.point_length_mm"),
          .cad_file = c.path("needle.cad_file"),
          .cad_facet_um = c.real("needle.cad_facet_um"),
          .cad_facet_deg = c.real("needle.cad_facet_deg")};
}

TissueCubeSpec parse_tissue_cube_spec(const Case& c) {
  return {.cube_edge_mm = c.real("tissue.cube_edge_mm"),
          .core_width_mm = c.real("tissue.core_width_mm"),
          .core_element_mm = c.real("tissue.core_element_mm"),
          .outer_element_mm = c.real("tissue.outer_element_mm")};
}

}  // namespace needlefem
