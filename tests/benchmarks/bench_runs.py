"""Resumable, timed `needlefem run` child processes for the benchmark studies
(accuracy_vs_speed.py, stability_map.py).

Each run lives in its own directory with `run.log` (the child's output) and `run.json` (the
command, exit code, wall and CPU time, timeout flag, and the parts of `summary.json` the studies
use). `run.json` is written last and atomically, so a study killed mid-run starts that run over
when restarted, and a run whose `run.json` records the same command is not run again.

Time: a loaded shared machine stretches wall time by whatever else runs, so besides the run's
own `solver.wall_s` each record keeps the CPU time (user + system, from wait4) of the
single-threaded run process: its wall time on an idle core.
"""
import argparse
import hashlib
import json
import os
import subprocess
import time
from pathlib import Path

from machine import use_blas_environment

ROOT = Path(__file__).resolve().parents[2]
DEFAULT_EXE = ROOT / "build" / "needlefem"


def study_arguments(doc, out_name, timeout_s):
    """The studies' common command line: --exe, --case (the paper's r = 0.5 mm, 20 deg, 0.25 mm
    tip), --out (out/OUT_NAME), --timeout (seconds after which a run is killed)."""
    parser = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    parser.add_argument("--exe", default=str(DEFAULT_EXE))
    parser.add_argument("--case", type=Path, default=ROOT / "cases" / "table1" / "r0.50_a20_f0.25.toml")
    parser.add_argument("--out", type=Path, default=ROOT / "out" / out_name)
    parser.add_argument("--timeout", type=float, default=timeout_s, help="seconds after which a run is killed")
    args = parser.parse_args()
    use_blas_environment(args.exe)
    return args


def set_args(overrides):
    """--set KEY=VALUE arguments for a dict of case overrides (values as the CLI parses them)."""
    args = []
    for key, value in overrides.items():
        args += ["--set", f"{key}={value}"]
    return args


def _summary_record(summary):
    """The parts of summary.json the studies read (the full file stays beside run.json)."""
    record = {key: summary.get(key) for key in ("status", "error", "time_reached_s", "solver", "mesh", "reactions")}
    record["max"] = {name: entry["value"] for name, entry in summary.get("max", {}).items()}
    needle = summary.get("needle")
    if needle:
        record["needle"] = {"max_axial_force_n": needle["max_axial_force_n"], "max_torque_n_m": needle["max_torque_n_m"]}
    return record


def run_case(case, out_dir, overrides, exe=DEFAULT_EXE, timeout_s=900.0):
    """Runs `needlefem run CASE --out OUT_DIR --set ...` unless OUT_DIR/run.json holds the same
    command; returns the run record (a dict). A run over timeout_s is killed and recorded as
    status "timeout"."""
    out_dir = Path(out_dir)
    command = [str(exe), "run", str(case), "--out", str(out_dir)] + set_args(overrides)
    record_file = out_dir / "run.json"
    if record_file.exists():
        record = json.loads(record_file.read_text())
        if record.get("command") == command[1:]:
            return record
    out_dir.mkdir(parents=True, exist_ok=True)
    record_file.unlink(missing_ok=True)
    (out_dir / "summary.json").unlink(missing_ok=True)
    timed_out = False
    with open(out_dir / "run.log", "w") as log:
        start = time.perf_counter()
        child = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT)
        while True:
            pid, status, usage = os.wait4(child.pid, os.WNOHANG)
            if pid:
                break
            if time.perf_counter() - start > timeout_s and not timed_out:
                child.kill()
                timed_out = True
            time.sleep(0.2)
        wall = time.perf_counter() - start
    child.returncode = os.waitstatus_to_exitcode(status)  # reaped by wait4: keep Popen from waiting again
    record = {"command": command[1:], "overrides": overrides, "exit_code": child.returncode, "timed_out": timed_out,
              "process_wall_s": round(wall, 3), "cpu_s": round(usage.ru_utime + usage.ru_stime, 3)}
    summary_file = out_dir / "summary.json"
    if summary_file.exists() and not timed_out:
        record.update(_summary_record(json.loads(summary_file.read_text())))
    else:
        record["status"] = "timeout" if timed_out else "failed"
        lines = (out_dir / "run.log").read_text().strip().splitlines()
        last = lines[-1] if lines else "no output"
        if timed_out:
            record["error"] = f"killed after {timeout_s:g} s; last output: {last}"
        elif child.returncode < 0:
            record["error"] = f"killed by signal {-child.returncode}; last output: {last}"
        else:
            record["error"] = last
    temporary = record_file.with_suffix(".tmp")
    temporary.write_text(json.dumps(record, indent=1) + "\n")
    temporary.replace(record_file)
    return record


def binary_identity(exe):
    """What the study ran: the executable's path, SHA-256 and modification time, and the
    checkout's commit (with -dirty when its tree has changes) at the time of the study."""
    exe = Path(exe)
    describe = subprocess.run(["git", "-C", str(ROOT), "describe", "--always", "--dirty"], capture_output=True, text=True)
    return {"exe": str(exe), "sha256": hashlib.sha256(exe.read_bytes()).hexdigest(),
            "modified": time.strftime("%Y-%m-%d %H:%M:%S", time.localtime(exe.stat().st_mtime)),
            "checkout": describe.stdout.strip()}


def key_default(exe, key):
    """A case key's default as `needlefem keys KEY` prints it ("KEY (real, ..., default 0.01)")."""
    listing = subprocess.run([str(exe), "keys", key], capture_output=True, text=True, check=True).stdout
    return float(listing.split("\n")[0].rsplit("default ", 1)[1].rstrip(")"))


def point_name(overrides):
    """A directory name from override values: 'core_element_mm=0.5__order=2'."""
    return "__".join(f"{key.split('.')[-1]}={value}" for key, value in overrides.items())
