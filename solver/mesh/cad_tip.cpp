// Rules and sizes: cad_tip.hpp.
#include "mesh/cad_tip.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include <fmt/core.h>
#include <gmsh.h>

#include "case/case_error.hpp"
#include "mesh/gmsh_session.hpp"

namespace needlefem {

namespace {

namespace occ = gmsh::model::occ;
constexpr double kMmPerM = 1e3;
// Coordinates this close (mm) count as on a plane: above OpenCASCADE's default tolerance
// (1e-7 mm), which also pads its bounding boxes.
constexpr double kFlushMm = 1e-4;
constexpr int kTriangle3 = 2;  // gmsh element type

struct Box {
  double x0, y0, z0, x1, y1, z1;
};

Box bounding_box(int dim, int tag) {
  Box b{};
  gmsh::model::getBoundingBox(dim, tag, b.x0, b.y0, b.z0, b.x1, b.y1, b.z1);
  return b;
}

// A broken rule of the CAD tip, reported under needle.cad_file.
CaseError cad_file_error(const NeedleTipSpec& spec, const std::string& reason) {
  return case_error(spec.origin, "needle.cad_file", reason);
}

}  // namespace

int import_cad_tip(const NeedleTipSpec& spec, const TissueCubeSpec& tissue) {
  const std::filesystem::path& file = spec.cad_file;
  const std::string name = file.string();
  if (name.empty()) throw cad_file_error(spec, "needle.kind = \"cad\" needs a CAD file (STEP, BREP or .geo)");
  if (!std::filesystem::is_regular_file(file)) throw cad_file_error(spec, fmt::format("'{}': no such file", name));
  gmsh::vectorpair before;
  gmsh::model::getEntities(before, 3);
  try {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), ::tolower);
    if (extension == ".geo") {
      gmsh::merge(name);
    } else {
      gmsh::vectorpair imported;
      occ::importShapes(name, imported, /*highestDimOnly=*/true);
    }
    occ::synchronize();
  } catch (const std::string& message) {
    throw cad_file_error(spec, fmt::format("'{}': gmsh cannot read it: {}", name, message));
  }
  gmsh::vectorpair after;
  gmsh::model::getEntities(after, 3);
  std::vector<int> volumes;
  for (const auto& [dim, tag] : after)
    if (std::find(before.begin(), before.end(), std::make_pair(dim, tag)) == before.end()) volumes.push_back(tag);
  if (volumes.size() != 1)
    throw cad_file_error(spec, fmt::format("'{}' holds {} solids: the tip must be one closed solid{}", name,
                                           volumes.size(),
                                           volumes.empty() ? " (open faces or a shell are not closed)" : ""));
  const int tip = volumes.front();
  const Box b = bounding_box(3, tip);
  const double edge = tissue.cube_edge_mm, core = tissue.core_width_mm;
  if (std::abs(b.z0) > kFlushMm)
    throw cad_file_error(spec, fmt::format("'{}': the rear face is not flush with the entry face: the solid "
                                           "starts at z = {:.4g} mm, not 0", name, b.z0));
  gmsh::vectorpair faces;
  gmsh::model::getBoundary({{3, tip}}, faces, false, false);
  const bool rear = std::any_of(faces.begin(), faces.end(), [](const auto& f) {
    const Box s = bounding_box(2, std::abs(f.second));
    return std::abs(s.z0) <= kFlushMm && std::abs(s.z1) <= kFlushMm;
  });
  if (!rear)
    throw cad_file_error(spec, fmt::format("'{}': no planar rear face on z = 0 (flush with the entry face)", name));
  const double reach = std::max({std::abs(b.x0), std::abs(b.x1), std::abs(b.y0), std::abs(b.y1)});
  if (reach >= core / 2)
    throw cad_file_error(spec, fmt::format("'{}': the tip does not fit the core: it reaches {:.4g} mm from the "
                                           "axis, half of tissue.core_width_mm is {:.4g} mm", name, reach, core / 2));
  if (b.z1 + tissue.core_element_mm > edge)
    throw cad_file_error(spec, fmt::format("'{}': the tip does not fit the cube: it is {:.4g} mm long; with one "
                                           "core element ({:.4g} mm) ahead of it it does not fit the {:.4g} mm cube",
                                           name, b.z1, tissue.core_element_mm, edge));
  return tip;
}

CadTipTriangulation triangulate_cad_tip(const NeedleTipSpec& spec, const TissueCubeSpec& tissue) {
  CadTipTriangulation out;
  GmshSession session("needlefem-cad-tip");
  GmshSession::guarded([&] {
    const int tip = import_cad_tip(spec, tissue);
    double volume_mm3 = 0;
    occ::getMass(3, tip, volume_mm3);
    out.cad_volume_m3 = volume_mm3 / std::pow(kMmPerM, 3);
    const double facet = spec.cad_facet_um / kMmPerM;
    gmsh::option::setNumber("Mesh.MeshSizeMax", facet);
    gmsh::option::setNumber("Mesh.MeshSizeMin", 0.0);
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", std::ceil(360.0 / spec.cad_facet_deg));
    // Sizes extend from the boundary curves into the faces: where a flat face's facets meet a curved
    // edge, the trimmed core's edge (cad_needle.hpp) is their chord, off the curved edge by s²/(8R);
    // a run with 50 µm facets inside the bevel face (sizes not extended) stalled at t = 0.08 s on
    // the paper's tip at the default mesh.
    // Delaunay: the fastest of gmsh's surface algorithms on the paper tip's 77k facets
    // (docs/speed.md).
    gmsh::option::setNumber("Mesh.Algorithm", 5);
    gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
    gmsh::option::setNumber("Mesh.ElementOrder", 1);
    gmsh::model::mesh::generate(2);
    std::vector<std::size_t> tags;
    std::vector<double> xyz, parametric;
    gmsh::model::mesh::getNodes(tags, xyz, parametric, -1, -1, false, false);
    std::map<std::size_t, int> index;
    for (std::size_t i = 0; i < tags.size(); ++i) {
      index[tags[i]] = static_cast<int>(i);
      out.vertices.push_back({xyz[3 * i] / kMmPerM, xyz[3 * i + 1] / kMmPerM, xyz[3 * i + 2] / kMmPerM});
    }
    gmsh::vectorpair faces;
    gmsh::model::getBoundary({{3, tip}}, faces, false, false);
    for (const auto& [dim, face] : faces) {
      std::vector<std::size_t> elements, nodes;
      gmsh::model::mesh::getElementsByType(kTriangle3, elements, nodes, std::abs(face));
      for (std::size_t e = 0; e < elements.size(); ++e)
        out.triangles.push_back({index.at(nodes[3 * e]), index.at(nodes[3 * e + 1]), index.at(nodes[3 * e + 2])});
    }
  });
  return out;
}

}  // namespace needlefem
