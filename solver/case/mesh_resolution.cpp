#include "case/mesh_resolution.hpp"

#include <tuple>

#include <fmt/format.h>

#include "case/specs/mesh_spec.hpp"

namespace needlefem {

namespace {

// The setting of docs/accuracy.md §3-4 (the paper's mesh).
constexpr double kConvergedCoreElementMm = 0.4;
constexpr double kConvergedOuterElementMm = 2.0;
constexpr long kConvergedOrder = 2;

}  // namespace

std::vector<std::string> coarser_than_converged(const MeshSpec& mesh) {
  if (!generates_brain_tip_scene(mesh)) return {};
  std::vector<std::string> coarser;
  for (const auto& [key, size, limit] :
       {std::tuple{"tissue.core_element_mm", mesh.tissue.core_element_mm, kConvergedCoreElementMm},
        std::tuple{"tissue.outer_element_mm", mesh.tissue.outer_element_mm, kConvergedOuterElementMm}})
    if (size > limit) coarser.push_back(fmt::format("{} = {:g} mm > {:g} mm", key, size, limit));
  if (mesh.order < kConvergedOrder) coarser.push_back(fmt::format("mesh.order = {} < {}", mesh.order, kConvergedOrder));
  return coarser;
}

nlohmann::json mesh_resolution_json(const MeshSpec& mesh) {
  if (!generates_brain_tip_scene(mesh)) return nullptr;
  const auto coarser = coarser_than_converged(mesh);
  return {{"as_converged", coarser.empty()},
          {"coarser", coarser},
          {"note", fmt::format("the convergence study (docs/accuracy.md section 4) found tissue.core_element_mm <= {:g} "
                               "mm, tissue.outer_element_mm <= {:g} mm and mesh.order {} adequate at any "
                               "mesh.refinement_level; on a coarser mesh the verdict may change with the mesh",
                               kConvergedCoreElementMm, kConvergedOuterElementMm, kConvergedOrder)}};
}

std::string coarse_mesh_warning(const std::vector<std::string>& coarser) {
  if (coarser.empty()) return "";
  return fmt::format("mesh coarser than the converged setting ({}): the verdict may change on a finer mesh "
                     "(docs/accuracy.md section 4)", fmt::join(coarser, ", "));
}

}  // namespace needlefem
