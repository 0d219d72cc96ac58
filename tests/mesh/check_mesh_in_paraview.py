#!/usr/bin/python3
"""Runs tests/output/check_paraview.py on the mesh.xdmf of a `needlefem mesh` output folder,
with the expectations taken from its mesh_report.json (counts, region range, quality ranges)."""
import json
import subprocess
import sys
from pathlib import Path

folder, checker = Path(sys.argv[1]), sys.argv[2]
report = json.loads((folder / "mesh_report.json").read_text())
regions = report["regions"]
min_scaled = min(r["min_scaled_jacobian"] for r in regions.values())
min_ratio = min(r["min_radius_ratio"] for r in regions.values())
command = [sys.executable, checker, str(folder / "mesh.xdmf"), "--cells", str(report["tets"]),
           "--points", str(report["nodes"]), "--rtol", "1e-6", "--atol", "1e-9",
           "--array", f"name=region,assoc=cell,min=0,max={len(regions) - 1},components=1",
           "--array", f"name=scaled_jacobian,assoc=cell,min={min_scaled},max=1",
           "--array", f"name=radius_ratio,assoc=cell,min={min_ratio}",
           "--array", f"name=partition,assoc=cell,min=0,max={report['partition']['parts'] - 1}"]
sys.exit(subprocess.run(command).returncode)
