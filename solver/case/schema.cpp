#include "case/schema.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace needlefem {

namespace {

KeySpec make(std::string key, KeyType type, KeyDefault fallback, std::string help, bool input_file = false) {
  KeySpec s;
  s.key = std::move(key);
  s.type = type;
  s.fallback = std::move(fallback);
  s.help = std::move(help);
  s.input_file = input_file;
  return s;
}

KeySpec real(std::string key, KeyDefault fallback, double min, double max, std::string help,
             bool min_exclusive = true) {
  KeySpec s = make(std::move(key), KeyType::Real, std::move(fallback), std::move(help));
  s.min = min;
  s.max = max;
  s.min_exclusive = min_exclusive;
  return s;
}
// `fallback`: a long, or std::monostate for an optional key whose default a parser derives.
KeySpec integer(std::string key, KeyDefault fallback, long min, long max, std::string help) {
  KeySpec s = make(std::move(key), KeyType::Integer, std::move(fallback), std::move(help));
  s.min = static_cast<double>(min);
  s.max = static_cast<double>(max);
  s.min_exclusive = false;
  return s;
}
KeySpec flag(std::string key, bool fallback, std::string help) {
  return make(std::move(key), KeyType::Flag, fallback, std::move(help));
}
KeySpec text(std::string key, std::string fallback, std::string help) {
  return make(std::move(key), KeyType::Text, std::move(fallback), std::move(help));
}
// A file the run reads, relative to the case file (a sweep rebases it in its points' case files).
KeySpec input_file(std::string key, std::string help) { return make(std::move(key), KeyType::Text, "", help, true); }
KeySpec choice(std::string key, std::string fallback, std::vector<std::string> choices, std::string help) {
  KeySpec s = make(std::move(key), KeyType::Choice, std::move(fallback), std::move(help));
  s.choices = std::move(choices);
  return s;
}
// A choice whose values were renamed: the former names still read as the new ones.
KeySpec renamed(KeySpec spec, std::vector<std::pair<std::string, std::string>> aliases) {
  spec.aliases = std::move(aliases);
  return spec;
}
KeySpec reals(std::string key, KeyDefault fallback, std::size_t length, double min, double max,
              std::string help, bool min_exclusive = false) {
  KeySpec s = make(std::move(key), KeyType::RealList, std::move(fallback), std::move(help));
  s.list_length = length;
  s.min = min;
  s.max = max;
  s.min_exclusive = min_exclusive;
  return s;
}

KeySpec names(std::string key, std::string help) {
  return make(std::move(key), KeyType::TextList, std::vector<std::string>{}, std::move(help));
}

const std::vector<std::string> kFaceConditions{"free", "fixed", "roller", "normal-displacement", "displacement"};

KeySpec face(const std::string& name, const std::string& fallback) {
  return choice("block." + name, fallback, kFaceConditions,
                "Condition on the block face " + name +
                    ": free, fixed (all components), roller (normal component zero), "
                    "normal-displacement (normal component of the applied affine field), "
                    "displacement (all components of the applied affine field)");
}

std::vector<KeySpec> build_schema() {
  return {
      // --- scene --------------------------------------------------------------------------
      choice("scene.kind", "brain-tip", {"brain-tip", "block", "mesh"},
             "brain-tip: tissue cube with a needle tip immersed at the entry face (paper 001); "
             "block: a box with per-face conditions for homogeneous verification problems; "
             "mesh: the user's gmsh mesh (scene.mesh_file) with conditions on its named surface groups "
             "([groups], [displacement], [pressure], [obstacle])"),
      input_file("scene.mesh_file",
           "brain-tip: a user-supplied gmsh .msh (millimetres; tets of the order mesh.order gives) with the same "
           "physical names, used instead of generating one. mesh: required; a .msh (millimetres, tets of order "
           "mesh.order) or a gmsh .geo that needlefem meshes at mesh.order with its sizes halved per "
           "mesh.refinement_level; either needs a physical volume \"tissue\" and the surface groups the conditions "
           "name. Relative to the case file"),

      // --- conditions on the named surface groups of the mesh scene (physics/mechanics/dirichlet.hpp)
      names("groups.fixed", "Mesh scene: surface groups held fixed (u = 0)"),
      names("groups.roller",
            "Mesh scene: surface groups that may slide in their plane (u.n = 0); each must be a plane x, y or z = "
            "const. Symmetry planes, and the end faces of a long body, which then deforms in plane strain"),
      names("groups.displaced",
            "Mesh scene: surface groups moved by u = s(t) (F - I) X + d(t) (displacement.gradient, "
            "displacement.translation_mm or translation_history_mm, the load factor of [loading])"),
      names("groups.pressure",
            "Mesh scene: surface groups loaded by the pressure s(t) pressure.value_pa (positive pushes into the "
            "tissue)"),
      reals("displacement.gradient", std::vector<double>{1, 0, 0, 0, 1, 0, 0, 0, 1}, 9, -100.0, 100.0,
            "Mesh scene: final deformation gradient F (row-major) of the affine part s(t) (F - I) X of the "
            "displaced groups' motion"),
      reals("displacement.translation_mm", std::vector<double>{0, 0, 0}, 3, -1e4, 1e4,
            "Mesh scene: final translation d of the displaced groups, reached as s(t) d"),
      reals("displacement.translation_history_mm", std::monostate{}, 0, -1e4, 1e4,
            "Mesh scene: translation of the displaced groups at each loading.history_time_s (x, y, z per time; "
            "linear in between), instead of displacement.translation_mm"),
      real("pressure.value_pa", 0.0, -1e12, 1e12, "Mesh scene: final pressure on groups.pressure, reached as s(t) p",
           false),
      flag("pressure.follower", true,
           "Mesh scene: true, the pressure acts on the deformed area along the deformed normal (a fluid's); "
           "false, a dead load on the reference area along the reference normal"),
      choice("obstacle.kind", "none", {"none", "plane", "sphere", "needle"},
             "Mesh scene: a rigid obstacle in frictional contact ([contact]) with obstacle.group: plane (solid "
             "behind the plane), sphere (solid ball), needle (the [needle] tip moved by [motion], axis along z, "
             "tip towards +z, rear-face centre at obstacle.point_mm; physics/contact/scene_obstacle.hpp). A mesh "
             "scene runs for loading.ramp_s + loading.hold_s: with a needle, set them to cover its motion"),
      text("obstacle.group", "", "Mesh scene: the surface group the obstacle touches"),
      reals("obstacle.point_mm", std::vector<double>{0, 0, 0}, 3, -1e4, 1e4,
            "Obstacle position at t = 0: a point of the plane, the sphere's centre, or the centre of the needle's "
            "rear face"),
      reals("obstacle.normal", std::vector<double>{0, 0, 1}, 3, -1.0, 1.0,
            "Plane obstacle: its outward normal (towards the tissue; normalised)"),
      real("obstacle.radius_mm", 1.0, 0.0, 1e4, "Sphere obstacle: radius"),
      reals("obstacle.velocity_mm_per_s", std::vector<double>{0, 0, 0}, 3, -1e6, 1e6,
            "Plane or sphere obstacle: velocity of its translation"),

      // --- tissue cube of the brain-tip scene -------------------------------------------------
      real("tissue.cube_edge_mm", 12.0, 0.0, 1000.0, "Edge of the tissue cube; the entry face is z = 0"),
      real("tissue.core_width_mm", 3.0, 0.0, 1000.0,
           "Width of the square refined core around the needle axis, through the whole cube"),
      real("tissue.core_element_mm", 0.4, 0.0, 100.0, "Element size inside the core (paper: 0.4)"),
      real("tissue.outer_element_mm", 2.0, 0.0, 100.0, "Element size outside the core (paper: 2)"),
      integer("tissue.curvature_elements", 0, 0, 360,
              "If > 0, refine near curved needle faces to this many elements per 2*pi of curvature "
              "(the paper used none: 0.4 mm everywhere in the core)"),

      // --- needle tip ---------------------------------------------------------------------------
      choice("needle.kind", "bevel", {"bevel", "compliant", "cad"},
             "bevel: cylinder with a bevel plane and a side-profile tip fillet (paper 001); "
             "compliant: magnetised head, thin neck (hinge) and shaft (paper 000); "
             "cad: the tip of needle.cad_file (the cavity carved from it, the contact needle its surface)"),
      input_file("needle.cad_file",
           "needle.kind = \"cad\": the tip as one closed solid in a STEP (.step, .stp), BREP (.brep) or gmsh "
           ".geo (OpenCASCADE) file, in millimetres, axis along +z, tip towards +z, a planar rear face on z = 0 "
           "(flush with the entry face), inside the core. Relative to the case file. Tip families: meshes/tips/"),
      text("needle.export_file", "",
           "Brain-tip scene: when meshing, also write the needle tip as built (any kind, millimetres) to this CAD "
           "file, the format by its extension (.step, .brep): the bevel tip exported so and read back with "
           "needle.kind = \"cad\" is the same shape. Relative to the case file"),
      real("needle.cad_facet_um", 50.0, 0.0, 1000.0,
           "needle.kind = \"cad\": largest facet of the triangulation the contact needle is (inside flat faces, "
           "away from curved edges; curved faces and edges follow needle.cad_facet_deg)"),
      real("needle.cad_facet_deg", 1.5, 0.0, 5.0,
           "needle.kind = \"cad\": angle a facet of the contact needle spans on a curved face (facet = radius x "
           "angle). The contact reads the needle's gap through a smooth spline on a grid of edge radius / 6, "
           "which hides facets finer than that grid (docs/accuracy.md 9)"),
      real("needle.radius_mm", 0.5, 0.0, 100.0, "Needle (shaft and head) radius r"),
      real("needle.bevel_deg", 20.0, 0.0, 90.0,
           "Bevel angle alpha between the bevel plane and the needle axis (ignored when fillet = radius)"),
      real("needle.fillet_mm", 0.25, 0.0, 100.0,
           "Tip fillet radius tau: an arc in the side profile tangent to the bevel line and the opposite "
           "generator; tau = radius gives the fully rounded (hemispherical) biopsy-style tip; 0 = sharp",
           false),
      real("needle.edge_radius_um", 100.0, 0.0, 1000.0,
           "Bevel tip: radius rho of the rounding of the bevel-cylinder and fillet-cylinder edges (capped by the "
           "fillet); CAD tip: of every convex edge. The contact needle is rounded with it (its normal is then continuous where the tissue "
           "presses on an edge) and the mesh is graded to resolve it (element size rho / (mesh.edge_elements_per_radius "
           "x 2^mesh.refinement_level) on the edges). A ground needle's edge radius is a few to some tens of micrometres; the default is "
           "the smallest radius with which the penalty contact's Newton iteration runs the default tip on the "
           "graded mesh (docs/study.md, Edge radius and mesh grading)"),
      real("needle.shaft_mm", 0.1, 0.0, 100.0, "Straight shaft behind the bevel heel (or behind the neck)"),
      real("needle.head_length_mm", 3.5, 0.0, 100.0, "Compliant tip: magnetised head length L (cylinder + cone)"),
      real("needle.neck_length_mm", 1.0, 0.0, 100.0, "Compliant tip: neck (hinge) length l"),
      real("needle.neck_diameter_mm", 0.2, 0.0, 100.0, "Compliant tip: neck diameter d"),
      real("needle.point_length_mm", 0.5, 0.0, 100.0, "Compliant tip: length of the conical point ending the head",
           false),
      flag("needle.deflection_check", false,
           "Brain-tip frictional runs: at every output time, solve the linear-elastic needle tip (region "
           "\"needle\", clamped on its rear face) under the contact loads and report its largest deflection "
           "(summary needle.deflection_check; physics/contact/needle_elasticity.hpp)"),
      real("needle.youngs_modulus_gpa", 200.0, 0.0, 1e4, "Young's modulus of the needle for needle.deflection_check"),
      real("needle.poisson_ratio", 0.29, -1.0, 0.499, "Poisson's ratio of the needle for needle.deflection_check"),
      flag("needle.mesh_volume", true,
           "Also mesh the needle tip volume (region \"needle\", conforming on the cavity): used by the "
           "deformable-needle option; the rigid needle needs only its geometry"),

      // --- block scene ------------------------------------------------------------------------
      reals("block.size_mm", std::vector<double>{1.0, 1.0, 1.0}, 3, 0.0, 1000.0,
            "Block edges along x, y, z; the block spans [0, size] on each axis", true),
      real("block.element_mm", 0.5, 0.0, 1000.0, "Element size in the block"),
      face("x_min", "roller"), face("x_max", "normal-displacement"), face("y_min", "roller"),
      face("y_max", "free"), face("z_min", "roller"), face("z_max", "free"),
      reals("block.applied_gradient", std::vector<double>{1.2, 0, 0, 0, 1, 0, 0, 0, 1}, 9, -100.0, 100.0,
            "Final deformation gradient F (row-major) of the affine field u = s(t) (F - I) X applied on "
            "displacement faces, s(t) rising from 0 to 1 over loading.ramp_s"),

      // --- needle motion (brain-tip) and loading history (block) -------------------------------
      // How long the needle moves is stated once, by one or more of motion.duration_s,
      // motion.insertion_travel_mm and motion.rotation_deg; the speeds are never derived from it
      // (Case::parse resolves motion.duration_s, the key every reader uses).
      real("motion.insertion_speed_mm_per_s", 1.0, 0.0, 1e4, "Needle insertion speed along its axis",
           false),
      real("motion.rotation_speed_deg_per_s", 180.0, -1e6, 1e6,
           "Needle rotation speed about its axis (paper: pi rad/s = 180 deg/s)"),
      real("motion.insertion_travel_mm", std::monostate{}, 0.0, 1e4,
           "How far the needle advances (paper: 0.1 mm); the motion then lasts travel / insertion speed "
           "(+ half of motion.ramp_s), so a changed speed keeps the depth"),
      real("motion.rotation_deg", std::monostate{}, -1e6, 1e6,
           "How far the needle turns, signed like the rotation speed (paper: pi/10 = 18 deg); the motion then "
           "lasts angle / rotation speed (+ half of motion.ramp_s)", false),
      real("motion.duration_s", 0.1, 0.0, 1e6,
           "Duration of the insertion and rotation; follows from motion.insertion_travel_mm or "
           "motion.rotation_deg when one is given (all that are given must agree to 1e-6). A --set or a "
           "sweep value of one of these three replaces the case file's statement of the motion's length"),
      real("motion.ramp_s", 0.0, 0.0, 1e6,
           "Start ramp: the speeds rise smoothly from 0 over this time (smoothstep; the travel loses "
           "speed * ramp / 2). 0 = full speed at t = 0 as in the paper (geometry/needle_motion.hpp)", false),
      real("loading.ramp_s", 1.0, 0.0, 1e6,
           "Block and mesh scenes: time over which the load factor s(t) rises linearly from 0 to 1"),
      real("loading.hold_s", 0.0, 0.0, 1e6,
           "Block and mesh scenes: time the loads are then held (after the last loading.history_time_s if given)",
           false),
      reals("loading.history_time_s", std::monostate{}, 0, 0.0, 1e6,
            "Mesh scene: times (from 0, increasing) of a piecewise-linear load history, instead of the ramp"),
      reals("loading.history_factor", std::monostate{}, 0, -1e6, 1e6,
            "Mesh scene: the load factor s at each loading.history_time_s (scales displacement.gradient, "
            "displacement.translation_mm and pressure.value_pa)"),

      // --- tissue material (physics/material) ------------------------------------------------
      // Hyperelastic constants are INSTANTANEOUS moduli (the elastic response before any Prony
      // relaxation); the key names say so, so long-term moduli are never entered silently.
      choice("material.preset", "miller-brain", {"miller-brain", "miller-brain-c10-c20", "custom"},
             "miller-brain: Miller's brain model, C10 = C01 = 263 Pa, C20 = C02 = 491 Pa (instantaneous), "
             "Prony g = 0.450, 0.365 at tau = 0.5, 50 s; miller-brain-c10-c20: paper 001's literal print "
             "C10 = 263, C20 = 491 Pa with the same Prony series; custom: the c.._instantaneous_pa and "
             "prony_* keys below"),
      choice("material.model", "polynomial", {"polynomial", "corotational-linear"},
             "polynomial: decoupled near-incompressible polynomial (N = 2) hyper-viscoelastic law; "
             "corotational-linear: paper 000's co-rotational linear elastic tissue (youngs_modulus_pa, "
             "poisson_ratio)"),
      real("material.c10_instantaneous_pa", std::monostate{}, -1e9, 1e9,
           "Custom preset: INSTANTANEOUS polynomial coefficient C10 (default 0)", false),
      real("material.c01_instantaneous_pa", std::monostate{}, -1e9, 1e9,
           "Custom preset: INSTANTANEOUS polynomial coefficient C01 (default 0)", false),
      real("material.c20_instantaneous_pa", std::monostate{}, -1e9, 1e9,
           "Custom preset: INSTANTANEOUS polynomial coefficient C20 (default 0)", false),
      real("material.c11_instantaneous_pa", std::monostate{}, -1e9, 1e9,
           "Custom preset: INSTANTANEOUS polynomial coefficient C11 (default 0)", false),
      real("material.c02_instantaneous_pa", std::monostate{}, -1e9, 1e9,
           "Custom preset: INSTANTANEOUS polynomial coefficient C02 (default 0)", false),
      real("material.bulk_modulus_pa", 1.0e7, 0.0, 1e15,
           "Bulk modulus K of the volumetric energy U(J) = K/2 (J - 1)^2 (Abaqus D1 = 2/K); the default "
           "is about 1e4 times Miller's instantaneous shear modulus (1052 Pa)"),
      reals("material.prony_g", std::monostate{}, 0, 0.0, 1.0,
            "Custom preset: Prony relative moduli g_i of the isochoric stress (sum < 1; none = elastic)"),
      reals("material.prony_tau_s", std::monostate{}, 0, 0.0, 1e12,
            "Custom preset: Prony relaxation times tau_i, one per prony_g entry", true),
      real("material.youngs_modulus_pa", 3050.0, 0.0, 1e15,
           "corotational-linear: Young's modulus E (default: 2 mu (1 + nu) with Miller's instantaneous "
           "shear modulus mu = 1052 Pa)"),
      real("material.poisson_ratio", 0.45, -1.0, 0.5, "corotational-linear: Poisson's ratio nu (< 0.5)"),

      // --- mesh options -----------------------------------------------------------------------
      integer("mesh.order", 2, 1, 2, "Element order: 2 = 10-node tets (default), 1 = 4-node tets"),
      flag("mesh.optimize_high_order", true,
           "Run gmsh's high-order optimisation (fixes curved tets next to needle faces)"),
      integer("mesh.partitions", 1, 1, 4096,
              "METIS element partitions (MPI ranks); the mesh report compares their interface size "
              "with a naive split"),
      integer("mesh.seed", 1, 0, 1000000, "Seed of gmsh's random factor, fixed for deterministic meshes"),
      integer("mesh.refinement_level", 0, 0, 4,
              "Mesh refinement near the needle: each level halves every element size near the needle (its "
              "surface and edges; the graded zone keeps its extent), and the block scene's element size; "
              "`needlefem converge` runs three consecutive levels"),
      integer("mesh.edge_elements_per_radius", std::monostate{}, 1, 4,
              "Brain-tip scene, bevel and CAD tips: the element size on the needle's edges at "
              "mesh.refinement_level 0 is max(rho, tissue.core_element_mm / 4) divided by this (rho: "
              "needle.edge_radius_um), halved per level. Not given: 2 on bevels under 15 deg, whose volume above "
              "the strain limit lies along the rounded leading edge and converges only with the rounding "
              "resolved from level 0; 1 (the rounding resolved from level 1 on) on the other tips, where 2 buys no "
              "narrower band (docs/accuracy.md section 14). The mesh report gives the value used"),

      // --- time integration (SUNDIALS IDA) and Newton-matrix solves (PETSc KSP) -------------
      real("integration.relative_tolerance", 3e-4, 0.0, 1.0,
           "IDA relative tolerance of the local error test over displacements and element pressures (also sets "
           "the Newton accuracy)"),
      real("integration.absolute_tolerance", 3e-8, 0.0, 1e6,
           "IDA absolute tolerance of the displacements, m (set for the needle scene's tenths of a millimetre; "
           "lower it for micrometre indentations)"),
      real("integration.pressure_absolute_tolerance_pa", 0.3, 0.0, 1e9,
           "IDA absolute tolerance of the element pressures of element.formulation = \"mixed\", Pa"),
      integer("integration.max_order", 5, 1, 5, "Highest BDF order IDA may use (1 = backward Euler)"),
      real("integration.initial_step_s", 0.0, 0.0, 1e6, "First step size; 0 lets IDA choose", false),
      real("integration.max_step_s", 0.0, 0.0, 1e6, "Largest step size; 0 means unbounded", false),
      integer("integration.max_newton_iterations", 20, 1, 100,
              "Newton iterations per step attempt before IDA cuts the step (IDA's default is 4; contact's "
              "stick/slip and open/close kinks need more; IDA still cuts at once when the iteration diverges)"),
      choice("integration.newton", "krylov", {"modified", "krylov"},
             "Newton linear solves: 'modified' reuses the factored Newton matrix; 'krylov' runs GMRES on the "
             "current Jacobian (difference quotients) preconditioned by the rarely refreshed factorisation"),
      integer("integration.krylov_dimension", 20, 1, 500, "GMRES basis size of integration.newton = krylov"),
      integer("integration.krylov_stale_iterations", 20, 1, 500,
              "integration.newton = krylov: GMRES iterations allowed with a Newton matrix factored in an earlier "
              "step (krylov_dimension with a fresh one); at the limit Newton retries with a fresh matrix. Sliding "
              "friction ages a matrix, so a low limit refactors it at most steps; a tied cavity (no sliding) "
              "does better with a low one (docs/speed.md)"),
      real("integration.krylov_aged_matrix_ratio", 2.0, 0.0, 1000.0,
           "integration.newton = krylov: a Newton matrix from an earlier step is refactored at the next step once a "
           "step it served needed more than this many times the GMRES iterations per Newton iteration of the step "
           "that factored it (0: only when GMRES fails): a matrix kept too long costs more GMRES iterations "
           "than fresh factorisations would (docs/measurements.md, Speed)"),
      real("integration.krylov_tolerance", 0.5, 1e-6, 1.0,
           "integration.newton = krylov: GMRES stops when its residual is below this fraction of the Newton "
           "test's tolerance (IDA's epslin). With the default Newton coefficient (0.05) that is 0.025 of the "
           "error-test tolerance, about as tight as IDA's own defaults (0.05 x 0.33). IDA's Newton test looks "
           "only at the updates, so a much looser solve can end Newton early with a wrong answer (docs/speed.md)"),
      choice("integration.krylov_preconditioner", "exact", {"exact", "symmetric"},
             "integration.newton = krylov: the Newton matrix that preconditions GMRES. 'exact': the matrix itself "
             "(single-precision LU where friction makes it unsymmetric), or 'symmetric' where that LU would not "
             "fit in the machine's memory (then an indefinite part is factored with a raised diagonal); "
             "'symmetric': Cholesky of the symmetric part of the matrix without friction's pressure coupling, "
             "half the factor and solve cost; where that part is indefinite MUMPS LU takes over (docs/speed.md, "
             "Experiments)"),
      real("integration.newton_convergence_coefficient", 0.05, 0.0, 1.0,
           "Newton stops when its error estimate is below this fraction of the error-test tolerance "
           "(IDA's epcon; IDA's own default is 0.33). The strain rate, a safety quantity, comes from IDA's y', "
           "which carries the Newton error divided by the step, so a loose Newton test inflates it and a very "
           "tight one stalls (docs/study.md, How far to trust the strain rate)"),
      real("integration.newton_matrix_cj_change", 0.9, 0.0, 0.99,
           "Refactor the Newton matrix (or preconditioner) when IDA's cj = alpha/h changed by more than this "
           "fraction (IDA's own default 0.25 suits 'modified' on stiff ODEs; the tissue matrix barely depends on cj)",
           false),
      flag("integration.suppress_algebraic_error", false,
           "Leave algebraic unknowns (displacements, pressures) out of the local error test"),
      real("integration.fixed_step_s", std::monostate{}, 0.0, 1e6,
           "Stability studies: steps of exactly this size with the error test switched off "
           "(Newton still converges to the tolerances; needs integration.newton = \"modified\"); absent = "
           "adaptive steps"),
      renamed(choice("integration.linear_solver", "cholesky", {"cholesky", "mumps", "gmres-gamg", "gmres-asm"},
                     "How the Newton matrix is factored. 'cholesky': sparse Cholesky of its symmetric part on the "
                     "free unknowns, in double precision by CHOLMOD where integration.newton = 'modified', in "
                     "single precision on CHOLMOD's ordering where 'krylov' (by LU where friction makes the matrix "
                     "unsymmetric, unless integration.krylov_preconditioner = 'symmetric'), MUMPS LU for a setup "
                     "that it cannot factor; 'mumps': MUMPS LU; 'gmres-gamg', 'gmres-asm': GMRES with AMG or "
                     "additive Schwarz/ILU. Override KSP details after `--` with -nf_ksp_* / -nf_pc_* options. "
                     "'cholmod', its former name, still reads as 'cholesky'"),
              {{"cholmod", "cholesky"}}),
      real("integration.linear_relative_tolerance", 1e-10, 0.0, 1.0,
           "Krylov solvers: relative residual reduction per linear solve"),

      // --- outputs of `needlefem run` (solver/run) ----------------------------------------------
      real("output.interval_s", 0.01, 0.0, 1e6,
           "Time between output times (fields, maxima, reactions); the history ends at motion.duration_s "
           "(brain-tip) or loading.ramp_s (or the last loading.history_time_s) + loading.hold_s (block, mesh), which is "
           "always an output time"),
      real("output.density_kg_per_m3", 1040.0, 0.0, 1e6,
           "Tissue density, used only to report the kinetic energy the quasi-static model neglects "
           "(brain: 1040)"),

      // --- tissue elements (physics/elements) -------------------------------------------------
      choice("element.formulation", "mixed", {"mixed", "displacement"},
             "mixed: mean-dilatation displacement/pressure element (element-constant pressure and "
             "dilatation condensed per element, like Abaqus C3D10H), free of volumetric locking; "
             "displacement: displacement-only element, which locks as K/mu grows (for the locking "
             "study). On 4-node tets both are the same element"),

      // --- needle-tissue contact (physics/contact) ----------------------------------------------
      real("contact.friction_coefficient", 0.5, 0.0, 10.0, "Coulomb friction coefficient mu", false),
      real("contact.penalty_factor", 30.0, 0.0, 1e8,
           "c in the normal penalty eps_N = c mu0 / h_face (mu0: the tissue's instantaneous shear modulus, "
           "h_face: size of each contact face). With the augmented enforcement it only regularises Newton: the "
           "contact loads do not depend on it (docs/accuracy.md), and a stiffer one makes the steps "
           "harder; with the plain penalty the interpenetration is ~ pressure h_face / (c mu0)"),
      choice("contact.normal_enforcement", "augmented", {"augmented", "penalty"},
             "augmented: the penalty acts on the penetration plus a multiplier offset that each accepted step "
             "sets from the last penetration and the multiplier's rate (an augmented Lagrangian whose Uzawa "
             "update is spread over the steps), which closes the penetration; penalty: the plain penalty, whose "
             "interpenetration error moves the contact loads with c (physics/contact/penalty_contact.hpp)"),
      real("contact.penalty_smoothing", 0.25, 0.0, 100.0,
           "s: the normal penalty is smoothed (C1, quadratic) over the first s h_face / c of penetration, "
           "i.e. below the pressure s mu0 / 2; 0 gives the plain kink (physics/contact/penalty_contact.hpp)",
           false),
      real("contact.elastic_slip", 0.005, 0.0, 1.0,
           "Return-map friction: elastic slip s0 per mean contact face size, one s0 per surface (Abaqus's 0.005): "
           "the stick stiffness is mu p / s0 at rest, falling to zero at 2 s0, where the point slides"),
      real("contact.rate_strengthening_s_per_m", 2.0, 0.0, 1e6,
           "Return-map friction: beta in the rate-strengthening traction -beta p v_T added to the Coulomb "
           "traction (friction coefficient mu + beta |v_T| while sliding at v_T)", false),
      choice("contact.friction_law", "return-map", {"return-map", "velocity"},
             "return-map: elastic stick up to contact.elastic_slip and radial return to the Coulomb cone, "
             "anchors updated at each accepted step; velocity: t_T = -mu p v_T / "
             "sqrt(|v_T|^2 + eps_v^2) through IDA's y', which stalls IDA on fine brain-tip meshes "
             "(physics/contact/penalty_contact.hpp)"),
      real("contact.slip_velocity_regularisation_mm_per_s", 1e-2, 0.0, 1e6,
           "Velocity law: eps_v; below the Coulomb limit the interface creeps at ~eps_v instead of sticking "
           "exactly"),
      choice("contact.friction_tangent", "secant", {"secant", "consistent"},
             "Velocity law: friction part of the Newton matrix, secant (robust as the Newton-Krylov "
             "preconditioner) or the consistent linearisation"),
      choice("contact.mode", "frictional", {"frictional", "tied"},
             "Brain-tip scene: frictional = penalty contact with Coulomb friction between the cavity and the "
             "rigid needle (the tissue may slide and separate); tied = cavity nodes moved rigidly with the "
             "needle (no sliding), the earlier model kept for comparison"),

      // --- design limits reported in summary.json (paper 001: 0.19 log strain, 10/s, 120 kPa) ---
      real("thresholds.log_strain", 0.19, 0.0, 100.0, "Limit on the max principal log strain"),
      real("thresholds.strain_rate_per_s", 10.0, 0.0, 1e9, "Limit on the max principal strain rate"),
      real("thresholds.stress_pa", 120000.0, 0.0, 1e12, "Limit on the von Mises stress"),
      real("thresholds.critical_distance_mm", 0.25, 0.001, 10.0,
           "Radius l of the ball over which each limited field is averaged for its mesh-objective "
           "(critical-distance) value. 0.25 mm: a ball 0.5 mm across, far larger than brain cells "
           "(10-20 um) and a needle edge, smaller than the needles (r >= 0.32 mm) and than the "
           "millimetre-scale in-vivo tissue tests behind the limits (paper 001, refs. 15-16); summary.json "
           "also gives the values at l/2 and 2 l (physics/fields/safety_metrics.hpp)"),
      real("thresholds.strain_rate_window_s", 0.01, 1e-5, 10.0,
           "Window over which the strain rate is judged (the rate of the largest principal stretch over it). "
           "0.01 s: the time 10 1/s takes to deliver 10 % strain; diffuse axonal injury is seen at strains over "
           "10 % and rates over 10 1/s together (Rashid et al. 2013, arXiv:1302.4175). Also reported at half "
           "and twice it (physics/fields/strain_rate_window.hpp)"),
      real("thresholds.percentile", 99.0, 1.0, 99.99,
           "Percentile P of each limited field over the region near the needle: the value the hottest "
           "(100 - P) % of that region's volume reaches"),
      real("thresholds.region_mm", 1.0, 0.01, 100.0,
           "The region near the needle for the percentile and the fraction above a limit: tissue within this "
           "distance of the cavity surface (reference configuration; all tissue when there is no cavity)"),

      // --- magnet steering of the compliant needle (steering/, `needlefem steer`, paper 000) ----
      // The needle geometry comes from needle.neck_length_mm, neck_diameter_mm, head_length_mm
      // and radius_mm. The tissue block spans x, y in [-size/2, size/2], z in [0, size_z]; the
      // needle enters at the centre of the z = 0 face along +z; the obstacle sits at the centre.
      real("steering.neck_youngs_modulus_gpa", 200.0, 0.0, 1e4, "Young's modulus of the neck (hinge) material"),
      real("steering.tissue_spring_constant_n_per_m2", 0.0, 0.0, 1e12,
           "Tissue spring constant mu_t per unit length resisting the head's rotation (Eq. 2.4); 0 = none",
           false),
      real("steering.force_angle_deg", 0.0, 0.0, 89.0,
           "Angle phi between the magnetic pull and the head's normal (Eq. 2.7)", false),
      real("steering.max_turning_angle_deg", 45.0, 0.0, 89.0,
           "Largest head turning angle a schedule may give (Eq. 2.7 is a small-rotation model)"),
      real("steering.magnet_residual_flux_density_t", 1.3, 0.0, 10.0,
           "Magnet residual flux density Br (not given in paper 000; N42 NdFeB)"),
      real("steering.magnet_pole_width_mm", 50.0, 0.0, 1e4, "Magnet pole width W (paper: 50)"),
      real("steering.magnet_pole_length_mm", 60.0, 0.0, 1e4, "Magnet pole length L (paper: 60)"),
      real("steering.magnet_thickness_mm", 20.0, 0.0, 1e4,
           "Magnet thickness T along its magnetisation (not given in paper 000)"),
      real("steering.magnet_correction_factor", 0.85, 0.0, 1.0, "Correction factor on Eq. 2.3 (paper: 0.8-0.9)"),
      reals("steering.schedule_depth_mm", std::monostate{}, 0, 0.0, 1e4,
            "Magnet schedule against insertion depth (strictly increasing); give this or schedule_time_s. "
            "Without either there is no magnet and the needle goes straight"),
      reals("steering.schedule_time_s", std::monostate{}, 0, 0.0, 1e6,
            "Magnet schedule against time (strictly increasing; depth = insertion_speed_mm_per_s * time)"),
      reals("steering.magnet_distance_mm", std::monostate{}, 0, 5.0, 5000.0,
            "Magnet pole-face distance to the head at each schedule entry (linear in between, held "
            "beyond the ends); park the magnet far away (e.g. 300 mm) to release the head"),
      reals("steering.pull_azimuth_deg", std::monostate{}, 0, -3600.0, 3600.0,
            "Direction of the pull at each schedule entry: azimuth about the insertion axis z from +x "
            "(the pull acts in the plane normal to the shaft)"),
      real("steering.insertion_depth_mm", 40.0, 0.0, 1e4, "Total insertion depth (length pushed in)"),
      real("steering.insertion_speed_mm_per_s", 1.0, 0.0, 1e4, "Insertion speed (sets the time axis)"),
      real("steering.depth_step_mm", 0.05, 0.0, 100.0, "Depth step of the path integration"),
      reals("steering.block_size_mm", std::vector<double>{30.0, 30.0, 40.0}, 3, 0.0, 1e4,
            "Tissue block edges along x, y, z", true),
      real("steering.obstacle_radius_mm", 4.0, 0.0, 1e4, "Radius of the obstacle sphere at the block's centre"),
      reals("steering.target_mm", std::vector<double>{0.0, 0.0, 34.0}, 3, -1e4, 1e4,
            "Target point (x, y, z) the tip should reach at the end of the insertion"),
      real("steering.target_tolerance_mm", 0.5, 0.0, 1e4,
           "Miss distance below which the summary reports the target as reached"),

      // --- PRBM check of the compliant needle (prbm_check/, `needlefem prbm-check`, paper 000) --
      // Needle geometry from needle.*, its Young's modulus from steering.neck_youngs_modulus_gpa.
      real("prbm_check.poisson_ratio", 0.3, -1.0, 0.5,
           "Poisson's ratio of the needle material (stainless steel: 0.3) in the tip FEM"),
      reals("prbm_check.angles_deg", std::vector<double>{2.0, 5.0, 10.0, 15.0, 20.0, 25.0, 30.0, 40.0}, 0, 0.0, 89.0,
            "PRBM turning angles (Eq. 2.7) whose head loads the FEM solves, follower and dead", true),
      real("prbm_check.element_mm", 0.2, 0.0, 100.0, "Tip FEM element size in the shaft and head"),
      real("prbm_check.neck_element_mm", 0.05, 0.0, 100.0,
           "Tip FEM element size in the neck and one neck diameter beyond its ends"),
      real("prbm_check.tolerance_percent", 5.0, 0.0, 100.0,
           "PRBM-vs-FEM angle error below which the PRBM counts as accurate"),

      // --- insertion-force trajectory (insertion_force/, `needlefem force-trajectory`, paper 000 Eq. 3.2)
      // Needle radius from needle.radius_mm, insertion speed from motion.insertion_speed_mm_per_s.
      input_file("insertion_force.energy_history",
           "history.csv of a `needlefem run` of the brain-tip scene (elastic_energy_j against time_s, with its "
           "summary.json beside it for the run's speed): the deformation stage's U(x); relative to the case file"),
      input_file("insertion_force.energy_case",
           "The case whose `needlefem run` writes energy_history (relative to the case file): while energy_history "
           "does not exist, force-trajectory stops naming the command that makes it"),
      real("insertion_force.extrapolation_warn_factor", 2.0, 1.0, 1e6,
           "Warn when the deformation stage runs beyond this multiple of the energy run's last sample: the force "
           "there is the power-law fit's extrapolation", false),
      real("insertion_force.extrapolation_limit_factor", 10.0, 1.0, 1e6,
           "Refuse a deformation stage beyond this multiple of the energy run's last sample (a longer run samples "
           "it: motion.duration_s of energy_case)", false),
      real("insertion_force.fracture_toughness_j_per_m2", 164.0, 0.0, 1e6,
           "Tissue fracture toughness J_c (paper 000 gives none; default: 164 J/m^2, bovine liver by the same "
           "energy-based needle-insertion method, Gokgol et al. 2012; Azar & Hayward 2008: 76-185 J/m^2)"),
      real("insertion_force.rupture_force_n", std::monostate{}, 0.0, 1e4,
           "Tissue rupture force F_r ending the deformation stage (paper 000: from experiments; required)"),
      real("insertion_force.shaft_friction_n_per_mm", 0.0, 0.0, 1e4,
           "Optional shaft friction per inserted length f_s (force f_s l during penetration); 0 = none", false),
      real("insertion_force.travel_mm", 10.0, 0.0, 1e4, "Total needle (haptic handle) displacement"),
      real("insertion_force.sample_interval_s", 0.001, 0.0, 1e3,
           "Time between trajectory samples (the rupture instant is added)"),
  };
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string type_name(const KeySpec& spec) {
  switch (spec.type) {
    case KeyType::Real: return "real";
    case KeyType::Integer: return "integer";
    case KeyType::Flag: return "true|false";
    case KeyType::Text: return "string";
    case KeyType::Choice: return fmt::format("{}", fmt::join(spec.choices, "|"));
    case KeyType::RealList:
      return spec.list_length ? fmt::format("{} reals", spec.list_length) : std::string("list of reals");
    case KeyType::TextList: return "list of strings";
  }
  return "";
}

std::string default_text(const KeyDefault& value) {
  return std::visit(
      [](const auto& v) -> std::string {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::monostate>) return "none (optional)";
        else if constexpr (std::is_same_v<T, bool>) return v ? "true" : "false";
        else if constexpr (std::is_same_v<T, std::string>) return v.empty() ? "\"\"" : "\"" + v + "\"";
        else if constexpr (std::is_same_v<T, std::vector<double>>) return fmt::format("[{}]", fmt::join(v, ", "));
        else if constexpr (std::is_same_v<T, std::vector<std::string>>) return fmt::format("{}", v);
        else return fmt::format("{}", v);
      },
      value);
}

// The schema stores an unbounded side as +-1e300.
bool has_min(const KeySpec& spec) { return spec.min > -1e299; }
bool has_max(const KeySpec& spec) { return spec.max < 1e299; }

}  // namespace

