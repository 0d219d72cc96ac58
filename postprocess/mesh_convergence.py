#!/usr/bin/python3
"""Observed order and Richardson extrapolation of a sweep's maxima over three or more mesh sizes.

Reads SWEEP_DIR/sweep.csv of a `needlefem sweep` whose only varying key is the core element size
(cases/sweeps/mesh_convergence.toml) and prints, and writes as SWEEP_DIR/convergence.json and
.csv, for each maximum Q (log strain, strain rate, von Mises stress, max principal stress, needle
force and torque) and each three consecutive sizes:

  h1 > h2 > h3 with a common ratio r = h1/h2 = h2/h3 (all sizes checked to 2 %),
  observed order   p = ln((Q1 - Q2)/(Q2 - Q3)) / ln r           (needs monotone convergence),
  Richardson       Q* = Q3 + (Q3 - Q2)/(r^p - 1),
  distance of each mesh from it  (Q_i - Q*)/Q*.

Oscillating or stagnating differences (Q1 - Q2 and Q2 - Q3 of opposite signs, or a ratio that
gives p <= 0) have no order: the row says so and gives the spread of the three values instead.
convergence.json's "quantities" holds the three finest sizes; "triples" every consecutive three.

usage: /usr/bin/python3 postprocess/mesh_convergence.py SWEEP_DIR [--key tissue.core_element_mm]
"""
import argparse
import csv
import json
import math
import pathlib
import sys

QUANTITIES = {
    "max_log_strain": "max log strain",
    "max_strain_rate_per_s": "max strain rate (1/s)",
    "max_von_mises_pa": "max von Mises (Pa)",
    "max_principal_stress_pa": "max principal stress (Pa)",
    "needle_max_axial_force_n": "needle axial force (N)",
    "needle_max_torque_n_m": "needle torque (N m)",
}


def richardson(h, q):
    """Observed order and extrapolated value of q over sizes h (descending), as a dict."""
    ratio = h[0] / h[1]
    d1, d2 = q[0] - q[1], q[1] - q[2]
    row = {"values": q, "spread": (max(q) - min(q)) / abs(q[2]) if q[2] else float("nan")}
    if d1 == 0.0 or d2 == 0.0 or d1 * d2 < 0.0 or abs(d1) <= abs(d2):
        row.update(order=None, converged=None, note="no monotone convergence: no order, no extrapolation")
        return row
    order = math.log(d1 / d2) / math.log(ratio)
    converged = q[2] + (q[2] - q[1]) / (ratio**order - 1.0)
    row.update(order=order, converged=converged, note="",
               distance=[(value - converged) / converged for value in q])
    return row


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("sweep_dir", type=pathlib.Path)
    parser.add_argument("--key", default="tissue.core_element_mm")
    args = parser.parse_args()
    path = args.sweep_dir / "sweep.csv"
    if not path.exists():
        sys.exit(f"{path}: no sweep table (run `needlefem sweep` first)")
    rows = [r for r in csv.DictReader(path.open()) if r["status"] == "completed"]
    if args.key not in (rows[0] if rows else {}):
        sys.exit(f"{path}: column '{args.key}' missing or no completed points")
    rows.sort(key=lambda r: -float(r[args.key]))
    if len(rows) < 3:
        sys.exit(f"{path}: needs at least three completed mesh sizes, found {len(rows)}")
    h = [float(r[args.key]) for r in rows]
    ratios = [h[i] / h[i + 1] for i in range(len(h) - 1)]
    if any(abs(ratio / ratios[0] - 1.0) > 0.02 for ratio in ratios):
        sys.exit(f"{path}: the sizes {h} do not have a common refinement ratio")
    result = {"sizes_mm": h, "ratio": ratios[0], "dofs": [int(r["dofs"]) for r in rows],
              "wall_s": [float(r["wall_s"]) for r in rows], "quantities": {}, "triples": []}
    print(f"core sizes {h} mm (ratio {ratios[0]:.3f}), dofs {result['dofs']}, wall {result['wall_s']} s")
    table = []
    for first in range(len(h) - 2):
        sizes = h[first:first + 3]
        triple = {"sizes_mm": sizes, "quantities": {}}
        print(f"sizes {sizes} mm:")
        for column, label in QUANTITIES.items():
            if not all(r.get(column) for r in rows):
                continue
            q = [abs(float(r[column])) for r in rows[first:first + 3]]
            row = richardson(sizes, q)
            triple["quantities"][column] = row
            if row["order"] is None:
                print(f"  {label:28s} {q[0]:.5g} {q[1]:.5g} {q[2]:.5g}  {row['note']}; spread {100 * row['spread']:.1f} %")
            else:
                print(f"  {label:28s} {q[0]:.5g} {q[1]:.5g} {q[2]:.5g}  order {row['order']:.2f}, Richardson "
                      f"{row['converged']:.5g}, {sizes[0]} mm is {100 * row['distance'][0]:+.1f} % from it")
            table.append([label] + sizes + q + [row["order"], row["converged"],
                                                row["distance"][0] if row["order"] else None])
        result["triples"].append(triple)
    result["quantities"] = result["triples"][-1]["quantities"]
    (args.sweep_dir / "convergence.json").write_text(json.dumps(result, indent=2))
    with (args.sweep_dir / "convergence.csv").open("w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["quantity", "h1_mm", "h2_mm", "h3_mm", "q1", "q2", "q3", "order", "richardson",
                         "distance_of_h1"])
        writer.writerows(table)


if __name__ == "__main__":
    main()
