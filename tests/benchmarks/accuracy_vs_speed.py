#!/usr/bin/python3
"""Benchmark (not a test): accuracy versus speed of the brain-tip run for one tip (paper 001's
r = 0.5 mm, 20 deg, 0.25 mm fillet; frictional needle contact).

Every method runs the same short history, 1 mm/s + 180 deg/s for motion.duration_s = 0.02 s
(outputs every 5 ms), with every other key at its default (`needlefem run` of the case).
Quantities: the four maxima a design study reads from summary.json: max principal log strain,
max principal strain rate, max von Mises stress, max needle axial force. Error of a method =
|q - q_ref| / |q_ref| against the reference run (0.4 mm core, the paper's mesh, TET10 mixed,
default tolerances; the tolerance family shows what tighter ones do); the chart shows the
largest of the error in log strain, von Mises and needle force: the max strain rate has its
own panel because it is dominated by spikes of the rate at single output times (IDA's ydot
after step failures: 99.5 1/s at 15 ms on the 1.0 mm mesh where the neighbouring outputs give
3.7), which no method controls. The reference is the paper's 0.4 mm mesh (its cost under each
version's defaults: docs/measurements.md, "Accuracy versus speed"). The tolerance family also reports its error against the tightest tolerance that
completed on its own mesh (the time-integration error alone).

Method families (one varied setting each, the others at the defaults):
  mesh         TET10 mixed, tissue.core_element_mm 1.0 / 0.7 / 0.5 (and the 0.4 mm reference)
  TET4         mesh.order = 1, core 0.7 / 0.5 / 0.35 / 0.25
  displacement element.formulation = displacement (TET10), core 1.0 / 0.7 / 0.5
  tolerance    integration.relative_tolerance 1e-2 ... 1e-6 at core 0.5, the absolute
               tolerances scaled with it (displacement 1e-4 rtol m, viscous stress and pressure 1e3 rtol Pa,
               the defaults' ratio), all on the very mesh of the mesh family's 0.5 mm run
               (scene.mesh_file): gmsh's meshes differ at round-off from run to run (same
               node and tet counts), which moves the maxima by ~0.2 % at 1.0 mm, more than
               the time-integration error of interest here
  newton       integration.newton_convergence_coefficient 0.1 / 0.03 / 0.01 (a tighter Newton
               stop than the default, IDA's 0.33), at core 0.5 on the same mesh
  corotational material.model = corotational-linear (its defaults: E = 3050 Pa, nu = 0.45,
               elastic; TET10 displacement element, the mixed one needs a volumetric split),
               core 1.0 / 0.7 / 0.5: the error includes the model's difference
If the reference run fails, the finest TET10 mixed run that completed is the reference (the
JSON says which). Its own discretisation error is estimated by Richardson extrapolation through
the three finest completed TET10 mixed runs (q = q* + C h^p, see richardson()), reported only
where the series is monotone with an order in (0.05, 8), otherwise stated as not in the
asymptotic range.

    tests/benchmarks/accuracy_vs_speed.py --out out/accuracy_vs_speed [--exe build/needlefem]
Resumable: runs already done (OUT/runs/<method>/run.json with the same command) are skipped.
Writes OUT/accuracy_vs_speed.csv, .json and .png.
"""
import csv
import json
import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from bench_runs import ROOT, binary_identity, key_default, point_name, run_case, study_arguments

args = study_arguments(__doc__, "accuracy_vs_speed", timeout_s=900.0)

COMMON = {"motion.duration_s": 0.02, "output.interval_s": 0.005}
CORE = "tissue.core_element_mm"
QUANTITIES = {  # column -> (label, how to read it from a run record)
    "log_strain": ("max log strain", lambda r: r["max"]["log_strain"]),
    "strain_rate": ("max strain rate", lambda r: r["max"]["strain_rate_per_s"]),
    "von_mises": ("max von Mises", lambda r: r["max"]["von_mises_pa"]),
    "axial_force": ("max needle axial force", lambda r: r["needle"]["max_axial_force_n"]),
}
SMOOTH = ("log_strain", "von_mises", "axial_force")   # error_max; the strain rate is spike-dominated


def tolerances(rtol):
    return {"integration.relative_tolerance": rtol, "integration.absolute_tolerance": float(f"{rtol * 1e-4:g}"),
            "integration.pressure_absolute_tolerance_pa": float(f"{rtol * 1e3:g}")}


