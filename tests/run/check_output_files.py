"""What a run leaves in its output directory when something else is there first.

  lock       A run owns its output directory: while another process holds it, a second run into
             the same --out is refused with one line and leaves the files there untouched (once,
             its H5Fcreate truncated the first run's result.h5 before failing, and the first run
             still said completed).
  disk-full  A full disk is named as such, and leaves no temporary files behind. /dev/full
             answers every write with ENOSPC: a symlink to it as the temporary a run writes
             summary.json (or result.xdmf) to gives that file a full disk without filling one.
             Once, the error said only "cannot write summary.json.partial" and the .partial stayed.

  interrupt  SIGTERM (then SIGINT) mid-run: the run stops after the step in progress with exit
             128 + signal, one line, summary.json "interrupted", and result.h5/.xdmf holding the
             same completed output times (once, the signal killed the run and left no summary).
  killed     SIGKILL mid-run, into an --out that held an earlier run's completed summary: summary.json
             says "running" with this run's case (once, the earlier summary was removed and nothing
             said what the directory held), result.h5 opens with the completed output times and
             result.xdmf lists them or one fewer.
  full-disk-mid-run
             A small tmpfs (mounted in a user namespace: unshare -Urm) fills up mid-run, once in
             result.h5 and once in the XDMF files: one line naming the file and "no space left on
             device", and the XDMF files list exactly the times result.h5 counts as complete
             (once, HDF5 printed its error stack, the error named summary.json instead, and
             result.xdmf listed a time result_surfaces.xdmf and the summary did not). Skipped
             (exit 77) where a user namespace cannot mount a tmpfs.
  cannot-create
             result.h5 cannot be created: --out is a file, result.h5 is a directory, and (on a tmpfs
             in a user namespace, with room for mesh.msh and a few pages) the disk is full. stderr
             holds exactly one line naming the path and the exit status is 1 (once, HDF5 printed
             its error stack when the file it could not finish was closed, then "HDF5: infinite
             loop closing library" or a SIGSEGV in MPI_Finalize).

Every mode checks the output directory it leaves with check_consistent().

usage: check_output_files.py MODE --exe NEEDLEFEM --case CASE --out DIR
"""
import argparse
import fcntl
import glob
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time

import h5py

SKIP = 77  # ctest's SKIP_RETURN_CODE for this script
PROGRESS = re.compile(r"^(mesh: meshing the |mesh: meshed in |mesh: from the mesh cache: |run: +t = |needlefem: note: )")


def error_lines(stderr):
    """stderr without the progress lines of meshing and of each output time, and notes."""
    return [line for line in stderr.splitlines() if not PROGRESS.match(line)]


def check_consistent(out, failures, label):
    """result.h5's completed times are exactly those each XDMF lists, each readable; no temporary
    is left; summary.json, if any, counts the same times and says completed only when it is."""
    try:
        with h5py.File(os.path.join(out, "result.h5"), "r") as result:
            count = int(result["/series/time_count"][0])
            times = [float(t) for t in result["/series/time"][:count]]
            for name in ("result.xdmf", "result_surfaces.xdmf"):
                path = os.path.join(out, name)
                if not os.path.exists(path):
                    continue
                with open(path) as f:
                    text = f.read()
                listed = sorted({float(t) for t in re.findall(r'<Time Value="([^"]+)"', text)})
                if listed != times:
                    failures.append(f"{label}: {name} lists {len(listed)} times, result.h5 completed {count}")
                for dataset in sorted(set(re.findall(r"result\.h5:(/series/steps/\d+/\w+)", text))):
                    if int(dataset.split("/")[3]) >= count or result[dataset][...].size == 0:
                        failures.append(f"{label}: {name} references {dataset}, not a completed time")
                        break
    except OSError as error:
        failures.append(f"{label}: result.h5 does not open: {error}")
        return None
    left = glob.glob(os.path.join(out, "*.tmp")) + glob.glob(os.path.join(out, "*.partial"))
    if left:
        failures.append(f"{label}: left {[os.path.basename(f) for f in left]}")
    summary_file = os.path.join(out, "summary.json")
    if os.path.exists(summary_file):
        with open(summary_file) as f:
            summary = json.load(f)
        if summary.get("output_times") != count:
            failures.append(f"{label}: summary.json counts {summary.get('output_times')} output times, result.h5 {count}")
        return summary
    return None


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


def start_past_two_output_times(run, out, **popen):
    """Starts the run (101 output times of the small block) and returns once it has written the
    first two (or ended, or a minute passed)."""
    history = os.path.join(out, "history.csv")
    process = subprocess.Popen(run + ["--out", out], stdout=subprocess.DEVNULL, **popen)
    deadline = time.monotonic() + 60
    while process.poll() is None and time.monotonic() < deadline:
        if os.path.exists(history):
            with open(history) as f:
                if sum(1 for _ in f) >= 3:  # header and two output times
                    break
        time.sleep(0.005)
    return process


