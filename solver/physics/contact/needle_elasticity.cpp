// Linear-elastic needle under contact loads; the model is in needle_elasticity.hpp.
#include "physics/contact/needle_elasticity.hpp"

#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include <fmt/core.h>
#include <petscmat.h>

#include "integration/ksp_solver.hpp"
#include "integration/petsc_arrays.hpp"
#include "integration/petsc_session.hpp"
#include "physics/elements/tet_element.hpp"
#include "physics/material/material.hpp"

namespace needlefem::contact {

namespace {

constexpr int kNodes = 10;
constexpr int kElementDofs = 3 * kNodes;
const std::string kNeedleRegion = "needle";
const std::string kRearSurface = "needle_rear";

}  // namespace

struct NeedleElasticity::Impl {
  std::vector<int> mesh_node;          // needle node -> mesh node
  std::vector<int> load_node;          // needle node -> the mesh node whose force acts on it (the
                                       // tissue node a needle node was split from, TetMesh::split_nodes)
  std::vector<char> clamped;           // per needle node: on needle_rear
  std::vector<Point3> position;        // per needle node: reference position, m
  std::vector<std::size_t> elements;   // mesh tets of the needle
  Mat matrix = nullptr;
  Vec rhs = nullptr, solution = nullptr;
  mutable KspSolver solver{PETSC_COMM_SELF};

  ~Impl() {
    MatDestroy(&matrix);
    VecDestroy(&rhs);
    VecDestroy(&solution);
  }
};

NeedleElasticity::NeedleElasticity(const TetMesh& mesh, double youngs_modulus_pa, double poisson_ratio)
    : impl_(std::make_unique<Impl>()) {
  if (!(youngs_modulus_pa > 0.0) || !(poisson_ratio > -1.0 && poisson_ratio < 0.5))
    throw std::invalid_argument(fmt::format("needle elasticity: need E > 0 and -1 < nu < 0.5, got E = {} Pa, nu = {}",
                                            youngs_modulus_pa, poisson_ratio));
  const int region = mesh.region_index(kNeedleRegion);
  if (region < 0 || mesh.nodes_per_tet != kNodes)
    throw std::runtime_error("needle elasticity: the mesh has no \"needle\" region of 10-node tetrahedra "
                             "(mesh the scene with needle.mesh_volume = true and quadratic elements)");
  const auto rear = mesh.surface_faces.find(kRearSurface);
  if (rear == mesh.surface_faces.end() || rear->second.empty())
    throw std::runtime_error("needle elasticity: the mesh has no \"needle_rear\" surface to clamp");
  Impl& m = *impl_;
  std::map<int, int> local;  // mesh node -> needle node
  for (std::size_t e = 0; e < mesh.tet_count(); ++e) {
    if (mesh.tet_region[e] != region) continue;
    m.elements.push_back(e);
    for (int a = 0; a < kNodes; ++a) {
      auto [it, added] = local.try_emplace(mesh.tet(e)[a], static_cast<int>(m.mesh_node.size()));
      if (added) {
        m.mesh_node.push_back(it->first);
        m.position.push_back(mesh.nodes[it->first]);
      }
    }
  }
  const std::size_t nodes = m.mesh_node.size();
  std::map<int, int> split_from;  // needle copy -> tissue node
  for (const auto& [tissue, copy] : mesh.split_nodes) split_from[copy] = tissue;
  for (int node : m.mesh_node) {
    const auto it = split_from.find(node);
    m.load_node.push_back(it == split_from.end() ? node : it->second);
  }
  std::vector<std::set<int>> neighbours(nodes);
  for (std::size_t e : m.elements)
    for (int a = 0; a < kNodes; ++a)
      for (int b = 0; b < kNodes; ++b) neighbours[local.at(mesh.tet(e)[a])].insert(local.at(mesh.tet(e)[b]));
  std::vector<PetscInt> nonzeros(3 * nodes);
  for (std::size_t a = 0; a < nodes; ++a)
    for (int i = 0; i < 3; ++i) nonzeros[3 * a + i] = static_cast<PetscInt>(3 * neighbours[a].size());
  const auto n = static_cast<PetscInt>(3 * nodes);
  petsc_check(MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, 0, nonzeros.data(), &m.matrix), "MatCreateSeqAIJ");
  petsc_check(VecCreateSeq(PETSC_COMM_SELF, n, &m.rhs), "VecCreateSeq");
  petsc_check(VecDuplicate(m.rhs, &m.solution), "VecDuplicate");

