#!/usr/bin/python3
"""Benchmark (not a test): paper 001's study at the paper's density (cases/sweeps/paper001_study.toml:
the seven Table I tips and the slow/medium/fast rate study, frictional contact, 0.4 mm core), timed.

With --levels 1 (default) the study is one `needlefem sweep`; OUT/bench_study.json holds, per
design point: status, wall time, steps, Newton iterations, Jacobian setups (= factorisations),
GMRES iterations, peak memory and DOF (from each run's summary.json), and the study's wall time
against its targets.

With --levels 3 every design gets its error band: `needlefem converge` on mesh.refinement_level
0, 1, 2 (OUT/<design>/level_<L>/, converge.csv/json beside them), --jobs designs at a time with
one thread each, shortest first (a study stopped early then has the most designs done). OUT/study_bands.csv then has, per design and metric, the three
levels' values, the observed order, the GCI band and the verdict, and bench_study.json the
per-level work and the targets of issue 24 (3 min per design, 20 min for the study, 2 cores).

    tests/benchmarks/bench_study.py [--exe build/needlefem] [--jobs 2] [--levels 1|3] [--out out/bench_study]

Resumable: completed runs are not run again and their recorded wall times are kept, so a resumed
study's total is the sum over the calls, not one measurement; start from an empty OUT for a timing.
"""
import argparse
import concurrent.futures
import csv
import json
import os
import subprocess
import time
import tomllib
from pathlib import Path

from machine import describe_machine, use_blas_environment

ROOT = Path(__file__).resolve().parents[2]
TARGETS_S = {1: {"per_case_s": 30.0, "study_s": 300.0}, 3: {"per_case_s": 180.0, "study_s": 1200.0}}
SHORT_KEYS = {"needle.radius_mm": "r", "needle.bevel_deg": "a", "needle.fillet_mm": "f",
              "motion.insertion_speed_mm_per_s": "v"}
BAND_METRICS = [
    f"safety.{limit}.{measure}" for limit in ("log_strain", "strain_rate_per_s", "stress_pa")
    for measure in ("critical_distance", "critical_distance_half_radius", "critical_distance_double_radius",
                    "percentile", "volume_above_limit_mm3", "point_max")
] + ["needle.max_axial_force_n", "needle.max_torque_n_m"]

parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
parser.add_argument("--exe", default=str(ROOT / "build" / "needlefem"))
parser.add_argument("--sweep", type=Path, default=ROOT / "cases" / "sweeps" / "paper001_study.toml")
parser.add_argument("--jobs", type=int, default=2, help="runs (or designs, with --levels 3) at a time; 2 cores")
parser.add_argument("--levels", type=int, choices=(1, 3), default=1,
                    help="1: the study at the case's mesh; 3: every design through three refinement levels")
parser.add_argument("--out", type=Path, default=ROOT / "out" / "bench_study")
args = parser.parse_args()
use_blas_environment(args.exe)


def solver_record(summary):
    """Work and size of one run, from its summary.json."""
    solver = summary["solver"]
    return {
        "status": summary.get("status"), "time_reached_s": summary.get("time_reached_s"),
        "wall_s": solver["wall_s"], "steps": solver["steps"], "newton_iterations": solver["newton_iterations"],
        "jacobian_setups": solver["jacobian_setups"], "gmres_iterations": solver["linear_iterations"],
        "newton_convergence_failures": solver["newton_convergence_failures"],
        "peak_rss_mb": solver["peak_rss_mb"], "dofs": solver["dofs"], "tets": summary["mesh"].get("tets"),
    }


def read_summary(directory):
    summary_file = directory / "summary.json"
    return json.loads(summary_file.read_text()) if summary_file.exists() else None


def sweep_study():
    """The study as one sweep at the case's mesh; returns (wall, exit code, points)."""
    start = time.perf_counter()
    sweep = subprocess.run([args.exe, "sweep", str(args.sweep), "--out", str(args.out), "--jobs", str(args.jobs)])
    wall = time.perf_counter() - start
    points = []
    with (args.out / "sweep.csv").open() as table:
        for row in csv.DictReader(table):
            point = {"point": row["point"], "grid": row["grids"], "status": row["status"]}
            summary = read_summary(args.out / row["point"])
            if summary:
                point.update(solver_record(summary))
            points.append(point)
    return wall, sweep.returncode, points


