#include "run/run_case.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <stdexcept>

#include <fmt/core.h>
#include <fmt/format.h>

#include "case/case.hpp"
#include "case/mesh_resolution.hpp"
#include "integration/blas_threads.hpp"
#include "integration/options_from_spec.hpp"
#include "integration/ida_integrator.hpp"
#include "integration/petsc_session.hpp"
#include "mesh/mesh_cache.hpp"
#include "interrupt/interrupt_guard.hpp"
#include "io_errors/io_errors.hpp"
#include "model/scene_model.hpp"
#include "output/history_table.hpp"
#include "output/result_file.hpp"
#include "output/xdmf_text.hpp"
#include "physics/fields/tissue_fields.hpp"
#include "physics/contact/needle_contact.hpp"
#include "physics/material/material.hpp"
#include "physics/mechanics/dirichlet.hpp"
#include "physics/mechanics/mechanics_system.hpp"
#include "run/hinge_coupling.hpp"
#include "run/mesh_scene_loads.hpp"
#include "run/needle_output.hpp"
#include "run/output_schedule.hpp"
#include "run/run_model.hpp"
#include "run/safety_report.hpp"
#include "run/software_versions.hpp"
#include "wall_clock/seconds_since.hpp"

namespace needlefem::run {

namespace {

using fields::kScalarQuantities;
constexpr double kMmPerM = 1e3;
constexpr double kStepReportSeconds = 10.0;



double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

// A run owns its output directory: an exclusive flock on the directory itself, held until the
// run ends (the kernel drops it when the process dies, so no stale lock is left behind). Taken
// before anything in the directory is removed or truncated, so a second run into the same --out
// is refused without touching the first run's result.h5 or summary.json.
class OutputDirectoryLock {
 public:
  explicit OutputDirectoryLock(const std::filesystem::path& dir)
      : fd_(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)) {
    if (fd_ < 0) throw std::runtime_error(fmt::format("{}: cannot open the output directory ({})", dir.string(),
                                                      std::strerror(errno)));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      ::close(fd_);
      if (error == EWOULDBLOCK)
        throw std::runtime_error(fmt::format("{}: another run is writing into this output directory; choose another "
                                             "--out or wait until it ends", dir.string()));
      throw std::runtime_error(fmt::format("{}: cannot lock the output directory ({})", dir.string(),
                                           std::strerror(error)));
    }
  }
  ~OutputDirectoryLock() { ::close(fd_); }
  OutputDirectoryLock(const OutputDirectoryLock&) = delete;
  OutputDirectoryLock& operator=(const OutputDirectoryLock&) = delete;

 private:
  int fd_;
};

void write_json_atomically(const std::filesystem::path& file, const nlohmann::json& json) {
  output::replace_file_atomically(file, json.dump(2) + "\n");
}


// Named boundary surfaces that carry tissue dofs: the reaction-force groups.
std::vector<std::string> reaction_surfaces(const TetMesh& mesh, const mechanics::DofMap& dofs) {
  std::vector<std::string> names;
  for (const auto& [name, nodes] : mesh.surface_faces)
    for (int node : nodes)
      if (dofs.node_dof[node] >= 0) {
        names.push_back(name);
        break;
      }
  return names;
}

std::vector<output::FieldSpec> field_specs() {
  using output::FieldCentre, output::FieldType;
  // Lengths in the mesh's millimetres (output/result_file.hpp): Warp By Vector at scale 1 shows
  // the deformation.
  std::vector<output::FieldSpec> specs{{"displacement", FieldCentre::node, FieldType::vector, "mm", kMmPerM},
                                       {"velocity", FieldCentre::node, FieldType::vector, "mm/s", kMmPerM},
                                       {"cauchy_stress", FieldCentre::cell, FieldType::symmetric_tensor, "Pa"}};
  for (const auto& q : fields::scalar_quantities()) specs.push_back({q.name, FieldCentre::cell, FieldType::scalar, q.unit});
  for (const auto& q : fields::scalar_quantities())
    specs.push_back({std::string("max_over_time_") + q.name, FieldCentre::cell, FieldType::scalar, q.unit});
  return specs;
}