const std::vector<KeySpec>& case_schema() {
  static const std::vector<KeySpec> schema = build_schema();
  return schema;
}

const std::string& current_choice(const KeySpec& spec, const std::string& value) {
  for (const auto& [former, current] : spec.aliases)
    if (value == former) return current;
  return value;
}

const KeySpec* find_key(const std::string& key) {
  for (const auto& spec : case_schema())
    if (spec.key == key) return &spec;
  return nullptr;
}

std::string closest_key(const std::string& key) {
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(3, key.size() / 4) + 1;
  for (const auto& spec : case_schema()) {
    std::size_t d = edit_distance(key, spec.key);
    if (d < best_distance) {
      best_distance = d;
      best = spec.key;
    }
  }
  return best;
}

std::string range_text(const KeySpec& spec) {
  return fmt::format("{}{}, {}", has_min(spec) ? (spec.min_exclusive ? "(" : "[") : "(",
                     has_min(spec) ? fmt::format("{}", spec.min) : "-inf",
                     has_max(spec) ? fmt::format("{}]", spec.max) : "inf)");
}

std::string describe_key(const KeySpec& spec) {
  std::string range;
  if ((spec.type == KeyType::Real || spec.type == KeyType::Integer || spec.type == KeyType::RealList) &&
      (has_min(spec) || has_max(spec)))
    range = ", range " + range_text(spec);
  return fmt::format("{} ({}{}, default {})\n    {}", spec.key, type_name(spec), range,
                     default_text(spec.fallback), spec.help);
}

}  // namespace needlefem
