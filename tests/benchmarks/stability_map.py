#!/usr/bin/python3
"""Benchmark (not a test): where each method of the brain-tip run fails, and how.

1. Locking: the clamped-guided beam of tests/mechanics/test_locking_convergence.cpp
   (cases/locking_beam.toml, `needlefem run`), transverse reaction / (E / 3 mu) normalised to
   K/mu = 10, for K/mu = 10 ... 1e6, TET4 / TET10 displacement / TET10 mixed. E = 9 K mu /
   (3K + mu) takes out the physical change of the bending stiffness; what remains is locking.
2. Steps without error control: the brain-tip run (tip r0.50_a20_f0.25, 1.0 mm core, 0.02 s,
   outputs every 5 ms, other keys at their defaults) with integration.fixed_step_s from 1e-4 to
   5e-3 s (the output interval caps the step), Newton krylov (default) and modified, maxima
   against the adaptive run at the default tolerances on the same mesh file; failure = a failed
   run or a maximum more than 10 % off.
3. Explicit step limit: an explicit central-difference integration (lumped mass, linear elastic
   TET4, Hughes 2000 Sec. 9.1: stable iff dt <= 2 / omega_max) of a 2 mm block of 0.4 mm Kuhn tets,
   bottom face clamped, brain instantaneous moduli (mu = 1052 Pa, K = 1e7 Pa, rho = 1040 kg/m^3),
   started from a random displacement: bounded at 0.98 dt_crit, blown up at 1.02 dt_crit. The
   CFL estimate dt = h_min / c, c = sqrt((K + 4 mu / 3) / rho), is checked against the exact
   2 / omega_max on the block and then evaluated on the paper's 0.4 mm brain-tip mesh (h_min =
   smallest corner-tet altitude of the tissue) and compared with the step sizes IDA takes there.
4. Contact: the brain-tip run (1.0 mm core, 0.02 s, adaptive IDA) over
   contact.penalty_factor x contact.elastic_slip (the return-map friction's allowed elastic slip per
   face size, whose stick stiffness mu p / s0 is the friction's stiffness), each on three mesh
   files (gmsh meshings of the same case with random seeds 1-3, which differ at round-off); outcome completed or
   failed (IDA_CONV_FAIL: Newton failures, step collapse), with the time reached.
5. Newton stop: the same brain-tip run over integration.newton_convergence_coefficient (IDA's
   epcon: Newton stops when its error estimate is below this fraction of the error test's
   tolerance) on the same three meshes.

    tests/benchmarks/stability_map.py --out out/stability [--exe build/needlefem]
Resumable (runs with the same command are not repeated). Writes OUT/stability.json, .png.
"""
import json
import math
import subprocess
from pathlib import Path

import h5py
import matplotlib
import numpy as np
import scipy.linalg

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from bench_runs import ROOT, binary_identity, key_default, point_name, run_case, study_arguments

args = study_arguments(__doc__, "stability", timeout_s=300.0)
BEAM = Path(__file__).resolve().parent / "cases" / "locking_beam.toml"

MU = 1052.0            # Pa, Miller's instantaneous shear modulus (2 (C10 + C01))
BULK = key_default(args.exe, "material.bulk_modulus_pa")   # Pa
DENSITY = 1040.0       # kg/m^3
DEFAULT_PENALTY = key_default(args.exe, "contact.penalty_factor")
DEFAULT_SLIP = key_default(args.exe, "contact.elastic_slip")
DEFAULT_NEWTON_COEFFICIENT = key_default(args.exe, "integration.newton_convergence_coefficient")
BRAIN = {"tissue.core_element_mm": 1.0, "motion.duration_s": 0.02, "output.interval_s": 0.005}
report = {"benchmark": "stability map", "case": str(args.case.relative_to(ROOT)), "binary": binary_identity(args.exe),
          "brain_tip_overrides": BRAIN}


def brain_run(group, overrides):
    name = point_name({key: value for key, value in overrides.items() if key != "scene.mesh_file"}) or "default"
    return run_case(args.case, args.out / group / name, {**BRAIN, **overrides}, exe=args.exe, timeout_s=args.timeout)