// One row per output time; flushed at once so a failed run keeps what it computed.
class HistoryCsv {
 public:
  // extra_header: further columns (each preceded by a comma) whose cells row() gets as text.
  HistoryCsv(const std::filesystem::path& file, const std::vector<std::string>& surfaces,
             const std::string& extra_header)
      : file_(file), stream_(file) {
    if (!stream_) throw std::runtime_error(fmt::format("{}: cannot write: {}", file.string(), io::system_reason(errno)));
    stream_ << fmt::format("{}", fmt::join(output::kHistoryCounterColumns, ","));
    for (const auto& q : fields::scalar_quantities()) {
      const std::string name = fields::history_maximum_column(q);
      stream_ << "," << name << output::history_position_columns(name);
    }
    for (const auto& s : surfaces) stream_ << fmt::format(",reaction_{0}_x_n,reaction_{0}_y_n,reaction_{0}_z_n", s);
    stream_ << ",elastic_energy_j,kinetic_energy_j" << extra_header << "\n";
  }
  void row(double t, const IdaCounters& counters, const fields::TissueFields& f, const std::vector<Point3>& reactions,
           double elastic_energy, const std::string& extra_cells) {
    stream_ << fmt::format("{:.9g},{},{}", t, counters.steps, counters.newton_iterations);
    for (const auto& m : f.maximum)
      stream_ << fmt::format(",{:.9g},{:.6g},{:.6g},{:.6g}", m.value, m.position[0] * kMmPerM,
                             m.position[1] * kMmPerM, m.position[2] * kMmPerM);
    for (const auto& r : reactions) stream_ << fmt::format(",{:.9g},{:.9g},{:.9g}", r[0], r[1], r[2]);
    stream_ << fmt::format(",{:.9g},{:.9g}", elastic_energy, f.kinetic_energy) << extra_cells << "\n";
    if (!stream_.flush())  // a full disk: stop here rather than go on with a history that lacks rows
      throw std::runtime_error(fmt::format("{}: cannot write: {}", file_.string(), io::system_reason(errno)));
  }

 private:
  std::filesystem::path file_;
  std::ofstream stream_;
};

// Everything summary.json reports, filled in as the run proceeds.
struct RunRecord {
  std::array<MaximumOverTime, kScalarQuantities> maxima;
  std::vector<std::string> surfaces;
  std::vector<Point3> reactions;  // at the last completed output time
  double time_reached_s = 0.0;
  std::size_t output_times_written = 0;
  double elastic_energy_j = 0.0;
  double max_kinetic_to_elastic = 0.0;
  IdaCounters counters;
  mechanics::MechanicsSystem::Rejections rejections;
  CondensedDaeSystem::FactorFailures factor_failures;
  NewtonMatrixFactor::Factorisations factorisations;
  IdaIntegrator::InitialRates initial_rates;  // the probe step giving y'(t0)
  long dofs = 0, displacement_dofs = 0;
  double mesh_s = 0.0, integration_s = 0.0, output_s = 0.0;
};

