#!/usr/bin/python3
"""Plot a `needlefem steer` path file (layout: solver/steering/path_file.hpp) as one PNG.

Left: the tip and shaft paths in the x-z and y-z planes with the tissue block, the obstacle
sphere (its section through the centre), the needle radius band and the target. Right: the head
turning angle, the flux density at the head and the magnetic pull against insertion depth.

usage: /usr/bin/python3 postprocess/plot_steering.py PATH.h5 [--png OUT.png]
(default OUT.png: PATH with the extension .png)
"""
import argparse
import math
import pathlib
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read(path):
    with h5py.File(path, "r") as f:
        if f.attrs.get("format") not in ("needlefem-steering-path", b"needlefem-steering-path"):
            raise SystemExit(f"{path}: not a needlefem steering path file")
        data = {name: f[name][()] for name in f if isinstance(f[name], h5py.Dataset)}
        data["scene"] = {name: f["scene"][name][()] for name in f["scene"]}
        data["outcome"] = {k: float(f.attrs[k]) for k in
                           ("obstacle_clearance_tip_path_m", "obstacle_clearance_needle_m", "target_miss_distance_m")}
    return data


def draw_plane(ax, data, axis, label):
    mm = 1e3
    scene = data["scene"]
    lo, hi = scene["block_min_m"] * mm, scene["block_max_m"] * mm
    ax.add_patch(plt.Rectangle((lo[2], lo[axis]), hi[2] - lo[2], hi[axis] - lo[axis],
                               fill=True, color="#f3e3dc", zorder=0, label="tissue block"))
    centre = scene["obstacle_centre_m"] * mm
    radius = float(scene["obstacle_radius_m"][0]) * mm
    ax.add_patch(plt.Circle((centre[2], centre[axis]), radius, color="#7a7a7a", alpha=0.8, label="obstacle"))
    tip = data["tip_position_m"] * mm
    pivot = data["pivot_position_m"] * mm
    needle_radius = float(scene["needle_radius_m"][0]) * mm
    ax.fill_between(tip[:, 2], tip[:, axis] - needle_radius, tip[:, axis] + needle_radius,
                    color="#1f77b4", alpha=0.2, lw=0)
    ax.plot(tip[:, 2], tip[:, axis], color="#1f77b4", lw=1.5, label="tip path")
    ax.plot(pivot[:, 2], pivot[:, axis], color="#ff7f0e", lw=1, ls="--", label="shaft (pivot) path")
    head_end = tip[-1]
    ax.plot([pivot[-1, 2], head_end[2]], [pivot[-1, axis], head_end[axis]], color="k", lw=2.5, label="head, final")
    target = scene["target_m"] * mm
    ax.plot(target[2], target[axis], marker="^", color="#d62728", ms=9, ls="none", label="target")
    ax.set_xlabel("z (insertion axis) [mm]")
    ax.set_ylabel(f"{label} [mm]")
    ax.set_aspect("equal")
    ax.set_xlim(min(lo[2], pivot[:, 2].min()) - 1, hi[2] + 1)
    ax.set_ylim(lo[axis] - 1, hi[axis] + 1)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("path_file", type=pathlib.Path)
    parser.add_argument("--png", type=pathlib.Path)
    args = parser.parse_args(argv)
    data = read(args.path_file)
    png = args.png or args.path_file.with_suffix(".png")

    fig = plt.figure(figsize=(13, 7), constrained_layout=True)
    grid = fig.add_gridspec(3, 2, width_ratios=[1.5, 1])
    draw_plane(fig.add_subplot(grid[0:2, 0]), data, 0, "x")
    side = fig.add_subplot(grid[2, 0])
    draw_plane(side, data, 1, "y")
    fig.axes[0].legend(loc="upper left", fontsize=8, ncol=2)

    depth = data["depth_m"] * 1e3
    force = np.linalg.norm(data["force_n"], axis=1)
    series = [(np.degrees(data["turning_angle_rad"]), "turning angle θ [deg]"),
              (data["flux_density_t"], "flux density B [T]"),
              (force, "magnetic pull F [N]")]
    for row, (values, label) in enumerate(series):
        ax = fig.add_subplot(grid[row, 1])
        ax.plot(depth, values)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        if row == 2:
            ax.set_xlabel("insertion depth [mm]")
    o = data["outcome"]
    fig.suptitle(f"{args.path_file.name}: obstacle clearance of the needle "
                 f"{o['obstacle_clearance_needle_m'] * 1e3:.2f} mm, of the tip path "
                 f"{o['obstacle_clearance_tip_path_m'] * 1e3:.2f} mm; "
                 f"target miss distance {o['target_miss_distance_m'] * 1e3:.3f} mm")
    fig.savefig(png, dpi=110)
    print(png)


if __name__ == "__main__":
    main(sys.argv[1:])