def relative_errors(record, reference):
    values = lambda r: {"log_strain": r["max"]["log_strain"], "strain_rate": r["max"]["strain_rate_per_s"],
                        "von_mises": r["max"]["von_mises_pa"], "axial_force": r["needle"]["max_axial_force_n"]}
    got, want = values(record), values(reference)
    return {name: abs(got[name] - want[name]) / abs(want[name]) for name in got}


# 1. Locking --------------------------------------------------------------------------------
RATIOS = [10, 1e2, 1e3, 1e4, 1e5, 1e6]
ELEMENTS = [("TET4", {"mesh.order": 1, "element.formulation": "displacement"}),
            ("TET10 displacement", {"mesh.order": 2, "element.formulation": "displacement"}),
            ("TET10 mixed", {"mesh.order": 2, "element.formulation": "mixed"})]
BEAM_MU = 1000.0
locking = {}
for name, element in ELEMENTS:
    series = []
    for ratio in RATIOS:
        overrides = {**element, "material.bulk_modulus_pa": ratio * BEAM_MU}
        record = run_case(BEAM, args.out / "locking" / point_name(overrides), overrides, exe=args.exe)
        youngs_ratio = 9 * ratio / (3 * ratio + 1) / 3          # E / (3 mu)
        series.append(record["reactions"]["x_max"][2] / youngs_ratio if record["status"] == "completed" else None)
    locking[name] = [None if s is None else s / series[0] for s in series]
    print(f"locking {name:20s} " + " ".join("failed" if s is None else f"{s:.4f}" for s in locking[name]), flush=True)
report["locking"] = {"k_over_mu": RATIOS, "normalised_reaction": locking,
                     "brain_default_k_over_mu": BULK / MU}

# 2. Fixed steps without error control ------------------------------------------------------
def mesh_realisation(name, core_mm, seed):
    """A gmsh mesh of the case with gmsh's random seed `seed` (mesh.seed), written once and
    reused: meshes of other seeds differ at round-off, and on this contact problem that alone can
    decide whether a run completes, so every comparison below runs on three fixed mesh files."""
    directory = args.out / "meshes" / name
    if not (directory / "mesh.msh").exists():
        subprocess.run([args.exe, "mesh", str(args.case), "--out", str(directory),
                        "--set", f"tissue.core_element_mm={core_mm}", "--set", f"mesh.seed={seed}"],
                       check=True, capture_output=True)
    return str(directory / "mesh.msh")


REALISATIONS = [mesh_realisation(name, BRAIN["tissue.core_element_mm"], seed)
                for seed, name in enumerate(("core1.0_a", "core1.0_b", "core1.0_c"), start=1)]
STEPS = [1e-4, 2e-4, 5e-4, 1e-3, 2e-3, 5e-3]      # the output interval (5 ms) caps the step
# The reference needs a mesh on which the adaptive run completes: the first such realisation.
for mesh_file in REALISATIONS:
    on_mesh = {"scene.mesh_file": mesh_file}
    adaptive = run_case(args.case, args.out / "fixed_step" / f"adaptive__{Path(mesh_file).parent.name}",
                        {**BRAIN, **on_mesh}, exe=args.exe, timeout_s=args.timeout)
    if adaptive["status"] == "completed":
        break
fixed = []
for newton in ("krylov", "modified"):
    for step in STEPS:
        record = brain_run("fixed_step", {**on_mesh, "integration.newton": newton, "integration.fixed_step_s": step})
        solver = record.get("solver") or {}
        row = {"newton": newton, "fixed_step_s": step, "status": record["status"], "cpu_s": record["cpu_s"],
               "time_reached_s": record.get("time_reached_s"), "steps": solver.get("steps"),
               "newton_iterations": solver.get("newton_iterations"), "max_pressure_pa": record.get("max", {}).get("pressure_pa")}
        if record["status"] == "completed" and adaptive["status"] == "completed":
            row["errors"] = relative_errors(record, adaptive)
            row["error_max"] = max(row["errors"].values())
        else:
            row["error"] = record.get("error")
        fixed.append(row)
        print(f"fixed step {newton} {step:g} s: {row['status']} error {row.get('error_max', float('nan')):.3g}", flush=True)