nlohmann::json summary_json(const Case& c, const RunSpecs& specs, const material::Material* material,
                            const SceneModel* scene, const SafetyReport* safety, const RunRecord& record,
                            double wall_s) {
  nlohmann::json s;
  s["case_file"] = c.origin();
  s["status"] = "completed";
  s["time_reached_s"] = record.time_reached_s;
  s["output_times"] = record.output_times_written;
  for (int q = 0; q < kScalarQuantities; ++q)
    if (std::isfinite(record.maxima[q].value)) s["max"][fields::scalar_quantities()[q].summary_key] = record.maxima[q].to_json();
  s["max_note"] = "maximum over all tissue quadrature points and output times; position_mm is the point's "
                  "reference (undeformed) position. strain_rate_per_s is the max principal strain rate, the one the "
                  "strain-rate limit judges; equivalent_strain_rate_per_s, sqrt(2/3 D:D), is not judged (see "
                  "safety.strain_rate_per_s.quantity)";
  for (std::size_t i = 0; i < record.reactions.size(); ++i) {
    const Point3& r = record.reactions[i];
    s["reactions"][record.surfaces[i]] = {r[0], r[1], r[2]};
  }
  if (safety) s.update(safety->summary(record.maxima));
  s["reactions_note"] = "force (N) the supports exert on the tissue nodes of each named surface, at time_reached_s";
  s["energy"] = {{"elastic_j", record.elastic_energy_j}, {"max_kinetic_to_elastic_ratio", record.max_kinetic_to_elastic},
                 {"density_kg_per_m3", specs.output.density_kg_per_m3}};
  s["solver"] = {{"wall_s", wall_s},
                 {"mesh_s", record.mesh_s},
                 {"integration_s", record.integration_s},
                 {"output_s", record.output_s},
                 {"steps", record.counters.steps},
                 {"newton_iterations", record.counters.newton_iterations},
                 {"jacobian_setups", record.counters.jacobian_setups},
                 {"residual_evaluations", record.counters.residual_evaluations},
                 {"error_test_failures", record.counters.error_test_failures},
                 {"newton_convergence_failures", record.counters.newton_convergence_failures},
                 {"linear_iterations", record.counters.linear_iterations},
                 {"stale_matrix_failures", record.counters.stale_matrix_failures},
                 {"stale_matrix_refusals", record.counters.stale_matrix_refusals},
                 {"stale_matrix_aged", record.counters.stale_matrix_aged},
                 {"step_rejections", {{"inverted_element_residuals", record.rejections.inverted_residuals},
                                      {"inverted_element_jacobians", record.rejections.inverted_jacobians},
                                      {"failed_factorisations", record.factor_failures.factorisations},
                                      {"failed_solves", record.factor_failures.solves}}},
                 {"linear_solver", linear_solver_name(specs.integration.linear_solver)},
                 {"blas_kernel", openblas_kernel()},
                 {"factorisations", {{"cholesky", record.factorisations.cholesky},
                                     {"lu", record.factorisations.lu},
                                     {"ksp", record.factorisations.ksp},
                                     {"shifted_cholesky", record.factorisations.shifted},
                                     {"lu_beyond_memory", record.factorisations.lu_beyond_memory},
                                     {"factor_mb", record.factorisations.factor_mb}}},
                 {"initial_rates", {{"converged", record.initial_rates.converged},
                                    {"iterations", record.initial_rates.iterations}}},
                 {"dofs", record.dofs},
                 {"displacement_dofs", record.displacement_dofs},
                 {"peak_rss_mb", peak_rss_mb()}};
  if (material) s["material"] = {{"name", material->name()}, {"description", material->description()}};
  if (scene)
    s["mesh"] = {{"nodes", scene->mesh.nodes.size()},
                 {"tets", scene->mesh.tet_count()},
                 {"element", scene->mesh.nodes_per_tet == 10 ? "TET10" : "TET4"},
                 {"msh_file", scene->msh_file.string()},
                 {"refinement_level", specs.mesh.refinement_level},
                 {"edge_elements_per_radius", scene->info.grading.edge_elements_per_radius},
                 {"needle_edge_element_mm", scene->info.grading.edge_elements.median},
                 {"cache", mesh_cache_json(scene->info)},
                 {"cavity_rounding", to_json(scene->cavity_rounding)}};
  if (const nlohmann::json resolution = mesh_resolution_json(specs.mesh); !resolution.is_null())
    s["mesh_resolution"] = resolution;
  s["files"] = {{"result", "result.h5"}, {"xdmf", "result.xdmf"}, {"history", "history.csv"}};
  s["software"] = software_versions();
  s["case"] = c.to_json();
  return s;
}

// summary.json while the run is under way: replaced by the final summary when it ends.
nlohmann::json running_summary_json(const Case& c) {
  return {{"case_file", c.origin()},
          {"status", "running"},
          {"note", "written when the run started and replaced when it ends; left like this, the run was killed: "
                   "result.h5's /series/time_count counts its complete output times (result.xdmf lists them, or "
                   "one fewer when the kill fell between the two)"},
          {"case", c.to_json()}};
}

void print_progress(std::FILE* stream, double t, double end, const IdaCounters& k, double integration_s) {
  if (!stream) return;
  const double eta = t > 0.0 ? integration_s * (end - t) / t : 0.0;
  fmt::print(stream, "run: t = {:.4g} s ({:3.0f}%)  steps {}  Newton its {}  Jacobians {}  wall {:.1f} s  ETA {:.1f} s\n",
             t, end > 0.0 ? 100.0 * t / end : 100.0, k.steps, k.newton_iterations, k.jacobian_setups, integration_s,
             eta);
  std::fflush(stream);
}

}  // namespace

SceneModel load_run_scene(const RunSpecs& specs, const std::filesystem::path& out_dir,
                          std::FILE* progress, std::shared_ptr<const contact::Needle>* needle) {
  SceneModel scene =
      load_scene_model(specs.mesh, specs.mechanics.boundary.groups, specs.pressure, specs.obstacle, out_dir, progress);
  if (!needle_in_contact(specs)) return scene;
  contact::RoundedCavity rounded = contact::round_cavity_to_needle(run_needle_specs(specs), scene.mesh);
  scene.cavity_rounding = rounded.rounding;
  if (needle) *needle = std::move(rounded.needle);
  if (scene.cavity_rounding.moved_nodes == 0) return scene;
  const double tissue_before = scene.quality.volume_of_regions_starting_with("tissue");
  scene.quality = measure_quality(scene.mesh);
  scene.cavity_rounding.tissue_volume_gained_m3 = scene.quality.volume_of_regions_starting_with("tissue") - tissue_before;
  return scene;
}

