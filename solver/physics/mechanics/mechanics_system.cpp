// Equations: mechanics_system.hpp.
#include "physics/mechanics/mechanics_system.hpp"

#include "integration/petsc_arrays.hpp"

#include <algorithm>
#include <atomic>
#include <numeric>
#include <stdexcept>

#include <omp.h>

#include <fmt/format.h>


namespace needlefem::mechanics {

namespace {

void check(PetscErrorCode code, const char* what) {
  if (code != 0) throw std::runtime_error(fmt::format("PETSc error {} in {}", static_cast<int>(code), what));
}

// Runs a DaeSystem callback body: no exception may reach the integrator's C callbacks.
template <class Body>
DaeStatus guarded(Body&& body) noexcept {
  try {
    return body();
  } catch (...) {
    return DaeStatus::fatal;
  }
}


// Runs body(k, out) for every element k = 0..elements-1 on the OpenMP threads, each thread adding
// into its own zeroed copy of `out` (size values) except the first, which adds into `out`; the
// copies are then added to `out` in thread order, the entries shared among the threads. Elements
// sharing a node never race, without a colouring of the mesh, and with the static schedule every
// entry is the same sum in the same order for a given thread count. `copies` (of threads 1, 2,
// ...) persist between calls: allocated afresh, each call's pages would come zeroed from the
// kernel, which showed in profiles (docs/speed.md, "Measurements formerly in code comments").
template <class Body>
void for_each_element_summed(std::size_t elements, double* out, std::size_t size,
                             std::vector<std::vector<double>>& copies, Body&& body) {
#pragma omp parallel
  {
#pragma omp single
    copies.resize(static_cast<std::size_t>(omp_get_num_threads()) - 1);  // implicit barrier
    const auto thread = static_cast<std::size_t>(omp_get_thread_num());
    double* target = out;
    if (thread > 0) {
      copies[thread - 1].assign(size, 0.0);
      target = copies[thread - 1].data();
    }
#pragma omp for schedule(static)
    for (std::size_t k = 0; k < elements; ++k) body(k, target);
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < size; ++i)
      for (const auto& copy : copies) out[i] += copy[i];
  }
}

}  // namespace

MechanicsSystem::MechanicsSystem(const TetMesh& mesh, const material::Material& material,
                                 elements::Formulation formulation, DirichletConditions conditions,
                                 const NewtonMatrixOptions& solver_options)
    : mesh_(mesh), dofs_(tissue_dof_map(mesh)), conditions_(std::move(conditions)), kernel_(material, formulation) {
  const int n = mesh.nodes_per_tet;
  std::vector<double> coordinates(3 * n);
  geometry_.reserve(dofs_.tissue_tets.size());
  for (std::size_t e : dofs_.tissue_tets) {
    for (int a = 0; a < n; ++a)
      for (int c = 0; c < 3; ++c) coordinates[3 * a + c] = mesh.nodes[mesh.tet(e)[a]][c];
    geometry_.push_back(elements::element_geometry(n, coordinates.data()));
  }
  const int points = static_cast<int>(elements::element_quadrature(n).size());
  viscous_per_element_ = static_cast<PetscInt>(points) * kernel_.prony_terms() * elements::kVoigt;
  prescribed_.assign(dofs_.dof_count, 0);
  for (const auto& d : conditions_.dofs) prescribed_[d.dof] = 1;
  create_newton_matrix();
  newton_factor_ = std::make_unique<NewtonMatrixFactor>(prescribed_, solver_options);
  check(VecCreateSeq(PETSC_COMM_SELF, dofs_.dof_count, &rhs_), "VecCreateSeq");
  check(VecDuplicate(rhs_, &solution_), "VecDuplicate");
}