def design_points():
    """The sweep's design points as (short name, grid, {key: value}) from `needlefem sweep --list`."""
    plan_dir = args.out / "plan"
    subprocess.run([args.exe, "sweep", str(args.sweep), "--out", str(plan_dir), "--list"], check=True,
                   stdout=subprocess.DEVNULL)
    designs = []
    with (plan_dir / "sweep.csv").open() as table:
        reader = csv.DictReader(table)
        keys = reader.fieldnames[reader.fieldnames.index("grids") + 1:reader.fieldnames.index("status")]
        for row in reader:
            values = {key: row[key] for key in keys}
            name = "_".join(f"{SHORT_KEYS[key]}{values[key]}" for key in SHORT_KEYS if key in values)
            designs.append((name, row["grids"], values))
    return designs


def converge_design(design):
    """`needlefem converge` of one design, one thread per run; returns (name, exit code, wall)."""
    name, _, values = design
    command = [args.exe, "converge", str(args.sweep.parent / base_case()), "--out", str(args.out / name), "--jobs", "1"]
    for key, value in values.items():
        command += ["--set", f"{key}={value}"]
    environment = dict(os.environ, OMP_NUM_THREADS="1")
    start = time.perf_counter()
    with open(args.out / f"{name}.log", "w") as log:
        result = subprocess.run(command, stdout=log, stderr=subprocess.STDOUT, env=environment)
    return name, result.returncode, time.perf_counter() - start


def base_case():
    with args.sweep.open("rb") as sweep_file:
        return tomllib.load(sweep_file)["base"]


def expected_work(design):
    """Expected cost: the slow rate case's history is twice as long, larger needles mesh finer."""
    values = design[2]
    return float(values.get("motion.duration_s", 0.1)) * float(values.get("needle.radius_mm", 0.5))


def converged_study():
    """Every design through three levels; returns (wall, exit code, points) and writes study_bands.csv."""
    designs = sorted(design_points(), key=expected_work)
    start = time.perf_counter()
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        finished = list(pool.map(converge_design, designs))
    wall = time.perf_counter() - start
    exit_codes = {name: code for name, code, _ in finished}
    command_walls = {name: seconds for name, _, seconds in finished}

    points, band_rows = [], []
    for name, grid, values in designs:
        levels = [solver_record(s) if (s := read_summary(level)) else {"level": level.name, "status": "missing"}
                  for level in sorted((args.out / name).glob("level_*"))]
        point = {"point": name, "grid": grid, "values": values, "exit_code": exit_codes[name],
                 "command_wall_s": command_walls[name], "levels": levels,
                 "levels_wall_s": sum(level.get("wall_s", 0.0) for level in levels)}
        table_file = args.out / name / "converge.json"
        if table_file.exists():
            report = json.loads(table_file.read_text())
            point["verdicts"] = report.get("verdicts")
            for row in report.get("metrics", []):
                if row.get("metric") in BAND_METRICS:
                    band_rows.append({"design": name, "grid": grid, **values, "metric": row["metric"],
                                      "values": " / ".join(f"{v:.6g}" for v in row.get("values", [])),
                                      "behaviour": row.get("behaviour"), "observed_order": row.get("observed_order"),
                                      "gci_fine": row.get("gci_fine"), "verdict": row.get("verdict")})
        points.append(point)
    if band_rows:
        with (args.out / "study_bands.csv").open("w", newline="") as table:
            writer = csv.DictWriter(table, fieldnames=list(band_rows[0]))
            writer.writeheader()
            writer.writerows(band_rows)
    return wall, max(exit_codes.values(), default=0), points


args.out.mkdir(parents=True, exist_ok=True)
study_wall, exit_code, points = sweep_study() if args.levels == 1 else converged_study()
case_walls = [p["wall_s"] if args.levels == 1 else p["command_wall_s"] for p in points
              if ("wall_s" if args.levels == 1 else "command_wall_s") in p]
targets = TARGETS_S[args.levels]
report = {
    "benchmark": f"paper 001 study at the 0.4 mm core (frictional contact), {args.levels} refinement level(s)",
    "sweep": str(args.sweep.relative_to(ROOT)) if args.sweep.is_relative_to(ROOT) else str(args.sweep),
    "jobs": args.jobs,
    "levels": args.levels,
    "machine": describe_machine(),
    "exit_code": exit_code,
    "study_wall_s": study_wall,
    "case_wall_s": {"min": min(case_walls, default=None), "max": max(case_walls, default=None),
                    "mean": sum(case_walls) / len(case_walls) if case_walls else None},
    "targets": {**targets, "study_met": exit_code == 0 and study_wall <= targets["study_s"],
                "cases_met": sum(1 for w in case_walls if w <= targets["per_case_s"]), "cases": len(points)},
    "points": points,
}
(args.out / "bench_study.json").write_text(json.dumps(report, indent=2) + "\n")
print(f"study {study_wall:.0f} s (target {targets['study_s']:.0f} s), cases {report['case_wall_s']}; "
      f"written {args.out / 'bench_study.json'}")
