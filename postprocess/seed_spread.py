#!/usr/bin/python3
"""The spread of a case's answers over mesh seeds (issue 24's test: the same case with nothing but
`mesh.seed` changed): one CSV row per metric, its value in each run and (max - min) / mean in %.

Reads RUN_DIR/summary.json of each `needlefem run` given, in the order given (seed 1 first, as in
docs/accuracy.md), and writes the table to OUT.csv (or standard output). Every run must have
completed: a run whose summary says otherwise stops the script with one line naming it.

`--finest-of CONVERGE.csv` puts the finest level of a `needlefem converge` table first, as one
more run: that level is the case at its own seed (1 unless the case sets another), so seeds 2-4
need not repeat it. The table has no solver figures; its cells in those rows stay empty and
their spread is over the other runs.

usage: /usr/bin/python3 postprocess/seed_spread.py RUN_DIR... [--finest-of CONVERGE.csv] [--csv OUT.csv]
example (docs/study/rounded_cavity/seed_spread_level2_r1.25_rounded.csv):
  for s in 1 2 3 4; do needlefem run cases/table1/r1.25_rounded.toml --set mesh.refinement_level=2 \\
      --set mesh.seed=$s --out out/seed$s; done
  /usr/bin/python3 postprocess/seed_spread.py out/seed1 out/seed2 out/seed3 out/seed4 --csv spread.csv
or, beside `needlefem converge cases/table1/r1.25_rounded.toml --out conv` (levels 0-2):
  /usr/bin/python3 postprocess/seed_spread.py out/seed2 out/seed3 out/seed4 --finest-of conv/converge.csv
"""
import argparse
import csv
import json
import pathlib
import re
import sys

QUANTITIES = ("log_strain", "strain_rate_per_s", "stress_pa")
MEASURES = ("critical_distance", "percentile", "volume_above_limit_mm3", "point_max")
METRIC_NAMES = tuple(f"safety.{q}.{m}" for q in QUANTITIES for m in MEASURES) + (
    "needle.max_axial_force_n", "needle.max_torque_n_m", "solver.dofs", "solver.wall_s")


def metrics(summary):
    """(name, value) of every compared metric of one run's summary."""
    return [(name, _lookup(summary, name)) for name in METRIC_NAMES]


def _lookup(summary, name):
    node = summary
    for key in name.split("."):
        node = node[key]
    return node["value"] if isinstance(node, dict) else node


def read_converge_table(path, program):
    """The level columns of a `needlefem converge` table, coarsest first (f_level0, f_level1, ...),
    and its rows by metric; a table that cannot be read or has no level column stops `program`
    with one line naming it."""
    try:
        with open(path, newline="") as table:
            reader = csv.DictReader(table)
            rows = {row["metric"]: row for row in reader}
    except OSError as error:
        sys.exit(f"{program}: {path}: cannot read it ({error})")
    levels = sorted(int(key[len("f_level"):]) for key in reader.fieldnames or () if re.fullmatch(r"f_level\d+", key))
    if not levels:
        sys.exit(f"{program}: {path}: no column f_level0, f_level1, ... (not a converge table)")
    return [f"f_level{level}" for level in levels], rows


def finest_level(path):
    """(name, value) of every metric of metrics()'s list in a converge table's finest level;
    the solver's figures, which the table does not carry, are None."""
    levels, rows = read_converge_table(path, "seed_spread")
    finest = levels[-1]
    values = {metric: row[finest] for metric, row in rows.items()}
    column = []
    for name in METRIC_NAMES:
        if name.startswith("solver."):
            column.append((name, None))
            continue
        try:
            column.append((name, float(values[name])))
        except (KeyError, ValueError):
            sys.exit(f"seed_spread: {path}: metric {name}: no number in {finest}")
    return column


def spread_percent(values):
    mean = sum(values) / len(values)
    return 0.0 if mean == 0 else 100.0 * (max(values) - min(values)) / abs(mean)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("runs", nargs="+", type=pathlib.Path)
    parser.add_argument("--finest-of", type=pathlib.Path, metavar="CONVERGE.csv")
    parser.add_argument("--csv", type=pathlib.Path)
    args = parser.parse_args()
    columns = [finest_level(args.finest_of)] if args.finest_of else []
    if len(columns) + len(args.runs) < 2:
        sys.exit("seed_spread: give at least two runs (run folders, or one and --finest-of)")
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
        known = [v for v in values if v is not None]
        writer.writerow([name] + ["" if v is None else f"{v:.6g}" for v in values] + [f"{spread_percent(known):.3g}"])
    if args.csv:
        out.close()


if __name__ == "__main__":
    main()
