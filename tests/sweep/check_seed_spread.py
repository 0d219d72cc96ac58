#!/usr/bin/python3
"""Test of postprocess/seed_spread.py on summaries with known values: the spread column is
(max - min) / mean in %, a metric that is zero everywhere spreads by 0, and a run that did not
complete stops the script with one line naming its summary.

usage: check_seed_spread.py --script postprocess/seed_spread.py --out DIR
"""
import argparse
import csv
import json
import pathlib
import shutil
import subprocess
import sys

parser = argparse.ArgumentParser()
parser.add_argument("--script", type=pathlib.Path, required=True)
parser.add_argument("--out", type=pathlib.Path, required=True)
args = parser.parse_args()
shutil.rmtree(args.out, ignore_errors=True)


def summary(log_strain_cd, status="completed"):
    measures = ("critical_distance", "percentile", "volume_above_limit_mm3", "point_max")
    safety = {q: {m: {"value": 0.0} for m in measures} for q in ("log_strain", "strain_rate_per_s", "stress_pa")}
    safety["log_strain"]["critical_distance"]["value"] = log_strain_cd
    safety["stress_pa"]["point_max"]["value"] = 1000.0
    return {"status": status, "safety": safety,
            "needle": {"max_axial_force_n": 5e-4, "max_torque_n_m": 3e-7},
            "solver": {"dofs": 1000, "wall_s": 1.0}}


def write_runs(name, values, statuses=None):
    runs = []
    for k, value in enumerate(values):
        run = args.out / name / f"seed{k + 1}"
        run.mkdir(parents=True)
        (run / "summary.json").write_text(json.dumps(summary(value, (statuses or {}).get(k, "completed"))))
        runs.append(str(run))
    return runs


failures = []
# 0.19, 0.20, 0.21: (0.21 - 0.19) / 0.20 = 10 %.
table = args.out / "spread.csv"
subprocess.run([sys.executable, str(args.script), *write_runs("good", [0.19, 0.20, 0.21]), "--csv", str(table)],
               check=True)
rows = {row["metric"]: row for row in csv.DictReader(table.open())}
expected = {"safety.log_strain.critical_distance": 10.0, "safety.stress_pa.point_max": 0.0,
            "safety.strain_rate_per_s.percentile": 0.0, "needle.max_axial_force_n": 0.0}
for metric, spread in expected.items():
    got = float(rows[metric]["spread_percent_of_mean"])
    if abs(got - spread) > 1e-9:
        failures.append(f"{metric}: spread {got} %, expected {spread} %")
if [rows["safety.log_strain.critical_distance"][f"run_{k}"] for k in (1, 2, 3)] != ["0.19", "0.2", "0.21"]:
    failures.append(f"values out of order: {rows['safety.log_strain.critical_distance']}")

runs = write_runs("running", [0.19, 0.20], statuses={1: "running"})
result = subprocess.run([sys.executable, str(args.script), *runs], capture_output=True, text=True)
lines = result.stderr.strip().splitlines()
if result.returncode == 0 or len(lines) != 1 or "seed2/summary.json" not in lines[0] or "running" not in lines[0]:
    failures.append(f"an unfinished run: exit {result.returncode}, stderr {result.stderr!r}")

for failure in failures:
    print("FAIL:", failure)
sys.exit(1 if failures else 0)
