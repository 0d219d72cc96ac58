#!/usr/bin/python3
"""Figure of a `needlefem converge` folder: each metric compared with a safety limit against the
relative element size near the needle (1 at the coarsest level, halving per level), with its
Richardson value, its GCI band around the finest value and the limit line (only in the legend when
the limit is so far off that the line would flatten the values); one panel per metric, the metric
that decides its limit's verdict marked "(decides)".

Reads DIR/converge.json (written by solver/convergence/convergence_report.cpp; this script only
draws it, the estimates are the C++ module's) and writes DIR/convergence.png. When the folder has
DIR/converge_history.csv (solver/convergence/history_bands.cpp), also DIR/convergence_history.png:
the limited quantities against time, each level's curve and the band around the finest at every
output time, with the limit line; below each, the quantity's change since its peak time with
the band of that change and the zero line: where the band leaves zero, the fall (or rise) from
the peak is resolved.

usage: /usr/bin/python3 postprocess/plot_convergence.py DIR [--png OUT.png] [--all] [--history Q,Q,...]
  --all      also the metrics without a limit (needle loads, volumes above a limit, ...)
  --history  the history.csv quantities to draw against time (default: the critical-distance
             values, else the point maxima, of the limited fields)
"""
import argparse
import csv
import json
import math
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def finite(x):
    return x is not None and math.isfinite(x)


def draw_limit(ax, limit, shown, squash=10):
    """The limit as a dashed line; when drawing it would squash the shown values more than
    `squash` times, only in the legend, saying where it lies."""
    shown = [v for v in shown if finite(v)]
    low, high = (min(shown), max(shown)) if shown else (limit, limit)
    span = max(high - low, 0.05 * abs(high), 1e-300)
    if max(high, limit) - min(low, limit) <= squash * span:
        ax.axhline(limit, color="C3", linestyle="--", label=f"limit {limit:g}")
    else:
        ax.plot([], [], color="C3", linestyle="--", label=f"limit {limit:g} ({'above' if limit > high else 'below'}, off scale)")


def number(text):
    return float(text) if text not in ("", None) else math.nan


