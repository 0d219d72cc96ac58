#!/usr/bin/python3
"""Test of postprocess/seed_spread.py on summaries with known values: the spread column is
(max - min) / mean in %, a metric that is zero everywhere spreads by 0, a run that did not
complete stops the script with one line naming its summary, and `--finest-of` puts a converge
table's finest level first (its empty solver cells left out of their spread).

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

# A converge table whose finest level (f_level2) holds 0.19 for the critical-distance strain,
# beside runs at 0.20 and 0.21: the same 10 % as above, the coarser levels ignored.
converge = args.out / "converge.csv"
with converge.open("w", newline="") as out:
    writer = csv.writer(out)
    writer.writerow(["metric", "f_level0", "f_level1", "f_level2", "observed_order"])
    for name, value in summary(0.19)["safety"].items():
        for measure, entry in value.items():
            writer.writerow([f"safety.{name}.{measure}", 9.0, 8.0, entry["value"], ""])
    writer.writerow(["needle.max_axial_force_n", 1.0, 1.0, 5e-4, ""])
    writer.writerow(["needle.max_torque_n_m", 1.0, 1.0, 3e-7, ""])
table = args.out / "spread_with_finest.csv"
subprocess.run([sys.executable, str(args.script), *write_runs("beside_converge", [0.20, 0.21]),
                "--finest-of", str(converge), "--csv", str(table)], check=True)
rows = {row["metric"]: row for row in csv.DictReader(table.open())}
cd = rows["safety.log_strain.critical_distance"]
if [cd[f"run_{k}"] for k in (1, 2, 3)] != ["0.19", "0.2", "0.21"] or abs(float(cd["spread_percent_of_mean"]) - 10.0) > 1e-9:
    failures.append(f"--finest-of: critical-distance row {cd}")
if rows["solver.dofs"]["run_1"] != "" or float(rows["solver.dofs"]["spread_percent_of_mean"]) != 0.0:
    failures.append(f"--finest-of: solver row {rows['solver.dofs']}")
not_converge = args.out / "not_converge.csv"
not_converge.write_text("metric,run_1\nsafety.log_strain.critical_distance,0.2\n")
result = subprocess.run([sys.executable, str(args.script), runs[0], "--finest-of", str(not_converge)],
                        capture_output=True, text=True)
lines = result.stderr.strip().splitlines()
if result.returncode == 0 or len(lines) != 1 or "not_converge.csv" not in lines[0]:
    failures.append(f"--finest-of a table without levels: exit {result.returncode}, stderr {result.stderr!r}")

for failure in failures:
    print("FAIL:", failure)
sys.exit(1 if failures else 0)
