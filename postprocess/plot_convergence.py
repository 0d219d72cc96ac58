#!/usr/bin/python3
"""Figure of a `needlefem converge` folder: each metric compared with a safety limit against the
relative element size near the needle (1 at the coarsest level, halving per level), with its
Richardson value, its GCI band around the finest value and the limit line (only in the legend when
the limit is so far off that the line would flatten the values); one panel per metric, the metric
that decides its limit's verdict marked "(decides)".

Reads DIR/converge.json (written by solver/convergence/convergence_report.cpp; this script only
draws it, the estimates are the C++ module's) and writes DIR/convergence.png.

usage: /usr/bin/python3 postprocess/plot_convergence.py DIR [--png OUT.png] [--all]
  --all  also the metrics without a limit (needle loads, volumes above a limit, ...)
"""
import argparse
import json
import math
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def finite(x):
    return x is not None and math.isfinite(x)


def draw_limit(ax, metric):
    """The limit as a dashed line; when drawing it would squash the values more than tenfold, only
    in the legend, saying where it lies."""
    limit = metric["limit_value"]
    shown = [v for v in metric["values"] + metric["band"] + [metric.get("f_extrapolated")] if finite(v)]
    low, high = (min(shown), max(shown)) if shown else (limit, limit)
    span = max(high - low, 0.05 * abs(high), 1e-300)
    if max(high, limit) - min(low, limit) <= 10 * span:
        ax.axhline(limit, color="C3", linestyle="--", label=f"limit {limit:g}")
    else:
        ax.plot([], [], color="C3", linestyle="--", label=f"limit {limit:g} ({'above' if limit > high else 'below'}, off scale)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("dir", type=pathlib.Path)
    parser.add_argument("--png", type=pathlib.Path)
    parser.add_argument("--all", action="store_true")
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
            draw_limit(ax, metric)
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


if __name__ == "__main__":
    main()
