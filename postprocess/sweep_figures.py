#!/usr/bin/python3
"""Figures of a `needlefem sweep` (paper 001, Figs. 4-6, and a safety map) and of one run.

Reads the sweep's table DIR/sweep.h5 (layout: solver/sweep/sweep_table.hpp) and, per design
point, DIR/<point>/summary.json (the resolved case: needle, motion; the threshold limits) and
DIR/<point>/history.csv (maxima per output time). Only completed points are drawn, except in the
safety map, which shows every point of the grid.

usage: /usr/bin/python3 postprocess/sweep_figures.py COMMAND ARGS [--png OUT.png]
  stress-strain SWEEP_DIR [--grid G]  max von Mises stress against max log strain over each run,
                                      one line per tip, with the strain and stress limits (Fig. 4)
  fillet SWEEP_DIR [--grid G]         max von Mises stress against fillet radius, one line per
                                      radius and bevel angle (Fig. 5)
  strain-rate SWEEP_DIR [--grid G]    max strain rate against time, one line per speed
                                      (slow/medium/fast when there are three), with the limit (Fig. 6)
  safety-map SWEEP_DIR [--grid G] [--x KEY] [--y KEY]
                                      each design's verdict (pass/fail: the critical-distance values
                                      against the limits, labelled with the limits that fail), run
                                      failed or impossible, over two swept keys (default: the first two
                                      that vary), one panel per value of the other swept keys; titled
                                      with a warning when designs are on a mesh coarser than the
                                      converged setting (also safety-steering)
  safety-steering SWEEP_DIR [--grid G]
                                      the designer's trade-off: each limit's safety margin
                                      1 - (critical-distance value)/limit against the largest lateral
                                      force the tip puts on the needle (what steers a bevel), one
                                      panel per limit, one marker per design (filled: the verdict
                                      passes), the point-maximum margin as a faint cross
  history RUN_DIR                     time histories of one run: maxima with their limits, reactions
  all SWEEP_DIR [--out DIR] [--design-grid G] [--rate-grid G]
                                      all of the above (history of the first completed point; the
                                      safety map of the design grid) as
                                      fig4_stress_strain.png, fig5_fillet.png, fig6_strain_rate.png,
                                      safety_map.png, safety_steering.png, history.png in DIR
                                      (default SWEEP_DIR/figures)
--grid G keeps the points of grid G (a [[grid]] name, or "main"). Default OUT: SWEEP_DIR/<figure>.png.
"""
import argparse
import csv
import itertools
import json
import math
import pathlib
import sys
import textwrap

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

# Paper 001's limits, used when a run's summary.json has no "thresholds".
PAPER_LIMITS = {"log_strain": 0.19, "strain_rate_per_s": 10.0, "stress_pa": 120e3}


class Sweep:
    """The table of a sweep directory, one entry per design point."""

    def __init__(self, directory):
        self.dir = pathlib.Path(directory)
        path = self.dir / "sweep.h5"
        if not path.exists():
            raise SystemExit(f"{path}: no sweep table (run `needlefem sweep` first)")
        with h5py.File(path, "r") as f:
            if f.attrs.get("format") != "needlefem-sweep-table":
                raise SystemExit(f"{path}: not a needlefem sweep table")
            self.columns = [str(c) for c in f.attrs["columns"]]
            self.table = {}
            for name in self.columns:
                data = f[name]
                self.table[name] = data.asstr()[()] if h5py.check_string_dtype(data.dtype) else data[()]
        first_key, last_key = self.columns.index("grids") + 1, self.columns.index("status")
        self.swept_keys = self.columns[first_key:last_key]
        self.rows = len(self.table["point"])

    def indices(self, grid=None, status="completed"):
        return [i for i in range(self.rows)
                if (status is None or self.table["status"][i] == status)
                and (grid is None or grid in self.table["grids"][i].split(","))]

    def summary(self, i):
        return json.loads((self.dir / self.table["point"][i] / "summary.json").read_text())

    def history(self, i):
        return read_history(self.dir / self.table["point"][i])

    def coarse_mesh_warning(self, rows):
        """The caption a verdict figure of these rows carries when any design among them is on a mesh
        coarser than the converged setting (column coarse_mesh, solver/case/mesh_resolution.hpp);
        "" when none is (or the table predates the column)."""
        column = self.table.get("coarse_mesh")
        designs = [i for i in rows if self.table["status"][i] != "impossible"]
        coarse = [column[i] for i in designs if column is not None and column[i]]
        if not coarse:
            return ""
        return (f"Warning: {len(coarse)} of {len(designs)} designs on a mesh coarser than the converged setting "
                f"({coarse[0]}): their verdicts may change on a finer mesh (docs/accuracy.md section 4)")

    def limits(self):
        for i in self.indices():
            return run_limits(self.summary(i))
        return dict(PAPER_LIMITS)


