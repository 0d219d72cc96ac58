// Equations: needle_contact.hpp.
#include "physics/contact/needle_contact.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <limits>
#include <map>
#include <utility>

#include <fmt/format.h>

#include "case/case_error.hpp"
#include "geometry/needle_motion.hpp"
#include "geometry/needle_tip.hpp"
#include "mesh/cad_tip.hpp"
#include "physics/contact/cad_needle.hpp"

namespace needlefem::contact {

namespace {

const std::string kCavity = "cavity";
constexpr double kMPerUm = 1e-6;

// Shape-function values at a triangle's centroid: TRI3 1/3 each; TRI6 corners -1/9, edges 4/9.
double centroid_weight(int nodes_per_face, int a) {
  if (nodes_per_face == 3) return 1.0 / 3.0;
  return a < 3 ? -1.0 / 9.0 : 4.0 / 9.0;
}

// A user's mesh (scene.mesh_file) must have been meshed from the needle the needle.* keys describe:
// otherwise the run would press one shape into the cavity of another, without a word. Its
// cavity's vertices lie on the meshed needle's surface (any mesher puts them there; mid-edge
// nodes may sit on chords), so they are checked against the sharp needle (the rounding of the
// contact needle's edges is not meshed) at t = 0; a vertex off it by more than a thousandth of
// the radius stops the run, naming the largest offset and where.
void require_cavity_on_needle(const MeshSpec& spec, const TetMesh& mesh, const RigidObstacle& sharp) {
  constexpr double kMmPerM = 1e3;
  const auto cavity = mesh.surface_faces.find(kCavity);
  if (cavity == mesh.surface_faces.end()) return;  // NeedleContact names the missing group
  const auto face_nodes = static_cast<std::size_t>(mesh.nodes_per_face());
  const auto for_each_vertex = [&](auto&& visit) {
    for (std::size_t f = 0; f < cavity->second.size(); f += face_nodes)
      for (std::size_t a = 0; a < 3; ++a) visit(mesh.nodes[cavity->second[f + a]]);
  };
  double radius = 0.0;  // of the cavity: the needle's
  for_each_vertex([&](const Point3& X) { radius = std::max(radius, std::hypot(X[0], X[1])); });
  const double tolerance = 1e-3 * radius;
  double largest = 0.0;
  Point3 where{};
  for_each_vertex([&](const Point3& X) {
    const double gap = sharp.project(X, 0.0).gap;
    if (std::abs(gap) > std::abs(largest)) largest = gap, where = X;
  });
  if (std::abs(largest) > tolerance)
    throw case_error(spec.origin, "scene.mesh_file",
                     fmt::format("the cavity does not fit the needle of the needle.* keys: its vertex at ({:.3g}, "
                                 "{:.3g}, {:.3g}) mm lies {:.3g} mm {} the needle's surface (tolerance {:.2g} mm); "
                                 "mesh the scene from the same needle keys",
                                 where[0] * kMmPerM, where[1] * kMmPerM, where[2] * kMmPerM,
                                 std::abs(largest) * kMmPerM, largest > 0 ? "outside" : "inside",
                                 tolerance * kMmPerM));
}

std::shared_ptr<const CadNeedleShape> cad_needle_shape(const NeedleTipSpec& spec, const CadTipTriangulation& cad,
                                                       double edge_radius) {
  try {
    return std::make_shared<CadNeedleShape>(TriangleSoup{cad.vertices, cad.triangles}, edge_radius);
  } catch (const std::invalid_argument& e) {
    throw case_error(spec.origin, "needle.cad_file", fmt::format("'{}': {}", spec.cad_file.string(), e.what()));
  }
}

}  // namespace

std::shared_ptr<const Needle> needle_from_spec(const NeedleSpecs& specs, std::shared_ptr<const Needle>* sharp,
                                               std::shared_ptr<const HeadTilt> tilt) {
  constexpr double kSharpEdge = 1e-12;  // m: the needle without its edge rounding
  const NeedleTipSpec& tip_spec = specs.mesh.needle_tip;
  const NeedleTip tip = needle_tip_from_spec(tip_spec);
  const double edge_radius = specs.mesh.needle_edge_radius_um * kMPerUm;
  const NeedleMotion motion = needle_motion_from_spec(specs.motion);
  switch (tip.kind) {
    case NeedleTip::Kind::Cad: {
      const CadTipTriangulation cad = triangulate_cad_tip(tip_spec, specs.mesh.tissue);
      if (sharp) *sharp = std::make_shared<RigidNeedle>(cad_needle_shape(tip_spec, cad, 0.0), motion);
      return std::make_shared<RigidNeedle>(cad_needle_shape(tip_spec, cad, edge_radius), motion);
    }
    case NeedleTip::Kind::Compliant:
      if (sharp) *sharp = std::make_shared<HingedNeedle>(tip.compliant, motion, kSharpEdge, tilt);
      return std::make_shared<HingedNeedle>(tip.compliant, motion, edge_radius, tilt);
    case NeedleTip::Kind::Bevel:
      break;
  }
  if (sharp) *sharp = std::make_shared<RigidNeedle>(tip.bevel, motion, kSharpEdge);
  return std::make_shared<RigidNeedle>(tip.bevel, motion, edge_radius);
}

RoundedCavity round_cavity_to_needle(const NeedleSpecs& specs, TetMesh& mesh) {
  constexpr double kRoundingMoveLimit = 4.0;  // edge radii
  const MeshSpec& spec = specs.mesh;
  const bool user_mesh = !spec.scene_mesh_file.empty();
  std::shared_ptr<const Needle> sharp;  // without the edge rounding, as the cavity was meshed
  RoundedCavity rounded{needle_from_spec(specs, user_mesh ? &sharp : nullptr), {}};
  if (user_mesh) require_cavity_on_needle(spec, mesh, *sharp);
  rounded.rounding = round_cavity(mesh, [&](const Point3& X) {
    const ObstacleProjection p = rounded.needle->project(X, 0.0);
    return Point3{X[0] - p.gap * p.normal[0], X[1] - p.gap * p.normal[1], X[2] - p.gap * p.normal[2]};
  });
  // A point of half-angle α rounded with ρ moves back by ρ (1/sin α - 1): more than kRoundingMoveLimit
  // ρ is a point sharper than about 11°, where the rounded needle in contact is no longer the tip's
  // shape. Measured: every Table I design and shipped tip family at most 2.0 ρ (r 1.25/20°/0.15);
  // the Quincke's lancet point left sharp 6.7 ρ.
  // The case's radius, not the needle's: a fully rounded tip has no edges to round (0) but its
  // nodes still move by round-off.
  const double edge_radius = spec.needle_edge_radius_um * kMPerUm;
  if (rounded.rounding.largest_move_m > kRoundingMoveLimit * edge_radius)
    throw case_error(spec.origin, "needle.edge_radius_um",
                     fmt::format("rounding the cavity to the needle's edges moved it by up to {:.3g} mm, more than "
                                 "{} edge radii: the tip has a point sharper than this radius rounds, so the needle in "
                                 "contact would not be its shape; blunt the point or lower the radius",
                                 rounded.rounding.largest_move_m * 1e3, kRoundingMoveLimit));
  return rounded;
}

NeedleContact::NeedleContact(ContactParameters parameters, const TetMesh& mesh,
                             std::shared_ptr<const Needle> needle)
    : mesh_(mesh), needle_(std::move(needle)) {
  parameters.reference_gap_offset = true;  // the cavity is meshed from the needle's shape
  smoothing_pressure_ = parameters.penalty_smoothing * parameters.reference_modulus;
  contact_ = std::make_shared<PenaltyContact>(mesh, kCavity, needle_, parameters);
  std::map<int, std::pair<double, int>> penalty_sum;  // node -> (sum of face penalties, faces)
  for (std::size_t f = 0; f < contact_->face_count(); ++f)
    for (int a = 0; a < contact_->nodes_per_face(); ++a) {
      auto& entry = penalty_sum[contact_->face_nodes(f)[a]];
      entry.first += contact_->penalty(f);
      entry.second += 1;
    }
  for (const auto& [node, sum] : penalty_sum) {
    cavity_nodes_.push_back(node);
    node_penalty_.push_back(sum.first / sum.second);
  }
}

NeedleLoad NeedleContact::load_on_needle(double t, const double* y, const double* ydot,
                                         const mechanics::DofMap& dofs) const {
  const ContactResultant r = contact_->resultant(t, y, ydot, dofs, needle_->rear_face_centre(t));
  return {r.force_on_obstacle, r.moment_on_obstacle, r.contact_area};
}

NeedleLoad NeedleContact::load_on_head(double t, const double* y, const double* ydot,
                                       const mechanics::DofMap& dofs) const {
  const HingedNeedle* hinged = hinged_needle();
  if (!hinged) throw std::logic_error("load_on_head: the needle has no head");
  const ContactResultant r = contact_->resultant(t, y, ydot, dofs, hinged->pivot(t), HingedNeedle::head);
  return {r.force_on_obstacle, r.moment_on_obstacle, r.contact_area};
}

NeedleContact::SurfaceFields NeedleContact::surface_fields(double t, const double* y,
                                                           const mechanics::DofMap& dofs) const {
  SurfaceFields out;
  out.pressure.assign(mesh_.nodes.size(), 0.0);
  out.slip.assign(mesh_.nodes.size(), 0.0);
  std::vector<double> offset_sum(mesh_.nodes.size(), 0.0), faces_at(mesh_.nodes.size(), 0.0);
  for (std::size_t f = 0; f < contact_->face_count(); ++f) {
    const double offset = contact_->mean_offset(f, t);
    for (int a = 0; a < contact_->nodes_per_face(); ++a) {
      offset_sum[contact_->face_nodes(f)[a]] += offset;
      faces_at[contact_->face_nodes(f)[a]] += 1.0;
    }
  }
  for (std::size_t i = 0; i < cavity_nodes_.size(); ++i) {
    const int node = cavity_nodes_[i];
    const Point3& X = mesh_.nodes[node];
    Point3 x;
    for (int c = 0; c < 3; ++c) x[c] = X[c] + y[dofs.dof(node, c)];
    const ObstacleProjection p = needle_->project(x, t);
    const double depth = offset_sum[node] / faces_at[node] - p.gap;  // the multiplier's offset, mean of its faces
    out.pressure[node] =
        normal_pressure(std::max(0.0, depth), node_penalty_[i], smoothing_pressure_ / node_penalty_[i]).pressure;
    const Point3 chi = needle_->from_body(X, t);
    Point3 relative;
    for (int c = 0; c < 3; ++c) relative[c] = x[c] - chi[c];
    const double normal_part = relative[0] * p.normal[0] + relative[1] * p.normal[1] + relative[2] * p.normal[2];
    double slip2 = 0.0;
    for (int c = 0; c < 3; ++c) slip2 += std::pow(relative[c] - normal_part * p.normal[c], 2);
    out.slip[node] = std::sqrt(slip2);
  }
  return out;
}

std::vector<Point3> NeedleContact::nodal_loads_in_needle_frame(double t, const double* y, const double* ydot,
                                                              const mechanics::DofMap& dofs) const {
  std::vector<double> residual(static_cast<std::size_t>(dofs.dof_count), 0.0);
  contact_->add_residual(t, y, ydot, dofs, residual.data());
  const Point3 origin = needle_->to_body({0.0, 0.0, 0.0}, t);
  std::vector<Point3> loads(mesh_.nodes.size(), Point3{});
  for (int node : cavity_nodes_) {
    const Point3 world{residual[dofs.dof(node, 0)], residual[dofs.dof(node, 1)], residual[dofs.dof(node, 2)]};
    const Point3 moved = needle_->to_body(world, t);  // R⁻¹ (f - d): subtract R⁻¹(-d) to rotate only
    for (int c = 0; c < 3; ++c) loads[node][c] = moved[c] - origin[c];
  }
  return loads;
}

NeedleContact::InitialGap NeedleContact::initial_gap() const {
  const double inf = std::numeric_limits<double>::infinity();
  InitialGap gap{{inf, -inf}, {inf, -inf}};
  auto include = [&](GapRange& range, const Point3& x) {
    const double g = needle_->project(x, 0.0).gap;
    range.min = std::min(range.min, g);
    range.max = std::max(range.max, g);
  };
  for (int node : cavity_nodes_) include(gap.nodes, mesh_.nodes[node]);
  const int m = contact_->nodes_per_face();
  for (std::size_t f = 0; f < contact_->face_count(); ++f) {
    Point3 centroid{};
    for (int a = 0; a < m; ++a)
      for (int c = 0; c < 3; ++c) centroid[c] += centroid_weight(m, a) * mesh_.nodes[contact_->face_nodes(f)[a]][c];
    include(gap.centroids, centroid);
  }
  return gap;
}

}  // namespace needlefem::contact