report["fixed_step"] = {
    "rows": fixed, "mesh": on_mesh["scene.mesh_file"],
    "reference": "adaptive IDA at the default tolerances on the same mesh (tolerances 1e-6 fail with IDA_CONV_FAIL)",
    "failing": {newton: [r["fixed_step_s"] for r in fixed if r["newton"] == newton and
                         r.get("error_max", math.inf) > 0.10] for newton in ("krylov", "modified")},
    "adaptive_default": {"status": adaptive["status"], "steps": (adaptive.get("solver") or {}).get("steps"),
                         "max_pressure_pa": adaptive["max"].get("pressure_pa")}}
if adaptive["status"] == "completed":
    report["fixed_step"]["adaptive_default"]["mean_step_s"] = 0.02 / adaptive["solver"]["steps"]


# 3. Explicit central differences ------------------------------------------------------------
def kuhn_block(cells, spacing):
    """Nodes and Kuhn tets (6 per cube, all sharing the cube's main diagonal) of a cube of cells^3."""
    n = cells + 1
    grid = np.stack(np.meshgrid(*[np.arange(n)] * 3, indexing="ij"), axis=-1).reshape(-1, 3)
    index = lambda i, j, k: (i * n + j) * n + k
    paths = [(0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)]  # axis order from corner 0 to 7
    tets = []
    for i, j, k in np.ndindex(cells, cells, cells):
        for path in paths:
            corner = [i, j, k]
            tet = [index(*corner)]
            for axis in path:
                corner[axis] += 1
                tet.append(index(*corner))
            tets.append(tet)
    return grid * spacing, np.array(tets)


def min_altitude(points, tets):
    """Smallest altitude 3V / (largest face area) over the tets (corner nodes)."""
    a, b, c, d = (points[tets[:, i]] for i in range(4))
    volume = np.abs(np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a))) / 6
    faces = [(b, c, d), (a, c, d), (a, b, d), (a, b, c)]
    area = np.max([np.linalg.norm(np.cross(q - p, r - p), axis=1) / 2 for p, q, r in faces], axis=0)
    return float(np.min(3 * volume / area))


def tet4_stiffness_and_mass(points, tets, lam, mu, density):
    """Linear elastic TET4 stiffness (B^T D B V) and row-sum lumped mass (rho V / 4 per node)."""
    size = 3 * len(points)
    stiffness = np.zeros((size, size))
    mass = np.zeros(size)
    elasticity = lam * np.outer([1, 1, 1, 0, 0, 0], [1, 1, 1, 0, 0, 0]) + mu * np.diag([2, 2, 2, 1, 1, 1])
    for tet in tets:
        x = points[tet]
        jacobian = np.column_stack([x[1] - x[0], x[2] - x[0], x[3] - x[0]])
        volume = abs(np.linalg.det(jacobian)) / 6
        gradients = np.vstack([-np.ones(3), np.eye(3)]) @ np.linalg.inv(jacobian)   # dN_a/dx, 4 x 3
        strain = np.zeros((6, 12))
        for node, (gx, gy, gz) in enumerate(gradients):
            strain[:, 3 * node:3 * node + 3] = [[gx, 0, 0], [0, gy, 0], [0, 0, gz], [gy, gx, 0], [0, gz, gy], [gz, 0, gx]]
        dofs = (3 * tet[:, None] + np.arange(3)).ravel()
        stiffness[np.ix_(dofs, dofs)] += volume * strain.T @ elasticity @ strain
        mass[dofs] += density * volume / 4
    return stiffness, mass


def central_difference(stiffness, mass, step, count, seed=1):
    """Largest |u| after each step of u'' = -M^-1 K u from a random u0, u'0 = 0."""
    u = np.random.default_rng(seed).standard_normal(len(mass)) * 1e-9
    velocity = -0.5 * step * (stiffness @ u) / mass          # v at t = dt/2
    history = []
    for _ in range(count):
        u = u + step * velocity
        velocity = velocity - step * (stiffness @ u) / mass
        history.append(float(np.max(np.abs(u))))
        if not math.isfinite(history[-1]) or history[-1] > 1.0:
            break
    return history


