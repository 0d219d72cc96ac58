#!/usr/bin/python3
"""Tests of `needlefem sweep` and of the sweep figures.

  resume   runs tests/sweep/tiny.toml (2 x 2 block points) with 2 jobs in its own process
           group, SIGKILLs the group once a point has completed and another has started,
           checks that nothing of the group survives, restarts: the restart must skip exactly
           the points completed before the kill and finish the rest; a third start runs
           nothing. Every row of sweep.csv and sweep.h5 appears exactly once and matches its
           run: max log strain = ln 1.2, max strain rate in [0.2/(1.2 ramp), 0.2/ramp] (closed
           forms of the uniaxial block, see tiny.toml; the ramps differ 66-fold), the strain-rate
           limit failed exactly by the 15 ms ramp (pass_*, verdict_strain_rate_per_s and the
           overall verdict), pass_* = (value <= limit).
  bad      runs tests/sweep/bad_points.toml: impossible points listed on the terminal with their
           rule and in the table as "impossible" with the rule; the run that fails recorded as
           "failed" with its error; the sweep exits 0.
  input-files runs tests/sweep/cad_base_case.toml, whose base case names its CAD tip relative to
           itself: the point's run finds the file (it fails on the narrow core, naming the
           core, not on a missing file).
  list     `sweep --list` of the paper-001 sweep files: the plan is made, point folder names are
           short and match their values in sweep.csv, the quick sweep's coarse mesh is warned of
           (terminal, coarse_mesh column, safety map title) and the full grid's is not.
  figures  runs postprocess/sweep_figures.py all and postprocess/render_max_strain.py (pvbatch
           under xvfb-run) on the resume test's sweep: every PNG exists and is not blank; the
           safety map marks each point with its verdict and failing limit.
"""
import argparse
import csv
import itertools
import json
import math
import os
import pathlib
import re
import shutil
import signal
import subprocess
import sys
import time

import h5py
import numpy as np

failures = []
LIMITS = {"log_strain": 0.19, "strain_rate_per_s": 10.0, "stress_pa": 120e3}
STRETCH_RATE = 0.2  # lambda goes from 1 to 1.2 over the ramp


def check(condition, message):
    print(("ok   " if condition else "FAIL ") + message)
    if not condition:
        failures.append(message)


def sweep(exe, sweep_file, out, jobs=1, **popen):
    return subprocess.Popen([exe, "sweep", str(sweep_file), "--out", str(out), "--jobs", str(jobs)],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, **popen)


def read_csv(out):
    with open(out / "sweep.csv") as f:
        return list(csv.DictReader(f))


def statuses(out):
    """Point directory -> status of its summary.json (what a restarted sweep will see)."""
    result = {}
    for summary in out.glob("*/summary.json"):
        result[summary.parent.name] = json.loads(summary.read_text())["status"]
    return result


def live_members(group):
    """Processes of a process group that are not zombies (an orphan's zombie may wait for a
    reaper that never comes in a container)."""
    live = []
    for stat in pathlib.Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[2]) == group and fields[0] != "Z":
            live.append(stat.parent.name)
    return live


def rate_range(ramp):
    """Closed-form strain rate of the block over its ramp: d(ln lambda)/dt = (0.2/ramp)/lambda,
    from 0.2/ramp at lambda = 1 down to 0.2/(1.2 ramp); the maximum over the output times lies
    in between (at t = 0 or at the first output time, depending on the initial rate)."""
    return STRETCH_RATE / ramp / 1.2, STRETCH_RATE / ramp


