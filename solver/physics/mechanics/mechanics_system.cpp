// Equations: mechanics_system.hpp.
#include "physics/mechanics/mechanics_system.hpp"

#include "integration/petsc_arrays.hpp"

#include <algorithm>
#include <atomic>
#include <numeric>
#include <stdexcept>

#include <fmt/format.h>


namespace needlefem::mechanics {

namespace {

void check(PetscErrorCode code, const char* what) {
  if (code != 0) throw std::runtime_error(fmt::format("PETSc error {} in {}", static_cast<int>(code), what));
}


// The tissue elements' nodes as blocks of the assembly (block = a node's first dof / 3) and the
// reference position of each block's node.
std::vector<int> element_blocks(const TetMesh& mesh, const DofMap& dofs) {
  std::vector<int> blocks;
  blocks.reserve(dofs.tissue_tets.size() * static_cast<std::size_t>(mesh.nodes_per_tet));
  for (std::size_t e : dofs.tissue_tets)
    for (int a = 0; a < mesh.nodes_per_tet; ++a) blocks.push_back(dofs.node_dof[mesh.tet(e)[a]] / 3);
  return blocks;
}

std::vector<Point3> block_positions(const TetMesh& mesh, const DofMap& dofs) {
  std::vector<Point3> positions(static_cast<std::size_t>(dofs.dof_count / 3));
  for (std::size_t node = 0; node < mesh.nodes.size(); ++node)
    if (dofs.node_dof[node] >= 0) positions[static_cast<std::size_t>(dofs.node_dof[node] / 3)] = mesh.nodes[node];
  return positions;
}

}  // namespace

MechanicsSystem::MechanicsSystem(const TetMesh& mesh, const material::Material& material,
                                 elements::Formulation formulation, DirichletConditions conditions)
    : mesh_(mesh),
      dofs_(tissue_dof_map(mesh)),
      conditions_(std::move(conditions)),
      kernel_(material, formulation),
      assembly_(mesh.nodes_per_tet, element_blocks(mesh, dofs_), block_positions(mesh, dofs_)) {
  const int points = static_cast<int>(elements::element_quadrature(mesh.nodes_per_tet).size());
  viscous_per_element_ = static_cast<PetscInt>(points) * kernel_.prony_terms() * elements::kVoigt;
  prescribed_.assign(dofs_.dof_count, 0);
  for (const auto& d : conditions_.dofs) prescribed_[d.dof] = 1;
}

MechanicsSystem::~MechanicsSystem() = default;

std::unique_ptr<MechanicsSystem> MechanicsSystem::from_spec(const MechanicsSpec& spec, const TetMesh& mesh) {
  const DofMap map = tissue_dof_map(mesh);
  return std::make_unique<MechanicsSystem>(mesh, material::material_from_spec(spec.material), spec.formulation,
                                           scene_conditions(spec.boundary, mesh, map));
}

void MechanicsSystem::initial_state(double t0, Vec y, Vec ydot) {
  check(VecSet(y, 0.0), "VecSet");
  check(VecSet(ydot, 0.0), "VecSet");
  WriteArray values(y);
  for (const auto& d : conditions_.dofs) values.data()[d.dof] = conditions_.value(mesh_, d, t0);
}

void MechanicsSystem::differential_mask(Vec id) {
  WriteArray mask(id);
  std::fill(mask.data(), mask.data() + displacement_dofs(), 0.0);
  std::fill(mask.data() + displacement_dofs(), mask.data() + pressure_offset(), 1.0);
  std::fill(mask.data() + pressure_offset(), mask.data() + local_size(), 0.0);
}

void MechanicsSystem::absolute_tolerances(Vec atol, double displacement_m, double viscous_stress_pa,
                                          double pressure_pa) const {
  WriteArray values(atol);
  std::fill(values.data(), values.data() + displacement_dofs(), displacement_m);
  std::fill(values.data() + displacement_dofs(), values.data() + pressure_offset(), viscous_stress_pa);
  std::fill(values.data() + pressure_offset(), values.data() + local_size(), pressure_pa);
}

bool MechanicsSystem::assemble_internal(const double* y, const double* ydot, double* f_u, double* f_q,
                                        double* energy) const {
  const int n = mesh_.nodes_per_tet, terms = kernel_.prony_terms();
  std::fill(f_u, f_u + displacement_dofs(), 0.0);
  std::atomic<bool> inverted = false;
  std::vector<double> element_energy(energy ? assembly_.elements() : 0);
  assembly_.sum_over_elements(assembly_.elements(), f_u, displacement_dofs(), [&](std::size_t k, double* forces) {
    if (inverted.load(std::memory_order_relaxed)) return;
    std::array<double, elements::kMaxElementDofs> u_e{};
    assembly_.gather(k, y, u_e.data());
    const double* q = terms ? y + viscous_offset(k) : nullptr;
    // The viscous rows receive the rates dQ/dt first, laid out like Q.
    double* f_q_element = f_q && terms ? f_q + (viscous_offset(k) - displacement_dofs()) : nullptr;
    const elements::ElementResult element =
        kernel_.evaluate(assembly_.geometry(k), u_e.data(), q, false, 1.0, element_pressure(y, k), f_q_element);
    if (element.inverted) {
      inverted = true;
      return;
    }
    if (energy) element_energy[k] = element.energy;
    const int* blocks = assembly_.blocks(k);
    for (int a = 0; a < n; ++a)
      for (int c = 0; c < 3; ++c) forces[3 * blocks[a] + c] += element.residual[3 * a + c];
    // F_p = p - U'(θ), behind the viscous rows.
    if (f_q && pressure_unknowns())
      f_q[viscous_dofs() + static_cast<PetscInt>(k)] = y[pressure_offset() + k] - element.volume_pressure;
    if (!f_q_element) return;
    // F_Q = Q' - dQ/dt.
    const double* q_rate = ydot + viscous_offset(k);
    for (PetscInt v = 0; v < viscous_per_element_; ++v) f_q_element[v] = q_rate[v] - f_q_element[v];
  });
  if (energy) *energy = std::accumulate(element_energy.begin(), element_energy.end(), 0.0);
  return !inverted;
}

DaeStatus MechanicsSystem::residual(double t, Vec y, Vec ydot, Vec F) {
  return guarded([&] {
    ReadArray state(y), rate(ydot);
    WriteArray out(F);
    if (!assemble_internal(state.data(), rate.data(), out.data(), out.data() + displacement_dofs(), nullptr)) {
      ++rejections_.inverted_residuals;
      return DaeStatus::recoverable;
    }
    for (const auto& load : surface_loads_) load->add_residual(t, state.data(), rate.data(), dofs_, out.data());
    for (const auto& d : conditions_.dofs)
      out.data()[d.dof] = state.data()[d.dof] - conditions_.value(mesh_, d, t);
    return DaeStatus::ok;
  });
}

void MechanicsSystem::step_accepted(double t, Vec y, Vec ydot) {
  if (surface_loads_.empty()) return;
  ReadArray state(y), rate(ydot);
  for (const auto& load : surface_loads_) load->accept_step(t, state.data(), rate.data(), dofs_);
}

DaeStatus MechanicsSystem::assemble_condensed(double t, Vec y, Vec ydot, double cj, NewtonMatrix form,
                                              Mat& matrix) {
  matrix = assembly_.matrix();
  {
    ReadArray state(y), rate(ydot);
    const bool inverted = !assemble_condensed_matrix(state.data(), cj);
    if (!inverted)
      for (const auto& load : surface_loads_)
        load->add_jacobian(t, state.data(), rate.data(), cj, dofs_, assembly_.matrix(), form);
    check(MatAssemblyBegin(assembly_.matrix(), MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(assembly_.matrix(), MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    if (inverted) {
      ++rejections_.inverted_jacobians;
      return DaeStatus::recoverable;  // assembled anyway: the next setup can zero it
    }
    std::vector<PetscInt> rows;
    rows.reserve(conditions_.dofs.size());
    for (const auto& d : conditions_.dofs) rows.push_back(d.dof);
    check(MatZeroRows(assembly_.matrix(), static_cast<PetscInt>(rows.size()), rows.data(), 1.0, nullptr, nullptr),
          "MatZeroRows");
    return DaeStatus::ok;
  }
}

bool MechanicsSystem::assemble_condensed_matrix(const double* state, double cj) {
  const int terms = kernel_.prony_terms();
  const double scale = material::condensed_fraction(kernel_.prony(), cj);
  if (terms) condensation_.resize(assembly_.elements());
  if (pressure_unknowns()) {
    pressure_gradient_.resize(assembly_.elements());
    pressure_stiffness_.resize(assembly_.elements());
  }
  return assembly_.assemble_elements(
      [&](std::size_t k, elements::ElementResult& element) {
        std::array<double, elements::kMaxElementDofs> u_e{};
        assembly_.gather(k, state, u_e.data());
        const double* q = terms ? state + viscous_offset(k) : nullptr;
        const elements::ElementGeometry& geometry = assembly_.geometry(k);
        element = kernel_.evaluate(geometry, u_e.data(), q, true, scale, element_pressure(state, k));
        if (element.inverted) return;
        if (pressure_unknowns()) {
          pressure_gradient_[k] = element.volume_gradient;
          pressure_stiffness_[k] = element.pressure_stiffness;
        }
        if (terms)
          for (int p = 0; p < geometry.points; ++p)
            condensation_[k].set_point(p, element.points[p], geometry.gradient_at(p), mesh_.nodes_per_tet,
                                       geometry.weight[p]);
      },
      nullptr, true);
}

bool MechanicsSystem::newton_matrix_serves(double factored_cj, double cj) const {
  constexpr double kServingTangentChange = 1e-3;
  for (const auto& load : surface_loads_)
    if (load->depends_on_rates()) return false;
  const double factored = material::condensed_fraction(kernel_.prony(), factored_cj);
  const double needed = material::condensed_fraction(kernel_.prony(), cj);
  return std::abs(factored - needed) <= kServingTangentChange * needed;
}

MechanicsSystem::ViscousSolveFactors MechanicsSystem::viscous_solve_factors(double cj) const {
  const auto& prony = kernel_.prony();
  ViscousSolveFactors f{std::vector<double>(prony.size()), std::vector<double>(prony.size())};
  // J_QQ⁻¹ = 1 / (cj - ∂rate/∂Q) = 1 / (cj + 1/τ_i) and ∂rate/∂S⁰ = g_i / τ_i (PronyTerm).
  for (std::size_t i = 0; i < prony.size(); ++i) {
    f.relaxation[i] = 1.0 / (cj - prony[i].rate_slope());
    f.rate_gain[i] = prony[i].rate_gain();
  }
  return f;
}

std::size_t MechanicsSystem::condensed_elements() const {
  return kernel_.prony_terms() || pressure_unknowns() ? assembly_.elements() : 0;
}

void MechanicsSystem::condense(Vec b, double cj, Vec condensed_rhs) {
  const int n = mesh_.nodes_per_tet, terms = kernel_.prony_terms();
  const PetscInt nu = displacement_dofs();
  const std::vector<double> relaxation = viscous_solve_factors(cj).relaxation;
  ReadArray in(b);
  WriteArray rhs(condensed_rhs);
  double* r = rhs.data();
  std::copy(in.data(), in.data() + nu, r);
  assembly_.sum_over_elements(condensed_elements(), r, nu, [&](std::size_t k, double* sums) {
    std::array<double, elements::kMaxElementDofs> force{};
    // -a_e b_p (the pressure row gives x_p = b_p + (U''/V_e) a_eᵀ x_u).
    if (pressure_unknowns()) {
      const double b_p = in.data()[pressure_offset() + static_cast<PetscInt>(k)];
      for (int c = 0; c < 3 * n; ++c) force[c] = -pressure_gradient_[k][c] * b_p;
    }
    // Σ_q w_q B_qᵀ Σ_i b_Qi / (cj + 1/τ_i).
    if (terms) {
      std::array<elements::PointLanes, elements::kVoigt> source{};
      for (int p = 0; p < assembly_.geometry(k).points; ++p) {
        const double* b_q = in.data() + viscous_offset(k) + static_cast<PetscInt>(p) * terms * elements::kVoigt;
        for (int m = 0; m < elements::kVoigt; ++m) {
          double sum = 0.0;
          for (int i = 0; i < terms; ++i) sum += relaxation[i] * b_q[i * elements::kVoigt + m];
          source[m][p] = static_cast<float>(sum);
        }
      }
      condensation_[k].add_stress_transpose(source, n, force.data());
    }
    const int* blocks = assembly_.blocks(k);
    for (int a = 0; a < n; ++a)
      for (int c = 0; c < 3; ++c) {
        const int dof = 3 * blocks[a] + c;
        if (!prescribed_[dof]) sums[dof] += force[3 * a + c];
      }
  });
}

void MechanicsSystem::expand(Vec b, Vec condensed_solution, double cj, Vec x) {
  const int n = mesh_.nodes_per_tet, terms = kernel_.prony_terms();
  const PetscInt nu = displacement_dofs();
  const ViscousSolveFactors factors = viscous_solve_factors(cj);
  const std::size_t elements = condensed_elements();
  ReadArray in(b), x_u(condensed_solution);
  WriteArray out(x);
  std::copy(x_u.data(), x_u.data() + nu, out.data());
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < elements; ++k) {
    std::array<double, elements::kMaxElementDofs> u_e{};
    assembly_.gather(k, x_u.data(), u_e.data());
    if (pressure_unknowns()) {
      const PetscInt row = pressure_offset() + static_cast<PetscInt>(k);
      double volume_change = 0.0;  // a_eᵀ x_u
      for (int c = 0; c < 3 * n; ++c) volume_change += pressure_gradient_[k][c] * u_e[c];
      out.data()[row] = in.data()[row] + pressure_stiffness_[k] * volume_change;
    }
    if (!terms) continue;
    const auto stress = condensation_[k].tangent_stress(u_e.data(), n);  // D⁰ B x_u, a lane per point
    for (int p = 0; p < assembly_.geometry(k).points; ++p) {
      const PetscInt offset = viscous_offset(k) + static_cast<PetscInt>(p) * terms * elements::kVoigt;
      for (int i = 0; i < terms; ++i)
        for (int m = 0; m < elements::kVoigt; ++m) {
          const PetscInt row = offset + i * elements::kVoigt + m;
          out.data()[row] = factors.relaxation[i] * (in.data()[row] + factors.rate_gain[i] * stress[m][p]);
        }
    }
  }
}

MechanicsSystem::Resultants MechanicsSystem::resultants(Vec y, const std::vector<std::string>& surfaces) const {
  ReadArray state(y);
  std::vector<double> f_u(displacement_dofs());
  Resultants result;
  if (!assemble_internal(state.data(), nullptr, f_u.data(), nullptr, &result.elastic_energy))
    throw std::runtime_error("reaction forces: inverted element");
  for (const auto& surface : surfaces) {
    const auto faces = mesh_.surface_faces.find(surface);
    if (faces == mesh_.surface_faces.end()) throw std::runtime_error("the mesh has no surface '" + surface + "'");
    std::vector<int> nodes = faces->second;
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    Point3 force{};
    for (int node : nodes)
      if (dofs_.node_dof[node] >= 0)
        for (int c = 0; c < 3; ++c) force[c] += f_u[dofs_.dof(node, c)];
    result.reactions.push_back(force);
  }
  return result;
}

Point3 MechanicsSystem::reaction_force(Vec y, const std::string& surface) const {
  return resultants(y, {surface}).reactions.front();
}

double MechanicsSystem::elastic_energy(Vec y) const { return resultants(y, {}).elastic_energy; }

}  // namespace needlefem::mechanics
