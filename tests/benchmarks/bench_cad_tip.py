#!/usr/bin/python3
"""Benchmark (not a test): a CAD tip against the analytic tip at the same mesh (issue 26).

The paper's tip (cases/table1/r0.50_a20_f0.25.toml, default mesh and motion, 0.1 s) three ways:
  analytic       needle.kind = "bevel"; also writes the tip as STEP (needle.export_file);
  cad_same_mesh  needle.kind = "cad" reading that STEP, on the analytic run's mesh file: only the
                 contact needle differs (the triangulated, trimmed-offset CAD surface);
  cad_own_mesh   needle.kind = "cad", the cavity carved from the STEP by the scene mesher.
Each run records wall and CPU time (bench_runs.py); the JSON holds the ratios to the analytic
run (target: the CAD tip within 1.3x the analytic wall time at the same mesh) and the relative
differences of the needle's largest axial force and torque and of the critical-distance safety
metrics (targets 1 % and 2 %).

    tests/benchmarks/bench_cad_tip.py --out out/bench_cad_tip [--exe build/needlefem]
Resumable. Writes OUT/bench_cad_tip.json.
"""
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_runs import binary_identity, run_case, study_arguments  # noqa: E402

METRICS = ["log_strain", "strain_rate_per_s", "stress_pa"]


def quantities(out_dir, record):
    summary = json.loads((Path(out_dir) / "summary.json").read_text())
    values = {"max_axial_force_n": summary["needle"]["max_axial_force_n"],
              "max_torque_n_m": summary["needle"]["max_torque_n_m"]}
    for m in METRICS:
        values[f"{m}_critical_distance"] = summary["safety"][m]["critical_distance"]["value"]
    return {"status": record.get("status"), "wall_s": record.get("process_wall_s"), "cpu_s": record.get("cpu_s"),
            "solver": {k: summary["solver"].get(k) for k in ("wall_s", "mesh_s", "integration_s", "steps",
                                                            "newton_iterations", "newton_convergence_failures")},
            "values": values}


def main():
    args = study_arguments(__doc__, "bench_cad_tip", 3600.0)
    out = args.out
    step = out / "analytic" / "tip.step"
    runs = {"analytic": ({"needle.export_file": step}, out / "analytic")}
    cad = {"needle.kind": "cad", "needle.cad_file": step}
    runs["cad_same_mesh"] = ({**cad, "scene.mesh_file": out / "analytic" / "mesh.msh"}, out / "cad_same_mesh")
    runs["cad_own_mesh"] = (cad, out / "cad_own_mesh")
    results = {}
    for name, (overrides, directory) in runs.items():
        record = run_case(args.case, directory, {k: str(v) for k, v in overrides.items()}, exe=args.exe,
                          timeout_s=args.timeout)
        results[name] = quantities(directory, record)
        print(name, results[name]["wall_s"], "s", results[name]["values"])
    reference = results["analytic"]
    for name in ("cad_same_mesh", "cad_own_mesh"):
        r = results[name]
        r["wall_ratio"] = r["wall_s"] / reference["wall_s"]
        r["cpu_ratio"] = r["cpu_s"] / reference["cpu_s"]
        r["relative_difference"] = {k: (v - reference["values"][k]) / reference["values"][k]
                                    for k, v in r["values"].items()}
    report = {"case": str(args.case), "binary": binary_identity(args.exe), "runs": results,
              "targets": {"wall_ratio": 1.3, "loads": 0.01, "critical_distance": 0.02}}
    (out / "bench_cad_tip.json").write_text(json.dumps(report, indent=1) + "\n")
    print(json.dumps({n: {k: results[n].get(k) for k in ("wall_ratio", "cpu_ratio", "relative_difference")}
                      for n in ("cad_same_mesh", "cad_own_mesh")}, indent=1))


if __name__ == "__main__":
    main()