spacing = 0.4e-3
points, tets = kuhn_block(5, spacing)
stiffness, mass = tet4_stiffness_and_mass(points, tets, BULK - 2 * MU / 3, MU, DENSITY)
free = (points[:, 2] > 1e-12).repeat(3)         # z = 0 face clamped
stiffness, mass = stiffness[np.ix_(free, free)], mass[free]
scaled = stiffness / np.sqrt(np.outer(mass, mass))
omega_max = math.sqrt(scipy.linalg.eigh(scaled, eigvals_only=True, subset_by_index=[len(mass) - 1, len(mass) - 1])[0])
wave_speed = math.sqrt((BULK + 4 * MU / 3) / DENSITY)
critical = 2 / omega_max
block_altitude = min_altitude(points, tets)
runs = {factor: central_difference(stiffness, mass, factor * critical, 3000) for factor in (0.98, 1.02)}
stable_growth = max(runs[0.98]) / runs[0.98][0]

mesh_dir = args.out / "paper_mesh_0.4"
if not (mesh_dir / "mesh.h5").exists():
    subprocess.run([args.exe, "mesh", str(args.case), "--out", str(mesh_dir)], check=True, capture_output=True)
with h5py.File(mesh_dir / "mesh.h5") as mesh:
    coordinates = mesh["mesh/coordinates_mm"][...] * 1e-3
    names = [str(n.decode() if isinstance(n, bytes) else n) for n in mesh["mesh/region"].attrs["names"]]
    region = mesh["mesh/region"][...]
    tissue = np.isin(region, [names.index("tissue_core"), names.index("tissue_outer")])
    paper_tets = mesh["mesh/tets"][...][tissue][:, :4]
paper_altitude = min_altitude(coordinates, paper_tets)
cfl_ratio = critical / (block_altitude / wave_speed)
accuracy_04 = ROOT / "out" / "accuracy_vs_speed" / "runs" / "core_element_mm=0.4" / "run.json"
ida = json.loads(accuracy_04.read_text()) if accuracy_04.exists() else None
ida_mean_step = 0.02 / ida["solver"]["steps"] if ida and ida["status"] == "completed" else None
report["explicit"] = {
    "wave_speed_m_per_s": wave_speed,
    "block": {"cells": 5, "spacing_mm": spacing * 1e3, "min_altitude_mm": block_altitude * 1e3,
              "exact_critical_step_s": critical, "cfl_estimate_s": block_altitude / wave_speed,
              "exact_over_cfl": cfl_ratio,
              "steps_run_at_0.98": len(runs[0.98]), "max_growth_at_0.98": stable_growth,
              "steps_to_blow_up_at_1.02": len(runs[1.02]), "final_amplitude_at_1.02": runs[1.02][-1]},
    "paper_mesh_0.4": {"tissue_tets": int(len(paper_tets)), "min_altitude_mm": paper_altitude * 1e3,
                       "cfl_step_s": paper_altitude / wave_speed,
                       "cfl_step_times_block_ratio_s": cfl_ratio * paper_altitude / wave_speed,
                       "note": "TET4 corner tets; the TET10 element's mid-side nodes lower the limit further"},
    "ida_mean_step_s_0.4_mm": ida_mean_step,
    "ida_steps_0.4_mm": ida["solver"]["steps"] if ida_mean_step else None}
print(f"explicit: c = {wave_speed:.1f} m/s, block dt_crit = {critical:.3e} s (CFL h/c = {block_altitude / wave_speed:.3e}),"
      f" paper mesh h_min = {paper_altitude * 1e3:.4f} mm -> CFL dt = {paper_altitude / wave_speed:.3e} s;"
      f" IDA mean step {ida_mean_step}", flush=True)

# 4. Contact penalty and friction stiffness (elastic slip) -------------------------------------
PENALTIES = [10, 100, 1000, 10000]
SLIPS = [0.0005, 0.005, 0.05]
contact = []
for penalty in PENALTIES:
    for slip in SLIPS:
        outcomes = []
        for index, mesh_file in enumerate(REALISATIONS):
            record = run_case(args.case, args.out / "contact" / f"{point_name({'c': penalty, 'elastic_slip': slip})}__mesh{index}",
                              {**BRAIN, "scene.mesh_file": mesh_file, "contact.penalty_factor": penalty,
                               "contact.elastic_slip": slip}, exe=args.exe, timeout_s=args.timeout)
            solver = record.get("solver") or {}
            outcomes.append({"status": record["status"], "time_reached_s": record.get("time_reached_s"),
                             "steps": solver.get("steps"), "newton_convergence_failures": solver.get("newton_convergence_failures"),
                             "cpu_s": record["cpu_s"], "error": record.get("error")})
        completed = sum(o["status"] == "completed" for o in outcomes)
        contact.append({"penalty_factor": penalty, "elastic_slip": slip, "completed": completed,
                        "runs": outcomes})
        print(f"contact c = {penalty:g}, elastic slip = {slip:g}: {completed}/{len(outcomes)} completed, t reached "
              f"{[o['time_reached_s'] for o in outcomes]}", flush=True)