def check_interrupt(args, run, failures):
    for sig in (signal.SIGTERM, signal.SIGINT):
        out = os.path.join(args.out, sig.name)
        shutil.rmtree(out, ignore_errors=True)
        process = start_past_two_output_times(run, out, stderr=subprocess.PIPE, text=True)
        process.send_signal(signal.SIGSTOP)  # held still, so the signal lands mid-run however fast it is
        running = process.poll() is None
        process.send_signal(sig)
        process.send_signal(signal.SIGCONT)
        stderr = process.communicate()[1]
        if not running:
            failures.append(f"inconclusive: the run ended before {sig.name} was sent")
            continue
        errors = error_lines(stderr)
        if process.returncode != 128 + sig.value:
            failures.append(f"{sig.name}: exit {process.returncode}, expected {128 + sig.value}")
        if len(errors) != 1 or f"needlefem: stopped by {sig.name} at t = " not in errors[0]:
            failures.append(f"{sig.name}: expected one line saying the run was stopped, got {errors!r}")
        summary = check_consistent(out, failures, sig.name)
        if summary is None or summary.get("status") != "interrupted":
            failures.append(f"{sig.name}: summary.json does not say interrupted")
        elif not 2 <= summary["output_times"] < 101:
            failures.append(f"{sig.name}: {summary['output_times']} output times kept, expected the 2+ before the stop")


def run_on_tmpfs(run, out, size_bytes):
    """Runs `run` into `out` with a tmpfs of size_bytes mounted there in a user namespace; the
    files are copied out beside it (the mount goes with the namespace). None if no tmpfs."""
    mount_point, copy = out + ".mnt", out
    shutil.rmtree(copy, ignore_errors=True)
    shutil.rmtree(mount_point, ignore_errors=True)
    os.makedirs(mount_point)
    script = ('mount -t tmpfs -o size="$1" tmpfs "$2" || exit 77; shift 2; "$@" --out "$MNT" 2>"$MNT.stderr"; '
              'status=$?; mkdir -p "$COPY" && cp -a "$MNT"/. "$COPY"/; exit $status')
    environment = dict(os.environ, MNT=mount_point, COPY=copy)
    result = subprocess.run(["unshare", "-Urm", "sh", "-c", script, "sh", str(size_bytes), mount_point] + run,
                            env=environment, capture_output=True, text=True)
    if result.returncode == SKIP:
        return None
    with open(mount_point + ".stderr") as f:
        return result.returncode, f.read(), mount_point