def run_limits(summary):
    limits = dict(PAPER_LIMITS)
    for name, entry in summary.get("thresholds", {}).items():
        if isinstance(entry, dict) and "limit" in entry:
            limits[name] = float(entry["limit"])
    return limits


def read_history(run_dir):
    with open(pathlib.Path(run_dir) / "history.csv") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise SystemExit(f"{run_dir}/history.csv: no rows")
    return {key: np.array([float(r[key]) for r in rows]) for key in rows[0]}


def tip_of(summary):
    needle = summary["case"]["needle"]
    return needle["radius_mm"], needle["bevel_deg"], needle["fillet_mm"]


def motion_of(summary):
    motion = summary["case"]["motion"]
    return motion["insertion_speed_mm_per_s"], motion["rotation_speed_deg_per_s"]


def tip_label(tip):
    radius, bevel, fillet = tip
    if fillet >= radius:
        return f"r {radius:g} mm, rounded"
    return f"r {radius:g} mm, {bevel:g}°, τ {fillet:g} mm"


def motion_label(motion):
    return f"{motion[0]:g} mm/s, {motion[1]:g}°/s"


def finish(fig, png):
    """Writes the PNG (legends and notes placed outside the axes included) and returns the figure."""
    png = pathlib.Path(png)
    png.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(png, dpi=130, bbox_inches="tight")
    plt.close(fig)
    print(f"wrote {png}")
    return fig


MARKERS = "osD^vP*Xph<>"


def line_styles(count):
    """`count` styles with distinct colours (tab10/tab20, or a colour map sampled evenly for a full
    grid) and cycling markers, so neighbouring colours of a large grid still differ in shape."""
    if count <= 10:
        colours = [plt.get_cmap("tab10")(k) for k in range(count)]
    elif count <= 20:
        colours = [plt.get_cmap("tab20")(k) for k in range(count)]
    else:
        colours = [plt.get_cmap("turbo")(x) for x in np.linspace(0.05, 0.95, count)]
    return [dict(color=c, marker=MARKERS[k % len(MARKERS)]) for k, c in enumerate(colours)]


def no_data(ax, text):
    ax.text(0.5, 0.5, text, ha="center", va="center", transform=ax.transAxes)


def finish_axes(fig, ax, png, drawn, xlabel, ylabel, title, legend_size=7):
    """Labels, grid and a legend beside the axes (never over the curves), then the PNG."""
    if not drawn:
        no_data(ax, "no completed runs")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    entries = len(ax.get_legend_handles_labels()[1])
    ax.legend(fontsize=legend_size, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0,
              ncol=1 if entries <= 24 else 2)
    ax.grid(True, which="both", alpha=0.3)
    return finish(fig, png)


def stress_strain(sweep, png, grid=None):
    """Fig. 4: the path (max log strain, max von Mises) of every completed run over time."""
    limits = sweep.limits()
    fig, ax = plt.subplots(figsize=(7, 5))
    points = sweep.indices(grid)
    summaries = {i: sweep.summary(i) for i in points}
    several_motions = len({motion_of(s) for s in summaries.values()}) > 1
    ordered = sorted(points, key=lambda i: (tip_of(summaries[i]), motion_of(summaries[i])))
    for i, style in zip(ordered, line_styles(len(ordered))):
        h = sweep.history(i)
        label = tip_label(tip_of(summaries[i]))
        if several_motions:
            label += f" ({motion_label(motion_of(summaries[i]))})"
        strain, stress = h["max_log_strain"], h["max_von_mises"] / 1e3
        keep = stress > 0  # the log axis cannot show the unloaded start
        ax.plot(strain[keep], stress[keep], ms=4, lw=1.2, markevery=[-1] if keep.sum() > 1 else None,
                label=label, **style)  # the marker shows where the run ends
    ax.axvline(limits["log_strain"], color="#d62728", ls="--", label=f"strain limit {limits['log_strain']:g}")
    ax.axhline(limits["stress_pa"] / 1e3, color="#9467bd", ls="--",
               label=f"stress limit {limits['stress_pa'] / 1e3:g} kPa")
    ax.set_yscale("log")
    ax.set_xlim(left=0)
    return finish_axes(fig, ax, png, points, "max principal logarithmic strain",
                       "max von Mises stress [kPa] (log scale)",
                       "Stress and log strain per needle tip (maxima over the tissue at each time)")


