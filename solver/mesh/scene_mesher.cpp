// Scene construction (all CAD in millimetres, as the .msh is):
//  brain-tip: box [-E/2, E/2]^2 x [0, E], a square core [-c/2, c/2]^2 x [0, E] and the needle tip
//  are fragmented together so that every interface is conforming; the tip sits with its rear
//  face on z = 0 and points into +z. Element size: a Box field, core_element inside the core,
//  outer_element outside (paper 001: 0.4 / 2 mm), optionally refined by curvature, and graded
//  down towards the needle (mesh/size_field.hpp).
//  block: box [0, Lx] x [0, Ly] x [0, Lz] with uniform element size.
// mesh.refinement_level L halves every size near the needle (and the block's size) per level.
#include "mesh/scene_mesher.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <vector>

#include <fmt/core.h>
#include <gmsh.h>

#include "case/case_error.hpp"
#include "case/specs/mesh_spec.hpp"
#include "geometry/needle_tip.hpp"
#include "mesh/cad_tip.hpp"
#include "mesh/gmsh_session.hpp"
#include "mesh/size_field.hpp"
#include "wall_clock/seconds_since.hpp"

namespace needlefem {

namespace {

namespace occ = gmsh::model::occ;
constexpr double kPi = 3.14159265358979323846;
constexpr double kMmPerM = 1e3;

using DimTags = gmsh::vectorpair;

// Side profile of the bevel tip in the plane y = y0, as a closed OCC face (mm). The profile is
// padded beyond the cylinder (by `pad`) on the sides where it does not shape the needle, so the
// later intersection never meets coincident faces.
int bevel_profile_face(const BevelTip& tip, double y0, double pad) {
  const double r = tip.radius * kMmPerM, shaft = tip.shaft * kMmPerM;
  std::vector<int> points{occ::addPoint(-r - pad, y0, -pad), occ::addPoint(r + pad, y0, -pad),
                          occ::addPoint(r + pad, y0, shaft), occ::addPoint(r, y0, shaft)};
  std::vector<int> curves;
  auto line_to = [&](int next) {
    curves.push_back(occ::addLine(points.back(), next));
    points.push_back(next);
  };
  for (std::size_t i = 1; i < points.size(); ++i) curves.push_back(occ::addLine(points[i - 1], points[i]));
  if (tip.fillet > 0) {
    const double xc = tip.fillet_centre_x() * kMmPerM, zc = tip.fillet_centre_z() * kMmPerM;
    const double tau = tip.fillet * kMmPerM, a = tip.bevel_rad;
    const int tangent_bevel = occ::addPoint(xc + tau * std::cos(a), y0, zc + tau * std::sin(a));
    line_to(tangent_bevel);
    const int centre = occ::addPoint(xc, y0, zc);
    const int tangent_generator = occ::addPoint(-r, y0, zc);
    curves.push_back(occ::addCircleArc(tangent_bevel, centre, tangent_generator));
    points.push_back(tangent_generator);
    line_to(occ::addPoint(-r - pad, y0, zc));
  } else {
    const double z_tip = tip.length() * kMmPerM;
    line_to(occ::addPoint(-r, y0, z_tip));
    line_to(occ::addPoint(-r - pad, y0, z_tip));
  }
  curves.push_back(occ::addLine(points.back(), points.front()));
  return occ::addPlaneSurface({occ::addCurveLoop(curves)});
}

int add_bevel_tip(const BevelTip& tip) {
  const double r = tip.radius * kMmPerM, shaft = tip.shaft * kMmPerM;
  DimTags out;
  std::vector<DimTags> out_map;
  if (tip.rounded()) {
    const int cylinder = occ::addCylinder(0, 0, 0, 0, 0, shaft, r);
    const int hemisphere = occ::addSphere(0, 0, shaft, r, -1, 0.0, kPi / 2, 2 * kPi);
    occ::fuse({{3, cylinder}}, {{3, hemisphere}}, out, out_map);
  } else {
    const double length = tip.length() * kMmPerM, pad = 0.1 * r;
    const int cylinder = occ::addCylinder(0, 0, 0, 0, 0, length + pad, r);
    const int profile = bevel_profile_face(tip, -r - pad, pad);
    DimTags prism;
    occ::extrude({{2, profile}}, 0, 2 * (r + pad), 0, prism);
    auto volume = std::find_if(prism.begin(), prism.end(), [](const auto& dt) { return dt.first == 3; });
    occ::intersect({{3, cylinder}}, {*volume}, out, out_map);
  }
  if (out.size() != 1 || out[0].first != 3) throw std::runtime_error("gmsh: the needle tip is not a single solid");
  return out[0].second;
}

}  // namespace

int add_compliant_tip(const CompliantTip& tip) {
  const double r = tip.radius * kMmPerM, s = tip.shaft * kMmPerM, l = tip.neck_length * kMmPerM;
  const double d = tip.neck_diameter * kMmPerM, head = tip.head_length * kMmPerM;
  const double point = tip.point_length * kMmPerM;
  DimTags parts{{3, occ::addCylinder(0, 0, 0, 0, 0, s, r)}, {3, occ::addCylinder(0, 0, s, 0, 0, l, d / 2)},
                {3, occ::addCylinder(0, 0, s + l, 0, 0, head - point, r)}};
  if (point > 0) parts.push_back({3, occ::addCone(0, 0, s + l + head - point, 0, 0, point, r, 0)});
  DimTags out;
  std::vector<DimTags> out_map;
  occ::fuse({parts.front()}, DimTags(parts.begin() + 1, parts.end()), out, out_map);
  if (out.size() != 1) throw std::runtime_error("gmsh: the compliant tip is not a single solid");
  return out[0].second;
}

int add_needle_tip(const NeedleTip& tip, const NeedleTipSpec& spec, const TissueCubeSpec& tissue) {
  const int needle = tip.kind == NeedleTip::Kind::Bevel       ? add_bevel_tip(tip.bevel)
                     : tip.kind == NeedleTip::Kind::Compliant ? add_compliant_tip(tip.compliant)
                                                              : import_cad_tip(spec, tissue);
  occ::synchronize();
  return needle;
}

namespace {

std::set<int> tags_of(const DimTags& dim_tags) {
  std::set<int> tags;
  for (const auto& [dim, tag] : dim_tags)
    if (dim == 3) tags.insert(tag);
  return tags;
}

std::set<int> minus(const std::set<int>& a, const std::set<int>& b) {
  std::set<int> out;
  std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::inserter(out, out.end()));
  return out;
}

std::set<int> united(std::set<int> a, const std::set<int>& b) {
  a.insert(b.begin(), b.end());
  return a;
}

void add_physical(int dim, const std::vector<int>& tags, const std::string& name) {
  if (tags.empty()) return;
  gmsh::model::setPhysicalName(dim, gmsh::model::addPhysicalGroup(dim, tags), name);
}

// Name of the outer box face a surface lies on ("x_min", ...), or "" if none.
std::string box_face_of(int surface, const std::array<double, 3>& lo, const std::array<double, 3>& hi) {
  double b[6];
  gmsh::model::getBoundingBox(2, surface, b[0], b[1], b[2], b[3], b[4], b[5]);
  const double tol = 1e-6 * std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  static const char* names[3][2] = {{"x_min", "x_max"}, {"y_min", "y_max"}, {"z_min", "z_max"}};
  for (int axis = 0; axis < 3; ++axis) {
    if (std::abs(b[axis] - lo[axis]) < tol && std::abs(b[axis + 3] - lo[axis]) < tol) return names[axis][0];
    if (std::abs(b[axis] - hi[axis]) < tol && std::abs(b[axis + 3] - hi[axis]) < tol) return names[axis][1];
  }
  return "";
}

std::vector<int> surfaces_of(const std::set<int>& volumes) {
  DimTags boundary;
  DimTags dim_tags;
  for (int v : volumes) dim_tags.push_back({3, v});
  gmsh::model::getBoundary(dim_tags, boundary, /*combined=*/false, /*oriented=*/false);
  std::set<int> unique;
  for (const auto& [dim, tag] : boundary) unique.insert(std::abs(tag));
  return {unique.begin(), unique.end()};
}

void set_mesh_options(const MeshSpec& spec) {
  gmsh::option::setNumber("Mesh.RandomSeed", static_cast<double>(spec.seed));
  gmsh::option::setNumber("Mesh.ElementOrder", static_cast<double>(spec.order));
  gmsh::option::setNumber("Mesh.SecondOrderLinear", 0);  // mid-side nodes on the curved CAD faces
  // The high-order optimiser keeps gmsh's six element layers around each element it curves.
  // One layer meshes faster (docs/speed.md), but it moved the tip maxima of thin needles (r = 0.32 mm, 10 deg, 0.15 mm: log strain 0.370 -> 0.422, von Mises 6738 ->
  // 5613 Pa; repeated meshings with six layers agree within 1 %).
  gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
  gmsh::option::setNumber("Mesh.Binary", 1);
  gmsh::option::setNumber("Mesh.SaveAll", 0);
}

}  // namespace

