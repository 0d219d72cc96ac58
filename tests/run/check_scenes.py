#!/usr/bin/env python3
"""Runs `needlefem run` on the verification cases of the mesh scene (cases/verification) and checks
them against closed forms, and checks that bad group input is refused.

  cylinder   thick-walled tube (plane strain, roller ends) under internal follower pressure:
             at every output time the applied pressure against the closed-form pressure of the
             incompressible solid at the measured inner stretch (thick_walled.py), within --tolerance;
             and the mesh.msh the .geo gave, run again as the user's .msh, gives the same result.
  sphere     the hollow sphere likewise.
  sliding    a block pressed on a rigid plane, then dragged (Coulomb friction mu): over the last half
             of the drag the force on the plane has T/N = mu within 1e-3 (relative), and at the first
             output of the drag T/N < mu with the bottom's median node slide within the elastic slip
             of the return map (a sticking point's regularisation, penalty_contact.hpp).
  punch      a rigid flat-ended punch (the needle obstacle) pressed into a bonded layer: at every
             output time the force against Boussinesq's with the layer correction (indentation.py)
             within --tolerance.
  hertz      a rigid sphere likewise against Hertz's with Dimitriadis's layer correction, at the
             full indentation (earlier times have too few elements across the contact).
  press-fit  a rigid rod pushed and turned through an undersized hole of a thick-walled tube: once
             its cylinder covers the slice, the contact pressure (from the force on the rod across
             the axis) against the tube's closed form at the interference (thick_walled.py), the
             friction torque and the axial force per length against mu p 2 pi a^2 cos(phi) and
             mu p 2 pi a sin(phi), tan(phi) = v / (omega a), all within --tolerance.
  errors     cases naming a missing group, a volume group, a non-planar roller group, an obstacle
             without its group, a load history whose lists differ in length, a mesh-scene key in the
             brain-tip scene: non-zero exit and one line naming the case file, the key and the
             culprit.
"""
import argparse
import csv
import json
import pathlib
import shutil
import subprocess
import sys

import h5py
import numpy as np

import indentation
import thick_walled

failures = []


def check(condition, message):
    print(("ok   " if condition else "FAIL ") + message)
    if not condition:
        failures.append(message)


def run(exe, case, out, extra=()):
    shutil.rmtree(out, ignore_errors=True)
    return subprocess.run([exe, "run", str(case), "--out", str(out), *extra], capture_output=True, text=True)


def run_to_the_end(args):
    """Runs the case; its output directory and summary, or None (a failed check) if it stopped."""
    result = run(args.exe, args.case, args.out)
    check(result.returncode == 0, f"run completes (exit {result.returncode}: {result.stderr.strip()[-300:]})")
    if result.returncode != 0:
        return None
    out = pathlib.Path(args.out)
    return out, json.loads((out / "summary.json").read_text())


def polynomial_constants(material):
    """The custom preset's coefficients of the echoed [material] (absent ones are 0)."""
    return {k: material.get(f"{k}_instantaneous_pa", 0.0) for k in ("c10", "c01", "c20", "c11", "c02")}


