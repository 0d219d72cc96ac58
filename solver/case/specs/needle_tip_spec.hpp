// The needle tip's shape keys ([needle]), parsed: the input of needle_tip_from_spec
// (geometry/needle_tip.hpp), of the CAD tip's import and triangulation (mesh/cad_tip.hpp) and of
// the commands that need the tip's dimensions (steer, prbm-check, force-trajectory). Also the
// tissue cube of the brain-tip scene that the tip must fit (its rules: geometry/needle_tip.hpp,
// mesh/cad_tip.hpp). Values are in the units their keys name; the geometry converts them to SI.
#pragma once

#include <filesystem>
#include <string>

namespace needlefem {

class Case;

enum class NeedleKind { bevel, compliant, cad };

struct NeedleTipSpec {
  std::string origin;  // the case's, for the CaseErrors of the tip's rules
  NeedleKind kind;
  double radius_mm;  // shaft and head
  // Bevel tip.
  double bevel_deg;
  double fillet_mm;
  double shaft_mm;  // behind the bevel heel, or behind the compliant tip's neck
  // Compliant tip.
  double head_length_mm;
  double neck_length_mm;
  double neck_diameter_mm;
  double point_length_mm;
  // CAD tip.
  std::filesystem::path cad_file;  // resolved against the case's folder; empty: none
  double cad_facet_um;             // the contact needle's largest facet
  double cad_facet_deg;            // the angle a facet spans on a curved face
};

NeedleTipSpec parse_needle_tip_spec(const Case& c);

// The brain-tip scene's tissue cube and its refined core (tissue.*), which the tip must fit, with
// their element sizes (the mesh stage's: case/specs/mesh_spec.hpp holds it).
struct TissueCubeSpec {
  double cube_edge_mm;
  double core_width_mm;
  double core_element_mm;
  double outer_element_mm;
};

TissueCubeSpec parse_tissue_cube_spec(const Case& c);

}  // namespace needlefem
