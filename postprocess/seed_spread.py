#!/usr/bin/python3
"""The spread of a case's answers over mesh seeds (issue 24's test: the same case with nothing but
`mesh.seed` changed): one CSV row per metric, its value in each run and (max - min) / mean in %.

Reads RUN_DIR/summary.json of each `needlefem run` given, in the order given (seed 1 first, as in
docs/accuracy.md), and writes the table to OUT.csv (or standard output). Every run must have
completed: a run whose summary says otherwise stops the script with one line naming it.

usage: /usr/bin/python3 postprocess/seed_spread.py RUN_DIR... [--csv OUT.csv]
example (docs/study/rounded_cavity/seed_spread_level2_r1.25_rounded.csv):
  for s in 1 2 3 4; do needlefem run cases/table1/r1.25_rounded.toml --set mesh.refinement_level=2 \\
      --set mesh.seed=$s --out out/seed$s; done
  /usr/bin/python3 postprocess/seed_spread.py out/seed1 out/seed2 out/seed3 out/seed4 --csv spread.csv
"""
import argparse
import csv
import json
import pathlib
import sys

QUANTITIES = ("log_strain", "strain_rate_per_s", "stress_pa")
MEASURES = ("critical_distance", "percentile", "volume_above_limit_mm3", "point_max")


def metrics(summary):
    """(name, value) of every compared metric of one run's summary."""
    rows = []
    for quantity in QUANTITIES:
        for measure in MEASURES:
            rows.append((f"safety.{quantity}.{measure}", summary["safety"][quantity][measure]["value"]))
    for key in ("max_axial_force_n", "max_torque_n_m"):
        rows.append((f"needle.{key}", summary["needle"][key]))
    rows.append(("solver.dofs", summary["solver"]["dofs"]))
    rows.append(("solver.wall_s", summary["solver"]["wall_s"]))
    return rows


def spread_percent(values):
    mean = sum(values) / len(values)
    return 0.0 if mean == 0 else 100.0 * (max(values) - min(values)) / abs(mean)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("runs", nargs="+", type=pathlib.Path)
    parser.add_argument("--csv", type=pathlib.Path)
    args = parser.parse_args()
    if len(args.runs) < 2:
        sys.exit("seed_spread: give at least two run folders")
    columns = []
    for run in args.runs:
        path = run / "summary.json"
        try:
            summary = json.loads(path.read_text())
        except (OSError, ValueError) as error:
            sys.exit(f"seed_spread: {path}: cannot read it ({error})")
        if summary.get("status") != "completed":
            sys.exit(f"seed_spread: {path}: status '{summary.get('status')}', not a completed run")
        try:
            columns.append(metrics(summary))
        except KeyError as error:
            sys.exit(f"seed_spread: {path}: no key {error} (a brain-tip run of this version?)")
    out = open(args.csv, "w", newline="") if args.csv else sys.stdout
    writer = csv.writer(out)
    writer.writerow(["metric"] + [f"run_{k + 1}" for k in range(len(columns))] + ["spread_percent_of_mean"])
    for row, (name, _) in enumerate(columns[0]):
        values = [column[row][1] for column in columns]
        writer.writerow([name] + [f"{v:.6g}" for v in values] + [f"{spread_percent(values):.3g}"])
    if args.csv:
        out.close()


if __name__ == "__main__":
    main()