def check_table(out, expected_points):
    rows = read_csv(out)
    names = [r["point"] for r in rows]
    check(sorted(names) == sorted(expected_points) and len(set(names)) == len(names),
          f"sweep.csv: every point exactly once ({len(names)} rows)")
    with h5py.File(out / "sweep.h5", "r") as h5:
        h5_names = list(h5["point"].asstr()[()])
        check(h5_names == names, "sweep.h5: the same rows in the same order")
        for column in ("max_log_strain", "max_strain_rate_per_s", "loading.ramp_s"):
            from_csv = np.array([float(r[column]) for r in rows])
            check(np.allclose(h5[column][()], from_csv, rtol=1e-8), f"sweep.h5 column {column} = sweep.csv")
    for r in rows:
        check(r["status"] == "completed", f"{r['point']}: completed")
        ramp = float(r["loading.ramp_s"])
        strain, rate = float(r["max_log_strain"]), float(r["max_strain_rate_per_s"])
        check(abs(strain - math.log(1.2)) <= 1e-3 * math.log(1.2), f"{r['point']}: max log strain {strain:.7f} = ln 1.2")
        low, high = rate_range(ramp)
        check(low * (1 - 1e-3) <= rate <= high * (1 + 1e-3),
              f"{r['point']}: max strain rate {rate:.5g} in the closed form's range [{low:.5g}, {high:.5g}] 1/s")
        for name, column in (("log_strain", "max_log_strain"), ("strain_rate_per_s", "max_strain_rate_per_s"),
                             ("stress_pa", "max_von_mises_pa")):
            passed = int(r[f"pass_{name}"])
            check(passed == int(float(r[column]) <= LIMITS[name]), f"{r['point']}: pass_{name} = {passed}")
        check(int(r["pass_strain_rate_per_s"]) == int(ramp > 0.1), f"{r['point']}: strain-rate limit fails only "
                                                                   "for the 15 ms ramp")
        # The block's field is homogeneous (to the integrator's error): a ball average is the point
        # value, and the whole block (1 mm³) is above a limit or none of it.
        cd = float(r["critical_distance_log_strain"])
        check(abs(cd - strain) <= 1e-5 * strain,
              f"{r['point']}: critical-distance log strain {cd:.9f} = point max {strain:.9f}")
        check(float(r["volume_above_log_strain_mm3"]) == 0.0 and int(r["verdict_log_strain"]) == 1,
              f"{r['point']}: no volume above the strain limit, verdict pass")
        # The critical-distance strain rate is the homogeneous rate, above 10 1/s only for the 15 ms ramp.
        check(int(r["verdict_strain_rate_per_s"]) == int(ramp > 0.1) and int(r["verdict"]) == int(ramp > 0.1),
              f"{r['point']}: verdict {r['verdict']} (strain-rate verdict {r['verdict_strain_rate_per_s']})")
        above = float(r["volume_above_strain_rate_per_s_mm3"])
        check(abs(above - (1.0 if ramp < 0.1 else 0.0)) <= 1e-9,
              f"{r['point']}: volume above the strain-rate limit {above:.9g} mm^3 (all of the block or none)")
        check(float(r["dofs"]) > 0 and float(r["wall_s"]) > 0, f"{r['point']}: dofs and wall time recorded")
    return rows


