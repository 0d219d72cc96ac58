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
  const std::size_t points = elements::element_quadrature(mesh.nodes_per_tet).size();
  if (kernel_.prony_terms()) history_per_element_ = points * material::prony_history_size(kernel_.prony().size());
  viscous_history_.assign(history_per_element_ * dofs_.tissue_tets.size(), 0.0);
  accepted_step_ = material::prony_step(kernel_.prony(), 0.0);
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
  std::fill(viscous_history_.begin(), viscous_history_.end(), 0.0);
  history_time_ = t0;
  check(VecSet(y, 0.0), "VecSet");
  check(VecSet(ydot, 0.0), "VecSet");
  WriteArray values(y);
  for (const auto& d : conditions_.dofs) values.data()[d.dof] = conditions_.value(mesh_, d, t0);
}

void MechanicsSystem::differential_mask(Vec id) { check(VecSet(id, 0.0), "VecSet"); }

void MechanicsSystem::absolute_tolerances(Vec atol, double displacement_m, double pressure_pa) const {
  WriteArray values(atol);
  std::fill(values.data(), values.data() + displacement_dofs(), displacement_m);
  std::fill(values.data() + pressure_offset(), values.data() + local_size(), pressure_pa);
}

material::PronyStep MechanicsSystem::prony_step_to(double t) const {
  if (t < history_time_)
    throw std::logic_error(fmt::format("a residual at t = {} s before the last accepted step at {} s", t, history_time_));
  return material::prony_step(kernel_.prony(), t - history_time_);
}

const elements::ViscousStep* MechanicsSystem::viscous_step(std::size_t tissue_element, const material::PronyStep& step,
                                                           elements::ViscousStep& view) const {
  if (!history_per_element_) return nullptr;
  view = {&step, viscous_history_.data() + tissue_element * history_per_element_};
  return &view;
}

const elements::ViscousStep* MechanicsSystem::accepted_viscous_state(std::size_t tissue_element,
                                                                     elements::ViscousStep& view) const {
  return viscous_step(tissue_element, accepted_step_, view);
}

bool MechanicsSystem::assemble_internal(const double* y, const material::PronyStep& step, double* f_u, double* f_p,
                                        double* energy) const {
  const int n = mesh_.nodes_per_tet;
  std::fill(f_u, f_u + displacement_dofs(), 0.0);
  std::atomic<bool> inverted = false;
  std::vector<double> element_energy(energy ? assembly_.elements() : 0);
  assembly_.sum_over_elements(assembly_.elements(), f_u, displacement_dofs(), [&](std::size_t k, double* forces) {
    if (inverted.load(std::memory_order_relaxed)) return;
    std::array<double, elements::kMaxElementDofs> u_e{};
    assembly_.gather(k, y, u_e.data());
    elements::ViscousStep view;
    const elements::ElementResult element =
        kernel_.evaluate(assembly_.geometry(k), u_e.data(), viscous_step(k, step, view), false, element_pressure(y, k));
    if (element.inverted) {
      inverted = true;
      return;
    }
    if (energy) element_energy[k] = element.energy;
    const int* blocks = assembly_.blocks(k);
    for (int a = 0; a < n; ++a)
      for (int c = 0; c < 3; ++c) forces[3 * blocks[a] + c] += element.residual[3 * a + c];
    // F_p = p - U'(θ).
    if (f_p && pressure_unknowns()) f_p[k] = y[pressure_offset() + k] - element.volume_pressure;
  });
  if (energy) *energy = std::accumulate(element_energy.begin(), element_energy.end(), 0.0);
  return !inverted;
}