def check_full_disk_mid_run(args, run, failures):
    if shutil.which("unshare") is None:
        print("skipped: no unshare")
        sys.exit(SKIP)
    # Fine elements and few output times: the fields of a time are far larger than its XDMF
    # text, so the disk fills in result.h5; coarse elements and 101 times: in the XDMF.
    cases = {"result.h5": ["--set", "block.element_mm=0.15", "--set", "output.interval_s=0.1"], "xdmf": []}
    for label, settings in cases.items():
        out = os.path.join(args.out, label.replace(".", "_"))
        complete = out + "_complete"
        shutil.rmtree(complete, ignore_errors=True)
        subprocess.run(run + settings + ["--out", complete], check=True, capture_output=True)
        with h5py.File(os.path.join(complete, "result.h5"), "r") as result:
            times = int(result["/series/time_count"][0])
            per_time = sum(d.nbytes // d.shape[0] for group in ("node", "cell")
                           for d in result["series"][group].values())
        used = sum(os.stat(f).st_blocks * 512 for f in glob.glob(os.path.join(complete, "*")))
        # Room for about half the run's output times. For result.h5, half a time's fields more:
        # larger than the XDMF text still to come, so the fields of the next time are what fails.
        size = used - (times // 2) * per_time + per_time // 2 if label == "result.h5" else used * 2 // 3
        outcome = run_on_tmpfs(run + settings, out, size)
        if outcome is None:
            print("skipped: a user namespace cannot mount a tmpfs here")
            sys.exit(SKIP)
        status, stderr, mount_point = outcome
        errors = error_lines(stderr)
        if status == 0:
            failures.append(f"{label}: a run on a full disk exited 0")
            continue
        named = (re.escape(os.path.join(mount_point, "result.h5")) + r": cannot write \w+: no space left on device"
                 if label == "result.h5" else re.escape(mount_point) + r"/result(_surfaces)?\.xdmf: cannot write: no space left on device")
        if len(errors) != 1 or not re.search(named, errors[0]):
            failures.append(f"{label}: expected one line naming the file and the full disk, got {errors!r}")
        summary = check_consistent(out, failures, label)
        if summary is not None and summary.get("status") != "failed":
            failures.append(f"{label}: summary.json says {summary.get('status')!r} on a full disk")


def check_killed(args, run, failures):
    out = args.out
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    with open(os.path.join(out, "summary.json"), "w") as f:  # an earlier run's, in the same --out
        json.dump({"status": "completed", "case": {}}, f)
    process = start_past_two_output_times(run, out, stderr=subprocess.DEVNULL)
    running = process.poll() is None
    process.send_signal(signal.SIGKILL)
    process.wait()
    if not running:
        failures.append("inconclusive: the run ended before SIGKILL was sent")
        return
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    if summary.get("status") != "running" or summary.get("case", {}).get("scene", {}).get("kind") != "block":
        failures.append(f"a killed run's summary.json says {summary.get('status')!r} for "
                        f"{summary.get('case', {}).get('scene')}, expected 'running' with its own case")
    try:
        with h5py.File(os.path.join(out, "result.h5"), "r") as result:
            count = int(result["/series/time_count"][0])
        with open(os.path.join(out, "result.xdmf")) as f:
            listed = len(re.findall(r'<Time Value="', f.read()))
        if count < 2 or listed not in (count, count - 1):
            failures.append(f"killed: result.h5 completed {count} output times, result.xdmf lists {listed}")
    except OSError as error:
        failures.append(f"killed: result.h5 or result.xdmf does not open: {error}")


def running_summary_size(run, out):
    """The size of the summary.json a run writes when it starts (killed once it is there)."""
    shutil.rmtree(out, ignore_errors=True)
    summary_file = os.path.join(out, "summary.json")
    process = subprocess.Popen(run + ["--out", out], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 60
    while process.poll() is None and time.monotonic() < deadline and not os.path.exists(summary_file):
        time.sleep(0.002)
    process.send_signal(signal.SIGKILL)
    process.wait()
    with open(summary_file) as f:
        if json.load(f)["status"] != "running":
            raise SystemExit(f"{summary_file}: expected the summary of a run under way")
    return os.path.getsize(summary_file)


def skip_rest(reason, failures):
    """Skips the rest of a mode: the test is skipped unless what ran before failed."""
    print(f"skipped the rest: {reason}")
    if not failures:
        sys.exit(SKIP)


def check_cannot_create(args, run, failures):
    def one_line(label, result, path):
        errors = error_lines(result.stderr)
        if result.returncode == 0:
            failures.append(f"{label}: exit 0")
        if len(errors) != 1 or not errors[0].startswith("needlefem: error: ") or path not in errors[0]:
            failures.append(f"{label}: expected one line naming {path}, got {errors!r}")

    shutil.rmtree(args.out, ignore_errors=True)
    os.makedirs(args.out)
    a_file = os.path.join(args.out, "a_file")
    with open(a_file, "w") as f:
        f.write("not a directory\n")
    one_line("--out is a file", subprocess.run(run + ["--out", a_file], capture_output=True, text=True), a_file)
    result_directory = os.path.join(args.out, "result_is_a_directory")
    os.makedirs(os.path.join(result_directory, "result.h5"))
    one_line("result.h5 is a directory", subprocess.run(run + ["--out", result_directory], capture_output=True,
                                                        text=True), os.path.join(result_directory, "result.h5"))

    if shutil.which("unshare") is None:
        return skip_rest("no unshare", failures)
    meshed = os.path.join(args.out, "meshed")
    subprocess.run([args.exe, "mesh", args.case, "--set", "block.element_mm=1", "--out", meshed], check=True,
                   capture_output=True)
    page = os.sysconf("SC_PAGE_SIZE")
    pages = lambda size: -(-size // page) * page  # noqa: E731
    room = (pages(os.path.getsize(os.path.join(meshed, "mesh.msh")))
            + pages(running_summary_size(run, os.path.join(args.out, "running"))))
    # Room for the "running" summary.json, mesh.msh and 0, 2 or 8 pages more: result.h5 fails at
    # its creation, at its first writes, or when it is flushed before the first output time.
    for extra_pages in (0, 2, 8):
        label = f"room for mesh.msh and {extra_pages} pages"
        outcome = run_on_tmpfs(run, os.path.join(args.out, f"full_{extra_pages}"), room + extra_pages * page)
        if outcome is None:
            return skip_rest("a user namespace cannot mount a tmpfs here", failures)
        status, stderr, mount_point = outcome
        one_line(label, subprocess.CompletedProcess([], status, "", stderr), os.path.join(mount_point, "result.h5"))
        if status != 1 or "no space left on device" not in stderr:
            failures.append(f"{label}: exit {status} (1 expected), the error must say the disk is full: {stderr!r}")


parser = argparse.ArgumentParser()
parser.add_argument("mode", choices=["lock", "disk-full", "interrupt", "killed", "full-disk-mid-run", "cannot-create"])
parser.add_argument("--exe", required=True)
parser.add_argument("--case", required=True)
parser.add_argument("--out", required=True)
args = parser.parse_args()
failures = []
{"lock": check_lock, "disk-full": check_disk_full, "interrupt": check_interrupt, "killed": check_killed,
 "full-disk-mid-run": check_full_disk_mid_run, "cannot-create": check_cannot_create}[args.mode](
    args, [args.exe, "run", args.case, "--set", "block.element_mm=1"], failures)
for failure in failures:
    print("FAIL:", failure)
if not failures:
    print("ok:", args.mode)
sys.exit(1 if failures else 0)