void MechanicsSystem::create_newton_matrix() {
  const int n = mesh_.nodes_per_tet;
  // Block (node) sparsity: nodes sharing a tissue tet, sorted per block row.
  const PetscInt block_rows = dofs_.dof_count / 3;
  std::vector<std::vector<PetscInt>> neighbours(block_rows);
  for (std::size_t e : dofs_.tissue_tets)
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        neighbours[dofs_.node_dof[mesh_.tet(e)[a]] / 3].push_back(dofs_.node_dof[mesh_.tet(e)[b]] / 3);
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  // The pattern is set now, once, as CSR with zero values: every block row's three rows hold
  // the three columns of each neighbour block. Prescribed rows become identity rows without
  // changing it, so the symbolic factorisation is reused from one setup to the next, and
  // setups add element matrices straight into the CSR values from the OpenMP threads
  // (MatSetValues is not thread-safe, and inserting through it by one thread was a measurable
  // part of each setup: docs/speed.md, "Measurements formerly in code comments").
  std::vector<PetscInt> row_start(static_cast<std::size_t>(dofs_.dof_count) + 1, 0), columns;
  for (PetscInt block = 0; block < block_rows; ++block)
    for (int i = 0; i < 3; ++i)
      row_start[3 * block + i + 1] = row_start[3 * block + i] + 3 * static_cast<PetscInt>(neighbours[block].size());
  columns.reserve(static_cast<std::size_t>(row_start.back()));
  for (PetscInt block = 0; block < block_rows; ++block)
    for (int i = 0; i < 3; ++i)
      for (const PetscInt column_block : neighbours[block])
        for (int j = 0; j < 3; ++j) columns.push_back(3 * column_block + j);
  check(MatCreate(PETSC_COMM_SELF, &jacobian_), "MatCreate");
  check(MatSetSizes(jacobian_, dofs_.dof_count, dofs_.dof_count, dofs_.dof_count, dofs_.dof_count), "MatSetSizes");
  check(MatSetType(jacobian_, MATSEQAIJ), "MatSetType");
  check(MatSetBlockSize(jacobian_, 3), "MatSetBlockSize");
  check(MatSeqAIJSetPreallocationCSR(jacobian_, row_start.data(), columns.data(), nullptr),
        "MatSeqAIJSetPreallocationCSR");
  check(MatSetOption(jacobian_, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE), "MatSetOption");
  // Position of entry (3 r_a + i, 3 c_b) in the values, for blocks (a, b) and rows i; the
  // three columns of a block follow it.
  value_positions_.resize(dofs_.tissue_tets.size() * static_cast<std::size_t>(3 * n * n));
  for (std::size_t k = 0; k < dofs_.tissue_tets.size(); ++k) {
    const int* nodes = mesh_.tet(dofs_.tissue_tets[k]);
    for (int a = 0; a < n; ++a) {
      const PetscInt block = dofs_.node_dof[nodes[a]] / 3;
      const auto& list = neighbours[block];
      for (int b = 0; b < n; ++b) {
        const PetscInt offset = 3 * (std::lower_bound(list.begin(), list.end(), dofs_.node_dof[nodes[b]] / 3) - list.begin());
        for (int i = 0; i < 3; ++i) value_positions_[(k * n + a) * 3 * n + 3 * b + i] = row_start[3 * block + i] + offset;
      }
    }
  }
}

MechanicsSystem::~MechanicsSystem() {
  VecDestroy(&solution_);
  VecDestroy(&rhs_);
  MatDestroy(&jacobian_);
}

