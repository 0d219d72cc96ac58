#!/usr/bin/python3
"""Benchmark (not a test): meshes every case of cases/table1 and the rate-study tip at two core
element sizes and writes one JSON with mesh time, nodes, tets, DOF estimate, min scaled
Jacobian, volume checks and the METIS interface size against a naive split.

    tests/benchmarks/bench_mesh_sizes.py [--exe build/needlefem] [--cores 0.4 0.2] [--out out/bench_mesh]
"""
import argparse
import json
import os
import subprocess
import tempfile
import time
from pathlib import Path

from machine import use_blas_environment

root = Path(__file__).resolve().parents[2]
parser = argparse.ArgumentParser()
parser.add_argument("--exe", default=str(root / "build" / "needlefem"))
parser.add_argument("--cores", nargs="+", type=float, default=[0.4, 0.2])
parser.add_argument("--out", type=Path, default=root / "out" / "bench_mesh")
args = parser.parse_args()
use_blas_environment(args.exe)
# A mesh cache of its own, empty: every meshing timed here is gmsh's (mesh/mesh_cache.hpp).
mesh_cache = tempfile.TemporaryDirectory(prefix="bench-mesh-cache-")
os.environ["NEEDLEFEM_MESH_CACHE"] = mesh_cache.name

cases = sorted((root / "cases" / "table1").glob("*.toml")) + [root / "cases" / "rate_study" / "medium.toml"]
rows = []
for case in cases:
    for core in args.cores:
        out = args.out / f"{case.stem}_core{core}"
        start = time.perf_counter()
        result = subprocess.run([args.exe, "mesh", str(case), "--out", str(out), "--set", f"tissue.core_element_mm={core}"],
                                capture_output=True, text=True)
        wall = time.perf_counter() - start
        row = {"case": case.stem, "core_element_mm": core, "exit_code": result.returncode, "wall_s": round(wall, 3)}
        if (out / "mesh_report.json").exists() and result.returncode == 0:
            r = json.loads((out / "mesh_report.json").read_text())
            row.update({
                "nodes": r["nodes"], "tets": r["tets"], "dof_estimate": r["dof_estimate"]["displacement"],
                "meshing_s": round(r["seconds"]["meshing"], 3), "inverted_tets": r["inverted_tets"],
                "min_scaled_jacobian": min(q["min_scaled_jacobian"] for q in r["regions"].values()),
                "tip_cad_vs_analytic": r["needle"]["cad_volume"]["relative_difference"],
                "cavity_vs_analytic": r["needle"]["cavity_volume_removed_from_mesh"]["relative_difference"],
                "metis_interface_nodes": r["partition"]["metis_interface_nodes"],
                "naive_interface_nodes": r["partition"]["naive_interface_nodes"],
                "high_order_optimisation": r["high_order_optimisation"]})
        else:
            row["error"] = result.stderr.strip()
        rows.append(row)
        print(json.dumps(row), flush=True)
args.out.mkdir(parents=True, exist_ok=True)
(args.out / "bench_mesh_sizes.json").write_text(json.dumps(rows, indent=1) + "\n")
print(f"written {args.out / 'bench_mesh_sizes.json'}")