def pressure(args, sphere):
    # The quadrature of the closed form against its hand-integrated neo-Hookean case.
    neo_hookean = {"c10": 0.5, "c01": 0.0, "c20": 0.0, "c11": 0.0, "c02": 0.0}
    for stretch in (1.1, 1.5, 2.0):
        value = thick_walled.internal_pressure(neo_hookean, 1.0, 2.0, stretch, sphere)
        exact = thick_walled.neo_hookean_pressure(1.0, 1.0, 2.0, stretch, sphere)
        check(abs(value - exact) <= 1e-12 * exact, f"closed form at stretch {stretch}: {value:.15g} vs {exact:.15g}")
    completed = run_to_the_end(args)
    if not completed:
        return
    out, summary = completed
    constants = polynomial_constants(summary["case"]["material"])
    with open(out / "history.csv") as f:
        applied = [float(row["pressure_pa"]) for row in csv.DictReader(f)]
    with h5py.File(out / "result.h5", "r") as h5:
        X = h5["/mesh/coordinates_mm"][()]
        inner = np.unique(h5["/mesh/surfaces/inner"][...].ravel())
        outer = np.unique(h5["/mesh/surfaces/outer"][...].ravel())
        u = h5["/series/node/displacement"][()]
    axes = 3 if sphere else 2  # the hoop stretch is r/R, r in the xy plane for the tube
    radius = lambda x, nodes: np.linalg.norm(x[nodes, :axes], axis=1)
    inner_radius, outer_radius = radius(X, inner).mean(), radius(X, outer).mean()
    worst = 0.0
    for k, p in enumerate(applied):
        if p == 0.0:
            continue
        stretches = radius(X + u[k], inner) / radius(X, inner)
        stretch = stretches.mean()
        reference = thick_walled.internal_pressure(constants, inner_radius, outer_radius, stretch, sphere)
        error = abs(p - reference) / reference
        worst = max(worst, error)
        check(error <= args.tolerance,
              f"t index {k}: inner stretch {stretch:.5f} (spread {np.ptp(stretches):.1e}), applied {p:.6g} Pa, "
              f"closed form {reference:.6g} Pa, rel. error {error:.2e} <= {args.tolerance:g}")
    print(f"largest relative pressure error {worst:.3e}")
    # The mesh the .geo gave, read back as the user's .msh: the same run.
    again = run(args.exe, args.case, out / "from_msh", ["--set", f"scene.mesh_file={(out / 'mesh.msh').resolve()}"])
    check(again.returncode == 0, f"the run from the written mesh.msh completes (exit {again.returncode})")
    if again.returncode == 0:
        with h5py.File(out / "from_msh" / "result.h5", "r") as h5:
            difference = np.abs(h5["/series/node/displacement"][()] - u).max()
        check(difference <= 1e-12 * np.abs(u).max(), f"... with the same displacements (largest difference {difference:.1e} mm)")


def sliding(args):
    completed = run_to_the_end(args)
    if not completed:
        return
    out, summary = completed
    mu = summary["case"]["contact"]["friction_coefficient"]
    press_end, drag_end = summary["case"]["loading"]["history_time_s"][1:3]
    with open(out / "history.csv") as f:
        rows = list(csv.DictReader(f))
    times = [float(r["time_s"]) for r in rows]
    ratio = [abs(float(r["obstacle_force_x_n"])) / -float(r["obstacle_force_z_n"]) if float(r["obstacle_force_z_n"]) < 0
             else 0.0 for r in rows]
    sliding_rows = [k for k, t in enumerate(times) if t >= 0.5 * (press_end + drag_end) - 1e-9]
    worst = max(abs(ratio[k] - mu) / mu for k in sliding_rows)
    check(worst <= 1e-3, f"sliding: T/N over t >= {times[sliding_rows[0]]:g} s within "
          f"[{min(ratio[k] for k in sliding_rows):.6f}, {max(ratio[k] for k in sliding_rows):.6f}], "
          f"largest rel. error {worst:.2e} <= 1e-3 against mu = {mu}")
    first_drag = next(k for k, t in enumerate(times) if t > press_end + 1e-9)
    with h5py.File(out / "result.h5", "r") as h5:
        X = h5["/mesh/coordinates_mm"][()]
        bottom_faces = h5["/mesh/surfaces/bottom"][()]
        bottom, top = np.unique(bottom_faces.ravel()), np.unique(h5["/mesh/surfaces/top"][...].ravel())
        u = h5["/series/node/displacement"]
        # The median: the edges of the bottom slide already under the press (the block bulges against
        # friction) and go on sliding first; the middle sticks.
        slide = [np.median(u[first_drag][nodes, 0] - u[first_drag - 1][nodes, 0]) for nodes in (bottom, top)]
    # A sticking point of the return map slips elastically by up to s0 = elastic_slip h_face,
    # h_face = sqrt(2 A_face) (physics/contact/penalty_contact.hpp): the largest over the bottom.
    corners = X[bottom_faces[:, :3]]
    areas = 0.5 * np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1)
    elastic_slip = summary["case"]["contact"]["elastic_slip"] * np.sqrt(2 * areas).max()
    check(ratio[first_drag] < mu and abs(slide[0]) <= elastic_slip,
          f"sticking at t = {times[first_drag]:g} s: T/N = {ratio[first_drag]:.4f} < mu, the bottom's median node moved "
          f"{slide[0]:.2e} mm (<= elastic slip {elastic_slip:.2e} mm) while the top moved {slide[1]:.2e} mm")