DEFAULT_RTOL = key_default(args.exe, "integration.relative_tolerance")
# A method run is killed after this long (only the reference gets --timeout): 3.5x the default
# 0.5 mm run, where the 0.4 mm mesh is both faster and more accurate; it bounds the study's cost.
METHOD_TIMEOUT_S = 150
MESH_FILE = "scene.mesh_file"
SAME_MESH = args.out / "runs" / "core_element_mm=0.5" / "mesh.msh"   # written by the mesh family's 0.5 mm run
REFERENCE = {CORE: 0.4}
METHODS = (  # (family, label, overrides)
    [("mesh", f"TET10 mixed {h} mm", {CORE: h}) for h in (1.0, 0.7, 0.5)]
    + [("TET4", f"TET4 {h} mm", {CORE: h, "mesh.order": 1}) for h in (0.7, 0.5, 0.35, 0.25)]
    + [("displacement", f"TET10 displacement {h} mm", {CORE: h, "element.formulation": "displacement"})
       for h in (1.0, 0.7, 0.5)]
    + [("tolerance", f"rtol {rtol:g}, 0.5 mm", {CORE: 0.5, MESH_FILE: str(SAME_MESH), **tolerances(rtol)})
       for rtol in (1e-2, 1e-3, 1e-5, 1e-6)]
    + [("newton", f"Newton coefficient {coefficient:g}, 0.5 mm",
        {CORE: 0.5, MESH_FILE: str(SAME_MESH), "integration.newton_convergence_coefficient": coefficient})
       for coefficient in (0.1, 0.03, 0.01)]
    + [("corotational", f"co-rotational {h} mm", {CORE: h, "material.model": "corotational-linear",
                                                   "element.formulation": "displacement"})
       for h in (1.0, 0.7, 0.5)]
    + [("reference", "reference TET10 mixed 0.4 mm", REFERENCE)])

records = []
for family, label, overrides in METHODS:
    out_dir = args.out / "runs" / (point_name({k: v for k, v in overrides.items() if k != MESH_FILE})
                                   + ("__same_mesh" if MESH_FILE in overrides else ""))
    timeout = args.timeout if family == "reference" else min(args.timeout, METHOD_TIMEOUT_S)
    record = run_case(args.case, out_dir, {**COMMON, **overrides}, exe=args.exe, timeout_s=timeout)
    print(f"{label:45s} {record['status']:9s} cpu {record['cpu_s']:8.1f} s", flush=True)
    records.append((family, label, overrides, out_dir, record))

# The reference: the 0.4 mm run, or, when it fails, the finest TET10 mixed run that completed.
series = sorted(((overrides[CORE], record) for family, _, overrides, _, record in records
                 if family in ("mesh", "reference") and record["status"] == "completed"), key=lambda item: -item[0])
if not series:
    raise SystemExit("no TET10 mixed run completed: no reference")
reference_core, reference = series[-1]
reference_note = (f"the {REFERENCE[CORE]} mm reference run" if reference_core == REFERENCE[CORE] else
                  f"the {REFERENCE[CORE]} mm reference run failed ({records[-1][4].get('error')}); the reference is the finest "
                  f"TET10 mixed run that completed, {reference_core} mm")
ref_values = {name: read(reference) for name, (_, read) in QUANTITIES.items()}


def richardson(name):
    """q = q* + C h^p through the three finest completed TET10 mixed runs (h1 > h2 > h3): the
    order p solves (q1 - q2)/(q2 - q3) = (h1^p - h2^p)/(h2^p - h3^p) (bisection), then
    C = (q2 - q3)/(h2^p - h3^p), q* = q3 - C h3^p."""
    if len(series) < 3:
        return {"note": "fewer than three completed meshes"}
    (h1, r1), (h2, r2), (h3, r3) = series[-3:]
    q1, q2, q3 = (QUANTITIES[name][1](r) for r in (r1, r2, r3))
    if (q1 - q2) * (q2 - q3) <= 0:
        return {"cores_mm": [h1, h2, h3], "values": [q1, q2, q3],
                "note": "mesh series not monotone: not in the asymptotic range"}
    ratio = lambda p: (h1 ** p - h2 ** p) / (h2 ** p - h3 ** p)   # increasing in p
    target, low, high = (q1 - q2) / (q2 - q3), 0.05, 8.0
    if not ratio(low) < target < ratio(high):
        return {"cores_mm": [h1, h2, h3], "values": [q1, q2, q3],
                "note": "observed order outside (0.05, 8): not in the asymptotic range"}
    for _ in range(100):
        middle = 0.5 * (low + high)
        low, high = (middle, high) if ratio(middle) < target else (low, middle)
    order = 0.5 * (low + high)
    extrapolated = q3 - (q2 - q3) / (h2 ** order - h3 ** order) * h3 ** order
    return {"cores_mm": [h1, h2, h3], "values": [q1, q2, q3], "order": order, "extrapolated": extrapolated,
            "reference_error": abs(ref_values[name] - extrapolated) / abs(extrapolated)}


rows = []
for family, label, overrides, out_dir, record in records:
    tag = {"tolerance": f"{overrides.get('integration.relative_tolerance')}",
           "newton": f"{overrides.get('integration.newton_convergence_coefficient')}"}.get(family, f"{overrides[CORE]}")
    row = {"family": family, "method": label, "tag": tag, "core_element_mm": overrides[CORE],
           "relative_tolerance": overrides.get("integration.relative_tolerance", DEFAULT_RTOL), "status": record["status"],
           "displacement_dofs": (record.get("solver") or {}).get("displacement_dofs"),
           "dofs": (record.get("solver") or {}).get("dofs"), "steps": (record.get("solver") or {}).get("steps"),
           "cpu_s": record["cpu_s"], "wall_s": (record.get("solver") or {}).get("wall_s", record["process_wall_s"]),
           "run": str(out_dir.relative_to(args.out))}
    for name, (_, read) in QUANTITIES.items():
        value = read(record) if record["status"] == "completed" else None
        row[name] = value
        row[f"error_{name}"] = None if value is None else abs(value - ref_values[name]) / abs(ref_values[name])
    errors = [row[f"error_{n}"] for n in SMOOTH]
    row["error_max"] = None if None in errors else max(errors)
    if record["status"] != "completed":
        row["error"] = record.get("error")
    rows.append(row)

