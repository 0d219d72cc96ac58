// Equations: surface_pressure.hpp.
#include "physics/mechanics/surface_pressure.hpp"

#include <array>
#include <stdexcept>

#include <fmt/format.h>

#include "physics/elements/triangle_face.hpp"

namespace needlefem::mechanics {

SurfacePressure::SurfacePressure(const TetMesh& mesh, const std::vector<std::string>& surfaces,
                                 std::function<double(double)> pressure, bool follower)
    : mesh_(mesh), nodes_per_face_(mesh.nodes_per_face()), pressure_(std::move(pressure)), follower_(follower) {
  for (const auto& name : surfaces) {
    const auto found = mesh.surface_faces.find(name);
    if (found == mesh.surface_faces.end()) throw std::runtime_error("the mesh has no surface '" + name + "'");
    face_nodes_.insert(face_nodes_.end(), found->second.begin(), found->second.end());
  }
}

void SurfacePressure::face_positions(std::size_t face, const double* y, const DofMap& dofs, double* x) const {
  for (int a = 0; a < nodes_per_face_; ++a) {
    const int node = face_nodes_[face * nodes_per_face_ + a];
    for (int c = 0; c < 3; ++c) x[3 * a + c] = mesh_.nodes[node][c] + (follower_ ? y[dofs.dof(node, c)] : 0.0);
  }
}

void SurfacePressure::face_terms(const double* x, double p, double* residual, double* jacobian) const {
  const int m = nodes_per_face_;
  std::array<double, 6> N{}, dN_dxi{}, dN_deta{};
  for (const auto& q : elements::kTriangleRule) {
    elements::triangle_shape(m, q.xi, q.eta, N.data(), dN_dxi.data(), dN_deta.data());
    Point3 x_xi{}, x_eta{};
    for (int a = 0; a < m; ++a)
      for (int c = 0; c < 3; ++c) {
        x_xi[c] += dN_dxi[a] * x[3 * a + c];
        x_eta[c] += dN_deta[a] * x[3 * a + c];
      }
    const Point3 area_normal{x_xi[1] * x_eta[2] - x_xi[2] * x_eta[1], x_xi[2] * x_eta[0] - x_xi[0] * x_eta[2],
                             x_xi[0] * x_eta[1] - x_xi[1] * x_eta[0]};
    for (int a = 0; a < m; ++a)
      for (int i = 0; i < 3; ++i) residual[3 * a + i] += q.weight * p * N[a] * area_normal[i];
    if (!jacobian) continue;
    // [v]× w = v × w: row i, column j of [v]× is ε_ikj v_k.
    const auto skew = [](const Point3& v) {
      return std::array<double, 9>{0.0, -v[2], v[1], v[2], 0.0, -v[0], -v[1], v[0], 0.0};
    };
    const auto skew_xi = skew(x_xi), skew_eta = skew(x_eta);
    for (int a = 0; a < m; ++a)
      for (int b = 0; b < m; ++b)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            jacobian[(3 * a + i) * 3 * m + 3 * b + j] +=
                q.weight * p * N[a] * (dN_deta[b] * skew_xi[3 * i + j] - dN_dxi[b] * skew_eta[3 * i + j]);
  }
}

void SurfacePressure::add_residual(double t, const double* y, const double*, const DofMap& dofs, double* f_u) const {
  const double p = pressure_(t);
  if (p == 0.0) return;
  const int m = nodes_per_face_;
  std::vector<double> x(3 * m), residual(3 * m);
  for (std::size_t f = 0; f < face_nodes_.size() / m; ++f) {
    face_positions(f, y, dofs, x.data());
    std::fill(residual.begin(), residual.end(), 0.0);
    face_terms(x.data(), p, residual.data(), nullptr);
    for (int a = 0; a < m; ++a)
      for (int c = 0; c < 3; ++c) f_u[dofs.dof(face_nodes_[f * m + a], c)] += residual[3 * a + c];
  }
}

void SurfacePressure::add_jacobian(double t, const double* y, const double*, double, const DofMap& dofs,
                                   Mat jacobian, NewtonMatrix) const {
  const double p = pressure_(t);
  if (!follower_ || p == 0.0) return;
  const int m = nodes_per_face_;
  std::vector<double> x(3 * m), residual(3 * m), matrix(9 * m * m);
  std::vector<PetscInt> blocks(m);
  for (std::size_t f = 0; f < face_nodes_.size() / m; ++f) {
    face_positions(f, y, dofs, x.data());
    std::fill(matrix.begin(), matrix.end(), 0.0);
    face_terms(x.data(), p, residual.data(), matrix.data());
    for (int a = 0; a < m; ++a) blocks[a] = dofs.node_dof[face_nodes_[f * m + a]] / 3;
    const PetscErrorCode code =
        MatSetValuesBlocked(jacobian, m, blocks.data(), m, blocks.data(), matrix.data(), ADD_VALUES);
    if (code != 0) throw std::runtime_error(fmt::format("PETSc error {} in MatSetValuesBlocked (pressure)", code));
  }
}

}  // namespace needlefem::mechanics
