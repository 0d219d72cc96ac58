// Whether a case's mesh is as fine as the setting the convergence study found adequate.
//
// docs/accuracy.md §3-4: the brain-tip scene at tissue.core_element_mm = 0.4 mm inside the core,
// tissue.outer_element_mm = 2 mm outside, quadratic tets (mesh.order 2), graded to the needle's
// edges, gives at mesh.refinement_level 0 critical-distance values within their GCI band
// (0.46-4.8 %) of levels 1 and 2, every limit's verdict decided; so any refinement level of that
// setting is adequate. Nothing coarser was shown to give the same verdicts: the safety map of
// paper 001's quick sweep (1 mm core, 3 mm outside) showed five safe designs where the 0.4 mm
// grid's showed one (issue #29). A run or sweep point on a coarser mesh says so beside its verdict
// (summary.json "mesh_resolution", the verdict lines of run and converge, the sweep's warning
// and coarse_mesh column).
// Only the generated brain-tip mesh was studied: the block scene and user meshes (scene.mesh_file)
// are not judged.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace needlefem {

struct MeshSpec;

// Each way the mesh is coarser than the studied setting, as "KEY = VALUE UNIT > LIMIT UNIT"
// ("tissue.core_element_mm = 1 mm > 0.4 mm"); empty when it is not, or when the rule does not apply.
std::vector<std::string> coarser_than_converged(const MeshSpec& mesh);

// summary.json's "mesh_resolution": {"as_converged": bool, "coarser": [...], "note": text};
// null when the rule does not apply.
nlohmann::json mesh_resolution_json(const MeshSpec& mesh);

// The warning that goes beside a verdict on a coarser mesh, e.g. "mesh coarser than the converged
// setting (tissue.core_element_mm = 1 mm > 0.4 mm): the verdict may change on a finer mesh
// (docs/accuracy.md §4)".
std::string coarse_mesh_warning(const std::vector<std::string>& coarser);

}  // namespace needlefem