def indentation_forces(summary, out):
    """Per output time: (time, the quarter model's force times 4, layer thickness in m)."""
    material = summary["case"]["material"]
    with open(out / "history.csv") as f:
        rows = list(csv.DictReader(f))
    with h5py.File(out / "result.h5", "r") as h5:
        z = h5["/mesh/coordinates_mm"][:, 2]
        faces = {name: np.unique(h5[f"/mesh/surfaces/{name}"][...].ravel()) for name in ("top", "base")}
    thickness = (z[faces["base"]].mean() - z[faces["top"]].mean()) * 1e-3
    shear = 2 * (material.get("c10_instantaneous_pa", 0.0) + material.get("c01_instantaneous_pa", 0.0))
    # The indenter pushes along +z; the quarter model (rollers on x = 0, y = 0) carries a quarter.
    forces = [(float(r["time_s"]), -4 * float(r["obstacle_force_z_n"])) for r in rows]
    return forces, shear, material["bulk_modulus_pa"], thickness


def indented(args, punch):
    completed = run_to_the_end(args)
    if not completed:
        return
    out, summary = completed
    case = summary["case"]
    forces, shear, bulk, thickness = indentation_forces(summary, out)
    if punch:
        radius = case["needle"]["radius_mm"] * 1e-3
        speed = case["motion"]["insertion_speed_mm_per_s"] * 1e-3
        reference = lambda t: indentation.flat_punch_force(shear, bulk, radius, speed * t, thickness)
    else:
        radius = case["obstacle"]["radius_mm"] * 1e-3
        speed = case["obstacle"]["velocity_mm_per_s"][2] * 1e-3
        reference = lambda t: indentation.sphere_force(shear, bulk, radius, speed * t, thickness)
    checked = [(t, f) for t, f in forces if t > 0] if punch else forces[-1:]
    for t, force in checked:
        error = abs(force - reference(t)) / reference(t)
        check(error <= args.tolerance, f"t = {t:g} s: depth {speed * t * 1e6:.3g} um, force {force:.6g} N, "
              f"closed form {reference(t):.6g} N, rel. error {error:.2e} <= {args.tolerance:g}")


