#include "model/mesh_quality.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include <nlohmann/json.hpp>

#include "model/tet_geometry.hpp"

namespace needlefem {

namespace {

double radius_ratio(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  auto sub = [](const Point3& p, const Point3& q) { return Point3{p[0] - q[0], p[1] - q[1], p[2] - q[2]}; };
  auto cross = [](const Point3& u, const Point3& v) {
    return Point3{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  };
  auto norm = [](const Point3& u) { return std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]); };
  const double volume = std::abs(oriented_volume(a, b, c, d));
  const double area = 0.5 * (norm(cross(sub(b, a), sub(c, a))) + norm(cross(sub(b, a), sub(d, a))) +
                             norm(cross(sub(c, a), sub(d, a))) + norm(cross(sub(c, b), sub(d, b))));
  const double r_in = 3 * volume / area;
  // Circumradius: |a|^2 (b x c) + ... relative to d, over 12 V.
  const Point3 u = sub(a, d), v = sub(b, d), w = sub(c, d);
  auto dot = [](const Point3& p, const Point3& q) { return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]; };
  const Point3 vw = cross(v, w), wu = cross(w, u), uv = cross(u, v);
  Point3 num;
  for (int k = 0; k < 3; ++k) num[k] = dot(u, u) * vw[k] + dot(v, v) * wu[k] + dot(w, w) * uv[k];
  const double r_circ = norm(num) / (12 * volume);
  return volume > 0 ? 3 * r_in / r_circ : 0.0;
}

}  // namespace

std::size_t MeshQuality::inverted() const {
  std::size_t n = 0;
  for (const auto& [name, q] : regions) n += q.inverted;
  return n;
}

double MeshQuality::volume_of_regions_starting_with(const std::string& prefix) const {
  double v = 0;
  for (const auto& [name, q] : regions)
    if (name.rfind(prefix, 0) == 0) v += q.volume_m3;
  return v;
}

MeshQuality measure_quality(const TetMesh& mesh) {
  MeshQuality out;
  out.tet_scaled_jacobian.resize(mesh.tet_count());
  out.tet_radius_ratio.resize(mesh.tet_count());
  std::vector<std::array<double, 3>> samples = tet_reference_nodes(mesh.nodes_per_tet);
  for (const auto& q : tet_quadrature_degree5()) samples.push_back(q.xi);
  std::vector<std::set<int>> region_nodes(mesh.region_names.size());
  for (const auto& name : mesh.region_names) {
    auto& q = out.regions[name];
    q.min_jacobian = q.min_scaled_jacobian = q.min_radius_ratio = std::numeric_limits<double>::infinity();
    q.max_jacobian = -std::numeric_limits<double>::infinity();
  }
  for (std::size_t e = 0; e < mesh.tet_count(); ++e) {
    const int region = mesh.tet_region[e];
    auto& q = out.regions[mesh.region_names[region]];
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const auto& xi : samples) {
      const double j = tet_jacobian_determinant(mesh, e, xi);
      lo = std::min(lo, j);
      hi = std::max(hi, j);
    }
    const int* t = mesh.tet(e);
    const double ratio = radius_ratio(mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]], mesh.nodes[t[3]]);
    out.tet_scaled_jacobian[e] = hi > 0 ? lo / hi : -1.0;
    out.tet_radius_ratio[e] = ratio;
    q.tets += 1;
    q.inverted += lo <= 0 ? 1 : 0;
    q.volume_m3 += tet_volume(mesh, e);
    q.min_jacobian = std::min(q.min_jacobian, lo);
    q.max_jacobian = std::max(q.max_jacobian, hi);
    q.min_scaled_jacobian = std::min(q.min_scaled_jacobian, out.tet_scaled_jacobian[e]);
    q.min_radius_ratio = std::min(q.min_radius_ratio, ratio);
    q.mean_radius_ratio += ratio;
    region_nodes[region].insert(t, t + mesh.nodes_per_tet);
  }
  for (std::size_t r = 0; r < mesh.region_names.size(); ++r) {
    auto& q = out.regions[mesh.region_names[r]];
    q.nodes = region_nodes[r].size();
    if (q.tets) q.mean_radius_ratio /= static_cast<double>(q.tets);
  }
  return out;
}

nlohmann::json to_json(const RegionQuality& q) {
  return {{"tets", q.tets},
          {"nodes", q.nodes},
          {"inverted_tets", q.inverted},
          {"volume_mm3", q.volume_m3 * 1e9},
          {"min_jacobian_mm3", q.min_jacobian * 1e9},
          {"max_jacobian_mm3", q.max_jacobian * 1e9},
          {"min_scaled_jacobian", q.min_scaled_jacobian},
          {"min_radius_ratio", q.min_radius_ratio},
          {"mean_radius_ratio", q.mean_radius_ratio}};
}

}  // namespace needlefem