// Curves the second-order mesh without inverting it. gmsh's direct optimiser is fast but on
// some fillets misses its scaled-Jacobian target and leaves inverted tets (measured: 2 tets for
// r = 0.83 mm, 20 deg, 0.25 mm). On a miss the mesh is generated again and optimised with one,
// then two more element layers around each bad element (Mesh.HighOrderNumLayers, 6 by default):
// on that tip 7 layers succeed at about half the cost of the elastic smoothing that follows if
// they miss too (HighOrderElastic on the fresh mesh, then HighOrder: the smoothing fixes such
// tets only on a fresh mesh; docs/speed.md). More layers are not always better: 10 and 12 missed
// on that tip. Returns what was done; the element check of the model stage has the last word.
std::string optimise_high_order() {
  constexpr int kMoreLayers = 2;
  double layers = 0.0;
  gmsh::option::getNumber("Mesh.HighOrderNumLayers", layers);
  std::string misses, done;
  for (int extra = 0; extra <= kMoreLayers && done.empty(); ++extra) {
    if (extra > 0) {
      gmsh::model::mesh::clear();
      gmsh::model::mesh::generate(3);
      gmsh::option::setNumber("Mesh.HighOrderNumLayers", layers + extra);
    }
    try {
      gmsh::model::mesh::optimize("HighOrder");
      done = extra == 0 ? "HighOrder"
                        : fmt::format("HighOrder missed its target with {} layers ({}); regenerated, HighOrder with {}",
                                      layers + extra - 1, misses, layers + extra);
    } catch (const std::string& miss) {
      misses += (misses.empty() ? "" : "; ") + miss;
    }
  }
  gmsh::option::setNumber("Mesh.HighOrderNumLayers", layers);
  if (!done.empty()) return done;
  gmsh::model::mesh::clear();
  gmsh::model::mesh::generate(3);
  gmsh::model::mesh::optimize("HighOrderElastic");
  try {
    gmsh::model::mesh::optimize("HighOrder");
    return "HighOrder missed its target (" + misses + "); regenerated, HighOrderElastic + HighOrder";
  } catch (const std::string& last_miss) {
    return "HighOrder missed its target also after HighOrderElastic (" + misses + "; " + last_miss + ")";
  }
}