  // K = Σ_e K_e at u = 0 (the co-rotational law's tangent there is Hooke's).
  const material::Material steel("needle", material::CorotationalLinear{youngs_modulus_pa, poisson_ratio});
  const elements::TetElementKernel kernel(steel, elements::Formulation::displacement);
  const std::vector<double> zero(kElementDofs, 0.0);
  std::vector<double> coordinates(kElementDofs);
  std::vector<PetscInt> rows(kElementDofs);
  for (std::size_t e : m.elements) {
    const int* element = mesh.tet(e);
    for (int a = 0; a < kNodes; ++a)
      for (int i = 0; i < 3; ++i) {
        coordinates[3 * a + i] = mesh.nodes[element[a]][i];
        rows[3 * a + i] = 3 * local.at(element[a]) + i;
      }
    const elements::ElementResult result =
        kernel.evaluate(elements::element_geometry(kNodes, coordinates.data()), zero.data(), nullptr, true);
    petsc_check(MatSetValues(m.matrix, kElementDofs, rows.data(), kElementDofs, rows.data(), result.stiffness.data(),
                             ADD_VALUES),
                "MatSetValues");
  }
  petsc_check(MatAssemblyBegin(m.matrix, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  petsc_check(MatAssemblyEnd(m.matrix, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  std::vector<PetscInt> clamped;
  m.clamped.assign(nodes, 0);
  for (int node : rear->second) {
    const auto it = local.find(node);
    if (it == local.end()) throw std::runtime_error("needle elasticity: a needle_rear node belongs to no needle tet");
    if (m.clamped[it->second]) continue;
    m.clamped[it->second] = 1;
    for (int i = 0; i < 3; ++i) clamped.push_back(3 * it->second + i);
  }
  petsc_check(MatZeroRowsColumns(m.matrix, static_cast<PetscInt>(clamped.size()), clamped.data(), 1.0, nullptr,
                                 nullptr),
              "MatZeroRowsColumns");
  if (!m.solver.factor(m.matrix))
    throw std::runtime_error("needle elasticity: factorising the needle's stiffness failed: " +
                             m.solver.last_failure());
}

NeedleElasticity::~NeedleElasticity() = default;

NeedleElasticity::Deflection NeedleElasticity::deflection(const std::vector<Point3>& nodal_forces) const {
  const Impl& m = *impl_;
  {
    WriteArray load(m.rhs);
    // Clamped rows are identity rows: a zero load keeps their solution at 0.
    for (std::size_t a = 0; a < m.mesh_node.size(); ++a)
      for (int i = 0; i < 3; ++i) load.data()[3 * a + i] = m.clamped[a] ? 0.0 : nodal_forces.at(m.load_node[a])[i];
  }
  if (!m.solver.solve(m.rhs, m.solution))
    throw std::runtime_error("needle elasticity: the needle's linear solve failed: " + m.solver.last_failure());
  Deflection out;
  const ReadArray u(m.solution), f(m.rhs);
  double work = 0.0;
  for (std::size_t a = 0; a < m.mesh_node.size(); ++a) {
    double size2 = 0.0;
    for (int i = 0; i < 3; ++i) {
      size2 += u.data()[3 * a + i] * u.data()[3 * a + i];
      work += f.data()[3 * a + i] * u.data()[3 * a + i];
    }
    if (std::sqrt(size2) > out.max_m) {
      out.max_m = std::sqrt(size2);
      out.where = m.position[a];
    }
  }
  out.elastic_energy_j = 0.5 * work;
  return out;
}

std::size_t NeedleElasticity::dofs() const { return 3 * impl_->mesh_node.size(); }
std::size_t NeedleElasticity::elements() const { return impl_->elements.size(); }

}  // namespace needlefem::contact