def plot_history(args, report):
    """DIR/convergence_history.png from DIR/converge_history.csv; returns its path, or None."""
    path = args.dir / "converge_history.csv"
    if not path.exists():
        return None
    with open(path) as f:
        rows = list(csv.DictReader(f))
    # Each limit's history columns by role (critical_distance, point_max), as its summaries name them.
    verdicts = report.get("verdicts", {}).values()
    limit_of = {column: v["limit"] for v in verdicts for column in v["history_columns"].values()}
    columns_of = {role: [v["history_columns"][role] for v in verdicts if role in v["history_columns"]]
                  for role in ("critical_distance", "point_max")}
    present = list(dict.fromkeys(r["quantity"] for r in rows))
    if args.history:
        quantities = args.history.split(",")
        unknown = [q for q in quantities if q not in present]
        if unknown:
            sys.exit(f"{path}: no quantity {', '.join(unknown)}")
    else:
        quantities = [q for q in present if q in columns_of["critical_distance"]] or [
            q for q in present if q in columns_of["point_max"]]
    if not quantities:
        return None
    level_columns = [c for c in rows[0] if c.startswith("f_level")]
    fig, axes = plt.subplots(2, len(quantities), figsize=(4.6 * len(quantities), 6.6), squeeze=False,
                             sharex="col")
    for ax, change_ax, quantity in zip(axes[0], axes[1], quantities):
        series = [r for r in rows if r["quantity"] == quantity]
        times = [number(r["time_s"]) for r in series]
        for i, column in enumerate(level_columns):
            finest = i == len(level_columns) - 1
            ax.plot(times, [number(r[column]) for r in series], "o-" if finest else "-", markersize=3,
                    color="C0" if finest else f"{0.75 - 0.5 * i / max(len(level_columns) - 1, 1):.2f}",
                    label=column.replace("f_", "").replace("level", "level "))
        low, high = [number(r["band_low"]) for r in series], [number(r["band_high"]) for r in series]
        ax.fill_between(times, low, high, color="C0", alpha=0.25, label="GCI band (finest)")
        if quantity in limit_of:
            # A curve's shape is the point here: the line only where it leaves the curve readable.
            draw_limit(ax, limit_of[quantity], low + high, squash=2)
        ax.set_title(quantity, fontsize=9)
        ax.legend(fontsize=7)
        change = [number(r["change_since_peak"]) for r in series]
        change_ax.plot(times, change, "o-", markersize=3, color="C0", label="finest level")
        change_ax.fill_between(times, [number(r["change_band_low"]) for r in series],
                               [number(r["change_band_high"]) for r in series], color="C0", alpha=0.25,
                               label="GCI band of the change")
        change_ax.axhline(0.0, color="k", linewidth=0.8)
        change_ax.set_title(f"change since the peak at t = {number(series[0]['peak_time_s']):g} s", fontsize=9)
        change_ax.set_xlabel("time (s)")
        change_ax.legend(fontsize=7)
    fig.tight_layout()
    out = args.dir / "convergence_history.png"
    fig.savefig(out, dpi=120)
    plt.close(fig)
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("dir", type=pathlib.Path)
    parser.add_argument("--png", type=pathlib.Path)
    parser.add_argument("--all", action="store_true")
    parser.add_argument("--history")
    args = parser.parse_args()
    path = args.dir / "converge.json"
    if not path.exists():
        sys.exit(f"{path}: no converge report (run `needlefem converge` first)")
    report = json.loads(path.read_text())
    sizes = [level["relative_size"] for level in report["levels"]]
    labels = [f"level {level['level']}" for level in report["levels"]]
    metrics = [m for m in report["metrics"] if args.all or "verdict" in m]
    if not metrics:
        sys.exit(f"{path}: no metric compared with a limit (use --all for the others)")

    deciders = {v["metric"] for v in report.get("verdicts", {}).values()}
    columns = min(3, len(metrics))
    rows = math.ceil(len(metrics) / columns)
    fig, axes = plt.subplots(rows, columns, figsize=(4.2 * columns, 3.4 * rows), squeeze=False)
    for ax, metric in zip(axes.flat, metrics):
        points = [(h, v) for h, v in zip(sizes, metric["values"]) if finite(v)]
        if points:
            ax.plot(*zip(*points), "o-", color="C0", label="runs")
        low, high = metric["band"]
        finest = sizes[-1]
        if finite(low) and finite(high):
            ax.fill_between([0.0, finest], [low, low], [high, high], color="C0", alpha=0.2,
                            label=f"GCI band ({metric['order']})")
            ax.errorbar([finest], [metric["values"][-1]], yerr=[[metric["values"][-1] - low], [high - metric["values"][-1]]],
                        color="C0", capsize=4)
        if finite(metric.get("f_extrapolated")):
            ax.plot([0.0], [metric["f_extrapolated"]], "*", color="C2", markersize=10, label="Richardson (h = 0)")
        if finite(metric.get("limit_value")) and "verdict" in metric:
            draw_limit(ax, metric["limit_value"], metric["values"] + metric["band"] + [metric.get("f_extrapolated")])
        title = metric["metric"] + (f": {metric['verdict']}" if "verdict" in metric else "")
        if metric["metric"] in deciders:
            title += " (decides)"
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("relative element size near the needle")
        ax.set_xlim(-0.05, 1.05 * max(sizes))
        ax.set_xticks(sizes, [f"{h:g}\n{label}" for h, label in zip(sizes, labels)], fontsize=7)
        ax.legend(fontsize=7)
    for ax in list(axes.flat)[len(metrics):]:
        ax.axis("off")
    verdicts = "; ".join(f"{name}: {v['verdict']} ({v['metric']})" for name, v in report.get("verdicts", {}).items())
    fig.suptitle(verdicts or "no safety limit", fontsize=9)
    fig.tight_layout()
    out = args.png or args.dir / "convergence.png"
    fig.savefig(out, dpi=120)
    print(f"plot_convergence: wrote {out}")
    history = plot_history(args, report)
    if history:
        print(f"plot_convergence: wrote {history}")


if __name__ == "__main__":
    main()