def fillet(sweep, png, grid=None):
    """Fig. 5: max von Mises stress against fillet radius, one line per radius/bevel (and motion)."""
    fig, ax = plt.subplots(figsize=(7, 5))
    groups = {}
    for i in sweep.indices(grid):
        s = sweep.summary(i)
        radius, bevel, tau = tip_of(s)
        key = (radius, bevel if tau < radius else None, motion_of(s))
        groups.setdefault(key, []).append((tau, s["max"]["von_mises_pa"]["value"] / 1e3))
    several_motions = len({k[2] for k in groups}) > 1
    ordered = sorted(groups.items(), key=lambda kv: (kv[0][0], kv[0][1] or 0))
    for ((radius, bevel, motion), values), style in zip(ordered, line_styles(len(ordered))):
        values.sort()
        label = f"r {radius:g} mm, " + (f"{bevel:g}°" if bevel is not None else "rounded")
        if several_motions:
            label += f" ({motion_label(motion)})"
        ax.plot([v[0] for v in values], [v[1] for v in values], label=label, **style)
    return finish_axes(fig, ax, png, groups, "tip fillet radius τ [mm]", "max von Mises stress [kPa]",
                "Maximum stress against fillet radius", legend_size=8)


def strain_rate(sweep, png, grid=None):
    """Fig. 6: max strain rate against time for each insertion/rotation speed: the point maxima
    (solid, what paper 001 plotted) and, dashed in the same colour, the value the verdict judges
    (the critical-distance rate sustained over the strain-rate window, docs/safety.md)."""
    limits = sweep.limits()
    fig, ax = plt.subplots(figsize=(7, 5))
    points = sweep.indices(grid)
    summaries = {i: sweep.summary(i) for i in points}
    points.sort(key=lambda i: (motion_of(summaries[i]), tip_of(summaries[i])))
    speeds = sorted({motion_of(s) for s in summaries.values()})
    names = dict(zip(speeds, ["slow", "medium", "fast"])) if len(speeds) == 3 else {}
    several_tips = len({tip_of(s) for s in summaries.values()}) > 1
    for i, style in zip(points, line_styles(len(points))):
        h = sweep.history(i)
        motion = motion_of(summaries[i])
        label = (f"{names[motion]}: " if motion in names else "") + motion_label(motion)
        if several_tips:
            label += f", {tip_label(tip_of(summaries[i]))}"
        ax.plot(h["time_s"], h["max_strain_rate"], ms=4, label=label + " (point maximum)", **style)
        if "critical_distance_strain_rate_per_s" in h:
            ax.plot(h["time_s"], h["critical_distance_strain_rate_per_s"], ls="--", ms=3,
                    label=label + " (judged: ball average over the window)", **style)
    ax.axhline(limits["strain_rate_per_s"], color="#d62728", ls=":",
               label=f"strain-rate limit {limits['strain_rate_per_s']:g} 1/s")
    return finish_axes(fig, ax, png, points, "time [s]", "max principal strain rate [1/s]",
                "Tissue strain rate against insertion and rotation speed")


def varying_keys(sweep, rows):
    """Swept keys that take more than one value over the given rows."""
    out = []
    for key in sweep.swept_keys:
        values = {sweep.table[key][i] for i in rows}
        values = {v for v in values if not (isinstance(v, float) and math.isnan(v))}
        if len(values) > 1:
            out.append(key)
    return out


# Words for the keys a design study sweeps; any other key is spelt out from its name and unit suffix.
KEY_WORDS = {"needle.radius_mm": "needle radius r [mm]", "needle.bevel_deg": "bevel angle α [°]",
             "needle.fillet_mm": "tip fillet radius τ [mm]", "needle.edge_radius_um": "edge radius ρ [µm]",
             "motion.insertion_speed_mm_per_s": "insertion speed [mm/s]",
             "motion.rotation_speed_deg_per_s": "rotation speed [°/s]"}
UNIT_SUFFIXES = (("_mm_per_s", "mm/s"), ("_deg_per_s", "°/s"), ("_mm", "mm"), ("_um", "µm"), ("_deg", "°"),
                 ("_pa", "Pa"), ("_s", "s"))


