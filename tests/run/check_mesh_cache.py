#!/usr/bin/python3
"""The mesh cache (mesh/mesh_cache.hpp), each check with a cache directory of its own under --out:

  repeat       the same case run twice: the first run meshes and publishes (miss), the second
               reads the entry (hit, same key); both runs' mesh.msh are the entry's bytes and
               the summaries (maxima, safety, reactions, energy, verdict, solver counts) are bit for bit
               the same
  seed         mesh.seed changed: another key, a miss
  physics      only motion and material keys changed: the same key, a hit
  unwritable   a cache directory that cannot be written: the run completes, meshed into its
               output directory, with one line on stderr saying so
  full         a cache directory on a disk too small for the mesh (a tmpfs; skipped where a user
               namespace cannot mount one): the same
  concurrent   two `needlefem mesh` of one scene started together: both complete with the same
               bytes, one entry, no temporary file of theirs left (and a day-old one of a killed
               writer removed)

Cases are the default brain tip on a coarse mesh with tied contact (seconds per run); where bit
for bit is checked the mesh is second order, whose curved nodes differ from one meshing to the next.

usage: check_mesh_cache.py --exe NEEDLEFEM --case CASE.toml --out DIR {repeat,seed,physics,unwritable,full,concurrent}
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

SMALL = ["--set", "tissue.core_element_mm=1.5", "--set", "tissue.outer_element_mm=4", "--set", "mesh.order=1",
         "--set", "contact.mode=tied", "--set", "motion.duration_s=0.02", "--set", "output.interval_s=0.01"]

# Where bit for bit needs the cache: two meshings of a second-order scene differ in the last
# digits of the nodes gmsh's high-order optimiser curves.
CURVED = ["--set", "mesh.order=2"]

failures = []


def check(condition, message):
    print(("ok: " if condition else "FAIL: ") + message)
    if not condition:
        failures.append(message)


def needlefem(args, command, out, cache, extra=(), wait=True):
    """Runs (or starts, wait=False) `needlefem COMMAND CASE --out OUT` with NEEDLEFEM_MESH_CACHE=cache."""
    shutil.rmtree(out, ignore_errors=True)
    environment = dict(os.environ, NEEDLEFEM_MESH_CACHE=str(cache))
    argv = [args.exe, command, str(args.case), "--out", str(out)] + SMALL + list(extra)
    if not wait:
        return subprocess.Popen(argv, env=environment, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    result = subprocess.run(argv, env=environment, capture_output=True, text=True)
    check(result.returncode == 0, f"needlefem {command} {' '.join(extra)} exits 0 "
          f"(got {result.returncode}: {result.stderr.strip()[-400:]})")
    return result


def run_cache(args, out, cache, extra=()):
    """The summary's mesh.cache of a run."""
    needlefem(args, "run", out, cache, extra)
    return json.loads((out / "summary.json").read_text())


def mesh_cache(args, out, cache, extra=()):
    """The mesh report's mesh_cache of `needlefem mesh`."""
    needlefem(args, "mesh", out, cache, extra)
    return json.loads((out / "mesh_report.json").read_text())["mesh_cache"]


def fresh(path):
    shutil.rmtree(path, ignore_errors=True)
    path.mkdir(parents=True)
    return path


def entries(cache):
    return sorted(p.name for p in cache.iterdir()) if cache.exists() else []


def repeat(args):
    cache = fresh(args.out / "cache")
    first = run_cache(args, args.out / "first", cache, CURVED)
    second = run_cache(args, args.out / "second", cache, CURVED)
    a, b = first["mesh"]["cache"], second["mesh"]["cache"]
    check(a["source"] == "miss" and b["source"] == "hit", f"first run meshes (miss), second reads the cache (hit): "
          f"{a['source']}, {b['source']}")
    check(a["key"] == b["key"] and len(a["key"]) == 16, f"the same key ({a['key']}, {b['key']})")
    entry = Path(b["file"])
    check(entry.parent == cache and entry.name == a["key"] + ".msh" and entries(cache) == [entry.name],
          f"one entry in the cache, named by the key ({entries(cache)})")
    same_bytes = all((args.out / run / "mesh.msh").read_bytes() == entry.read_bytes() for run in ("first", "second"))
    check(same_bytes, "both runs' mesh.msh are the entry's bytes")
    # Everything but where the mesh came from and the timings.
    differ = sorted(part for part in first.keys() | second.keys()
                    if part not in ("mesh", "solver") and first.get(part) != second.get(part))
    check(not differ and "max" in first and "safety" in first,
          f"summary maxima, safety, reactions, energy and verdict bit for bit the same (differ: {differ})")
    timings = ("wall_s", "mesh_s", "integration_s", "output_s", "peak_rss_mb")
    counts = [name for name in first["solver"] if name not in timings and first["solver"][name] != second["solver"][name]]
    check(not counts, f"the same steps, Newton and linear iterations (differ: {counts})")


def seed(args):
    cache = fresh(args.out / "cache")
    base = mesh_cache(args, args.out / "base", cache)
    other = mesh_cache(args, args.out / "seed", cache, ["--set", "mesh.seed=2"])
    check(base["source"] == "miss" and other["source"] == "miss", f"mesh.seed = 2 meshes anew ({other['source']})")
    check(base["key"] != other["key"] and len(entries(cache)) == 2, f"another key ({base['key']}, {other['key']}), "
          f"two entries")


