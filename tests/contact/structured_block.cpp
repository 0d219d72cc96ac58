#include "structured_block.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>

#include "model/tet_geometry.hpp"

namespace needlefem::contact::testing {

std::vector<double> graded_coordinates(double fine, double fine_extent, double growth, double length) {
  std::vector<double> x{0.0};
  while (x.back() + 0.5 * fine < fine_extent) x.push_back(x.back() + fine);
  std::vector<double> coarse;
  double size = fine * growth, total = 0.0;
  while (total + 0.5 * size < length - x.back()) {
    coarse.push_back(size);
    total += size;
    size *= growth;
  }
  const double scale = (length - x.back()) / total, start = x.back();
  double position = start;
  for (double cell : coarse) x.push_back(position += cell * scale);
  x.back() = length;
  return x;
}

std::vector<double> graded_towards_end(double fine, double fine_extent, double growth, double length) {
  std::vector<double> x = graded_coordinates(fine, fine_extent, growth, length);
  for (double& value : x) value = length - value;
  std::reverse(x.begin(), x.end());
  return x;
}

TetMesh structured_block(const std::vector<double>& xs, const std::vector<double>& ys, const std::vector<double>& zs) {
  // Nodes on the doubled grid: even indices are grid points, odd ones edge/face/cell midpoints.
  const std::array<std::vector<double>, 3> axes{xs, ys, zs};
  std::array<int, 3> size{};
  std::array<std::vector<double>, 3> doubled;
  for (int d = 0; d < 3; ++d) {
    size[d] = 2 * static_cast<int>(axes[d].size() - 1) + 1;
    for (int i = 0; i < size[d]; ++i)
      doubled[d].push_back(i % 2 == 0 ? axes[d][i / 2] : 0.5 * (axes[d][i / 2] + axes[d][i / 2 + 1]));
  }
  using Index = std::array<int, 3>;
  auto node_of = [&](const Index& i) { return (i[2] * size[1] + i[1]) * size[0] + i[0]; };
  TetMesh mesh;
  mesh.nodes_per_tet = 10;
  mesh.region_names = {"tissue"};
  for (int k = 0; k < size[2]; ++k)
    for (int j = 0; j < size[1]; ++j)
      for (int i = 0; i < size[0]; ++i) mesh.nodes.push_back({doubled[0][i], doubled[1][j], doubled[2][k]});
  auto mid = [](const Index& a, const Index& b) { return Index{(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2}; };
  const std::array<const char*, 6> plane_names{"x_min", "x_max", "y_min", "y_max", "z_min", "z_max"};
  auto boundary_plane = [&](const Index& a, const Index& b, const Index& c) {
    for (int d = 0; d < 3; ++d) {
      if (a[d] == 0 && b[d] == 0 && c[d] == 0) return 2 * d;
      const int last = size[d] - 1;
      if (a[d] == last && b[d] == last && c[d] == last) return 2 * d + 1;
    }
    return -1;
  };
  std::array<int, 3> permutation{0, 1, 2};
  std::vector<std::array<int, 3>> permutations;
  do permutations.push_back(permutation);
  while (std::next_permutation(permutation.begin(), permutation.end()));
  for (int k = 0; k + 1 < size[2]; k += 2)
    for (int j = 0; j + 1 < size[1]; j += 2)
      for (int i = 0; i + 1 < size[0]; i += 2)
        for (const auto& p : permutations) {
          std::array<Index, 4> v;
          v[0] = {i, j, k};
          for (int s = 0; s < 3; ++s) {
            v[s + 1] = v[s];
            v[s + 1][p[s]] += 2;
          }
          auto point = [&](const Index& a) { return mesh.nodes[node_of(a)]; };
          if (oriented_volume(point(v[0]), point(v[1]), point(v[2]), point(v[3])) < 0.0) std::swap(v[1], v[2]);
          for (const Index& a : v) mesh.tet_nodes.push_back(node_of(a));
          for (const auto& [a, b] : {std::pair{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}})
            mesh.tet_nodes.push_back(node_of(mid(v[a], v[b])));
          mesh.tet_region.push_back(0);
          for (int opposite = 0; opposite < 4; ++opposite) {
            std::array<Index, 3> f;
            for (int s = 0, n = 0; s < 4; ++s)
              if (s != opposite) f[n++] = v[s];
            const int plane = boundary_plane(f[0], f[1], f[2]);
            if (plane < 0) continue;
            // Outward: the opposite vertex lies on the negative side of (f1 - f0) x (f2 - f0).
            if (oriented_volume(point(f[0]), point(f[1]), point(f[2]), point(v[opposite])) > 0.0) std::swap(f[1], f[2]);
            auto& faces = mesh.surface_faces[plane_names[plane]];
            for (const Index& a : f) faces.push_back(node_of(a));
            faces.push_back(node_of(mid(f[0], f[1])));
            faces.push_back(node_of(mid(f[1], f[2])));
            faces.push_back(node_of(mid(f[2], f[0])));
          }
        }
  return mesh;
}

void constrain(mechanics::DirichletConditions& conditions, const TetMesh& mesh, const mechanics::DofMap& dofs,
               const std::string& surface, const std::vector<int>& components, mechanics::DisplacementField field) {
  conditions.fields.push_back(std::move(field));
  const int index = static_cast<int>(conditions.fields.size()) - 1;
  std::vector<int> nodes = mesh.surface_faces.at(surface);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  for (int node : nodes)
    for (int c : components) {
      const int dof = dofs.dof(node, c);
      std::erase_if(conditions.dofs, [&](const mechanics::PrescribedDof& d) { return d.dof == dof; });
      conditions.dofs.push_back({dof, node, c, index});
    }
}

material::Material neo_hookean(double shear_modulus, double bulk_modulus) {
  material::PolynomialTissue law;
  law.isochoric.elastic.c10 = 0.5 * shear_modulus;
  law.volumetric.bulk_modulus = bulk_modulus;
  return material::Material("neo-hookean", law);
}

int solve_static(mechanics::MechanicsSystem& system, double t, Vec y, Vec ydot, int max_iterations) {
  Vec residual, correction;
  VecDuplicate(y, &residual);
  VecDuplicate(y, &correction);
  VecSet(ydot, 0.0);
  int iterations = -1;
  for (int iteration = 1; iteration <= max_iterations; ++iteration) {
    if (system.residual(t, y, ydot, residual) != DaeStatus::ok) break;
    if (system.setup_jacobian(t, y, ydot, 1.0) != DaeStatus::ok) break;
    if (system.solve_jacobian(residual, correction) != DaeStatus::ok) break;
    VecAXPY(y, -1.0, correction);
    double step = 0.0, size = 0.0;
    VecNorm(correction, NORM_2, &step);
    VecNorm(y, NORM_2, &size);
    if (step <= 1e-10 * size) {
      iterations = iteration;
      break;
    }
  }
  VecDestroy(&residual);
  VecDestroy(&correction);
  return iterations;
}

}  // namespace needlefem::contact::testing
