#!/usr/bin/python3
"""Where each study case stands against issue 24's accuracy targets: from its committed
`needlefem converge` table and seed tables, the worst band (GCI) of each kind of mesh-objective
metric, the verdicts, and the worst spread over mesh seeds, each against its target.

The targets: every critical-distance value, percentile and needle load within a 5 % band, a
volume above a limit within 10 %, and every one of them within 2 % over `mesh.seed` 1-4 at the
finest level. The volume above the rate limit's seed spread is given apart, as docs/accuracy.md
section 15 reads it, and judged like the others.

MANIFEST (TOML) lists the cases, paths relative to it:
  [[case]]
  design = "r 0.50/20 deg/0.25"               # the row's name
  case = "cases/table1/r0.50_a20_f0.25.toml"  # what the tables were run from (informative)
  edge_elements_per_radius = 1                 # the grading the tables were run with
  converge = "rounded_cavity/converge_r0.50_a20_f0.25.csv"
  seeds = ["rounded_cavity/seed_spread_level2_r0.50_a20_f0.25.csv"]  # postprocess/seed_spread.py tables
  seed_1_from_converge = false                 # true: the seed tables hold seeds 2-4 only, and
                                               # seed 1 is the converge table's finest level
  seeds_edge_elements_per_radius = 1           # only if the seeds were run with another grading
                                               # than the converge table (shown as a miss)
  one_level_up = "edge_grading/converge_..._levels_0-3.csv"  # optional: a converge table of four or
                                               # more levels, whose finest_in_coarser_band column
                                               # says whether each band of the three levels below
                                               # its finest held the finest value
A case without seed tables (seeds = []) is shown with its seed cells empty and that as a miss.

A sequence whose differences do not shrink over the levels ("divergent" in the converge table)
has no order, and the converge table gives it the band of an oscillating one, 3 x half its
spread (Stern et al. 2001). That band holds where the differences are the meshes' scatter, not
where they are a trend. The seeds measure the scatter: a divergent metric whose last difference
(finest level against the one below) is larger than its range over the seeds is a miss, "not
converging"; without seeds every divergent metric is.
One level up: each band of levels 0-2 claims to hold the converged value, which a fourth level
tests directly (`needlefem converge --levels 4`). Of the metrics above, those whose band missed
the finest value of the `one_level_up` table are misses; a metric that is zero on every level
(no volume above the limit) is not counted.
A missing file, a table without a metric, or a seed table whose runs are fewer than two stops
the script with one line naming the file (and the metric).

usage: /usr/bin/python3 postprocess/standing.py MANIFEST.toml [--csv OUT.csv] [--markdown]
(--markdown prints the table as docs/accuracy.md section 15 gives it, bands and spreads above
their targets in bold)
example (docs/accuracy.md section 15's table, and every miss named in a CSV):
  /usr/bin/python3 postprocess/standing.py docs/study/standing.toml --markdown --csv standing.csv
"""
import argparse
import csv
import pathlib
import re
import sys
import tomllib

from seed_spread import QUANTITIES, read_converge_table, spread_percent

CD = tuple(f"safety.{q}.critical_distance" for q in QUANTITIES)
PERCENTILES = tuple(f"safety.{q}.percentile" for q in QUANTITIES)
VOLUMES = tuple(f"safety.{q}.volume_above_limit_mm3" for q in QUANTITIES)
LOADS = ("needle.max_axial_force_n", "needle.max_torque_n_m")
RATE_VOLUME = "safety.strain_rate_per_s.volume_above_limit_mm3"
BAND_TARGET_PERCENT = {**{m: 5.0 for m in CD + PERCENTILES + LOADS}, **{m: 10.0 for m in VOLUMES}}
SEED_METRICS = CD + PERCENTILES + VOLUMES + LOADS
SEED_TARGET_PERCENT = 2.0


def fail(path, reason):
    sys.exit(f"standing: {path}: {reason}")


def read_table(path):
    try:
        with open(path, newline="") as table:
            reader = csv.DictReader(table)
            return reader.fieldnames or [], {row["metric"]: row for row in reader}
    except OSError as error:
        fail(path, f"cannot read it ({error})")


def number(path, row, column, metric):
    try:
        return float(row[column])
    except (KeyError, TypeError, ValueError):
        fail(path, f"metric {metric}: no number in {column}")


def converge_bands(path):
    """{metric: band in % of the finest value}, {CD metric: verdict}, the finest level's values, and
    {divergent metric: |its finest value - the level below's|}."""
    levels, rows = read_converge_table(path, "standing")
    if len(levels) < 2:
        fail(path, "fewer than two levels")
    below, finest = levels[-2:]
    bands, verdicts, values, steps = {}, {}, {}, {}
    for metric in BAND_TARGET_PERCENT:
        if metric not in rows:
            fail(path, f"metric {metric}: not in the table")
        bands[metric] = 100.0 * number(path, rows[metric], "gci_fine", metric)
        values[metric] = number(path, rows[metric], finest, metric)
        if rows[metric].get("observed_order") == "divergent":
            steps[metric] = abs(values[metric] - number(path, rows[metric], below, metric))
    for metric in CD:
        verdicts[metric] = rows[metric].get("verdict") or ""
    return bands, verdicts, values, steps


