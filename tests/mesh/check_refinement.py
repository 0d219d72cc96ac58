#!/usr/bin/python3
"""mesh.refinement_level halves the element sizes near the needle, and the block's size;
mesh.edge_elements_per_radius = 2 halves those on the needle's edges alone.

Meshes a case at two consecutive levels with `needlefem mesh` and compares the sizes that
mesh_report.json measured on the meshes themselves (mean edge length of the tissue tets touching
the cavity's sharp edges, and of those touching the cavity surface; scene_mesher.cpp): each
median must shrink by 0.5 +- 0.1 per level, and the sizes must follow their targets. For the
block scene the tet count must grow by about 2^3 per level. With --edge-elements, level 0 is
meshed with 1 and 2 edge elements per radius: the edge target and median must halve, the surface
target stay.
"""
import argparse
import json
import subprocess
import sys
from pathlib import Path

failures = []


def check(condition, message):
    print(("ok: " if condition else "FAIL: ") + message)
    if not condition:
        failures.append(message)


def mesh(exe, case, out, level, extra, edge_elements=1):
    out.mkdir(parents=True, exist_ok=True)
    args = [exe, "mesh", case, "--out", str(out), "--set", f"mesh.refinement_level={level}",
            "--set", f"mesh.edge_elements_per_radius={edge_elements}"] + extra
    result = subprocess.run(args, capture_output=True, text=True)
    check(result.returncode == 0, f"level {level}: needlefem mesh exits 0 ({result.stderr.strip()})")
    return json.loads((out / "mesh_report.json").read_text())


parser = argparse.ArgumentParser()
parser.add_argument("--exe", required=True)
parser.add_argument("--case", required=True)
parser.add_argument("--out", required=True, type=Path)
parser.add_argument("--block", action="store_true")
parser.add_argument("--edge-elements", action="store_true")
parser.add_argument("--set", action="append", default=[])
args = parser.parse_args()
extra = [x for s in args.set for x in ("--set", s)]

if args.edge_elements:
    one, two = (mesh(args.exe, args.case, args.out / f"edge_elements{n}", 0, extra, n) for n in (1, 2))
    ratio = two["grading"]["needle_edge_element_mm"]["median"] / one["grading"]["needle_edge_element_mm"]["median"]
    check(abs(ratio - 0.5) <= 0.1, f"edge elements: median with 2 per radius / with 1 = {ratio:.3f} (0.5 +- 0.1)")
    targets = [r["grading"]["target_mm"] for r in (one, two)]
    check(abs(targets[1]["edge"] / targets[0]["edge"] - 0.5) < 1e-12,
          f"edge target {targets[0]['edge']:.4f} -> {targets[1]['edge']:.4f} mm")
    check(targets[1]["surface"] == targets[0]["surface"], f"surface target stays {targets[0]['surface']:.4f} mm")
    check(one["inverted_tets"] == 0 and two["inverted_tets"] == 0, "no inverted tets")
    sys.exit(1 if failures else 0)

coarse, fine = (mesh(args.exe, args.case, args.out / f"level{k}", k, extra) for k in (0, 1))
if args.block:
    ratio = fine["tets"] / coarse["tets"]
    check(5.0 <= ratio <= 11.0, f"block tets grow by {ratio:.2f} per level (8 for halved sizes)")
else:
    for report, level in ((coarse, 0), (fine, 1)):
        g = report["grading"]
        check(g["refinement_level"] == level, f"the report names level {level}")
        check(g["edge_curves"] >= 2, f"level {level}: {g['edge_curves']} sharp cavity edges found (bevel and fillet)")
        edge = g["needle_edge_element_mm"]
        # Tets touching an edge curve at one corner reach out into the graded zone: their mean
        # edge length is 1-2 times the size aimed at on the curve.
        check(edge["tets"] > 0 and 0.8 * g["target_mm"]["edge"] <= edge["median"] <= 2.0 * g["target_mm"]["edge"],
              f"level {level}: edge elements {edge['median']:.4f} mm (median of {edge['tets']} tets) near the "
              f"target {g['target_mm']['edge']:.4f} mm")
    for name in ("needle_edge_element_mm", "cavity_element_mm"):
        ratio = fine["grading"][name]["median"] / coarse["grading"][name]["median"]
        check(abs(ratio - 0.5) <= 0.1, f"{name}: median level 1 / level 0 = {ratio:.3f} (0.5 +- 0.1)")
    check(fine["grading"]["grading_distance_mm"] == coarse["grading"]["grading_distance_mm"],
          "the graded zone keeps its extent")
    check(fine["inverted_tets"] == 0 and coarse["inverted_tets"] == 0, "no inverted tets")
sys.exit(1 if failures else 0)