namespace {

// The objects a pass's output times write to.
struct PassOutputs {
  const fields::TissueFieldEvaluator& evaluator;
  output::ResultFile& file;
  HistoryCsv& history;
  std::array<std::vector<double>, kScalarQuantities>& max_over_time;  // per tet, over the times so far
};

// One run with the options' head tilt (if any). What the summary reports (the record, the scene,
// the material, the needle and safety reports) outlives the integration's own objects, so that a
// run that fails or is stopped still writes its summary.
class RunPass {
 public:
  RunPass(const Case& c, const RunSpecs& specs, const RunOptions& options) : c_(c), specs_(specs), options_(options) {}

  nlohmann::json run() {
    std::filesystem::create_directories(options_.out_dir);
    const OutputDirectoryLock owned(options_.out_dir);
    const auto summary_file = options_.out_dir / "summary.json";
    // Until the run ends, summary.json says it is running (replacing a stale one), so that a run
    // killed outright (SIGKILL, a power cut) leaves a summary that claims nothing it did not finish.
    write_json_atomically(summary_file, running_summary_json(c_));
    try {
      integrate();
    } catch (const std::exception& e) {
      write_failed_summary(summary_file, e);
      throw;
    }
    nlohmann::json summary = this->summary();
    write_json_atomically(summary_file, summary);
    return summary;
  }

 private:
  void integrate() {
    std::shared_ptr<const contact::Needle> needle;  // the one the cavity was rounded to, untilted
    scene_ = std::make_unique<SceneModel>(load_run_scene(specs_, options_.out_dir, options_.progress, &needle));
    require_valid_elements(*scene_);
    record_.mesh_s = seconds_since(start_);
    stop_if_asked(times_.front());
    const TetMesh& mesh = scene_->mesh;

    const PetscSession petsc(options_.petsc_options);
    material_ = std::make_unique<material::Material>(material::material_from_spec(specs_.mechanics.material));
    const RunModel model = build_run_model(specs_, mesh, *material_, std::move(needle), options_.head_tilt);
    mechanics::MechanicsSystem& system = *model.system;
    if (model.needle)
      needle_ = std::make_unique<NeedleOutput>(specs_.needle_deflection_check, mesh, system, model.needle);
    if (model.pressure || model.obstacle)
      scene_loads_ = std::make_unique<MeshSceneLoads>(system, model.pressure, model.obstacle);
    // The needle's PETSc solvers go before the session does, also when the run fails.
    const struct ReleaseNeedleSolvers {
      NeedleOutput* needle;
      ~ReleaseNeedleSolvers() {
        if (needle) needle->release_solvers();
      }
    } release_needle_solvers{needle_.get()};
    record_.dofs = system.local_size();
    record_.displacement_dofs = system.displacement_dofs();
    record_.surfaces = reaction_surfaces(mesh, system.dof_map());
    const fields::TissueFieldEvaluator evaluator(system, mesh, specs_.output.density_kg_per_m3);
    safety_ = std::make_unique<SafetyReport>(specs_.thresholds, mesh, evaluator);

    std::vector<output::FieldSpec> specs = field_specs();
    if (needle_) for (auto& spec : NeedleOutput::field_specs()) specs.push_back(std::move(spec));
    output::ResultFile file(options_.out_dir / "result.h5", mesh, c_.to_toml(), specs, times_.size());
    HistoryCsv history(options_.out_dir / "history.csv", record_.surfaces,
                       safety_->history_header() + (needle_ ? needle_->history_header() : "") +
                           (scene_loads_ ? scene_loads_->history_header() : ""));
    std::array<std::vector<double>, kScalarQuantities> max_over_time;
    for (auto& cells : max_over_time) cells.assign(mesh.tet_count(), 0.0);
    PassOutputs outputs{evaluator, file, history, max_over_time};

    IdaIntegrator integrator(system, ida_options_from_spec(specs_.integration), times_.front(), PETSC_COMM_SELF);
    prepare_integrator(integrator, system);
    last_report_ = WallClock::now();
    double integration_s = 0.0;
    const double inversion_s = (specs_.mechanics.boundary.scene_kind == SceneKind::block
                                    ? mechanics::block_inversion_time_s(specs_.mechanics.boundary.block)
                                    : std::nullopt)
                                   .value_or(std::numeric_limits<double>::infinity());
    for (const double t : times_) {
      stop_if_asked(integrator.time());
      const auto step_start = WallClock::now();
      if (t >= inversion_s)
        throw c_.error("block.applied_gradient",
                       fmt::format("the applied field turns the block inside out at t = {:.4g} s (det F <= 0); the "
                                   "output times before it are kept", inversion_s));
      try {
        if (t > integrator.time())
          integrator.advance_to(t, [&](double t_step) {
            report_step(integrator, system, t_step);
            if (t_step < t) safety_->observe_step(t_step, integrator.state());
          });
      } catch (const std::exception&) {
        record_solver_counts(integrator, system);  // the failed run's summary shows the failed attempts
        throw;
      }
      integration_s += seconds_since(step_start);
      write_output_time(t, integrator, system, outputs);
      record_.integration_s = integration_s;
      // By the first output every solver has been set up and has solved (the initial-rates
      // probe, the needle's fields): an option after -- that none of them read is a mistake.
      if (t == times_.front()) petsc.require_options_used();
      print_progress(options_.progress, t, times_.back(), record_.counters, integration_s);
    }
    file.close();
  }