report["contact"] = {"rows": contact, "meshes": REALISATIONS,
                     "defaults": {"penalty_factor": DEFAULT_PENALTY, "elastic_slip": DEFAULT_SLIP}}

# 5. Newton convergence coefficient -----------------------------------------------------------
COEFFICIENTS = [0.01, 0.03, 0.1, 0.33]
newton_stop = []
for coefficient in COEFFICIENTS:
    outcomes = []
    for index, mesh_file in enumerate(REALISATIONS):
        record = run_case(args.case, args.out / "newton" / f"coefficient={coefficient}__mesh{index}",
                          {**BRAIN, "scene.mesh_file": mesh_file, "integration.newton_convergence_coefficient": coefficient},
                          exe=args.exe, timeout_s=args.timeout)
        outcomes.append({"status": record["status"], "time_reached_s": record.get("time_reached_s"),
                         "steps": (record.get("solver") or {}).get("steps"), "cpu_s": record["cpu_s"],
                         "error": record.get("error")})
    newton_stop.append({"coefficient": coefficient, "completed": sum(o["status"] == "completed" for o in outcomes),
                        "runs": outcomes})
    print(f"Newton coefficient {coefficient:g}: {newton_stop[-1]['completed']}/{len(outcomes)} completed", flush=True)
report["newton_coefficient"] = {"rows": newton_stop, "default": DEFAULT_NEWTON_COEFFICIENT}

args.out.mkdir(parents=True, exist_ok=True)
(args.out / "stability.json").write_text(json.dumps(report, indent=1) + "\n")

# Chart ---------------------------------------------------------------------------------------
figure, axes = plt.subplots(2, 3, figsize=(17, 9))
axis = axes[0, 0]
for name, series in locking.items():
    line, = axis.loglog(RATIOS, [math.nan if s is None else s for s in series], marker="o", label=name)
    for ratio, value in zip(RATIOS, series):
        if value is None:   # failed run: a cross on the K/mu = 10 level
            axis.plot(ratio, 1.0, marker="x", markersize=10, color=line.get_color())
axis.axvline(BULK / MU, color="black", linestyle="--", linewidth=0.8)
axis.text(BULK / MU, 0.5, f" brain default\n K/mu = {BULK / MU:.0f}", fontsize=8, transform=axis.get_xaxis_transform())
axis.set_xlabel("K / mu")
axis.set_ylabel("beam reaction / (E / 3 mu), relative to K/mu = 10\n(> 1: too stiff = locking; x: run failed)")
axis.set_title("1. locking (clamped-guided beam, 0.5 mm elements)", fontsize=10)
axis.legend(fontsize=8)

axis = axes[0, 1]
krylov = [r for r in fixed if r["newton"] == "krylov" and "errors" in r]
for quantity, marker in (("log_strain", "o"), ("strain_rate", "s"), ("von_mises", "^"), ("axial_force", "v")):
    axis.loglog([r["fixed_step_s"] for r in krylov], [max(r["errors"][quantity], 1e-6) for r in krylov], marker=marker,
                label=f"Newton krylov: {quantity}")
modified = [r for r in fixed if r["newton"] == "modified" and "errors" in r]
for quantity, marker in (("strain_rate", "s"), ("von_mises", "^")):
    axis.loglog([r["fixed_step_s"] for r in modified], [max(r["errors"][quantity], 1e-6) for r in modified],
                marker=marker, linestyle="--", color="grey", label=f"Newton modified: {quantity}")
for r in fixed:
    if r["status"] != "completed":
        axis.plot(r["fixed_step_s"], 1.0, marker="x", color="red", markersize=10)
        axis.annotate(f"{r['newton']}: failed at {r['time_reached_s'] * 1e3:.0f} ms", (r["fixed_step_s"], 1.0), fontsize=7,
                      rotation=60, xytext=(0, 5), textcoords="offset points")