// Last resort for the tets the optimiser leaves inverted (measured: 1 tet of 66k on the
// r = 1.25 mm rounded tip at refinement level 1, after every pass above): each edge of such a tet
// is made straight, its mid-edge node moved to the midpoint of its end vertices. The tet then has
// the constant Jacobian of its linear tet, positive for every tet of gmsh's linear mesh; the
// neighbours that share a straightened edge are checked again. The geometric cost is local: a
// straightened boundary edge leaves the curved surface by its sagitta, h²/(8R) (0.3 µm for a
// 0.05 mm edge on a 1.25 mm radius). Checked where the model stage checks (model/mesh_quality:
// the nodes and a quadrature rule), with gmsh's own sample points. Returns the count straightened.
std::size_t straighten_inverted_tets() {
  constexpr int kTet10 = 11;
  std::string name;
  int dim = 0, order = 0, node_count = 0, vertex_count = 0;
  std::vector<double> samples, gauss, weights;
  gmsh::model::mesh::getElementProperties(kTet10, name, dim, order, node_count, samples, vertex_count);
  std::vector<std::array<int, 3>> edges;  // mid-edge node, end vertices (local indices)
  for (int mid = vertex_count; mid < node_count; ++mid)
    for (int a = 0; a < vertex_count; ++a)
      for (int b = a + 1; b < vertex_count; ++b) {
        double distance = 0;
        for (int k = 0; k < 3; ++k)
          distance += std::abs(samples[3 * mid + k] - 0.5 * (samples[3 * a + k] + samples[3 * b + k]));
        if (distance < 1e-12) edges.push_back({mid, a, b});
      }
  gmsh::model::mesh::getIntegrationPoints(kTet10, "Gauss6", gauss, weights);
  samples.insert(samples.end(), gauss.begin(), gauss.end());
  const std::size_t per_tet = samples.size() / 3;

  std::set<std::size_t> straightened;
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<std::size_t> tags, nodes;
    std::vector<double> jacobians, determinants, coordinates;
    gmsh::model::mesh::getElementsByType(kTet10, tags, nodes);
    gmsh::model::mesh::getJacobians(kTet10, samples, jacobians, determinants, coordinates);
    for (std::size_t e = 0; e < tags.size(); ++e) {
      const auto first = determinants.begin() + static_cast<std::ptrdiff_t>(e * per_tet);
      if (*std::min_element(first, first + static_cast<std::ptrdiff_t>(per_tet)) > 0 || straightened.count(tags[e]))
        continue;
      const std::size_t* tet = &nodes[e * static_cast<std::size_t>(node_count)];
      for (const auto& [mid, a, b] : edges) {
        std::vector<double> xa, xb, parametric;
        gmsh::model::mesh::getNode(tet[a], xa, parametric);
        gmsh::model::mesh::getNode(tet[b], xb, parametric);
        gmsh::model::mesh::setNode(tet[mid], {0.5 * (xa[0] + xb[0]), 0.5 * (xa[1] + xb[1]), 0.5 * (xa[2] + xb[2])}, {});
      }
      straightened.insert(tags[e]);
      changed = true;
    }
  }
  return straightened.size();
}