DaeStatus MechanicsSystem::residual(double t, Vec y, Vec ydot, Vec F) {
  return guarded([&] {
    ReadArray state(y), rate(ydot);
    WriteArray out(F);
    if (!assemble_internal(state.data(), prony_step_to(t), out.data(), out.data() + pressure_offset(), nullptr)) {
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
  ReadArray state(y), rate(ydot);
  if (history_per_element_) {
    const material::PronyStep step = prony_step_to(t);
    const std::size_t per_point = material::prony_history_size(kernel_.prony().size());
    std::atomic<bool> inverted = false;
#pragma omp parallel for schedule(static)
    for (std::size_t k = 0; k < assembly_.elements(); ++k) {
      std::array<double, elements::kMaxElementDofs> u_e{};
      assembly_.gather(k, state.data(), u_e.data());
      elements::ViscousStep view;
      const elements::ElementResult element = kernel_.evaluate(assembly_.geometry(k), u_e.data(),
                                                               viscous_step(k, step, view), false,
                                                               element_pressure(state.data(), k));
      if (element.inverted) {
        inverted = true;
        continue;
      }
      double* history = viscous_history_.data() + k * history_per_element_;
      for (int p = 0; p < assembly_.geometry(k).points; ++p)
        material::advance_history(step, element.points[p].elastic_stress, history + p * per_point);
    }
    // IDA's last Newton update is not checked by a residual: an element it inverted cannot carry
    // a history, and the run stops with the time (the histories are then partly advanced).
    if (inverted)
      throw std::runtime_error(fmt::format("IDA accepted a state at t = {:.9g} s with an inverted tissue element", t));
    history_time_ = t;
  }
  for (const auto& load : surface_loads_) load->accept_step(t, state.data(), rate.data(), dofs_);
}

DaeStatus MechanicsSystem::assemble_condensed(double t, Vec y, Vec ydot, double cj, NewtonMatrix form,
                                              Mat& matrix) {
  matrix = assembly_.matrix();
  {
    ReadArray state(y), rate(ydot);
    const bool inverted = !assemble_condensed_matrix(state.data(), t);
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

bool MechanicsSystem::assemble_condensed_matrix(const double* state, double t) {
  const material::PronyStep step = prony_step_to(t);
  if (pressure_unknowns()) {
    pressure_gradient_.resize(assembly_.elements());
    pressure_stiffness_.resize(assembly_.elements());
  }
  return assembly_.assemble_elements(
      [&](std::size_t k, elements::ElementResult& element) {
        std::array<double, elements::kMaxElementDofs> u_e{};
        assembly_.gather(k, state, u_e.data());
        elements::ViscousStep view;
        element = kernel_.evaluate(assembly_.geometry(k), u_e.data(), viscous_step(k, step, view), true,
                                   element_pressure(state, k));
        if (element.inverted || !pressure_unknowns()) return;
        pressure_gradient_[k] = element.volume_gradient;
        pressure_stiffness_[k] = element.pressure_stiffness;
      },
      nullptr, true);
}

bool MechanicsSystem::newton_matrix_serves(double factored_cj, double cj) const {
  constexpr double kServingTangentChange = 1e-3;
  for (const auto& load : surface_loads_)
    if (load->depends_on_rates()) return false;
  const double factored = material::prony_step(kernel_.prony(), 1.0 / factored_cj).elastic_fraction;
  const double needed = material::prony_step(kernel_.prony(), 1.0 / cj).elastic_fraction;
  return std::abs(factored - needed) <= kServingTangentChange * needed;
}

void MechanicsSystem::condense(Vec b, double /*cj*/, Vec condensed_rhs) {
  const int n = mesh_.nodes_per_tet;
  const PetscInt nu = displacement_dofs();
  ReadArray in(b);
  WriteArray rhs(condensed_rhs);
  double* r = rhs.data();
  std::copy(in.data(), in.data() + nu, r);
  if (!pressure_unknowns()) return;
  // -a_e b_p (the pressure row gives x_p = b_p + (U''/V_e) a_eᵀ x_u).
  assembly_.sum_over_elements(assembly_.elements(), r, nu, [&](std::size_t k, double* sums) {
    const double b_p = in.data()[pressure_offset() + static_cast<PetscInt>(k)];
    const int* blocks = assembly_.blocks(k);
    for (int a = 0; a < n; ++a)
      for (int c = 0; c < 3; ++c) {
        const int dof = 3 * blocks[a] + c;
        if (!prescribed_[dof]) sums[dof] -= pressure_gradient_[k][3 * a + c] * b_p;
      }
  });
}

void MechanicsSystem::expand(Vec b, Vec condensed_solution, double /*cj*/, Vec x) {
  const int n = mesh_.nodes_per_tet;
  const PetscInt nu = displacement_dofs();
  ReadArray in(b), x_u(condensed_solution);
  WriteArray out(x);
  std::copy(x_u.data(), x_u.data() + nu, out.data());
  if (!pressure_unknowns()) return;
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < assembly_.elements(); ++k) {
    std::array<double, elements::kMaxElementDofs> u_e{};
    assembly_.gather(k, x_u.data(), u_e.data());
    const PetscInt row = pressure_offset() + static_cast<PetscInt>(k);
    double volume_change = 0.0;  // a_eᵀ x_u
    for (int c = 0; c < 3 * n; ++c) volume_change += pressure_gradient_[k][c] * u_e[c];
    out.data()[row] = in.data()[row] + pressure_stiffness_[k] * volume_change;
  }
}

MechanicsSystem::Resultants MechanicsSystem::resultants(Vec y, const std::vector<std::string>& surfaces) const {
  ReadArray state(y);
  std::vector<double> f_u(displacement_dofs());
  Resultants result;
  if (!assemble_internal(state.data(), accepted_step_, f_u.data(), nullptr, &result.elastic_energy))
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
