// Linear-elastic needle under contact loads; the model is in needle_elasticity.hpp.
#include "physics/contact/needle_elasticity.hpp"

#include <cmath>
#include <map>
#include <stdexcept>

#include <fmt/core.h>
#include <petscvec.h>

#include "integration/ksp_solver.hpp"
#include "integration/petsc_arrays.hpp"
#include "integration/petsc_session.hpp"
#include "physics/elements/tet_element.hpp"
#include "physics/material/material.hpp"
#include "physics/mechanics/tet_assembly.hpp"

namespace needlefem::contact {

namespace {

constexpr int kNodes = 10;
const std::string kNeedleRegion = "needle";
const std::string kRearSurface = "needle_rear";

}  // namespace

struct NeedleElasticity::Impl {
  std::vector<int> mesh_node;          // needle node -> mesh node
  std::vector<int> load_node;          // needle node -> the mesh node whose force acts on it (the
                                       // tissue node a needle node was split from, TetMesh::split_nodes)
  std::vector<Point3> position;        // per needle node: reference position, m
  // The needle's tets over needle nodes, K at u = 0 and the clamp of needle_rear.
  std::unique_ptr<mechanics::TetAssembly> assembly;
  Vec rhs = nullptr, solution = nullptr;
  mutable KspSolver solver{PETSC_COMM_SELF};

  ~Impl() {
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
  std::vector<int> element_nodes;  // the needle's tets over needle nodes
  for (std::size_t e = 0; e < mesh.tet_count(); ++e) {
    if (mesh.tet_region[e] != region) continue;
    for (int a = 0; a < kNodes; ++a) {
      auto [it, added] = local.try_emplace(mesh.tet(e)[a], static_cast<int>(m.mesh_node.size()));
      if (added) {
        m.mesh_node.push_back(it->first);
        m.position.push_back(mesh.nodes[it->first]);
      }
      element_nodes.push_back(it->second);
    }
  }
  std::map<int, int> split_from;  // needle copy -> tissue node
  for (const auto& [tissue, copy] : mesh.split_nodes) split_from[copy] = tissue;
  for (int node : m.mesh_node) {
    const auto it = split_from.find(node);
    m.load_node.push_back(it == split_from.end() ? node : it->second);
  }
  std::vector<PetscInt> clamped;
  std::vector<char> on_rear(m.mesh_node.size(), 0);
  for (int node : rear->second) {
    const auto it = local.find(node);
    if (it == local.end()) throw std::runtime_error("needle elasticity: a needle_rear node belongs to no needle tet");
    if (on_rear[it->second]) continue;
    on_rear[it->second] = 1;
    for (int i = 0; i < 3; ++i) clamped.push_back(3 * it->second + i);
  }

  // K = Σ_e K_e at u = 0 (the co-rotational law's tangent there is Hooke's), clamped.
  m.assembly = std::make_unique<mechanics::TetAssembly>(kNodes, std::move(element_nodes), m.position, std::move(clamped));
  m.rhs = m.assembly->create_vector();
  m.solution = m.assembly->create_vector();
  const material::Material steel("needle", material::CorotationalLinear{youngs_modulus_pa, poisson_ratio});
  const elements::TetElementKernel kernel(steel, elements::Formulation::displacement);
  m.assembly->add_elements(kernel, std::vector<double>(m.assembly->dofs(), 0.0).data(), nullptr, true);
  if (!m.solver.factor(m.assembly->matrix()))
    throw std::runtime_error("needle elasticity: factorising the needle's stiffness failed: " +
                             m.solver.last_failure());
}

NeedleElasticity::~NeedleElasticity() = default;

NeedleElasticity::Deflection NeedleElasticity::deflection(const std::vector<Point3>& nodal_forces) const {
  const Impl& m = *impl_;
  {
    WriteArray load(m.rhs);
    for (std::size_t a = 0; a < m.mesh_node.size(); ++a)
      for (int i = 0; i < 3; ++i) load.data()[3 * a + i] = nodal_forces.at(m.load_node[a])[i];
    // Clamped rows are identity rows: a zero load keeps their solution at 0.
    m.assembly->clamp_residual(load.data());
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
std::size_t NeedleElasticity::elements() const { return impl_->assembly->elements(); }

}  // namespace needlefem::contact