def resume(args):
    out = pathlib.Path(args.out)
    shutil.rmtree(out, ignore_errors=True)
    # Point folders: each swept key's label and the point's value (e = block.element_mm, r = loading.ramp_s).
    expected = [f"e{e}_r{r}" for e in ("0.5", "1") for r in ("0.015", "1")]
    listed = subprocess.run([args.exe, "sweep", str(args.sweep), "--out", str(out), "--list"], capture_output=True,
                            text=True)
    order = [line.split("to run: ")[1].split(" ")[0] for line in listed.stdout.splitlines() + listed.stderr.splitlines()
             if "to run: " in line]
    check(sorted(order) == sorted(expected) and all(name.startswith("e0.5_") for name in order[:2]),
          f"the longest runs (finest mesh) are started first: {order}")
    check("point folders are named by label and value: e = block.element_mm, r = loading.ramp_s" in listed.stdout,
          "the sweep prints what the labels of the point folders stand for")
    shutil.rmtree(out, ignore_errors=True)
    start = time.monotonic()
    first = sweep(args.exe, args.sweep, out, jobs=2, start_new_session=True)
    killed = False
    while first.poll() is None and time.monotonic() - start < 60:
        done = [n for n, s in statuses(out).items() if s == "completed"]
        started = [p.parent.name for p in out.glob("*/run.log")]
        if done and len(started) > len(done):
            os.killpg(first.pid, signal.SIGKILL)
            killed = True
            break
        time.sleep(0.02)
    first.wait()
    log = first.stdout.read()
    check(killed, f"sweep killed mid-way (SIGKILL to its process group) after {time.monotonic() - start:.1f} s")
    time.sleep(0.2)
    check(not live_members(first.pid), "no process of the killed sweep's group survives")
    done_before = sorted(n for n, s in statuses(out).items() if s == "completed")
    check(0 < len(done_before) < 4, f"{len(done_before)} of 4 points completed before the kill")
    print(log)

    second = sweep(args.exe, args.sweep, out, jobs=2)
    log, _ = second.communicate()
    print(log)
    check(second.returncode == 0, "restarted sweep exits 0")
    check(f"{len(done_before)} already done, {4 - len(done_before)} to run" in log,
          f"restart skips the {len(done_before)} completed points and runs the other {4 - len(done_before)}")
    for name in done_before:
        check(f"started {name}" not in log, f"restart does not run {name} again")
    check("ETA" in log and f"[4/4]" in log, "progress shows done/total and ETA")
    rows = check_table(out, expected)
    wall = time.monotonic() - start

    logs = {p: p.stat().st_mtime_ns for p in out.glob("*/run.log")}
    third = sweep(args.exe, args.sweep, out)
    log, _ = third.communicate()
    check(third.returncode == 0 and "4 already done, 0 to run" in log, "a finished sweep started again runs nothing")
    check(logs == {p: p.stat().st_mtime_ns for p in out.glob("*/run.log")}, "no run log rewritten")
    check(read_csv(out) == rows, "the table is unchanged")
    print(f"tiny sweep with kill and restart: {wall:.1f} s wall")

    # A point run before a choice was renamed echoes the former name in its summary.json
    # (integration.linear_solver "cholmod", now "cholesky"): it still counts as done.
    renamed = next(out.glob("*/summary.json"))
    summary = json.loads(renamed.read_text())
    check(summary["case"]["integration"]["linear_solver"] == "cholesky", "summary.json echoes the current name")
    summary["case"]["integration"]["linear_solver"] = "cholmod"
    renamed.write_text(json.dumps(summary))
    fourth = sweep(args.exe, args.sweep, out)
    log, _ = fourth.communicate()
    check(fourth.returncode == 0 and "4 already done, 0 to run" in log,
          "a point whose summary names a choice by its former name is not run again")


def completed_sweep(args, what):
    """Runs args.sweep into a fresh args.out to its end; checks that it exits 0."""
    out = pathlib.Path(args.out)
    shutil.rmtree(out, ignore_errors=True)
    process = sweep(args.exe, args.sweep, out)
    log, _ = process.communicate()
    print(log)
    check(process.returncode == 0, f"{what} exits 0")
    return out, log


def bad(args):
    out, log = completed_sweep(args, "a sweep with impossible and failed points")
    rows = {r["grids"]: r for r in read_csv(out)}
    expected_rules = {"impossible": ["fillet-exceeds-radius", "fillet-fits-bevel"], "wide": ["core-contains-needle"],
                      "out-of-range": ["case"]}
    for rule in sum(expected_rules.values(), []):
        check(f"rule '{rule}'" in log, f"terminal lists an impossible point with rule '{rule}'")
    impossible = [r for r in read_csv(out) if r["status"] == "impossible"]
    check(sorted(r["rules"] for r in impossible) == sorted(sum(expected_rules.values(), [])),
          f"table: 4 impossible rows with their rules ({[r['rules'] for r in impossible]})")
    check(all(not (out / r["point"]).exists() for r in impossible), "impossible points are not run")
    check("out of range" in rows["out-of-range"]["error"], "the out-of-range key's reason is in the table")
    failed = rows["missing-mesh"]
    check(failed["status"] == "failed" and "no_such_mesh.msh' not found" in failed["error"],
          f"the failing run is recorded with its error: {failed['error']}")


def input_files(args):
    out, _ = completed_sweep(args, "the sweep")
    (row,) = read_csv(out)
    check(row["status"] == "failed" and "does not fit the core" in row["error"] and "no such file" not in row["error"],
          f"the point's run read the base case's CAD file and stopped at the core: {row['error']}")


def png_ok(path):
    import matplotlib.image
    if not path.exists() or path.stat().st_size < 5000:
        return False
    image = matplotlib.image.imread(str(path))
    return float(np.std(image[..., :3])) > 0.01