axis.axhline(0.10, color="red", linestyle=":", linewidth=0.8, label="10 % error")
default = report["fixed_step"]["adaptive_default"]
if default.get("mean_step_s"):
    axis.axvline(default["mean_step_s"], color="green", linestyle="--", linewidth=0.8,
                 label=f"adaptive IDA (the reference): mean step, {default['steps']} steps")
axis.set_xlabel("step, s")
axis.set_ylabel("relative error of the maximum vs the adaptive run")
axis.set_ylim(1e-4, 30)
axis.set_title("2. steps without error control (1.0 mm core, 0.02 s; x = run failed)", fontsize=10)
axis.legend(fontsize=7, loc="lower right")

axis = axes[1, 0]
for factor, history in runs.items():
    axis.semilogy(np.arange(1, len(history) + 1) * factor * critical * 1e3, history, label=f"dt = {factor} dt_crit")
axis.set_xlabel("time, ms")
axis.set_ylabel("max |u|, m")
explicit = report["explicit"]
axis.set_title("3. explicit central differences (2 mm block, 0.4 mm TET4)", fontsize=10)
text = (f"c = {wave_speed:.0f} m/s; block: dt_crit = {critical:.2e} s = {cfl_ratio:.2f} h_min/c\n"
        f"paper 0.4 mm mesh: h_min = {paper_altitude * 1e3:.3f} mm, h_min/c = {paper_altitude / wave_speed:.1e} s")
if ida_mean_step:
    text += f"\nIDA at 0.4 mm: mean step {ida_mean_step:.1e} s ({ida_mean_step / (paper_altitude / wave_speed):.0f}x)"
axis.text(0.02, 0.97, text, transform=axis.transAxes, fontsize=8, va="top")
axis.legend(fontsize=8, loc="lower right")

axis = axes[1, 1]
colours = {3: "tab:green", 2: "yellowgreen", 1: "tab:orange", 0: "tab:red"}
for row in contact:
    axis.scatter(row["elastic_slip"], row["penalty_factor"], s=90, color=colours[row["completed"]],
                 marker="o" if row["completed"] == len(REALISATIONS) else "X")
    failed = [o["time_reached_s"] for o in row["runs"] if o["status"] != "completed"]
    if failed:
        axis.annotate("/".join(f"{t * 1e3:.0f}" for t in failed) + " ms", (row["elastic_slip"],
                      row["penalty_factor"]), fontsize=7, xytext=(6, -11), textcoords="offset points")
axis.scatter(DEFAULT_SLIP, DEFAULT_PENALTY, s=320, facecolors="none", edgecolors="black", linewidths=1.5)
axis.set_xscale("log")
axis.set_yscale("log")
axis.set_xlabel("elastic slip s0 / h_face (stick stiffness mu p / s0)")
axis.set_ylabel("penalty factor c")
axis.set_title("4. contact (1.0 mm core, 0.02 s, 3 meshes): runs completed green 3/3 ... red 0/3\n"
               "(last output time reached by failed runs); black ring: the defaults", fontsize=9)
axis = axes[0, 2]
for index in range(len(REALISATIONS)):
    cpu = [row["runs"][index]["cpu_s"] for row in newton_stop]
    done = [row["runs"][index]["status"] == "completed" for row in newton_stop]
    axis.semilogx(COEFFICIENTS, cpu, color="grey", linewidth=0.6)
    for coefficient, seconds, ok in zip(COEFFICIENTS, cpu, done):
        axis.plot(coefficient, seconds, marker="o" if ok else "X", color="tab:green" if ok else "tab:red", markersize=8)
axis.axvline(DEFAULT_NEWTON_COEFFICIENT, color="black", linestyle="--", linewidth=0.8)
axis.text(DEFAULT_NEWTON_COEFFICIENT, 0.9, " default", transform=axis.get_xaxis_transform(), fontsize=8)
axis.set_xlabel("integration.newton_convergence_coefficient")
axis.set_ylabel("CPU s of the run (to completion or failure)")
axis.set_title("5. Newton stop (1.0 mm core, 0.02 s, 3 meshes):\ngreen completed, red X failed", fontsize=10)
axes[1, 2].axis("off")
figure.tight_layout()
figure.savefig(args.out / "stability.png", dpi=110)
print(f"written {args.out / 'stability.json'}, .png")
