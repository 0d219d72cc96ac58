#!/usr/bin/python3
"""Benchmark (not a test): paper 001's study at the paper's density (cases/sweeps/paper001_study.toml:
the seven Table I tips and the slow/medium/fast rate study, frictional contact, 0.4 mm core), run
as one `needlefem sweep` and timed. Writes OUT/bench_study.json with, per design point: status,
wall time, steps, Newton iterations, Jacobian setups (= factorisations), GMRES iterations, peak
memory and DOF (from each run's summary.json), and for the whole study its wall time against the
targets (30 s per case, 5 min for the study, on 2 cores).

    tests/benchmarks/bench_study.py [--exe build/needlefem] [--jobs 2] [--out out/bench_study]

Resumable like the sweep itself: points already completed for the same case are not run again,
and their recorded wall times are kept, so a resumed study's total is the sum over the sweep
calls, not one measurement; start from an empty OUT for a timing.
"""
import argparse
import csv
import json
import subprocess
import time
from pathlib import Path

from machine import describe_machine

ROOT = Path(__file__).resolve().parents[2]
TARGET_PER_CASE_S = 30.0
TARGET_STUDY_S = 300.0

parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
parser.add_argument("--exe", default=str(ROOT / "build" / "needlefem"))
parser.add_argument("--sweep", type=Path, default=ROOT / "cases" / "sweeps" / "paper001_study.toml")
parser.add_argument("--jobs", type=int, default=2, help="runs at a time (the machine has 2 cores)")
parser.add_argument("--out", type=Path, default=ROOT / "out" / "bench_study")
args = parser.parse_args()

start = time.perf_counter()
sweep = subprocess.run([args.exe, "sweep", str(args.sweep), "--out", str(args.out), "--jobs", str(args.jobs)])
study_wall = time.perf_counter() - start

points = []
with (args.out / "sweep.csv").open() as table:
    for row in csv.DictReader(table):
        point = {"point": row["point"], "grid": row["grids"], "status": row["status"]}
        summary_file = args.out / row["point"] / "summary.json"
        if summary_file.exists():
            summary = json.loads(summary_file.read_text())
            solver = summary["solver"]
            point.update({
                "time_reached_s": summary.get("time_reached_s"),
                "wall_s": solver["wall_s"],
                "steps": solver["steps"],
                "newton_iterations": solver["newton_iterations"],
                "jacobian_setups": solver["jacobian_setups"],
                "gmres_iterations": solver["linear_iterations"],
                "newton_convergence_failures": solver["newton_convergence_failures"],
                "peak_rss_mb": solver["peak_rss_mb"],
                "dofs": solver["dofs"],
                "displacement_dofs": solver["displacement_dofs"],
                "meets_case_target": solver["wall_s"] <= TARGET_PER_CASE_S,
            })
        points.append(point)

walls = [p["wall_s"] for p in points if "wall_s" in p]
report = {
    "benchmark": "paper 001 study at the 0.4 mm core (frictional contact)",
    "sweep": str(args.sweep.relative_to(ROOT)) if args.sweep.is_relative_to(ROOT) else str(args.sweep),
    "jobs": args.jobs,
    "machine": describe_machine(),
    "sweep_exit_code": sweep.returncode,
    "study_wall_s": study_wall,
    "case_wall_s": {"min": min(walls, default=None), "max": max(walls, default=None),
                    "mean": sum(walls) / len(walls) if walls else None},
    "targets": {"per_case_s": TARGET_PER_CASE_S, "study_s": TARGET_STUDY_S,
                "study_met": study_wall <= TARGET_STUDY_S,
                "cases_met": sum(1 for p in points if p.get("meets_case_target")), "cases": len(points)},
    "points": points,
}
(args.out / "bench_study.json").write_text(json.dumps(report, indent=2) + "\n")
print(f"study {study_wall:.0f} s (target {TARGET_STUDY_S:.0f} s), cases {report['case_wall_s']}; "
      f"written {args.out / 'bench_study.json'}")
