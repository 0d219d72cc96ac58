// A design sweep (SWEEP.toml) expanded into design points.
//
// SWEEP.toml:
//   base = "../table1/r0.50_a20_f0.25.toml"   # the base case, relative to the sweep file
//   [set]                                       # fixed overrides for every point
//   "tissue.core_element_mm" = 0.4
//   [axes]                                      # a grid: the Cartesian product of these lists
//   "needle.radius_mm" = [0.32, 0.5, 0.83]
//   [linked]                                    # lists of equal length that vary together: one axis
//   "motion.insertion_speed_mm_per_s" = [0.5, 1, 2]
//   "motion.rotation_speed_deg_per_s" = [90, 180, 360]
//   [[grid]]                                    # further grids, each with its own set/axes/linked
//   name = "rate-study"
//   set = { "needle.fillet_mm" = 0.25 }
//   linked = { ... }
// The top-level [axes]/[linked] form the grid "main" (when given); the sweep is the union of
// its grids. Keys are case keys (`needlefem keys`), quoted ("needle.radius_mm") or as TOML
// dotted keys; any scalar key may be swept. Files a run reads (scene.mesh_file, needle.cad_file,
// ...) are relative to the file that gives them: the base case or the sweep file.
//
// Each point is base + [set] + its grid's set + its axis values, merged as TOML tables (so
// the point's case gives exactly the keys a hand-written case would) and validated by the
// case loader and the geometry rules (geometry/needle_tip.hpp). Its directory name lists the
// values of every swept key (the keys that any grid varies or sets), each after a short label,
// so points of different grids describing the same case share one directory and one row, and a
// point keeps its name when values are added to an axis (a sweep resumes across such edits).
// A label is the initials of the key's last part without its unit words ("needle.radius_mm" r,
// "needle.bevel_deg" b, "motion.insertion_speed_mm_per_s" is): "r0.5_b20_f0.25_is1_rs180"; keys
// whose initials clash get their words ("radius", "ramp"), then the whole key. The table
// (sweep_table.hpp) has every value in a column of its own; the labels are in plan.name_labels.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geometry/needle_tip.hpp"

namespace needlefem::sweep {

struct DesignPoint {
  std::string name;                       // directory name under the sweep's output folder
  std::vector<std::string> grids;         // grids that contain it
  nlohmann::json values;                  // swept key -> the point's value (resolved when valid)
  std::string case_text;                  // the point's case file (TOML)
  nlohmann::json resolved;                // Case::to_json() of the point: what its summary.json echoes
  std::vector<RuleViolation> violations;  // non-empty: impossible, not run (rule "case" for key errors)
  std::vector<std::string> coarse_mesh;   // how its mesh is coarser than the converged setting (case/mesh_resolution.hpp)
  bool valid() const { return violations.empty(); }
};

struct SweepPlan {
  std::filesystem::path sweep_file;
  std::filesystem::path base_case;
  std::vector<std::string> swept_keys;  // table columns, in order of first appearance
  std::vector<std::string> name_labels; // per swept key, its label in the point names
  std::vector<DesignPoint> points;      // in grid order, each axis varying fastest last
};

// Reads and expands a sweep file. Errors in the sweep file itself (syntax, unknown case keys,
// non-scalar keys, unequal linked lists) throw CaseError "FILE: key 'K': reason"; errors of
// single points are recorded in their violations.
SweepPlan load_sweep(const std::filesystem::path& sweep_file);

// A plan of one axis without a sweep file: the base case with the --set overrides `set`
// ("key=value", validated and typed by the case loader) in every point, and `key` taking the
// value of each point in turn, point i named names[i] (`needlefem converge`: the refinement
// levels). Errors of the base case or of the overrides throw CaseError; plan.sweep_file is empty.
struct AxisPoint {
  std::string name;
  nlohmann::json value;  // a scalar of the key's type
};
SweepPlan plan_axis(const std::filesystem::path& base_case, const std::vector<std::string>& set,
                    const std::string& key, const std::vector<AxisPoint>& points);

}  // namespace needlefem::sweep