def one_level_up(path):
    """(held, checked, [metrics whose band missed]) over BAND_TARGET_PERCENT's metrics of a converge
    table with a fourth level: its finest_in_coarser_band column, yes or no per metric."""
    levels, rows = read_converge_table(path, "standing")
    if len(levels) < 4:
        fail(path, f"{len(levels)} levels: the band one level up needs four or more")
    held, missed = 0, []
    for metric in BAND_TARGET_PERCENT:
        if metric not in rows:
            fail(path, f"metric {metric}: not in the table")
        if all(number(path, rows[metric], level, metric) == 0 for level in levels):
            continue
        answer = rows[metric].get("finest_in_coarser_band") or ""
        if answer not in ("yes", "no"):
            fail(path, f"metric {metric}: finest_in_coarser_band is '{answer}', not yes or no")
        if answer == "yes":
            held += 1
        else:
            missed.append(metric)
    return held, held + len(missed), missed


def seed_values(paths, seed_1):
    """{metric: [value per seed]} over the seed tables' runs (after seed_1's values if given)."""
    values = {m: ([seed_1[m]] if seed_1 else []) for m in SEED_METRICS}
    for path in paths:
        fields, rows = read_table(path)
        runs = [f for f in fields if re.fullmatch(r"run_\d+", f)]
        if not runs:
            fail(path, "no column run_1, run_2, ... (not a seed_spread.py table)")
        for metric in SEED_METRICS:
            if metric not in rows:
                fail(path, f"metric {metric}: not in the table")
            values[metric] += [number(path, rows[metric], run, metric) for run in runs]
    return values


def percent_text(value):
    """A percentage to three significant digits, a large one whole: 1318, not 1.32e+03."""
    return f"{value:.3g}" if abs(value) < 1000 else f"{value:.0f}"


def worst(percents, metrics):
    metric = max(metrics, key=lambda m: percents[m])
    return percents[metric], metric


def standing(case, root):
    converge = root / case["converge"]
    bands, verdicts, finest, steps = converge_bands(converge)
    seed_paths = [root / p for p in case.get("seeds", [])]
    trends = []
    misses = [f"{m} band {bands[m]:.3g} %" for m in BAND_TARGET_PERCENT if bands[m] > BAND_TARGET_PERCENT[m]]
    misses += [f"{m} undecided" for m in CD if verdicts[m] == "undecided"]
    cd_band, cd_metric = worst(bands, CD)
    row = {
        "design": case["design"], "case": case.get("case", ""),
        "edge_elements_per_radius": case.get("edge_elements_per_radius", ""),
        "converge_table": case["converge"], "seed_tables": " ".join(case.get("seeds", [])),
        "cd_band_worst_percent": percent_text(cd_band), "cd_band_worst_metric": cd_metric,
        "percentile_band_worst_percent": percent_text(worst(bands, PERCENTILES)[0]),
        **{f"{m.split('.')[1]}_volume_band_percent": percent_text(bands[m]) if finest[m] > 0 else "none above"
           for m in VOLUMES},
        "force_band_percent": percent_text(bands[LOADS[0]]), "torque_band_percent": percent_text(bands[LOADS[1]]),
        "verdicts": " ".join(f"{m.split('.')[1]}:{verdicts[m]}" for m in CD),
        "seeds": "", "seed_spread_worst_percent": "", "seed_spread_worst_metric": "",
        "strain_rate_volume_seed_spread_percent": "",
        "one_level_up_table": case.get("one_level_up", ""), "one_level_up_held": "", "one_level_up_missed": "",
    }
    if "one_level_up" in case:
        held, checked, missed = one_level_up(root / case["one_level_up"])
        row["one_level_up_held"] = f"{held} of {checked}"
        row["one_level_up_missed"] = " ".join(missed)
        misses += [f"{m} band of the three levels below missed the fourth" for m in missed]
    if seed_paths:
        values = seed_values(seed_paths, finest if case.get("seed_1_from_converge") else None)
        count = len(values[CD[0]])
        if count < 2:
            fail(seed_paths[0], "fewer than two seeds")
        spreads = {m: spread_percent(v) for m, v in values.items()}
        others = tuple(m for m in SEED_METRICS if m != RATE_VOLUME)
        row["seeds"] = count
        seed_spread, row["seed_spread_worst_metric"] = worst(spreads, others)
        row["seed_spread_worst_percent"] = percent_text(seed_spread)
        row["strain_rate_volume_seed_spread_percent"] = percent_text(spreads[RATE_VOLUME]) if any(values[RATE_VOLUME]) \
            else "none above"
        misses += [f"{m} seed spread {spreads[m]:.3g} %" for m in SEED_METRICS if spreads[m] > SEED_TARGET_PERCENT]
        for metric, step in steps.items():
            scatter = max(values[metric]) - min(values[metric])
            if step > scatter:
                trends.append(metric)
                misses.append(f"{metric} not converging: its last level step {100 * step / abs(finest[metric]):.3g} % "
                              f"exceeds its seed range {100 * scatter / abs(finest[metric]):.3g} %")
        if count < 4:
            misses.append(f"{count} seeds, not 4")
        grading = case.get("seeds_edge_elements_per_radius", case.get("edge_elements_per_radius"))
        if grading != case.get("edge_elements_per_radius"):
            misses.append(f"seeds run with edge_elements_per_radius {grading}, "
                          f"the converge table with {case.get('edge_elements_per_radius')}")
    else:
        misses.append("no seed table")
        trends += list(steps)
        misses += [f"{metric} not converging (no seed range to judge its last level step by)" for metric in steps]
    row["not_converging"] = " ".join(trends)
    row["misses"] = "; ".join(misses)
    return row