  // Absolute tolerances per kind of unknown, and consistent initial rates: the needle starts moving
  // at t0 while the tissue rests, so IDA starts from the rates of a probe step a millionth of the
  // first output interval long (ida_integrator.hpp).
  void prepare_integrator(IdaIntegrator& integrator, const mechanics::MechanicsSystem& system) {
    Vec atol = nullptr;
    petsc_check(VecDuplicate(integrator.state(), &atol), "VecDuplicate");
    const IntegrationSpec& integration = specs_.integration;
    system.absolute_tolerances(atol, integration.absolute_tolerance, integration.pressure_absolute_tolerance_pa);
    integrator.set_absolute_tolerances(atol);
    VecDestroy(&atol);
    if (times_.size() < 2) return;
    const double horizon = times_[1] - times_[0];
    record_.initial_rates = integrator.make_initial_rates_consistent(1e-6 * horizon, horizon);
    if (!record_.initial_rates.converged && options_.progress)
      fmt::print(options_.progress, "run: note: the probe step for consistent initial rates did not converge at "
                 "every unknown (largest weighted update {:.3g}); IDA starts from the tissue at rest, and the rates "
                 "reported at t = 0 are zero\n", record_.initial_rates.last_update);
  }

  // After each accepted step: a stop request ends the run here; long output intervals still report
  // progress, a line per accepted step at most every few seconds.
  void report_step(const IdaIntegrator& integrator, const mechanics::MechanicsSystem& system, double t_step) {
    stop_if_asked(t_step);
    if (!options_.progress || seconds_since(last_report_) < kStepReportSeconds) return;
    last_report_ = WallClock::now();
    const IdaCounters k = integrator.counters();
    const auto& r = system.rejections();
    const auto& f = system.factor_failures();
    fmt::print(options_.progress, "run:   t = {:.6g} s  step {:.3g} s  order {}  steps {}  Newton its {}  "
               "convergence failures {}  error-test failures {}  inverted elements {}+{}  failed solves {}\n",
               t_step, k.last_step, k.last_order, k.steps, k.newton_iterations, k.newton_convergence_failures,
               k.error_test_failures, r.inverted_residuals, r.inverted_jacobians, f.factorisations + f.solves);
    std::fflush(options_.progress);
  }

  void record_solver_counts(const IdaIntegrator& integrator, const mechanics::MechanicsSystem& system) {
    record_.counters = integrator.counters();
    record_.rejections = system.rejections();
    record_.factor_failures = system.factor_failures();
    record_.factorisations = system.factorisations();
  }

