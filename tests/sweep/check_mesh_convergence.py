#!/usr/bin/python3
"""postprocess/mesh_convergence.py on a synthetic four-mesh sweep table: a quantity
Q(h) = Q* + C h^p must give back p and Q* (to round-off) from both triples of consecutive sizes,
one that oscillates must be reported without an order, and sizes without a common ratio must be
refused.

usage: check_mesh_convergence.py SCRIPT WORK_DIR
"""
import csv
import json
import math
import pathlib
import subprocess
import sys

script, work = sys.argv[1], pathlib.Path(sys.argv[2])
work.mkdir(parents=True, exist_ok=True)
sizes = [0.4 * math.sqrt(2.0), 0.4, 0.4 / math.sqrt(2.0), 0.2]
exact_strain, order, constant = 0.25, 1.7, 0.3


def write_table(directory, h):
    directory.mkdir(parents=True, exist_ok=True)
    with (directory / "sweep.csv").open("w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["point", "status", "tissue.core_element_mm", "dofs", "wall_s", "max_log_strain",
                         "max_von_mises_pa"])
        for i, size in enumerate(h):
            strain = exact_strain + constant * size**order
            stress = 3000.0 + (40.0 if i % 2 else 0.0)  # 3000, 3040, 3000, 3040: no monotone convergence
            writer.writerow([f"p{i}", "completed", size, 1000 * (i + 1), 10.0 * (i + 1), strain, stress])


good = work / "good"
write_table(good, sizes)
run = subprocess.run([sys.executable, script, str(good)], capture_output=True, text=True)
print(run.stdout, run.stderr)
assert run.returncode == 0, "the script failed on a valid table"
result = json.loads((good / "convergence.json").read_text())
assert len(result["triples"]) == 2, result["triples"]
assert result["quantities"] == result["triples"][-1]["quantities"], "the headline is not the finest triple"
for triple in result["triples"]:
    h1 = triple["sizes_mm"][0]
    strain = triple["quantities"]["max_log_strain"]
    assert abs(strain["order"] - order) < 1e-9, strain
    assert abs(strain["converged"] - exact_strain) < 1e-12, strain
    expected_distance = constant * h1**order / exact_strain
    assert abs(strain["distance"][0] - expected_distance) < 1e-9, strain
    stress = triple["quantities"]["max_von_mises_pa"]
    assert stress["order"] is None and stress["converged"] is None, stress
    print(f"h1 = {h1:.4f}: order {strain['order']:.12f} (exact {order}), Richardson {strain['converged']:.15f} "
          f"(exact {exact_strain})")

bad = work / "bad"
write_table(bad, [0.4, 0.3, 0.2])
run = subprocess.run([sys.executable, script, str(bad)], capture_output=True, text=True)
assert run.returncode != 0 and "common refinement ratio" in run.stderr, run.stderr
print("sizes 0.4, 0.3, 0.2 refused:", run.stderr.strip())
