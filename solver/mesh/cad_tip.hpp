// A needle tip from a CAD file (needle.kind = "cad", needle.cad_file): a STEP (.step/.stp),
// BREP (.brep) or gmsh geometry (.geo, OpenCASCADE kernel) in millimetres, axis along +z, the
// rear face of the tip a plane face on z = 0 (flush with the tissue's entry face), tip towards +z.
// The scene mesher carves the cavity from it (scene_mesher.cpp, the same fragment as the bevel
// tip); the contact needle is its surface triangulated here (physics/contact/cad_needle.hpp).
//
// Validity rules, each reported as one line naming the file and the key needle.cad_file:
//   one closed solid      the file must hold exactly one volume (a shell or open faces have none);
//   rear face flush       the solid starts at z = 0 and has a planar face on z = 0;
//   fits the core         |x|, |y| <= half of tissue.core_width_mm (strictly inside);
//   fits the cube         one core element of tissue ahead of the foremost point.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "case/specs/needle_tip_spec.hpp"

namespace needlefem {

// Loads the CAD tip of `spec` (parse_needle_tip_spec) into the current gmsh model (inside a
// GmshSession), checks the rules against `tissue` and returns the tip's volume tag
// (synchronised). Throws CaseError for a broken rule or a file gmsh cannot read.
int import_cad_tip(const NeedleTipSpec& spec, const TissueCubeSpec& tissue);

struct CadTipTriangulation {
  std::vector<std::array<double, 3>> vertices;  // m
  std::vector<std::array<int, 3>> triangles;    // vertex indices, as gmsh orients them
  double cad_volume_m3 = 0.0;                   // from the OpenCASCADE model
};

// The tip's boundary triangulated with facets spanning at most needle.cad_facet_deg on curved
// faces and edges, the sizes extended from the edges into the faces, at most needle.cad_facet_um
// (own gmsh session).
CadTipTriangulation triangulate_cad_tip(const NeedleTipSpec& spec, const TissueCubeSpec& tissue);

}  // namespace needlefem