# Time-integration error alone: each tolerance on the 0.5 mm mesh against the tightest one that
# completed there.
same_mesh = [r for r in rows if r["status"] == "completed" and
             (r["family"] in ("tolerance", "newton") or r["method"] == "TET10 mixed 0.5 mm")]
tightest = min((r for r in same_mesh if r["family"] != "newton"), key=lambda r: r["relative_tolerance"])
for row in same_mesh:
    row["error_max_vs_tightest_tolerance_same_mesh"] = max(abs(row[n] - tightest[n]) / abs(tightest[n]) for n in SMOOTH)

report = {"benchmark": "accuracy versus speed, brain-tip scene with frictional needle contact",
          "case": str(args.case.relative_to(ROOT)), "binary": binary_identity(args.exe),
          "common_overrides": COMMON, "reference": REFERENCE,
          "error_definition": "|q - q_ref| / |q_ref| per maximum; error_max = the largest over " + ", ".join(SMOOTH)
                              + " (the strain rate is spike-dominated, see error_strain_rate)",
          "time_note": "cpu_s: user+system CPU time of the single-threaded run process (its wall time on an idle "
                       "core); wall_s: the run's own wall time on the shared, loaded machine",
          "reference_values": ref_values, "reference_note": reference_note,
          "tightest_completed_tolerance_on_0.5_mm": tightest["method"],
          "reference_richardson": {name: richardson(name) for name in QUANTITIES},
          "rows": rows}
args.out.mkdir(parents=True, exist_ok=True)
(args.out / "accuracy_vs_speed.json").write_text(json.dumps(report, indent=1) + "\n")
columns = list(dict.fromkeys(key for row in rows for key in row))
with open(args.out / "accuracy_vs_speed.csv", "w", newline="") as f:
    writer = csv.DictWriter(f, fieldnames=columns)
    writer.writeheader()
    writer.writerows(rows)

STYLE = {"mesh": ("o", "tab:blue"), "TET4": ("s", "tab:orange"), "displacement": ("^", "tab:red"),
         "tolerance": ("D", "tab:green"), "newton": ("P", "tab:olive"), "corotational": ("v", "tab:purple")}
figure = plt.figure(figsize=(12, 5.5))
grid = figure.add_gridspec(2, 4)
panels = [(figure.add_subplot(grid[:, :2]), "error_max", "largest error of max log strain, von Mises, needle force")]
for index, name in enumerate(QUANTITIES):
    panels.append((figure.add_subplot(grid[index // 2, 2 + index % 2]), f"error_{name}",
                   QUANTITIES[name][0] + ("" if name in SMOOTH else " (spikes)")))
for axis, column, title in panels:
    for family, (marker, colour) in STYLE.items():
        points = [(r["cpu_s"], r[column], r["tag"]) for r in rows if r["family"] == family and r[column]]
        failures = sum(r["family"] == family and r["status"] != "completed" for r in rows)
        label = family + (f" ({failures} failed)" if failures else "")
        axis.loglog([p[0] for p in points], [p[1] for p in points], marker=marker, color=colour, linestyle="-",
                    linewidth=0.8, label=label)
        if column == "error_max":
            for x, y, text in points:
                axis.annotate(text, (x, y), fontsize=7, xytext=(3, 3), textcoords="offset points")
    top = axis.get_ylim()[1]
    for r in rows:   # failed runs: a cross at the top, at the CPU time they took to fail
        if r["family"] in STYLE and r["status"] != "completed":
            axis.plot(r["cpu_s"], top, marker="x", color=STYLE[r["family"]][1], markersize=8, clip_on=False)
    axis.axvline(reference["cpu_s"], color="black", linestyle="--", linewidth=0.8)
    axis.set_title(title, fontsize=10 if column == "error_max" else 8)
    axis.tick_params(labelsize=7)
    axis.grid(True, which="both", linewidth=0.3)
panels[0][0].set_xlabel("run time, s (CPU time of the single-threaded run)")
panels[0][0].set_ylabel("relative error of the maximum vs reference")
panels[0][0].legend(fontsize=8, title="labels: core mm / rtol / Newton coefficient\n"
                    "x at the top: run failed; dashed: reference run time", title_fontsize=7)
figure.suptitle(f"Accuracy vs speed, r = 0.5 mm / 20 deg / 0.25 mm tip, {COMMON['motion.duration_s']} s of "
                f"insertion + rotation (reference: {reference_core} mm TET10 mixed, rtol 1e-4)", fontsize=10)
figure.tight_layout()
figure.savefig(args.out / "accuracy_vs_speed.png", dpi=120)
print(f"written {args.out / 'accuracy_vs_speed.csv'}, .json, .png")