def key_label(key):
    """A case key in words with its unit: "needle.fillet_mm" -> "tip fillet radius τ [mm]"."""
    if key in KEY_WORDS:
        return KEY_WORDS[key]
    section, name = key.split(".", 1) if "." in key else ("", key)
    for suffix, unit in UNIT_SUFFIXES:
        if name.endswith(suffix):
            return f"{section} {name[:-len(suffix)]}".strip().replace("_", " ") + f" [{unit}]"
    return f"{section} {name}".strip().replace("_", " ")


def value_text(key, value):
    """`key = value` in words for a panel title."""
    label = key_label(key)
    unit = label[label.rfind("[") + 1:-1] if label.endswith("]") else ""
    words = label[:label.rfind(" [")] if unit else label
    return f"{words} {value:g} {unit}".strip() if isinstance(value, float) else f"{words} {value}"


def map_mark(sweep, i):
    """(mark, label) of design point i on the safety map: its verdict with the failing limits, or
    why it has none (run failed, impossible with its rules, pending)."""
    t = sweep.table
    status = t["status"][i]
    if status == "completed":
        if t["verdict"][i] == 0:
            failing = [c[len("verdict_"):] for c in sweep.columns if c.startswith("verdict_") and t[c][i] == 0]
            return "fail", ", ".join(failing)
        # The point maxima are mesh-dependent next to a needle edge: say when they alone fail.
        return "pass", "point maxima fail" if t["safe"][i] == 0 else ""
    if status == "failed":
        return "run failed", ""
    return status, t["rules"][i] if status == "impossible" else ""


def safety_map(sweep, png, x=None, y=None, grid=None):
    """Every design point over two swept keys: its verdict (which limits fail), run failed, impossible."""
    if "verdict" not in sweep.table:
        raise SystemExit(f"{sweep.dir}/sweep.h5: no verdict column (an older table; `needlefem sweep SWEEP.toml "
                         f"--out {sweep.dir} --list` rewrites it)")
    rows = sweep.indices(grid, status=None)
    keys = varying_keys(sweep, rows)
    x = x or (keys[0] if keys else sweep.swept_keys[0])
    rest = [k for k in keys if k != x]
    y = y or (rest[0] if rest else None)
    for key in filter(None, (x, y)):
        if key not in sweep.table:
            raise SystemExit(f"safety-map: '{key}' is not a swept key of {sweep.dir} ({', '.join(sweep.swept_keys)})")
    panel_keys = [k for k in keys if k not in (x, y)]
    t = sweep.table
    panels = sorted({tuple(t[k][i] for k in panel_keys) for i in rows})
    columns = min(3, len(panels))
    lines = math.ceil(len(panels) / columns)
    fig, axes = plt.subplots(lines, columns, figsize=(4.6 * columns, 3.9 * lines), squeeze=False)
    styles = {"pass": dict(marker="o", color="#2ca02c"), "fail": dict(marker="X", color="#d62728"),
              "run failed": dict(marker="^", color="k"), "impossible": dict(marker="s", color="#b0b0b0"),
              "pending": dict(marker="o", color="#1f77b4", fillstyle="none")}
    seen = set()
    notes = {}  # note -> its letter: a letter beside a marker never overprints its neighbours
    for ax, panel in zip(axes.flat, panels):
        for i in rows:
            if tuple(t[k][i] for k in panel_keys) != panel:
                continue
            status, note = map_mark(sweep, i)
            yv = t[y][i] if y else 0.0
            ax.plot(t[x][i], yv, ls="none", ms=11, label=None if status in seen else status, **styles[status])
            seen.add(status)
            if note:
                letter = notes.setdefault(note, "abcdefghijklmnopqrstuvwxyz"[len(notes) % 26])
                ax.annotate(letter, (t[x][i], yv), textcoords="offset points", xytext=(7, 5), fontsize=7)
        ax.set_xlabel(key_label(x))
        ax.set_ylabel(key_label(y) if y else "")
        if not y:
            ax.set_yticks([])
        title = ", ".join(value_text(k, v) for k, v in zip(panel_keys, panel))
        ax.set_title(textwrap.fill(title, 60) or (f"grid {grid}" if grid else "design grid"), fontsize=8)
        ax.margins(0.2)
        ax.grid(True, alpha=0.3)
    for ax in list(axes.flat)[len(panels):]:
        ax.axis("off")
    handles = [plt.Line2D([], [], ls="none", ms=9, label=s, **styles[s]) for s in styles if s in seen]
    title = textwrap.fill("Verdict per design: critical-distance values against the limits (letters: the failing "
                          "limits or violated geometry rules below)", 40 * columns)
    warning = textwrap.fill(sweep.coarse_mesh_warning(rows), 40 * columns)
    # Room above the panels for the title and the warning: about 0.2 inch a line.
    title_lines = title.count("\n") + 1 + (warning.count("\n") + 1 if warning else 0)
    top = 1 - (0.15 + 0.2 * title_lines) / fig.get_figheight()
    fig.tight_layout(rect=(0, 0, 1, top))
    fig.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.0, top), fontsize=8)
    fig.suptitle(title, fontsize=10, x=0.02, ha="left")
    if warning:
        fig.text(0.02, 1 - (0.1 + 0.2 * (title.count("\n") + 1)) / fig.get_figheight(), warning, fontsize=10,
                 ha="left", va="top", color="#d62728")
    if notes:
        fig.text(0.02, 0.0, "\n".join(textwrap.fill(f"{letter}: {note}", 45 * columns) for note, letter in notes.items()),
                 fontsize=7, va="top", ha="left")
    return finish(fig, png)