SHORT_NAMES = {**dict(zip(CD, ("CD log strain", "CD strain rate", "CD von Mises"))),
               **dict(zip(PERCENTILES, ("99th percentile log strain", "99th percentile strain rate",
                                        "99th percentile von Mises"))),
               **dict(zip(VOLUMES, ("volume > 0.19", "volume > 10 1/s", "volume > 120 kPa"))),
               LOADS[0]: "force", LOADS[1]: "torque"}


def percent_cell(text, target):
    """A band or spread as docs/accuracy.md writes it, in bold above its target."""
    try:
        value = float(text)
    except ValueError:
        return text
    cell = f"{text} %"
    return f"**{cell}**" if value > target else cell


def one_level_up_cell(row):
    if not row["one_level_up_held"]:
        return "no fourth level"
    missed = ", ".join(SHORT_NAMES[m] for m in row["one_level_up_missed"].split())
    return row["one_level_up_held"] + (f"; **missed: {missed}**" if missed else "")


def markdown(rows):
    """docs/accuracy.md section 15's table."""
    lines = ["| design (n) | CD bands, worst | 99th percentiles, worst | volume > 0.19 | volume > 10 1/s | force / torque "
             "| seeds at the finest level, every metric but the volume > 10 1/s | volume > 10 1/s over seeds "
             "| not converging beyond the seeds' scatter | bands held one level up |", "|" + "---|" * 10]
    for row in rows:
        seeds = f"{row['seeds']} seeds: ≤ {percent_cell(row['seed_spread_worst_percent'], SEED_TARGET_PERCENT)}" \
            if row["seeds"] else "**no seed table**"
        if "seeds run with edge_elements_per_radius" in row["misses"]:
            seeds += " (**another grading**)"
        lines.append("| " + " | ".join([
            f"{row['design']} ({row['edge_elements_per_radius']})",
            percent_cell(row["cd_band_worst_percent"], 5.0),
            percent_cell(row["percentile_band_worst_percent"], 5.0),
            percent_cell(row["log_strain_volume_band_percent"], 10.0),
            percent_cell(row["strain_rate_per_s_volume_band_percent"], 10.0),
            f"{percent_cell(row['force_band_percent'], 5.0)} / {percent_cell(row['torque_band_percent'], 5.0)}",
            seeds,
            percent_cell(row["strain_rate_volume_seed_spread_percent"], SEED_TARGET_PERCENT) if row["seeds"] else "",
            ", ".join(SHORT_NAMES[m] for m in row["not_converging"].split()) or "none",
            one_level_up_cell(row)]) + " |")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("manifest", type=pathlib.Path)
    parser.add_argument("--csv", type=pathlib.Path)
    parser.add_argument("--markdown", action="store_true", help="print docs/accuracy.md section 15's table")
    args = parser.parse_args()
    try:
        manifest = tomllib.loads(args.manifest.read_text())
    except (OSError, tomllib.TOMLDecodeError) as error:
        fail(args.manifest, f"cannot read it ({error})")
    cases = manifest.get("case")
    if not isinstance(cases, list) or not cases:
        fail(args.manifest, "key 'case': required, a list of [[case]] tables")
    for k, case in enumerate(cases):
        for key in ("design", "converge"):
            if key not in case:
                fail(args.manifest, f"key 'case[{k}].{key}': required")
    rows = [standing(case, args.manifest.parent) for case in cases]
    if args.markdown:
        print(markdown(rows))
    out = open(args.csv, "w", newline="") if args.csv else sys.stdout
    writer = csv.DictWriter(out, fieldnames=list(rows[0]))
    writer.writeheader()
    writer.writerows(rows)
    if args.csv:
        out.close()
        for row in rows:
            print(f"{row['design']}: {row['misses'] or 'meets every target'}")


if __name__ == "__main__":
    main()
