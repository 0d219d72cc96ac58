#!/usr/bin/python3
"""`needlefem force-trajectory`: its prerequisite and how far it extrapolates the energy run.

  1. With no energy history yet, one line names the command that makes it: the energy case of
     cases/compliant/insertion_force.toml run into the history's folder.
  2. On a synthetic energy run, U = c x^2 sampled to 0.1 mm (c = 50 J/m^2, so F_def = 2 c x and the
     rupture force F_r is reached at x_r = F_r / (2 c)): F_r = 0.015 N (x_r = 0.15 mm, 1.5 times
     the run) passes silently; 0.04 N (0.4 mm, 4 times) warns on stderr and says 4 in the JSON;
     0.25 N (2.5 mm, 25 times, above the case's limit of 20) is refused in one line naming
     insertion_force.extrapolation_limit_factor.

usage: check_force_trajectory.py --exe NEEDLEFEM --case insertion_force.toml --out DIR
"""
import argparse
import json
import pathlib
import shutil
import subprocess
import sys

C = 50.0  # J/m^2
SPEED_MM_PER_S = 1.0
failures = []


def check(condition, message):
    print(("ok   " if condition else "FAIL ") + message)
    if not condition:
        failures.append(message)


def force_trajectory(args, cwd, *overrides):
    command = [args.exe, "force-trajectory", str(args.case), "--out", "trajectory"]
    for o in overrides:
        command += ["--set", o]
    return subprocess.run(command, cwd=cwd, capture_output=True, text=True)


def synthetic_run(folder):
    """history.csv and summary.json of a tied run whose elastic energy is U = C x^2, x = v t."""
    folder.mkdir(parents=True)
    rows = ["time_s,elastic_energy_j"]
    for k in range(11):
        t = 0.01 * k
        x = SPEED_MM_PER_S * t * 1e-3
        rows.append(f"{t!r},{C * x * x!r}")
    (folder / "history.csv").write_text("\n".join(rows) + "\n")
    summary = {"status": "completed", "case": {"motion": {"insertion_speed_mm_per_s": SPEED_MM_PER_S},
                                               "contact": {"mode": "tied"}}}
    (folder / "summary.json").write_text(json.dumps(summary))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--exe", required=True)
    parser.add_argument("--case", required=True, type=pathlib.Path)
    parser.add_argument("--out", required=True, type=pathlib.Path)
    args = parser.parse_args()
    out = args.out.resolve()
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)

    missing = force_trajectory(args, out, f"insertion_force.energy_history={out / 'missing_run' / 'history.csv'}")
    lines = missing.stderr.strip().splitlines()
    energy_case = (args.case.parent / "paper000_hinge.toml").resolve()
    expected = (f"{args.case.resolve()}: key 'insertion_force.energy_history': missing_run/history.csv does not "
                f"exist; make it first: {pathlib.Path(args.exe).resolve()} run {energy_case} --out missing_run")
    check(missing.returncode != 0 and lines == [f"needlefem: error: {expected}"],
          f"a missing energy history names the command that makes it: {lines}")

    synthetic_run(out / "run")
    history = f"insertion_force.energy_history={out / 'run' / 'history.csv'}"
    common = [history, "insertion_force.fracture_toughness_j_per_m2=1"]
    for rupture_n, factor in ((0.015, 1.5), (0.04, 4.0)):
        result = force_trajectory(args, out, *common, f"insertion_force.rupture_force_n={rupture_n}")
        summary = json.loads((out / "trajectory" / "insertion_force.json").read_text()) if result.returncode == 0 else {}
        said = summary.get("energy_extrapolated_by", float("nan"))
        check(result.returncode == 0 and abs(said - factor) <= 1e-9 * factor,
              f"F_r = {rupture_n} N: energy_extrapolated_by {said} = {factor} ({result.stderr.strip()})")
        warning = (f"force-trajectory: warning: the deformation stage runs to x = {factor / 10:g} mm, {factor:g} times "
                   f"the energy run's last sample (0.1 mm): the force there is the power-law fit's extrapolation "
                   f"(insertion_force.extrapolation_warn_factor = 2)")
        check(result.stderr.strip().splitlines() == ([warning] if factor > 2 else []),
              f"F_r = {rupture_n} N: {'a warning' if factor > 2 else 'no warning'} on stderr: {result.stderr.strip()}")

    refused = force_trajectory(args, out, *common, "insertion_force.rupture_force_n=0.25")
    lines = refused.stderr.strip().splitlines()
    expected = (f"{args.case.resolve()}: key 'insertion_force.extrapolation_limit_factor': the deformation stage runs "
                f"to x = 2.5 mm, 25 times the energy run's last sample (0.1 mm), more than 20 times")
    check(refused.returncode != 0 and len(lines) == 1 and lines[0].startswith(f"needlefem: error: {expected}"),
          f"25 times the run is refused in one line: {lines}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