SAFETY_LIMITS = (("log_strain", "log strain"), ("strain_rate_per_s", "strain rate"), ("stress_pa", "von Mises stress"))


def safety_steering(sweep, png, grid=None):
    points = [i for i in sweep.indices(grid) if not math.isnan(sweep.table.get("needle_max_lateral_force_n",
                                                                                   [math.nan] * sweep.rows)[i])]
    fig, axes = plt.subplots(1, len(SAFETY_LIMITS), figsize=(5.2 * len(SAFETY_LIMITS), 4.6), sharey=False)
    styles = line_styles(len(points))
    for ax, (name, label) in zip(axes, SAFETY_LIMITS):
        for n, i in enumerate(points):
            summary = sweep.summary(i)
            entry = summary.get("safety", {}).get(name)
            if not entry:
                continue
            limit = entry["limit"]
            lateral_mn = sweep.table["needle_max_lateral_force_n"][i] * 1e3
            margin = 1 - entry["critical_distance"]["value"] / limit
            point_margin = 1 - entry["point_max"]["value"] / limit
            colour = styles[n]["color"]
            ax.plot(lateral_mn, margin, styles[n]["marker"], color=colour,
                    mfc=colour if entry["verdict"] == "pass" else "none",
                    label=f"{tip_label(tip_of(summary))}, {motion_label(motion_of(summary))}")
            ax.plot(lateral_mn, point_margin, "x", color=colour, alpha=0.35)
        ax.axhline(0.0, color="k", lw=0.8)
        ax.set_xlabel("largest lateral force on the needle [mN]")
        ax.set_ylabel(f"{label} margin 1 - value/limit")
        ax.set_title(f"{label}: safe above 0", fontsize=10)
        ax.grid(True, alpha=0.3)
    if not points:
        no_data(axes[0], "no completed runs with needle loads")
    handles, labels = axes[0].get_legend_handles_labels()
    if handles:
        fig.legend(handles, labels, loc="lower center", ncol=min(4, len(labels)), fontsize=7, frameon=False)
        fig.subplots_adjust(bottom=0.12 + 0.035 * math.ceil(len(labels) / 4))
    fig.suptitle("Safety beside steering: marker per design = critical-distance margin (filled = pass), "
                 "faint x = point-maximum margin",
                 fontsize=10)
    warning = sweep.coarse_mesh_warning(points)
    if warning:
        fig.text(0.5, 1.0, textwrap.fill(warning, 150), fontsize=10, ha="center", va="bottom", color="#d62728")
    return finish(fig, png)


