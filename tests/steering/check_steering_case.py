#!/usr/bin/python3
"""`needlefem steer` on a case, then checks the summary JSON and the HDF5 path file against each
other and against required bounds, and (with --plot) that postprocess/plot_steering.py writes a
non-empty PNG.

usage: check_steering_case.py --exe NEEDLEFEM --case CASE.toml --out DIR
           [--min-clearance-mm X] [--max-miss-mm Y] [--plot SCRIPT]
"""
import argparse
import json
import math
import pathlib
import subprocess
import sys

import h5py
import numpy as np


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--exe", required=True)
    p.add_argument("--case", required=True, type=pathlib.Path)
    p.add_argument("--out", required=True, type=pathlib.Path)
    p.add_argument("--min-clearance-mm", type=float)
    p.add_argument("--max-miss-mm", type=float)
    p.add_argument("--plot", type=pathlib.Path)
    a = p.parse_args()

    subprocess.run([a.exe, "steer", str(a.case), "--out", str(a.out)], check=True, stdout=subprocess.DEVNULL)
    summary = json.loads((a.out / (a.case.stem + ".json")).read_text())
    h5 = a.out / (a.case.stem + ".h5")
    failures = []
    with h5py.File(h5, "r") as f:
        tip = f["tip_position_m"][()]
        target = f["scene/target_m"][()]
        miss = np.linalg.norm(tip[-1] - target) * 1e3
        if not math.isclose(miss, summary["target_miss_distance_mm"], rel_tol=1e-9, abs_tol=1e-12):
            failures.append(f"miss distance: file {miss} mm, summary {summary['target_miss_distance_mm']} mm")
        # The tip path's clearance from the samples alone is an upper bound of the polyline's.
        centre, radius = f["scene/obstacle_centre_m"][()], f["scene/obstacle_radius_m"][0]
        sampled = (np.linalg.norm(tip - centre, axis=1).min() - radius) * 1e3
        clearance = summary["obstacle_clearance_tip_path_mm"]
        if not (clearance <= sampled + 1e-9 and sampled - clearance < 0.01):
            failures.append(f"tip-path clearance {clearance} mm vs sampled {sampled} mm")
        # The closest approach is to the target, not the obstacle: at most the sampled distance and the
        # final miss, above the polyline's lower bound between samples.
        closest, sampled = summary["target_closest_approach_mm"], np.linalg.norm(tip - target, axis=1).min() * 1e3
        step = np.linalg.norm(np.diff(tip, axis=0), axis=1).max() * 1e3
        if not (closest <= min(sampled, summary["target_miss_distance_mm"]) + 1e-9 and sampled - closest <= step):
            failures.append(f"target closest approach {closest} mm vs sampled {sampled} mm (step {step} mm)")
        if not math.isclose(f.attrs["target_closest_approach_m"] * 1e3, closest, rel_tol=1e-12):
            failures.append("the path file's target_closest_approach_m differs from the summary")
        heads = f["head_direction"][()]
        if np.abs(np.linalg.norm(heads, axis=1) - 1).max() > 1e-12:
            failures.append("head directions are not unit vectors")
    print(f"obstacle clearance: needle {summary['obstacle_clearance_needle_mm']:.4f} mm, tip path "
          f"{summary['obstacle_clearance_tip_path_mm']:.4f} mm; target: miss "
          f"{summary['target_miss_distance_mm']:.4f} mm, "
          f"closest approach {summary['target_closest_approach_mm']:.4f} mm, "
          f"max theta {summary['max_turning_angle_deg']:.2f} deg")
    if a.min_clearance_mm is not None and not summary["obstacle_clearance_needle_mm"] > a.min_clearance_mm:
        failures.append(f"needle clearance {summary['obstacle_clearance_needle_mm']} mm <= {a.min_clearance_mm} mm")
    if a.max_miss_mm is not None and not summary["target_miss_distance_mm"] < a.max_miss_mm:
        failures.append(f"miss distance {summary['target_miss_distance_mm']} mm >= {a.max_miss_mm} mm")
    if not summary["tip_stays_in_block"]:
        failures.append("the tip leaves the tissue block")
    if a.plot:
        png = a.out / (a.case.stem + ".png")
        png.unlink(missing_ok=True)
        subprocess.run(["/usr/bin/python3", str(a.plot), str(h5), "--png", str(png)], check=True,
                       stdout=subprocess.DEVNULL)
        data = png.read_bytes() if png.exists() else b""
        if len(data) < 10000 or not data.startswith(b"\x89PNG\r\n\x1a\n"):
            failures.append(f"{png}: missing, not a PNG, or nearly empty ({len(data)} bytes)")
    for f in failures:
        print("FAIL:", f)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