def figures(args):
    sweep_dir = pathlib.Path(args.sweep_dir)
    out = pathlib.Path(args.out)
    shutil.rmtree(out, ignore_errors=True)
    result = subprocess.run([sys.executable, args.figures, "all", str(sweep_dir), "--out", str(out)],
                            capture_output=True, text=True)
    print(result.stdout, result.stderr)
    check(result.returncode == 0, "sweep_figures.py all exits 0")
    for name in ("fig4_stress_strain", "fig5_fillet", "fig6_strain_rate", "safety_map", "safety_steering", "history"):
        check(png_ok(out / f"{name}.png"), f"{name}.png written and not blank")
    # The safety map marks each design by its verdict, labelled with the limits that fail: the
    # 15 ms ramp's strain rate (0.2/0.015 s = 13 1/s) fails, the 1 s ramp passes.
    sys.path.insert(0, str(pathlib.Path(args.figures).parent))
    import sweep_figures
    table = sweep_figures.Sweep(sweep_dir)
    for i in range(table.rows):
        ramp = table.table["loading.ramp_s"][i]
        expected = ("pass", "") if ramp > 0.1 else ("fail", "strain_rate_per_s")
        mark = sweep_figures.map_mark(table, i)
        check(mark == expected, f"safety map marks {table.table['point'][i]} {mark} (expected {expected})")
        # ... which are the summary's critical-distance verdicts (safety.<limit>.verdict), not the point maxima.
        safety = table.summary(i)["safety"]
        failing = [name for name in LIMITS if safety[name]["verdict"] == "fail"]
        check(mark[0] == ("fail" if failing else "pass") and mark[1].split(", ")[:len(failing)] == failing,
              f"{table.table['point'][i]}: the mark is summary.json's safety verdicts (failing: {failing})")
    point = read_csv(sweep_dir)[0]["point"]
    png = out / "max_log_strain.png"
    # A 24-bit screen for GLX; two retries a few seconds apart, because pvbatch now and then aborts
    # creating its X window when the virtual server is slow to come up on a loaded machine (seen
    # once in ~10 -j2 suite runs, in vtkXOpenGLRenderWindow::CreateAWindow, and once on both of two
    # back-to-back attempts), which is the server's start, not the script.
    command = ["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24", "pvbatch", args.render,
               str(sweep_dir / point / "result.xdmf"), "--png", str(png)]
    for attempt in range(3):
        if attempt:
            time.sleep(3)
        result = subprocess.run(command, capture_output=True, text=True)
        print(result.stdout, result.stderr[-2000:])
        if result.returncode == 0:
            break
    check(result.returncode == 0 and png_ok(png), "render_max_strain.py renders a non-blank PNG")
    # The block's field is homogeneous (to ~1e-4), so the cut's maximum is the field's at the last
    # time, and never above it.
    with h5py.File(sweep_dir / point / "result.h5", "r") as h5:
        last = int(h5["/series/time_count"][0]) - 1
        field_max = float(np.max(h5["/series/cell/max_over_time_log_strain"][last]))
    shown = [float(w.split()[-4]) for w in result.stdout.splitlines() if w.startswith("wrote ")]
    check(len(shown) == 1 and field_max * (1 - 1e-3) <= shown[0] <= field_max * (1 + 1e-5),
          f"the rendered field is max_over_time_log_strain at the last time ({shown} vs {field_max:.7g})")
    check_scale_bar(png, result.stdout, block_mm=1.0)  # cases/block_uniaxial.toml: a 1 mm cube


def longest_run(mask):
    """(start, length) of the longest run of True in a 1-D boolean array."""
    best, start = (0, 0), None
    for i, value in enumerate(list(mask) + [False]):
        if value and start is None:
            start = i
        elif not value and start is not None:
            best = max(best, (i - start, start))
            start = None
    return best[1], best[0]