def press_fit(args):
    completed = run_to_the_end(args)
    if not completed:
        return
    out, summary = completed
    case = summary["case"]
    constants = polynomial_constants(case["material"])
    with h5py.File(out / "result.h5", "r") as h5:
        X = h5["/mesh/coordinates_mm"][()]
        group = lambda name: np.unique(h5[f"/mesh/surfaces/{name}"][...].ravel())
        hole, outer = (np.linalg.norm(X[group(name), :2], axis=1).mean() for name in ("inner", "outer"))
        length = (X[group("z1"), 2].mean() - X[group("z0"), 2].mean()) * 1e-3
    rod = case["needle"]["radius_mm"]
    pressure = thick_walled.internal_pressure(constants, hole, outer, rod / hole, sphere=False)
    a = rod * 1e-3
    speed = case["motion"]["insertion_speed_mm_per_s"] * 1e-3
    spin = np.radians(case["motion"]["rotation_speed_deg_per_s"])
    phi = np.arctan2(speed, spin * a)
    mu = case["contact"]["friction_coefficient"]
    references = {"pressure_pa": pressure, "torque_n_m_per_m": mu * pressure * 2 * np.pi * a * a * np.cos(phi),
                  "axial_force_n_per_m": mu * pressure * 2 * np.pi * a * np.sin(phi)}
    # The rod's rounded end has passed the slice once its cylinder reaches the far end face: the
    # last half second of the motion.
    steady_from = case["motion"]["duration_s"] - 0.5
    with open(out / "history.csv") as f:
        rows = [r for r in csv.DictReader(f) if float(r["time_s"]) >= steady_from - 1e-9]
    for row in rows:
        force = [float(row[f"obstacle_force_{c}_n"]) for c in "xyz"]
        # On the quarter (rollers on x = 0 and y = 0) a uniform pressure p pushes the rod by -p a L
        # along x and along y, and the hoop friction adds and takes the same from the two.
        measured = {"pressure_pa": -(force[0] + force[1]) / (2 * a * length),
                    "torque_n_m_per_m": -4 * float(row["obstacle_moment_z_n_m"]) / length,
                    "axial_force_n_per_m": -4 * force[2] / length}
        for name, reference in references.items():
            error = abs(measured[name] - reference) / reference
            check(error <= args.tolerance, f"t = {row['time_s']} s: {name} {measured[name]:.6g} against "
                  f"{reference:.6g}, rel. error {error:.2e} <= {args.tolerance:g}")


def errors(args):
    source = pathlib.Path(args.case).resolve()
    work = pathlib.Path(args.out)
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    text = source.read_text()
    geo = (source.parent / "thick_cylinder.geo").as_posix()
    text = text.replace('mesh_file = "thick_cylinder.geo"', f'mesh_file = "{geo}"')
    bad = {
        "missing_group": (text.replace('pressure = ["inner"]', 'pressure = ["innner"]'), "groups.pressure", "innner"),
        "volume_group": (text.replace('pressure = ["inner"]', 'pressure = ["tissue"]'), "groups.pressure", "tissue"),
        "curved_roller": (text.replace('roller = ["x0", "y0", "z0", "z1"]', 'roller = ["x0", "y0", "z0", "outer"]'),
                          "groups.roller", "outer"),
        "no_obstacle_group": (text + '\n[obstacle]\nkind = "plane"\n', "obstacle.group", "plane"),
        "short_history": (text.replace("ramp_s = 1.0", "history_time_s = [0.0, 1.0]\nhistory_factor = [0.0, 0.5, 1.0]"),
                          "loading.history_factor", "history_time_s"),
        "brain_tip_groups": ('[groups]\nfixed = ["x_min"]\n', "groups.fixed", "mesh"),
    }
    for name, (case_text, key, word) in bad.items():
        case = work / f"{name}.toml"
        case.write_text(case_text)
        result = run(args.exe, case, work / name)
        lines = [line for line in result.stderr.splitlines() if line.strip() and not line.startswith("mesh:")]
        check(result.returncode != 0 and len(lines) == 1 and str(case) in lines[0] and key in lines[0]
              and word in lines[0], f"{name}: exit {result.returncode}, one line with file, {key} and '{word}': {lines}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("check", choices=["cylinder", "sphere", "sliding", "punch", "hertz", "press-fit", "errors"])
    parser.add_argument("--exe", required=True)
    parser.add_argument("--case", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--tolerance", type=float, default=0.005)
    args = parser.parse_args()
    if args.check == "errors":
        errors(args)
    elif args.check == "sliding":
        sliding(args)
    elif args.check == "press-fit":
        press_fit(args)
    elif args.check in ("punch", "hertz"):
        indented(args, punch=args.check == "punch")
    else:
        pressure(args, sphere=args.check == "sphere")
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
