#!/usr/bin/python3
"""Benchmark (not a test): one case's error band, `needlefem converge` through three refinement
levels, timed. Writes OUT/bench_converge.json with the whole command's wall time against the
target (3 min for one Table I case on 2 cores, issue 24), and per level: tets, unknowns, steps,
Newton iterations, Jacobian setups, GMRES iterations, wall time and peak memory (from each
level's summary.json), and the converge table's band of the metrics that decide the verdict.

    tests/benchmarks/bench_converge.py [--exe build/needlefem] [--case CASE] [--jobs 1] [--out out/bench_converge]

Start from an empty OUT for a timing: converge resumes, and a level already run is not run again.
"""
import argparse
import json
import shutil
import subprocess
import time
from pathlib import Path

from machine import describe_machine, use_blas_environment

ROOT = Path(__file__).resolve().parents[2]
TARGET_S = 180.0
DECIDING_METRICS = [
    "safety.log_strain.critical_distance", "safety.strain_rate_per_s.critical_distance",
    "safety.stress_pa.critical_distance", "needle.max_axial_force_n", "needle.max_torque_n_m",
]

parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
parser.add_argument("--exe", default=str(ROOT / "build" / "needlefem"))
parser.add_argument("--case", type=Path, default=ROOT / "cases" / "table1" / "r0.50_a20_f0.25.toml")
parser.add_argument("--jobs", type=int, default=1, help="levels at a time (each run threads over the cores)")
parser.add_argument("--out", type=Path, default=ROOT / "out" / "bench_converge")
args = parser.parse_args()
use_blas_environment(args.exe)

if args.out.exists():
    shutil.rmtree(args.out)
start = time.perf_counter()
converge = subprocess.run([args.exe, "converge", str(args.case), "--out", str(args.out), "--jobs", str(args.jobs)])
wall = time.perf_counter() - start

levels = []
for level_dir in sorted(args.out.glob("level_*")):
    summary = json.loads((level_dir / "summary.json").read_text())
    solver = summary["solver"]
    levels.append({
        "level": level_dir.name, "status": summary["status"], "tets": summary["mesh"].get("tets"),
        "dofs": solver["dofs"], "steps": solver["steps"], "newton_iterations": solver["newton_iterations"],
        "jacobian_setups": solver["jacobian_setups"], "gmres_iterations": solver["linear_iterations"],
        "wall_s": solver["wall_s"], "peak_rss_mb": solver["peak_rss_mb"],
    })
bands = {}
table_file = args.out / "converge.json"
if table_file.exists():
    for row in json.loads(table_file.read_text()).get("metrics", []):
        if row.get("metric") in DECIDING_METRICS:
            bands[row["metric"]] = {key: row.get(key) for key in
                                    ("values", "behaviour", "observed_order", "gci_fine", "band", "verdict")}
report = {
    "benchmark": "needlefem converge: one case through three refinement levels",
    "case": str(args.case.relative_to(ROOT)) if args.case.is_relative_to(ROOT) else str(args.case),
    "jobs": args.jobs,
    "machine": describe_machine(),
    "converge_exit_code": converge.returncode,
    "wall_s": wall,
    "target_s": TARGET_S,
    "target_met": converge.returncode == 0 and wall <= TARGET_S,
    "levels": levels,
    "bands": bands,
}
args.out.mkdir(parents=True, exist_ok=True)
(args.out / "bench_converge.json").write_text(json.dumps(report, indent=2) + "\n")
print(f"converge {wall:.0f} s (target {TARGET_S:.0f} s); written {args.out / 'bench_converge.json'}")