namespace {

std::string generate_and_write(const MeshSpec& spec, const std::filesystem::path& msh_file,
                               const std::function<void()>& measure = {}) {
  gmsh::model::mesh::generate(3);
  std::string optimisation = "none";
  if (spec.order == 2 && spec.optimize_high_order) {
    optimisation = optimise_high_order();
    if (const std::size_t straightened = straighten_inverted_tets())
      optimisation += fmt::format("; {} tets still inverted made straight-edged", straightened);
  }
  if (measure) measure();
  std::filesystem::create_directories(msh_file.parent_path().empty() ? "." : msh_file.parent_path());
  // Write beside and rename, so an interrupted run never leaves a truncated .msh behind.
  const auto partial = msh_file.string() + ".partial.msh";
  gmsh::write(partial);
  std::filesystem::rename(partial, msh_file);
  return optimisation;
}

// The brain-tip scene's physical groups: surfaces cavity, entry, the cube's faces and "fixed",
// needle_rear (and needle_surface with the needle meshed); volumes tissue_core, tissue_outer (and
// needle). Returns the surface groups.
std::map<std::string, std::vector<int>> add_scene_groups(bool mesh_needle, double edge, const std::set<int>& core_volumes,
                                                         const std::set<int>& outer_volumes,
                                                         const std::set<int>& needle_volumes) {
  const std::vector<int> needle_surfaces = surfaces_of(needle_volumes);
  std::map<std::string, std::vector<int>> groups;
  const std::array<double, 3> lo{-edge / 2, -edge / 2, 0}, hi{edge / 2, edge / 2, edge};
  for (int s : surfaces_of(united(core_volumes, outer_volumes))) {
    const bool on_needle = std::count(needle_surfaces.begin(), needle_surfaces.end(), s) > 0;
    const std::string face = box_face_of(s, lo, hi);
    if (on_needle) groups["cavity"].push_back(s);
    else if (face == "z_min") groups["entry"].push_back(s);
    else if (!face.empty()) {
      groups[face].push_back(s);
      groups["fixed"].push_back(s);
    }
  }
  for (int s : needle_surfaces)
    if (box_face_of(s, lo, hi) == "z_min") groups["needle_rear"].push_back(s);
  if (mesh_needle) groups["needle_surface"] = needle_surfaces;
  if (groups["cavity"].empty() || groups["entry"].empty() || groups["needle_rear"].empty())
    throw std::runtime_error("gmsh: could not identify the cavity, entry and needle-rear surfaces");
  for (const auto& [name, tags] : groups) add_physical(2, tags, name);
  add_physical(3, {core_volumes.begin(), core_volumes.end()}, "tissue_core");
  add_physical(3, {outer_volumes.begin(), outer_volumes.end()}, "tissue_outer");
  if (mesh_needle) add_physical(3, {needle_volumes.begin(), needle_volumes.end()}, "needle");

  return groups;
}

SceneMeshInfo mesh_brain_tip(const MeshSpec& spec, const std::filesystem::path& msh_file) {
  const NeedleTip tip = needle_tip_from_spec(spec.needle_tip);
  const double edge = spec.tissue.cube_edge_mm, core = spec.tissue.core_width_mm;
  SceneMeshInfo info;
  info.grading.refinement_level = static_cast<int>(spec.refinement_level);
  info.needle_description = tip.describe();
  info.needle_analytic_volume_m3 = tip.analytic_volume();
  info.domain_volume_m3 = std::pow(edge / kMmPerM, 3);

  const int needle = add_needle_tip(tip, spec.needle_tip, spec.tissue);
  double cad_volume_mm3 = 0;
  occ::getMass(3, needle, cad_volume_mm3);
  info.needle_cad_volume_m3 = cad_volume_mm3 / std::pow(kMmPerM, 3);
  // A CAD tip has no independent volume: its own is the reference.
  if (tip.kind == NeedleTip::Kind::Cad) info.needle_analytic_volume_m3 = info.needle_cad_volume_m3;
  if (!spec.needle_export_file.empty()) gmsh::write(spec.needle_export_file.string());

  const int cube = occ::addBox(-edge / 2, -edge / 2, 0, edge, edge, edge);
  const int core_box = occ::addBox(-core / 2, -core / 2, 0, core, core, edge);
  DimTags pieces;
  std::vector<DimTags> piece_map;  // per input: cube, core, needle
  occ::fragment({{3, cube}}, {{3, core_box}, {3, needle}}, pieces, piece_map);
  const std::set<int> needle_volumes = tags_of(piece_map[2]);
  const std::set<int> core_volumes = minus(tags_of(piece_map[1]), needle_volumes);
  const std::set<int> outer_volumes = minus(tags_of(piece_map[0]), tags_of(piece_map[1]));
  occ::synchronize();

  auto groups = add_scene_groups(spec.needle_mesh_volume, edge, core_volumes, outer_volumes, needle_volumes);
  std::vector<int> edges;  // the cavity's sharp edges
  const int size_field = add_size_field(spec, tip, edge, core, groups["cavity"], info.grading, edges);
  gmsh::model::mesh::field::setAsBackgroundMesh(size_field);
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", static_cast<double>(spec.curvature_elements));
  set_mesh_options(spec);
  info.high_order_optimisation = generate_and_write(spec, msh_file, [&] {
    DimTags edge_entities, cavity_entities;
    for (int e : edges) edge_entities.push_back({1, e});
    for (int s : groups["cavity"]) cavity_entities.push_back({2, s});
    const std::set<int> tissue_volumes = united(core_volumes, outer_volumes);
    info.grading.edge_elements = element_sizes_touching(tissue_volumes, edge_entities);
    info.grading.cavity_elements = element_sizes_touching(tissue_volumes, cavity_entities);
  });
  return info;
}

SceneMeshInfo mesh_block(const MeshSpec& spec, const std::filesystem::path& msh_file) {
  const std::array<double, 3>& size = spec.block_size_mm;
  const int box = occ::addBox(0, 0, 0, size[0], size[1], size[2]);
  occ::synchronize();
  const std::array<double, 3> lo{0, 0, 0}, hi{size[0], size[1], size[2]};
  for (int s : surfaces_of({box})) add_physical(2, {s}, box_face_of(s, lo, hi));
  add_physical(3, {box}, "tissue");
  const double h = spec.block_element_mm * refinement_size_factor(spec);
  gmsh::option::setNumber("Mesh.MeshSizeMin", h);
  gmsh::option::setNumber("Mesh.MeshSizeMax", h);
  set_mesh_options(spec);
  SceneMeshInfo info;
  info.grading.refinement_level = static_cast<int>(spec.refinement_level);
  info.high_order_optimisation = generate_and_write(spec, msh_file);
  info.domain_volume_m3 = size[0] * size[1] * size[2] / std::pow(kMmPerM, 3);
  return info;
}

// The mesh scene's user geometry (a gmsh .geo in millimetres, with its physical groups and
// element sizes), meshed at mesh.order with every size scaled by 2^-mesh.refinement_level.
SceneMeshInfo mesh_user_geometry(const MeshSpec& spec, const std::filesystem::path& msh_file) {
  const std::filesystem::path& geo = spec.scene_mesh_file;
  try {
    gmsh::open(geo.string());
  } catch (const std::string& message) {
    throw case_error(spec.origin, "scene.mesh_file", fmt::format("gmsh cannot read '{}': {}", geo.string(), message));
  }
  gmsh::option::setNumber("Mesh.MeshSizeFactor", refinement_size_factor(spec));
  set_mesh_options(spec);
  SceneMeshInfo info;
  info.grading.refinement_level = static_cast<int>(spec.refinement_level);
  info.high_order_optimisation = generate_and_write(spec, msh_file);
  return info;
}

}  // namespace

SceneMeshInfo generate_scene_mesh(const MeshSpec& spec, const std::filesystem::path& msh_file, std::FILE* progress) {
  if (generates_brain_tip_scene(spec)) require_valid_brain_tip_scene(spec.needle_tip, spec.tissue);
  if (progress) {
    fmt::print(progress, "mesh: meshing the {} scene with gmsh (mesh.refinement_level {})\n",
               scene_kind_name(spec.scene_kind), spec.refinement_level);
    std::fflush(progress);
  }
  const auto start = WallClock::now();
  SceneMeshInfo info;
  GmshSession session("needlefem");
  GmshSession::guarded([&] {
    info = spec.scene_kind == SceneKind::block  ? mesh_block(spec, msh_file)
           : spec.scene_kind == SceneKind::mesh ? mesh_user_geometry(spec, msh_file)
                                                : mesh_brain_tip(spec, msh_file);
  });
  info.seconds = seconds_since(start);
  return info;
}

}  // namespace needlefem
