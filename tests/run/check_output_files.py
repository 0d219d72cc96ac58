"""What a run leaves in its output directory when something else is there first.

  lock       A run owns its output directory: while another process holds it, a second run into
             the same --out is refused with one line and leaves the files there untouched (once,
             its H5Fcreate truncated the first run's result.h5 before failing, and the first run
             still said completed).
  disk-full  A full disk is named as such, and leaves no temporary files behind. /dev/full
             answers every write with ENOSPC: a symlink to it as the temporary a run writes
             summary.json (or result.xdmf) to gives that file a full disk without filling one.
             Once, the error said only "cannot write summary.json.partial" and the .partial stayed.

usage: check_output_files.py {lock,disk-full} --exe NEEDLEFEM --case CASE --out DIR
"""
import argparse
import fcntl
import glob
import json
import os
import shutil
import signal
import subprocess
import sys
import time

import h5py


def check_lock(args, run, failures):
    command = run + ["--set", "loading.ramp_s=0.01", "--out", args.out]
    shutil.rmtree(args.out, ignore_errors=True)
    os.makedirs(args.out)
    sentinels = {"result.h5": b"the first run's result", "summary.json": b'{"status": "completed"}\n'}
    for name, content in sentinels.items():
        with open(os.path.join(args.out, name), "wb") as f:
            f.write(content)

    holder = os.open(args.out, os.O_RDONLY | os.O_DIRECTORY)
    fcntl.flock(holder, fcntl.LOCK_EX)  # as a live run holds it
    second = subprocess.run(command, capture_output=True, text=True)
    lines = second.stderr.strip().splitlines()
    if second.returncode == 0:
        failures.append("a second run into a held directory exited 0")
    if len(lines) != 1 or "another run is writing into this output directory" not in lines[0]:
        failures.append(f"expected one line naming the held directory, got: {second.stderr!r}")
    for name, content in sentinels.items():
        with open(os.path.join(args.out, name), "rb") as f:
            if f.read() != content:
                failures.append(f"{name} was changed by the refused run")
    os.close(holder)

    # Two real runs: the second starts while the first writes; it is refused and the first completes
    # with a readable result.h5 (its lock is the one a live run holds, released when it ends).
    shutil.rmtree(args.out)
    first = subprocess.Popen(run + ["--set", "loading.ramp_s=0.05", "--out", args.out], stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    while not os.path.exists(os.path.join(args.out, "history.csv")) and first.poll() is None and time.monotonic() < deadline:
        time.sleep(0.02)
    # Stopped mid-run, the first run is still alive and holds its directory however fast it is.
    first_running = first.poll() is None
    if first_running:
        first.send_signal(signal.SIGSTOP)
    second = subprocess.run(command, capture_output=True, text=True)
    first.send_signal(signal.SIGCONT)
    first_stderr = first.communicate()[1]
    if not first_running:
        failures.append("inconclusive: the first run ended before the second started")
    elif second.returncode == 0 or "another run is writing into this output directory" not in second.stderr:
        failures.append(f"a second run into a live run's directory was not refused: {second.stderr.strip()!r}")
    if first.returncode != 0:
        failures.append(f"the first run failed: {first_stderr.strip()}")
    else:
        try:
            with h5py.File(os.path.join(args.out, "result.h5"), "r") as result:
                if int(result["/series/time_count"][0]) < 2:
                    failures.append("the first run's result.h5 lacks its output times")
        except OSError as error:
            failures.append(f"the first run's result.h5 does not open: {error}")
        with open(os.path.join(args.out, "summary.json")) as f:
            if json.load(f).get("status") != "completed":
                failures.append("the first run's summary does not say completed")


def check_disk_full(args, run, failures):
    for target in ("summary.json", "result.xdmf"):
        out = os.path.join(args.out, target.replace(".", "_"))
        shutil.rmtree(out, ignore_errors=True)
        os.makedirs(out)
        os.symlink("/dev/full", os.path.join(out, target + ".tmp"))
        result = subprocess.run(run + ["--set", "loading.ramp_s=0.01", "--out", out], capture_output=True, text=True)
        last = result.stderr.strip().splitlines()[-1] if result.stderr.strip() else ""
        if result.returncode == 0:
            failures.append(f"{target} on a full disk: exit 0")
        if f"{os.path.join(out, target)}: cannot write: no space left on device" not in last:
            failures.append(f"{target} on a full disk: the error does not say so with the path: {last!r}")
        left = glob.glob(os.path.join(out, "*.tmp")) + glob.glob(os.path.join(out, "*.partial"))
        if left:
            failures.append(f"{target} on a full disk left {[os.path.basename(f) for f in left]}")


parser = argparse.ArgumentParser()
parser.add_argument("mode", choices=["lock", "disk-full"])
parser.add_argument("--exe", required=True)
parser.add_argument("--case", required=True)
parser.add_argument("--out", required=True)
args = parser.parse_args()
failures = []
{"lock": check_lock, "disk-full": check_disk_full}[args.mode](
    args, [args.exe, "run", args.case, "--set", "block.element_mm=1"], failures)
for failure in failures:
    print("FAIL:", failure)
if not failures:
    print("ok:", args.mode)
sys.exit(1 if failures else 0)