std::unique_ptr<MechanicsSystem> MechanicsSystem::from_spec(const MechanicsSpec& spec, const TetMesh& mesh,
                                                           const NewtonMatrixOptions& solver_options) {
  const DofMap map = tissue_dof_map(mesh);
  return std::make_unique<MechanicsSystem>(mesh, material::material_from_spec(spec.material), spec.formulation,
                                           scene_conditions(spec.boundary, mesh, map), solver_options);
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

void MechanicsSystem::gather_displacement(const double* y, std::size_t tissue_element, double* u_e) const {
  const int* nodes = mesh_.tet(dofs_.tissue_tets[tissue_element]);
  for (int a = 0; a < mesh_.nodes_per_tet; ++a)
    for (int c = 0; c < 3; ++c) u_e[3 * a + c] = y[dofs_.dof(nodes[a], c)];
}

bool MechanicsSystem::assemble_internal(const double* y, const double* ydot, double* f_u, double* f_q,
                                        double* energy) const {
  const int n = mesh_.nodes_per_tet, terms = kernel_.prony_terms();
  std::fill(f_u, f_u + displacement_dofs(), 0.0);
  std::atomic<bool> inverted = false;
  std::vector<double> element_energy(energy ? geometry_.size() : 0);
  for_each_element_summed(geometry_.size(), f_u, displacement_dofs(), thread_sums_, [&](std::size_t k, double* forces) {
    if (inverted.load(std::memory_order_relaxed)) return;
    std::array<double, elements::kMaxElementDofs> u_e{};
    gather_displacement(y, k, u_e.data());
    const double* q = terms ? y + viscous_offset(k) : nullptr;
    // The viscous rows receive the rates dQ/dt first, laid out like Q.
    double* f_q_element = f_q && terms ? f_q + (viscous_offset(k) - displacement_dofs()) : nullptr;
    const elements::ElementResult element =
        kernel_.evaluate(geometry_[k], u_e.data(), q, false, 1.0, element_pressure(y, k), f_q_element);
    if (element.inverted) {
      inverted = true;
      return;
    }
    if (energy) element_energy[k] = element.energy;
    const int* nodes = mesh_.tet(dofs_.tissue_tets[k]);
    for (int a = 0; a < n; ++a)
      for (int c = 0; c < 3; ++c) forces[dofs_.dof(nodes[a], c)] += element.residual[3 * a + c];
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

void MechanicsSystem::accept_step(double t, Vec y, Vec ydot) {
  newton_factor_->step_accepted();
  if (surface_loads_.empty()) return;
  ReadArray state(y), rate(ydot);
  for (const auto& load : surface_loads_) load->accept_step(t, state.data(), rate.data(), dofs_);
}

DaeStatus MechanicsSystem::setup_jacobian(double t, Vec y, Vec ydot, double cj) {
  return guarded([&] {
    ReadArray state(y), rate(ydot);
    const bool inverted = !assemble_condensed_matrix(state.data(), cj);
    const NewtonMatrix form =
        newton_factor_->wants_symmetric_matrix() ? NewtonMatrix::symmetric_preconditioner : NewtonMatrix::exact;
    if (!inverted)
      for (const auto& load : surface_loads_)
        load->add_jacobian(t, state.data(), rate.data(), cj, dofs_, jacobian_, form);
    check(MatAssemblyBegin(jacobian_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(jacobian_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    if (inverted) {
      ++rejections_.inverted_jacobians;
      return DaeStatus::recoverable;  // assembled anyway: the next setup can zero it
    }
    std::vector<PetscInt> rows;
    rows.reserve(conditions_.dofs.size());
    for (const auto& d : conditions_.dofs) rows.push_back(d.dof);
    check(MatZeroRows(jacobian_, static_cast<PetscInt>(rows.size()), rows.data(), 1.0, nullptr, nullptr),
          "MatZeroRows");
    if (!newton_factor_->factor(jacobian_)) {
      ++rejections_.failed_factorisations;
      return DaeStatus::recoverable;
    }
    cj_ = cj;
    return DaeStatus::ok;
  });
}

bool MechanicsSystem::assemble_condensed_matrix(const double* state, double cj) {
  const int n = mesh_.nodes_per_tet, terms = kernel_.prony_terms();
  const double scale = material::condensed_fraction(kernel_.prony(), cj);
  if (terms) condensation_.resize(geometry_.size());
  if (pressure_unknowns()) {
    pressure_gradient_.resize(geometry_.size());
    pressure_stiffness_.resize(geometry_.size());
  }
  check(MatZeroEntries(jacobian_), "MatZeroEntries");
  std::atomic<bool> inverted = false;
  PetscScalar* values = nullptr;
  check(MatSeqAIJGetArray(jacobian_, &values), "MatSeqAIJGetArray");
  // A batch of element matrices is evaluated on the threads, then added by the threads each
  // owning a range of rows, element by element: every entry sums its elements in mesh order,
  // so the matrix does not depend on the thread count or timing (atomic adds would).
  constexpr std::size_t kBatch = 1024;
  std::vector<elements::ElementResult> batch(kBatch);
  const auto rows = static_cast<std::size_t>(displacement_dofs());
  for (std::size_t first = 0; first < geometry_.size() && !inverted; first += kBatch) {
    const std::size_t count = std::min(kBatch, geometry_.size() - first);
#pragma omp parallel
    {
#pragma omp for schedule(static)
      for (std::size_t e = 0; e < count; ++e) {
        const std::size_t k = first + e;
        std::array<double, elements::kMaxElementDofs> u_e{};
        gather_displacement(state, k, u_e.data());
        const double* q = terms ? state + viscous_offset(k) : nullptr;
        batch[e] = kernel_.evaluate(geometry_[k], u_e.data(), q, true, scale, element_pressure(state, k));
        if (batch[e].inverted) inverted = true;
        if (pressure_unknowns()) {
          pressure_gradient_[k] = batch[e].volume_gradient;
          pressure_stiffness_[k] = batch[e].pressure_stiffness;
        }
      }  // implicit barrier: the batch is complete
      const auto threads = static_cast<std::size_t>(omp_get_num_threads());
      const auto thread = static_cast<std::size_t>(omp_get_thread_num());
      const std::size_t row_begin = rows * thread / threads, row_end = rows * (thread + 1) / threads;
      for (std::size_t e = 0; e < count && !inverted; ++e) {
        const std::size_t k = first + e;
        const int* nodes = mesh_.tet(dofs_.tissue_tets[k]);
        const PetscInt* positions = value_positions_.data() + k * 3 * n * n;
        for (int a = 0; a < n; ++a)
          for (int i = 0; i < 3; ++i) {
            const auto row_index = static_cast<std::size_t>(dofs_.node_dof[nodes[a]] + i);
            if (row_index < row_begin || row_index >= row_end) continue;
            const double* row = batch[e].stiffness.data() + static_cast<std::size_t>(3 * a + i) * 3 * n;
            for (int b = 0; b < n; ++b) {
              PetscScalar* target = values + positions[(a * n + b) * 3 + i];
              for (int j = 0; j < 3; ++j) target[j] += row[3 * b + j];
            }
          }
      }
#pragma omp for schedule(static)
      for (std::size_t e = 0; e < count; ++e) {
        const elements::ElementGeometry& geometry = geometry_[first + e];
        if (terms && !inverted)
          for (int p = 0; p < geometry.points; ++p)
            condensation_[first + e].set_point(p, batch[e].points[p], geometry.gradient_at(p), n, geometry.weight[p]);
      }
    }
  }
  check(MatSeqAIJRestoreArray(jacobian_, &values), "MatSeqAIJRestoreArray");
  return !inverted;
}

bool MechanicsSystem::newton_matrix_serves(double factored_cj, double cj) const {
  constexpr double kServingTangentChange = 1e-3;
  for (const auto& load : surface_loads_)
    if (load->depends_on_rates()) return false;
  const double factored = material::condensed_fraction(kernel_.prony(), factored_cj);
  const double needed = material::condensed_fraction(kernel_.prony(), cj);
  return std::abs(factored - needed) <= kServingTangentChange * needed;
}

DaeStatus MechanicsSystem::solve_jacobian(Vec b, Vec x) {
  return guarded([&] {
    const int n = mesh_.nodes_per_tet, terms = kernel_.prony_terms();
    const auto& prony = kernel_.prony();
    const PetscInt nu = displacement_dofs();
    // J_QQ⁻¹ = 1 / (cj - ∂rate/∂Q) = 1 / (cj + 1/τ_i) and ∂rate/∂S⁰ = g_i / τ_i (PronyTerm).
    std::vector<double> relaxation(terms), rate_gain(terms);
    for (int i = 0; i < terms; ++i) {
      relaxation[i] = 1.0 / (cj_ - prony[i].rate_slope());
      rate_gain[i] = prony[i].rate_gain();
    }
    // Elements with unknowns condensed out of the factored matrix.
    const std::size_t condensed_elements = terms || pressure_unknowns() ? geometry_.size() : 0;
    {
      ReadArray in(b);
      WriteArray rhs(rhs_);
      double* r = rhs.data();
      std::copy(in.data(), in.data() + nu, r);
      for_each_element_summed(condensed_elements, r, nu, thread_sums_, [&](std::size_t k, double* sums) {
        std::array<double, elements::kMaxElementDofs> force{};
        // -a_e b_p (the pressure row gives x_p = b_p + (U''/V_e) a_eᵀ x_u).
        if (pressure_unknowns()) {
          const double b_p = in.data()[pressure_offset() + static_cast<PetscInt>(k)];
          for (int c = 0; c < 3 * n; ++c) force[c] = -pressure_gradient_[k][c] * b_p;
        }
        // Σ_q w_q B_qᵀ Σ_i b_Qi / (cj + 1/τ_i).
        if (terms) {
          std::array<elements::PointLanes, elements::kVoigt> source{};
          for (int p = 0; p < geometry_[k].points; ++p) {
            const double* b_q = in.data() + viscous_offset(k) + static_cast<PetscInt>(p) * terms * elements::kVoigt;
            for (int m = 0; m < elements::kVoigt; ++m) {
              double sum = 0.0;
              for (int i = 0; i < terms; ++i) sum += relaxation[i] * b_q[i * elements::kVoigt + m];
              source[m][p] = static_cast<float>(sum);
            }
          }
          condensation_[k].add_stress_transpose(source, n, force.data());
        }
        const int* nodes = mesh_.tet(dofs_.tissue_tets[k]);
        for (int a = 0; a < n; ++a)
          for (int c = 0; c < 3; ++c) {
            const int dof = dofs_.dof(nodes[a], c);
            if (!prescribed_[dof]) sums[dof] += force[3 * a + c];
          }
      });
    }
    if (!newton_factor_->solve(rhs_, solution_)) {
      ++rejections_.failed_solves;
      return DaeStatus::recoverable;
    }

    ReadArray in(b), x_u(solution_);
    WriteArray out(x);
    std::copy(x_u.data(), x_u.data() + nu, out.data());
#pragma omp parallel for schedule(static)
    for (std::size_t k = 0; k < condensed_elements; ++k) {
      std::array<double, elements::kMaxElementDofs> u_e{};
      gather_displacement(x_u.data(), k, u_e.data());
      if (pressure_unknowns()) {
        const PetscInt row = pressure_offset() + static_cast<PetscInt>(k);
        double volume_change = 0.0;  // a_eᵀ x_u
        for (int c = 0; c < 3 * n; ++c) volume_change += pressure_gradient_[k][c] * u_e[c];
        out.data()[row] = in.data()[row] + pressure_stiffness_[k] * volume_change;
      }
      if (!terms) continue;
      const auto stress = condensation_[k].tangent_stress(u_e.data(), n);  // D⁰ B x_u, a lane per point
      for (int p = 0; p < geometry_[k].points; ++p) {
        const PetscInt offset = viscous_offset(k) + static_cast<PetscInt>(p) * terms * elements::kVoigt;
        for (int i = 0; i < terms; ++i)
          for (int m = 0; m < elements::kVoigt; ++m) {
            const PetscInt row = offset + i * elements::kVoigt + m;
            out.data()[row] = relaxation[i] * (in.data()[row] + rate_gain[i] * stress[m][p]);
          }
      }
    }
    return DaeStatus::ok;
  });
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
