#!/usr/bin/python3
"""The README's workflows run as written from a fresh clone.

Every ```sh block of README.md is taken line by line, a line's commands joined by && one by one.
The install and whole-suite commands (INSTALLS) are skipped; every other command runs as written,
in the README's order, with bash, in a scratch project root laid out as a fresh clone after
scripts/setup.sh (the source tree's folders linked in, build/ the build tree, no out/). The
environment variable NEEDLEFEM_SET (solver/case/case.hpp) makes every case small: a coarse linear
mesh, tied contact and one output time after the start. A command that exits non-zero, or a README
with fewer commands than its workflows have, fails the test.

usage: check_readme.py --readme README.md --source SOURCE_DIR --build BUILD_DIR --root SCRATCH_DIR
"""
import argparse
import os
import pathlib
import re
import shutil
import subprocess
import sys
import time

# Commands that install packages or run the whole test suite (which holds this test).
INSTALLS = ("scripts/setup.sh", "scripts/test.sh")
# What makes every case of the workflows small (`needlefem keys` explains each key).
# The motion stays as the cases state it: overriding its length would make every case move alike
# and hide a sweep whose points state it differently.
SMALL = "tissue.core_element_mm=1.5 tissue.outer_element_mm=4 mesh.order=1 contact.mode=tied output.interval_s=0.1"
# The README's workflows: quick start (a run), the sweep with its figures and render, converge
# with its plot.
FEWEST_COMMANDS = 6


def readme_commands(readme):
    commands = []
    for block in re.findall(r"^```sh\n(.*?)^```", readme.read_text(), flags=re.S | re.M):
        for line in block.splitlines():
            line = line.split(" #", 1)[0].strip()  # a trailing comment is not part of the command
            commands += [part.strip() for part in line.split("&&") if part.strip()]
    return commands


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--readme", type=pathlib.Path, required=True)
    parser.add_argument("--source", type=pathlib.Path, required=True)
    parser.add_argument("--build", type=pathlib.Path, required=True)
    parser.add_argument("--root", type=pathlib.Path, required=True)
    args = parser.parse_args()

    shutil.rmtree(args.root, ignore_errors=True)
    args.root.mkdir(parents=True)
    for entry in args.source.iterdir():
        if entry.name not in (".git", "build", "out"):
            (args.root / entry.name).symlink_to(entry.resolve())
    (args.root / "build").symlink_to(args.build.resolve())
    environment = dict(os.environ, NEEDLEFEM_SET=SMALL, OMP_NUM_THREADS="1")

    commands = readme_commands(args.readme)
    failures = []
    run = [c for c in commands if not c.startswith(INSTALLS)]
    print(f"{len(commands)} commands in {args.readme}, {len(commands) - len(run)} install commands skipped")
    if len(run) < FEWEST_COMMANDS:
        failures.append(f"only {len(run)} commands to run, the README's workflows have {FEWEST_COMMANDS}")
    for command in run:
        start = time.monotonic()
        # pvbatch under xvfb-run now and then aborts creating its X window while the virtual
        # server comes up on a loaded machine (the same as tests/sweep/check_sweep.py's render):
        # that abort, and only that, is tried again, twice, a few seconds apart.
        for attempt in range(3):
            if attempt:
                time.sleep(3)
            result = subprocess.run(["bash", "-c", command], cwd=args.root, env=environment, capture_output=True,
                                    text=True)
            if result.returncode == 0 or "CreateAWindow" not in result.stderr:
                break
        print(f"{'ok  ' if result.returncode == 0 else 'FAIL'} {time.monotonic() - start:5.1f} s  {command}")
        if result.returncode != 0:
            failures.append(f"exit {result.returncode}: {command}\n{(result.stdout + result.stderr)[-1500:]}")
    for failure in failures:
        print("FAIL:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