def check_scale_bar(png, stdout, block_mm):
    """The render's scale bar is drawn where the script says, and its length in pixels is its
    length in mm at the scale of the rendered field (the 1 mm block's cut, measured in the image)."""
    import matplotlib.image
    said = [line for line in stdout.splitlines() if line.startswith("scale bar ")]
    check(len(said) == 1, f"the render states its scale bar: {said}")
    if len(said) != 1:
        return
    numbers = re.findall(r"[-+0-9.]+", said[0])
    length_mm, x, y, pixels = float(numbers[0]), int(numbers[1]), int(numbers[2]), float(numbers[3])
    image = matplotlib.image.imread(png)[..., :3].mean(axis=2)
    field_start, field_pixels = longest_run(image[image.shape[0] // 2] < 0.95)  # the field, left to right
    dark = [longest_run(image[row] < 0.3) for row in range(y - 6, y + 7)]
    start, drawn = max(dark, key=lambda run: run[1])
    expected = length_mm / block_mm * field_pixels
    check(abs(start - x) <= 3 and abs(drawn - pixels) <= 4 and abs(drawn - expected) <= 0.01 * expected + 4,
          f"scale bar {length_mm:g} mm drawn {drawn} px from x = {start} (said {pixels:.0f} px from {x}; the "
          f"{block_mm:g} mm field is {field_pixels} px wide, so {expected:.0f} px)")
    check(length_mm == 0.2, f"scale bar {length_mm:g} mm: the largest 1-2-5 length within a quarter of the field")


def steering(args):
    """A brain-tip sweep's safety metrics and lateral force reach the table and the chart."""
    out = pathlib.Path(args.out)
    shutil.rmtree(out, ignore_errors=True)
    process = subprocess.run([args.exe, "sweep", args.sweep, "--out", str(out), "--jobs", "1"],
                             capture_output=True, text=True)
    print(process.stdout[-2000:], process.stderr[-2000:])
    check(process.returncode == 0, "the brain-tip sweep exits 0")
    for r in read_csv(out):
        check(r["status"] == "completed", f"{r['point']}: completed")
        summary = json.loads((out / r["point"] / "summary.json").read_text())
        check(float(r["needle_max_lateral_force_n"]) > 0, f"{r['point']}: lateral force {r['needle_max_lateral_force_n']} N")
        for name in LIMITS:
            cd = float(r[f"critical_distance_{name}"])
            check(abs(cd - summary["safety"][name]["critical_distance"]["value"]) <= 1e-8 * cd,
                  f"{r['point']}: critical_distance_{name} {cd:.6g} = the summary's (9 digits in the CSV)")
            check(int(r[f"verdict_{name}"]) == int(cd <= LIMITS[name]), f"{r['point']}: verdict_{name}")
        every = all(summary["safety"][name]["critical_distance"]["value"] <= LIMITS[name] for name in LIMITS)
        line = next((l for l in process.stdout.splitlines() if f"completed {r['point']} in " in l), "")
        check(f": verdict {summary['verdict']} (point maxima:" in line,
              f"{r['point']}: the sweep's progress line gives the verdict {summary['verdict']}: {line}")
        check(int(r["verdict"]) == int(every) and summary["verdict"] == ("pass" if every else "fail"),
              f"{r['point']}: verdict {r['verdict']} = every limit passes ({every})")
    png = out / "safety_steering.png"
    result = subprocess.run([sys.executable, args.figures, "safety-steering", str(out), "--png", str(png)],
                            capture_output=True, text=True)
    print(result.stdout, result.stderr[-2000:])
    check(result.returncode == 0 and png_ok(png), "safety-steering chart written and not blank")


def full_grid(out):
    """A synthetic sweep directory the size of the quick design grid: 4 radii x 2 bevels x 3 fillets
    (24 points, 22 of them completed tips, 2 impossible with long rule names), with made-up maxima."""
    radii, bevels, fillets = [0.32, 0.5, 0.83, 1.25], [10.0, 20.0], [0.15, 0.25, 0.45]
    rows = []
    for radius, bevel, fillet in itertools.product(radii, bevels, fillets):
        impossible = radius == 0.32 and fillet == 0.45
        rows.append((radius, bevel, fillet, "impossible" if impossible else "completed"))
    out.mkdir(parents=True)
    verdicts = ["verdict_log_strain", "verdict_strain_rate_per_s", "verdict_stress_pa"]
    columns = ["point", "grids", "needle.radius_mm", "needle.bevel_deg", "needle.fillet_mm", "status", "verdict",
               *verdicts, "safe", "rules", "needle_max_lateral_force_n"]
    table = {c: [] for c in columns}
    for n, (radius, bevel, fillet, status) in enumerate(rows):
        name = f"p{n:02d}"
        for column, value in zip(columns, [name, "main", radius, bevel, fillet, status]):
            table[column].append(value)
        passes = int(n % 3 != 0)
        for column in ["verdict", *verdicts]:
            table[column].append(passes if status == "completed" else -1)
        # The point maxima disagree with the critical-distance verdict on every other design.
        table["safe"].append((passes if n % 2 else 1 - passes) if status == "completed" else -1)
        table["rules"].append("fillet-fits-bevel: the fillet does not fit the bevel face, core-contains-needle"
                              if status == "impossible" else "")
        table["needle_max_lateral_force_n"].append(1e-4 * (n + 1) if status == "completed" else math.nan)
        if status != "completed":
            continue
        (out / name).mkdir()
        case = {"needle": {"radius_mm": radius, "bevel_deg": bevel, "fillet_mm": fillet},
                "motion": {"insertion_speed_mm_per_s": 1.0, "rotation_speed_deg_per_s": 180.0}}
        limits = {"log_strain": 0.19, "strain_rate_per_s": 10.0, "stress_pa": 1.2e5}
        safety = {name: {"limit": limit, "verdict": "pass" if passes else "fail",
                         "critical_distance": {"value": limit * (0.5 + 0.02 * n)},
                         "point_max": {"value": limit * (1.0 + 0.05 * n)}} for name, limit in limits.items()}
        (out / name / "summary.json").write_text(json.dumps({"status": "completed", "case": case, "safety": safety,
                                                             "max": {"von_mises_pa": {"value": 1e3 * (n + 1)}}}))
        with open(out / name / "history.csv", "w") as f:
            f.write("time_s,max_log_strain,max_von_mises,max_strain_rate\n")
            for k in range(6):
                f.write(f"{0.02 * k},{0.01 * k * (1 + n / 10)},{200.0 * k * (n + 1)},{k * 0.5}\n")
    with h5py.File(out / "sweep.h5", "w") as f:
        f.attrs["format"] = "needlefem-sweep-table"
        f.attrs["columns"] = columns
        for column, values in table.items():
            f[column] = values if not isinstance(values[0], str) else np.array(values, dtype=h5py.string_dtype())
    return sum(r[3] == "completed" for r in rows)


def overlaps(a, b):
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


def full_grid_figures(args):
    """Fig. 4 and the safety map stay readable at the size of the full design grid."""
    out = pathlib.Path(args.out)
    shutil.rmtree(out, ignore_errors=True)
    designs = full_grid(out / "sweep")
    sys.path.insert(0, str(pathlib.Path(args.figures).parent))
    import sweep_figures
    table = sweep_figures.Sweep(out / "sweep")
    fig = sweep_figures.stress_strain(table, out / "fig4.png")
    check(png_ok(out / "fig4.png"), "fig4.png written and not blank")
    ax = fig.axes[0]
    designs_drawn = [line for line in ax.get_lines() if not line.get_label().startswith(("strain limit", "stress limit"))]
    colours = {tuple(line.get_color()) if not isinstance(line.get_color(), str) else line.get_color() for line in designs_drawn}
    check(len(designs_drawn) == designs and len(colours) == designs,
          f"Fig. 4: {len(colours)} distinct colours for {len(designs_drawn)} lines of {designs} designs")
    renderer = fig.canvas.get_renderer()
    check(not overlaps(ax.get_legend().get_window_extent(renderer), ax.get_window_extent(renderer)),
          "Fig. 4: the legend lies outside the axes")
    fig = sweep_figures.safety_steering(table, out / "safety_steering.png")
    check(png_ok(out / "safety_steering.png"), "safety_steering.png written and not blank")
    drawn = [line for line in fig.axes[0].get_lines() if not line.get_label().startswith("_")]
    styles = {(tuple(line.get_color()) if not isinstance(line.get_color(), str) else line.get_color(),
               line.get_marker()) for line in drawn}
    check(len(drawn) == designs and len(styles) == designs,
          f"safety beside steering: {len(styles)} distinct colour-marker pairs for {len(drawn)} of {designs} designs")
    fig = sweep_figures.safety_map(table, out / "safety_map.png")
    check(png_ok(out / "safety_map.png"), "safety_map.png written and not blank")
    marks = [sweep_figures.map_mark(table, i)[0] for i in table.indices()]
    by_verdict = ["pass" if table.table["verdict"][i] == 1 else "fail" for i in table.indices()]
    by_maxima = ["pass" if table.table["safe"][i] == 1 else "fail" for i in table.indices()]
    check(marks == by_verdict and marks != by_maxima,
          "safety map: each design marked by its critical-distance verdict, not by the point maxima")
    renderer = fig.canvas.get_renderer()
    labels = [a.get_xlabel() for a in fig.axes] + [a.get_ylabel() for a in fig.axes if a.get_ylabel()]
    check(all("[" in label and "." not in label.split("[")[0] for label in labels if label),
          f"safety map: axis labels in words with units ({sorted(set(labels))})")
    texts = [t for a in fig.axes for t in a.texts if t.get_text()]
    boxes = [t.get_window_extent(renderer) for t in texts]
    clashes = sum(overlaps(boxes[i], boxes[j]) for i in range(len(boxes)) for j in range(i))
    check(texts and clashes == 0, f"safety map: {len(texts)} design labels, {clashes} overlapping")


def listed(args):
    """`sweep --list` of the project's paper-001 sweep files: the plan is made (once, two grids'
    shared point with different motion keys stopped it), the point folders are short and each
    name is its labels and its values in sweep.csv; the quick sweep's coarse mesh is warned of on
    the terminal, in the table and in the safety map's title."""
    sys.path.insert(0, str(pathlib.Path(args.figures).parent))
    import sweep_figures
    for sweep_file in args.sweep.split(","):
        out = pathlib.Path(args.out) / pathlib.Path(sweep_file).stem
        shutil.rmtree(out, ignore_errors=True)
        result = subprocess.run([args.exe, "sweep", sweep_file, "--out", str(out), "--list"], capture_output=True,
                                text=True)
        name = pathlib.Path(sweep_file).name
        check(result.returncode == 0, f"{name}: --list exits 0 ({result.stderr.strip()[:200]})")
        if result.returncode != 0:
            continue
        legend = [line.split("value: ")[1].split(";")[0] for line in result.stdout.splitlines()
                  if "point folders are named by label and value: " in line]
        check(len(legend) == 1, f"{name}: the labels of the point folders are printed")
        if len(legend) != 1:
            continue
        labels = [entry.split(" = ") for entry in legend[0].split(", ")]
        rows = read_csv(out)
        longest = max(len(r["point"]) for r in rows)
        check(longest <= 40, f"{name}: {len(rows)} point folders, the longest {longest} characters")
        # The quick sweep's coarse mesh is said beside every verdict: a warning when the sweep starts
        # and a coarse_mesh column naming the sizes; the full grid at the paper's mesh has neither.
        quick = "quick" in name
        coarse = "tissue.core_element_mm = 1 mm > 0.4 mm; tissue.outer_element_mm = 3 mm > 2 mm"
        possible = [r for r in rows if r["status"] != "impossible"]
        check(all(r["coarse_mesh"] == (coarse if quick else "") for r in possible),
              f"{name}: coarse_mesh column {'names the coarse sizes' if quick else 'empty'} on every possible point")
        warned = [line for line in result.stdout.splitlines() if "warning: " in line]
        check(len(warned) == 1 and f"24 of the 24 possible design points: mesh coarser than the converged setting"
              in warned[0] if quick else not warned, f"{name}: coarse-mesh warning {warned}")
        fig = sweep_figures.safety_map(sweep_figures.Sweep(out), out / "safety_map.png")
        title = " ".join([fig._suptitle.get_text()] + [t.get_text() for t in fig.texts])
        check(("Warning: 24 of 24 designs on a mesh coarser than the converged setting" in title.replace("\n", " "))
              == quick, f"{name}: the safety map's title warns of the coarse mesh exactly when it is: {title!r}")
        for r in rows:
            expected = "_".join(label + (r[key] if r[key].replace(".", "").replace("-", "").isdigit() else "-" + r[key])
                                for label, key in labels)
            check(r["point"] == expected, f"{name}: folder {r['point']} = its values in sweep.csv ({expected})")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("mode", choices=["resume", "bad", "input-files", "figures", "steering", "full-grid", "list"])
    parser.add_argument("--exe")
    parser.add_argument("--sweep")
    parser.add_argument("--out", required=True)
    parser.add_argument("--sweep-dir")
    parser.add_argument("--figures")
    parser.add_argument("--render")
    args = parser.parse_args()
    {"resume": resume, "bad": bad, "input-files": input_files, "figures": figures, "steering": steering,
     "full-grid": full_grid_figures, "list": listed}[args.mode](args)
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