def history(run_dir, png):
    """Time histories of one run: maxima against their limits, reactions on the cavity."""
    run_dir = pathlib.Path(run_dir)
    h = read_history(run_dir)
    summary = json.loads((run_dir / "summary.json").read_text())
    limits = run_limits(summary)
    t = h["time_s"]
    fig, axes = plt.subplots(2, 2, figsize=(10, 7), sharex=True)
    panels = [(axes[0, 0], ["max_log_strain"], 1.0, "max principal log strain", limits["log_strain"]),
              (axes[0, 1], ["max_strain_rate", "max_equivalent_strain_rate"], 1.0, "max strain rate [1/s]",
               limits["strain_rate_per_s"]),
              (axes[1, 0], ["max_von_mises", "max_max_principal_stress"], 1e3, "max stress [kPa]", None)]
    for ax, names, scale, label, limit in panels:
        for name in names:
            ax.plot(t, h[name] / scale, marker=".", label=name[len("max_"):].replace("_", " "))
        if limit is not None:
            ax.axhline(limit, color="#d62728", ls="--", label=f"limit {limit:g}")
        ax.set_ylabel(label)
        ax.legend(fontsize=7)
        ax.grid(True, alpha=0.3)
    stress_limit = limits["stress_pa"] / 1e3
    axes[1, 0].set_title(f"(stress limit {stress_limit:g} kPa)", fontsize=8)
    ax = axes[1, 1]
    surface = "cavity" if "reaction_cavity_z_n" in h else next(
        (k[len("reaction_"):-len("_z_n")] for k in h if k.startswith("reaction_") and k.endswith("_z_n")), None)
    if surface:
        for component in "xyz":
            ax.plot(t, h[f"reaction_{surface}_{component}_n"] * 1e3, marker=".", label=f"{component}")
        ax.set_ylabel(f"reaction on {surface} [mN]")
        ax.legend(fontsize=7)
    else:
        no_data(ax, "no reaction surfaces")
    ax.grid(True, alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel("time [s]")
    case = summary["case"]
    title = run_dir.name
    if case.get("scene", {}).get("kind") == "brain-tip":
        title = f"{tip_label(tip_of(summary))}, {motion_label(motion_of(summary))}"
    fig.suptitle(f"Time histories: {title} ({summary.get('status', '?')})", fontsize=10)
    finish(fig, png)


def all_figures(sweep, out, design_grid=None, rate_grid=None):
    """Every figure of the sweep into the folder `out` (the `all` command; the study report embeds them):
    returns [(PNG path, caption)] in reading order."""
    out = pathlib.Path(out)
    drawn = [(out / "safety_map.png", "Verdict of each design (critical-distance values against the limits)",
              lambda png: safety_map(sweep, png, grid=design_grid)),
             (out / "safety_steering.png", "Safety margin of each limit against the lateral force on the needle",
              lambda png: safety_steering(sweep, png, design_grid)),
             (out / "fig4_stress_strain.png", "Max von Mises stress against max log strain per tip (paper 001 Fig. 4; "
              "point maxima)", lambda png: stress_strain(sweep, png, design_grid)),
             (out / "fig5_fillet.png", "Max von Mises stress against fillet radius (paper 001 Fig. 5; point maxima)",
              lambda png: fillet(sweep, png, design_grid)),
             (out / "fig6_strain_rate.png", "Max strain rate against time per speed (paper 001 Fig. 6; point maxima)",
              lambda png: strain_rate(sweep, png, rate_grid))]
    completed = sweep.indices()
    if completed:
        run_dir = sweep.dir / sweep.table["point"][completed[0]]
        drawn.append((out / "history.png", f"Time histories of {run_dir.name}", lambda png: history(run_dir, png)))
    for png, _, draw in drawn:
        draw(png)
    return [(png, caption) for png, caption, _ in drawn]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    commands = parser.add_subparsers(dest="command", required=True)
    for name in ("stress-strain", "fillet", "strain-rate", "safety-steering"):
        p = commands.add_parser(name)
        p.add_argument("sweep_dir")
        p.add_argument("--grid")
        p.add_argument("--png")
    p = commands.add_parser("safety-map")
    p.add_argument("sweep_dir")
    p.add_argument("--grid")
    p.add_argument("--x")
    p.add_argument("--y")
    p.add_argument("--png")
    p = commands.add_parser("history")
    p.add_argument("run_dir")
    p.add_argument("--png")
    p = commands.add_parser("all")
    p.add_argument("sweep_dir")
    p.add_argument("--out")
    p.add_argument("--design-grid")
    p.add_argument("--rate-grid")
    args = parser.parse_args(argv)

    if args.command == "history":
        history(args.run_dir, args.png or pathlib.Path(args.run_dir) / "history.png")
        return 0
    sweep = Sweep(args.sweep_dir)
    figures = {"stress-strain": stress_strain, "fillet": fillet, "strain-rate": strain_rate,
               "safety-steering": safety_steering}
    if args.command in figures:
        figures[args.command](sweep, args.png or sweep.dir / f"{args.command}.png", args.grid)
    elif args.command == "safety-map":
        safety_map(sweep, args.png or sweep.dir / "safety_map.png", args.x, args.y, args.grid)
    else:
        all_figures(sweep, pathlib.Path(args.out) if args.out else sweep.dir / "figures", args.design_grid,
                    args.rate_grid)
    return 0


if __name__ == "__main__":
    sys.exit(main())