def physics(args):
    cache = fresh(args.out / "cache")
    base = mesh_cache(args, args.out / "base", cache)
    changed = ["--set", "motion.insertion_speed_mm_per_s=2", "--set", "motion.rotation_speed_deg_per_s=90",
               "--set", "material.preset=miller-brain-c10-c20", "--set", "material.bulk_modulus_pa=2e7"]
    summary = run_cache(args, args.out / "run", cache, changed)
    other = summary["mesh"]["cache"]
    check(other["source"] == "hit" and other["key"] == base["key"],
          f"motion and material keys changed: the same key, a hit ({other['source']}, {other['key']})")


def unwritable(args):
    root = fresh(args.out / "cache")
    if os.geteuid() == 0:  # root writes into a read-only directory: a path through a file cannot be made
        (root / "file").write_text("not a directory\n")
        cache = root / "file" / "meshes"
    else:
        cache = root / "read_only"
        cache.mkdir()
        cache.chmod(0o555)
    out = args.out / "run"
    result = needlefem(args, "run", out, cache)
    summary = json.loads((out / "summary.json").read_text())
    check(summary["status"] == "completed", f"the run completes ({summary['status']})")
    notes = [line for line in result.stderr.splitlines() if "mesh cache" in line]
    check(len(notes) == 1 and "cannot be written" in notes[0] and str(cache) in notes[0],
          f"one line says the cache cannot be written ({notes})")
    check(summary["mesh"]["cache"]["source"] == "off" and (out / "mesh.msh").is_file(),
          f"the summary says the cache was off; the mesh is in the output directory")


def full(args):
    """A cache on a tmpfs too small for the mesh (mounted in a user namespace: unshare -Urm; exit 77
    where none can be mounted): gmsh's write is cut short, the run completes without the cache."""
    if shutil.which("unshare") is None:
        print("skipped: no unshare")
        return 77
    cache = fresh(args.out / "cache")
    out = args.out / "run"
    script = 'mount -t tmpfs -o size=64k tmpfs "$NEEDLEFEM_MESH_CACHE" || exit 77; exec "$@"'
    environment = dict(os.environ, NEEDLEFEM_MESH_CACHE=str(cache))
    result = subprocess.run(["unshare", "-Urm", "sh", "-c", script, "sh", args.exe, "run", str(args.case),
                             "--out", str(out)] + SMALL + CURVED, env=environment, capture_output=True, text=True)
    if result.returncode == 77:
        print(f"skipped: a user namespace cannot mount a tmpfs here ({result.stderr.strip()})")
        return 77
    check(result.returncode == 0, f"the run exits 0 ({result.returncode}: {result.stderr.strip()[-400:]})")
    summary = json.loads((out / "summary.json").read_text())
    notes = [line for line in result.stderr.splitlines() if "mesh cache" in line]
    check(len(notes) == 1 and "cannot be written" in notes[0], f"one line says the cache cannot be written ({notes})")
    check(summary["status"] == "completed" and summary["mesh"]["cache"]["source"] == "off",
          f"the run completes with the cache off ({summary['status']}, {summary['mesh']['cache']['source']})")


def concurrent(args):
    cache = fresh(args.out / "cache")
    # What a writer killed while meshing leaves: removed once it is a day old, kept before.
    stale, recent = cache / ".0123456789abcdef.99999-0.partial.msh", cache / ".0123456789abcdef.99998-0.partial.msh"
    stale.write_text("partial\n")
    recent.write_text("partial\n")
    os.utime(stale, (time.time() - 2 * 86400,) * 2)
    jobs = [needlefem(args, "mesh", args.out / f"job{i}", cache, CURVED, wait=False) for i in range(2)]
    results = [job.communicate() + (job.returncode,) for job in jobs]
    check(all(code == 0 for _, _, code in results), f"both jobs exit 0 ({[r[2] for r in results]}: "
          f"{[r[1].strip()[-300:] for r in results if r[2]]})")
    reports = [json.loads((args.out / f"job{i}" / "mesh_report.json").read_text())["mesh_cache"] for i in range(2)]
    check(len({r["key"] for r in reports}) == 1 and all(r["source"] in ("miss", "hit") for r in reports),
          f"the same key, read from the cache ({[r['source'] for r in reports]})")
    check(entries(cache) == sorted([recent.name, reports[0]["key"] + ".msh"]),
          f"one entry, none of the jobs' temporary files left, a day-old one removed ({entries(cache)})")
    meshes = [(args.out / f"job{i}" / "mesh.msh").read_bytes() for i in range(2)]
    check(meshes[0] == meshes[1], "both jobs' mesh.msh are the same bytes")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--exe", required=True)
    parser.add_argument("--case", type=Path, required=True)
    parser.add_argument("--out", type=Path, required=True)
    parser.add_argument("check", choices=["repeat", "seed", "physics", "unwritable", "full", "concurrent"])
    args = parser.parse_args()
    fresh(args.out)
    if globals()[args.check](args) == 77:
        return 77
    print(f"{len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