  // The fields, maxima, needle loads, reactions and safety metrics at output time t.
  void write_output_time(double t, const IdaIntegrator& integrator, const mechanics::MechanicsSystem& system,
                         PassOutputs& out) {
    const auto output_start = WallClock::now();
    const TetMesh& mesh = scene_->mesh;
    const fields::TissueFields f = out.evaluator.evaluate(integrator.state(), integrator.state_rate());
    std::vector<std::span<const double>> values{f.displacement, f.velocity, f.cauchy_stress};
    for (const auto& cells : f.cell_maximum) values.emplace_back(cells);
    for (int q = 0; q < kScalarQuantities; ++q) {
      for (std::size_t e = 0; e < mesh.tet_count(); ++e)
        out.max_over_time[q][e] = std::max(out.max_over_time[q][e], f.cell_maximum[q][e]);
      values.emplace_back(out.max_over_time[q]);
      record_.maxima[q].update(f.maximum[q].value, t, f.maximum[q].position);
    }
    if (needle_) {
      needle_->evaluate(t, integrator.state(), integrator.state_rate());
      values.emplace_back(needle_->pressure());
      values.emplace_back(needle_->slip());
    }
    out.file.append_time(t, values);
    record_.time_reached_s = t;
    record_.output_times_written = out.file.completed_times();

    auto resultants = system.resultants(integrator.state(), record_.surfaces);
    record_.reactions = std::move(resultants.reactions);
    record_.elastic_energy_j = resultants.elastic_energy;
    if (record_.elastic_energy_j > 0.0)
      record_.max_kinetic_to_elastic = std::max(record_.max_kinetic_to_elastic, f.kinetic_energy / record_.elastic_energy_j);
    record_solver_counts(integrator, system);
    safety_->add_time(t, f);
    out.history.row(t, record_.counters, f, record_.reactions, record_.elastic_energy_j,
                    safety_->history_cells() + (needle_ ? needle_->history_cells() : "") +
                        (scene_loads_ ? scene_loads_->history_cells(t, integrator.state(), integrator.state_rate()) : ""));
    record_.output_s += seconds_since(output_start);
  }

  // A stop request (options.stop) ends the run after the step in progress, keeping every completed
  // output time.
  void stop_if_asked(double t) const {
    if (!options_.stop || !options_.stop->load()) return;
    throw Interrupted(InterruptGuard::signal_number(),
                      fmt::format("stopped by {} at t = {:.6g} s; result.h5 and result.xdmf hold the {} output times "
                                  "completed before", signal_name(InterruptGuard::signal_number()), t,
                                  record_.output_times_written));
  }

  nlohmann::json summary() const {
    nlohmann::json summary =
        summary_json(c_, specs_, material_.get(), scene_.get(), safety_.get(), record_, seconds_since(start_));
    if (needle_) summary.update(needle_->summary());
    return summary;
  }

  void write_failed_summary(const std::filesystem::path& summary_file, const std::exception& e) const {
    nlohmann::json failed = summary();
    failed["status"] = dynamic_cast<const Interrupted*>(&e) ? "interrupted" : "failed";
    failed["error"] = e.what();
    // A run that stopped early can fail a limit but not pass one: the rest of its history is unknown.
    if (failed.value("verdict", "") == "pass") failed["verdict"] = "undecided";
    try {
      write_json_atomically(summary_file, failed);
    } catch (const std::exception& summary_error) {  // a full disk: say both, in one line
      std::error_code ignored;  // "running" would tell of a kill: better no summary than a wrong one
      std::filesystem::remove(summary_file, ignored);
      throw std::runtime_error(fmt::format("{} (and no summary.json: {})", e.what(), summary_error.what()));
    }
  }

  const Case& c_;
  const RunSpecs& specs_;
  const RunOptions& options_;
  const WallClock::time_point start_ = WallClock::now();
  const std::vector<double> times_ = output_times(specs_.output, specs_.loading());  // its case errors before anything is written
  RunRecord record_;
  std::unique_ptr<SceneModel> scene_;
  std::unique_ptr<material::Material> material_;
  std::unique_ptr<NeedleOutput> needle_;
  std::unique_ptr<MeshSceneLoads> scene_loads_;
  std::unique_ptr<SafetyReport> safety_;
  WallClock::time_point last_report_;  // of the last progress line of an accepted step
};

nlohmann::json run_one_pass(const Case& c, const RunSpecs& specs, const RunOptions& options) {
  return RunPass(c, specs, options).run();
}

}  // namespace

nlohmann::json run_case(const Case& c, const RunOptions& options) {
  const RunSpecs specs = parse_run_specs(c);  // its case errors before anything is written
  if (!head_turns_in_tissue(specs)) return run_one_pass(c, specs, options);
  return run_hinged_case(specs, options, [&c](const RunSpecs& pass_specs, const RunOptions& pass_options) {
    return run_one_pass(c, pass_specs, pass_options);
  });
}

}  // namespace needlefem::run
