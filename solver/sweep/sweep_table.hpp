// What a sweep's output folder says about its design points, and the summary table built
// from it: DIR/sweep.csv and DIR/sweep.h5, one row per design point of the plan (so every
// point appears exactly once, whatever ran when), both written atomically (temporary file
// renamed over the old one) under an exclusive lock on DIR/.sweep.lock, so that sweep
// processes started by an MPI launcher can each rewrite them.
//
// Columns: point (directory), grids, one column per swept key (the point's value), status
// (completed | failed | pending | impossible), the maxima of the run's summary.json
// (max.log_strain, max.strain_rate_per_s, max.von_mises_pa, max.principal_stress_pa), the
// needle's largest axial force, torque and lateral force (summary "needle", when the run reports it),
// the mesh-objective metrics of each limit (summary "safety", run/safety_report.hpp):
// critical_distance_<limit>, volume_above_<limit>_mm3, percentile_<limit>, verdict_<limit>
// (1 pass, 0 fail, empty/-1 unknown: the critical-distance value against the limit) and verdict
// (the run's summary "verdict": 0 when any limit fails, 1 when all pass), coarse_mesh (how the
// point's mesh is coarser than the setting the convergence study found adequate, "; "-separated,
// empty when it is not: case/mesh_resolution.hpp; such verdicts may change with the mesh),
// pass_<threshold> (the point maxima, as paper 001 judged; 1 pass, 0 fail, empty/-1 unknown) and
// safe (all those pass), dofs,
// wall_s (the run's own wall time), time_reached_s, rules (violated geometry rules) and error.
//
// Thresholds: a run's summary "thresholds" when present (an object or list of entries, each a
// boolean or an object with a boolean "pass"/"passed"/"safe"/"ok", or "value" and "limit");
// otherwise paper 001's limits on the maxima: log strain 0.19, strain rate 10 1/s and
// von Mises stress 120 kPa.
//
// HDF5 layout of sweep.h5: one 1-D dataset per column at the root, named as the CSV column
// (float64 with NaN for empty, int8 for verdict, verdict_*, pass_* and safe with -1 for unknown, UTF-8 strings);
// root attributes "columns" (the column order), "sweep_file", "base_case" and
// "format" = "needlefem-sweep-table".
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "sweep/sweep_plan.hpp"

namespace needlefem::sweep {

struct PointRecord {
  std::string status;      // completed, failed, pending or impossible
  nlohmann::json summary;  // the run's summary.json (null unless completed or failed)
  std::string error;
};

std::filesystem::path point_directory(const std::filesystem::path& out_dir, const DesignPoint& point);

// A point counts as run only when DIR/<point>/summary.json echoes the point's own case.
PointRecord read_point(const DesignPoint& point, const std::filesystem::path& out_dir);


// Writes `text` to `file` through a temporary file renamed over it.
void write_file_atomically(const std::filesystem::path& file, const std::string& text);

void write_tables(const SweepPlan& plan, const std::filesystem::path& out_dir);

}  // namespace needlefem::sweep
