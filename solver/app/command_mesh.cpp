// `needlefem mesh CASE.toml [--out DIR]`: meshes the case's scene and writes
//   DIR/mesh.msh          gmsh mesh (millimetres)
//   DIR/mesh.h5 + .xdmf   the mesh with per-tet region, scaled Jacobian, radius ratio, partition
//   DIR/mesh_report.json  counts per region, Jacobian and quality ranges, tip and cavity volumes,
//                         METIS partition effect, timings, whether the mesh came from the mesh
//                         cache (mesh/mesh_cache.hpp), and the resolved case.
#include <algorithm>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "case/case.hpp"
#include "mesh/mesh_cache.hpp"
#include "model/partition.hpp"
#include "model/scene_model.hpp"
#include "output/result_file.hpp"
#include "output/xdmf_text.hpp"
#include "run/run_case.hpp"
#include "wall_clock/seconds_since.hpp"

namespace needlefem::app {

namespace {

constexpr double kMm3PerM3 = 1e9;

nlohmann::json volume_comparison(double value_m3, double reference_m3) {
  return {{"mm3", value_m3 * kMm3PerM3}, {"relative_difference", (value_m3 - reference_m3) / reference_m3}};
}

nlohmann::json mesh_report(const Case& c, const SceneModel& scene, const Partition& partition, double total_s) {
  nlohmann::json report;
  report["case_file"] = c.origin();
  report["case"] = c.to_json();
  report["msh_file"] = scene.msh_file.string();
  report["user_mesh"] = scene.user_mesh;
  report["mesh_cache"] = mesh_cache_json(scene.info);
  const TetMesh& mesh = scene.mesh;
  report["element"] = mesh.nodes_per_tet == 10 ? "TET10" : "TET4";
  report["nodes"] = mesh.nodes.size();
  report["tets"] = mesh.tet_count();
  for (const auto& [name, q] : scene.quality.regions) report["regions"][name] = to_json(q);
  report["inverted_tets"] = scene.quality.inverted();
  report["cavity_rounding"] = to_json(scene.cavity_rounding);
  for (const auto& [name, faces] : mesh.surface_faces)
    report["surfaces"][name] = faces.size() / static_cast<std::size_t>(mesh.nodes_per_face());
  std::vector<char> in_tissue(mesh.nodes.size(), 0);
  for (std::size_t e = 0; e < mesh.tet_count(); ++e)
    if (mesh.region_names[mesh.tet_region[e]].rfind("tissue", 0) == 0)
      for (int k = 0; k < mesh.nodes_per_tet; ++k) in_tissue[mesh.tet(e)[k]] = 1;
  const auto tissue_nodes = static_cast<std::size_t>(std::count(in_tissue.begin(), in_tissue.end(), 1));
  report["dof_estimate"] = {{"tissue_nodes", tissue_nodes}, {"displacement", 3 * tissue_nodes}};

  const double tissue_volume = scene.quality.volume_of_regions_starting_with("tissue");
  if (!scene.info.needle_description.empty()) {
    const double analytic = scene.info.needle_analytic_volume_m3;
    report["needle"] = {{"description", scene.info.needle_description},
                        {"analytic_volume_mm3", analytic * kMm3PerM3},
                        {"cad_volume", volume_comparison(scene.info.needle_cad_volume_m3, analytic)},
                        // what the mesher carved, before the run rounds the cavity (cavity_rounding)
                        {"cavity_volume_removed_from_mesh",
                         volume_comparison(scene.info.domain_volume_m3 - tissue_volume +
                                               scene.cavity_rounding.tissue_volume_gained_m3, analytic)}};
    if (scene.quality.regions.count("needle"))
      report["needle"]["needle_mesh_volume"] = volume_comparison(scene.quality.regions.at("needle").volume_m3, analytic);
  }
  report["partition"] = {{"parts", partition.parts},
                         {"metis_interface_nodes", partition.interface_nodes},
                         {"naive_interface_nodes", partition.naive_interface_nodes},
                         {"metis_edge_cut", partition.edge_cut},
                         {"max_imbalance", partition.max_imbalance}};
  if (!scene.user_mesh) report["grading"] = to_json(scene.info.grading);
  report["high_order_optimisation"] = scene.info.high_order_optimisation;
  report["seconds"] = {{"meshing", scene.info.seconds}, {"total", total_s}};
  return report;
}

void write_json(const std::filesystem::path& file, const nlohmann::json& json) {
  output::replace_file_atomically(file, json.dump(2) + "\n");
}

void run_mesh(const CaseOptions& options) {
  const auto start = WallClock::now();
  const Case c = Case::load(options.case_file, options.overrides);
  const std::filesystem::path out(options.out_dir);
  std::filesystem::create_directories(out);
  const run::RunSpecs specs = run::parse_run_specs(c);
  const SceneModel scene = run::load_run_scene(specs, out, stderr);
  // The configured part count, or 2 to show what METIS buys when the mesh runs serially.
  const Partition partition = partition_tets(scene.mesh, std::max<int>(2, static_cast<int>(specs.mesh.partitions)));

  {
    output::ResultFile file(out / "mesh.h5", scene.mesh, c.to_toml());
    const output::FieldSpec scaled{"scaled_jacobian", output::FieldCentre::cell, output::FieldType::scalar, "1"};
    const output::FieldSpec ratio{"radius_ratio", output::FieldCentre::cell, output::FieldType::scalar, "1"};
    const output::FieldSpec part{"partition", output::FieldCentre::cell, output::FieldType::scalar, "1"};
    file.write_static_field(scaled, scene.quality.tet_scaled_jacobian);
    file.write_static_field(ratio, scene.quality.tet_radius_ratio);
    const std::vector<double> parts(partition.tet_part.begin(), partition.tet_part.end());
    file.write_static_field(part, parts);
    file.close();
  }
  const double total = seconds_since(start);
  const auto report = mesh_report(c, scene, partition, total);
  write_json(out / "mesh_report.json", report);
  fmt::print("mesh: {} nodes, {} {} tets, {} inverted; written {}\n", scene.mesh.nodes.size(), scene.mesh.tet_count(),
             report["element"].get<std::string>(), scene.quality.inverted(), (out / "mesh_report.json").string());
  if (report.contains("needle"))
    fmt::print("needle: {}; CAD volume {:+.3e} rel., cavity removed from mesh {:+.3e} rel. of analytic\n",
               scene.info.needle_description, report["needle"]["cad_volume"]["relative_difference"].get<double>(),
               report["needle"]["cavity_volume_removed_from_mesh"]["relative_difference"].get<double>());
  require_valid_elements(scene);
}

}  // namespace

void add_mesh_command(CLI::App& app) {
  add_case_command(app, "mesh",
                   "Mesh a case's scene: .msh, HDF5/XDMF view and a JSON mesh report",
                   "out/mesh", run_mesh);
}

}  // namespace needlefem::app
