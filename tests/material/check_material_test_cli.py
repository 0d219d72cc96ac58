"""Runs `needlefem material-test` the ways its documentation shows and checks the CSV header,
the row times and the stresses against closed forms for Miller's brain model
(incompressible uniaxial: sigma = 2 (l^2 - 1/l)(W1 + W2/l); simple shear: tau = 2 g (W1 + W2)).

usage: check_material_test_cli.py NEEDLEFEM_EXECUTABLE
"""
import csv
import io
import math
import os
import subprocess
import sys
import tempfile

HEADER = "time_s,stretch,shear,nominal_stress_pa,cauchy_stress_pa,log_strain,strain_rate_per_s"
MILLER = dict(c10=263.0, c01=263.0, c20=491.0, c11=0.0, c02=491.0)
EXE = sys.argv[1]
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


def run(*args, expect_ok=True):
    result = subprocess.run([EXE, "material-test", *args], capture_output=True, text=True)
    check((result.returncode == 0) == expect_ok, f"{args}: exit {result.returncode}: {result.stderr.strip()}")
    return result


def rows_of(*args):
    result = run(*args)
    lines = result.stdout.splitlines()
    check(lines and lines[0] == HEADER, f"{args}: header {lines[:1]}")
    return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(io.StringIO(result.stdout))]


def w_derivatives(i1, i2, c=MILLER):
    a, b = i1 - 3, i2 - 3
    return c["c10"] + 2 * c["c20"] * a + c["c11"] * b, c["c01"] + c["c11"] * a + 2 * c["c02"] * b


def close(value, reference, tolerance=1e-6):
    return abs(value - reference) <= tolerance * abs(reference)


help_text = run("--help").stdout
check("INSTANTANEOUS" in help_text and "long-term" in help_text, "--help must say the moduli are instantaneous")

for target in (1.5, 0.7):
    rows = rows_of("--material", "miller-brain", "--history", "uniaxial", "--to", str(target), "--steps", "8")
    check(len(rows) == 9 and rows[-1]["stretch"] == target, f"uniaxial {target}: rows")
    for row in rows[1:]:
        l = row["stretch"]
        w1, w2 = w_derivatives(l * l + 2 / l, 2 * l + 1 / l**2)
        sigma = 2 * (l * l - 1 / l) * (w1 + w2 / l)
        check(close(row["cauchy_stress_pa"], sigma), f"uniaxial l={l}: {row['cauchy_stress_pa']} vs {sigma}")
        check(close(row["nominal_stress_pa"], sigma / l), f"uniaxial nominal l={l}")

rows = rows_of("--material", "miller-brain", "--history", "shear", "--to", "1.0", "--steps", "10")
check(len(rows) == 11, "shear rows")
for row in rows[1:]:
    g = row["shear"]
    w1, w2 = w_derivatives(3 + g * g, 3 + g * g)
    check(close(row["cauchy_stress_pa"], 2 * g * (w1 + w2)), f"shear g={g}")

rows = rows_of("--material", "miller-brain", "--history", "relaxation", "--to", "1.1", "--ramp", "0.1", "--hold", "100")
times = [row["time_s"] for row in rows]
for required in (0.05, 0.1, 0.6, 5, 50, 100):
    check(any(abs(t - required) < 1e-9 for t in times), f"relaxation: no row at t = {required}")
hold = [row["cauchy_stress_pa"] for row in rows if row["time_s"] >= 0.1 - 1e-12]
check(all(b < a for a, b in zip(hold, hold[1:])), "relaxation: stress must fall during the hold")
check(0.185 < hold[-1] / hold[0] < 0.4, f"relaxation: remaining fraction {hold[-1] / hold[0]}")

rows = rows_of("--material", "miller-brain", "--history", "constant-rate", "--rate", "0.64", "--to", "0.7")
check(close(rows[-1]["time_s"], 0.3 / 0.64, 1e-9) and close(rows[-1]["stretch"], 0.7, 1e-12), "constant-rate end")
check(close(rows[-1]["strain_rate_per_s"], -0.64 / 0.7, 1e-9), "constant-rate strain rate")
check(all(row["cauchy_stress_pa"] <= 0 for row in rows), "constant-rate: compression")

# A case file's [material] table; a literal-print preset through --material.
with tempfile.TemporaryDirectory() as folder:
    case_file = os.path.join(folder, "neo.toml")
    with open(case_file, "w") as f:
        f.write('[material]\npreset = "custom"\nc10_instantaneous_pa = 500.0\n')
    rows = rows_of("--case", case_file, "--history", "shear", "--to", "0.5", "--steps", "1")
    check(close(rows[-1]["cauchy_stress_pa"], 2 * 0.5 * 500.0), "neo-Hookean case: tau = mu gamma")
rows = rows_of("--material", "miller-brain-c10-c20", "--to", "1.2", "--steps", "1")
l = 1.2
w1, w2 = w_derivatives(l * l + 2 / l, 2 * l + 1 / l**2, dict(c10=263.0, c01=0, c20=491.0, c11=0, c02=0))
check(close(rows[-1]["cauchy_stress_pa"], 2 * (l * l - 1 / l) * (w1 + w2 / l)), "miller-brain-c10-c20 uniaxial")

bad = run("--material", "no-such-brain", expect_ok=False)
check(bad.stderr.startswith("needlefem: error:") and "material.preset" in bad.stderr, f"bad preset: {bad.stderr}")

if failures:
    print("\n".join(failures))
    sys.exit(1)
print("material-test command: all checks passed")
