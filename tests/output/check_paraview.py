#!/usr/bin/python3
"""Open an XDMF file in ParaView (headless) and check what ParaView sees.

Run with Debian's /usr/bin/python3 (python3-paraview) or /usr/bin/pvpython:

  check_paraview.py FILE.xdmf [--reader both|xdmf2|xdmf3] [--cells N] [--points N]
      [--times T1,T2,...] [--array SPEC]... [--expect EXPECT.json] [--rtol R] [--atol A]

SPEC is comma-separated key=value:
  name=NAME            array name (required)
  assoc=point|cell     point (node) or cell data (default point)
  min=X, max=Y         expected range (either or both)
  component=K|magnitude  component whose range is checked; default: 0 for one-component
                       arrays, the magnitude otherwise
  components=C         expected number of components
  time=T               pipeline time at which the range is checked (default: first time)
EXPECT.json holds the same as an object: {"cells": N, "points": N, "times": [...],
"arrays": [{"name": ..., "assoc": ..., "min": ..., ...}]}; command-line values win.

Every check runs with each selected reader: "xdmf2" is ParaView's XDMFReader, "xdmf3" its
Xdmf3ReaderS (what File > Open picks by default). For multi-block outputs (several grids),
cells and points are summed over blocks and ranges taken over all blocks.
Exit status 0 when every check passes, 1 otherwise (each failure printed), 2 on bad usage.
"""
import argparse
import json
import os
import sys


def parse_array_spec(text):
    spec = {}
    for item in text.split(","):
        key, sep, value = item.partition("=")
        if not sep:
            raise argparse.ArgumentTypeError(f"array spec item '{item}' is not key=value")
        spec[key.strip()] = value.strip()
    if "name" not in spec:
        raise argparse.ArgumentTypeError(f"array spec '{text}' has no name=")
    unknown = set(spec) - {"name", "assoc", "min", "max", "component", "components", "time"}
    if unknown:
        raise argparse.ArgumentTypeError(f"array spec '{text}': unknown keys {sorted(unknown)}")
    return spec


def normalise_array(spec):
    """Array spec with typed values (from the command line or JSON)."""
    result = {"name": str(spec["name"]), "assoc": str(spec.get("assoc", "point"))}
    if result["assoc"] not in ("point", "cell"):
        raise ValueError(f"array {result['name']}: assoc must be point or cell")
    for key in ("min", "max", "time"):
        if key in spec:
            result[key] = float(spec[key])
    if "components" in spec:
        result["components"] = int(spec["components"])
    if "component" in spec:
        value = str(spec["component"])
        result["component"] = -1 if value == "magnitude" else int(value)
    return result


def open_reader(kind, path):
    import paraview.simple as pv
    if kind == "xdmf2":
        return pv.XDMFReader(FileNames=[path])
    return pv.Xdmf3ReaderS(FileName=[path])


def close_enough(found, expected, rtol, atol):
    return abs(found - expected) <= atol + rtol * abs(expected)


def check_with_reader(kind, path, expect, rtol, atol):
    """List of failure messages (empty when everything matches)."""
    import paraview.simple as pv
    failures = []
    reader = open_reader(kind, path)
    values = reader.TimestepValues  # a list, or a bare float for a single time
    times = [float(v) for v in values] if hasattr(values, "__iter__") else [float(values)]
    first_time = times[0] if times else 0.0
    reader.UpdatePipeline(first_time)
    info = reader.GetDataInformation()
    cells, points = info.GetNumberOfCells(), info.GetNumberOfPoints()
    print(f"[{kind}] {path}: {cells} cells, {points} points, times {times}")

    if "cells" in expect and cells != expect["cells"]:
        failures.append(f"[{kind}] cells: found {cells}, expected {expect['cells']}")
    if "points" in expect and points != expect["points"]:
        failures.append(f"[{kind}] points: found {points}, expected {expect['points']}")
    if "times" in expect:
        wanted = expect["times"]
        if len(times) != len(wanted) or not all(close_enough(f, w, rtol, atol) for f, w in zip(times, wanted)):
            failures.append(f"[{kind}] times: found {times}, expected {wanted}")

    for spec in expect.get("arrays", []):
        time = spec.get("time", first_time)
        reader.UpdatePipeline(time)
        data = reader.PointData if spec["assoc"] == "point" else reader.CellData
        label = f"[{kind}] {spec['assoc']} array '{spec['name']}' at t={time}"
        if spec["name"] not in data.keys():
            failures.append(f"{label}: missing (found {sorted(data.keys())})")
            continue
        array = data[spec["name"]]
        count = array.GetNumberOfComponents()
        if "components" in spec and count != spec["components"]:
            failures.append(f"{label}: {count} components, expected {spec['components']}")
        component = spec.get("component", 0 if count == 1 else -1)
        low, high = array.GetRange(component)
        print(f"{label} component {component}: range [{low:.17g}, {high:.17g}], {count} components")
        if "min" in spec and not close_enough(low, spec["min"], rtol, atol):
            failures.append(f"{label}: min {low:.17g}, expected {spec['min']:.17g}")
        if "max" in spec and not close_enough(high, spec["max"], rtol, atol):
            failures.append(f"{label}: max {high:.17g}, expected {spec['max']:.17g}")
    pv.Delete(reader)
    return failures


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("file", help="the .xdmf file")
    parser.add_argument("--reader", choices=("both", "xdmf2", "xdmf3"), default="both")
    parser.add_argument("--cells", type=int)
    parser.add_argument("--points", type=int)
    parser.add_argument("--times", type=lambda text: [float(t) for t in text.split(",")])
    parser.add_argument("--array", type=parse_array_spec, action="append", default=[])
    parser.add_argument("--expect", help="JSON file with expectations")
    parser.add_argument("--rtol", type=float, default=1e-12)
    parser.add_argument("--atol", type=float, default=1e-12)
    args = parser.parse_args()

    expect = {}
    if args.expect:
        with open(args.expect) as stream:
            expect = json.load(stream)
    for key in ("cells", "points", "times"):
        if getattr(args, key) is not None:
            expect[key] = getattr(args, key)
    try:
        expect["arrays"] = [normalise_array(a) for a in expect.get("arrays", []) + args.array]
    except (KeyError, ValueError) as error:
        parser.error(str(error))

    # ParaView's Xdmf3 readers crash on a bare relative name: always pass an absolute path.
    path = os.path.abspath(args.file)
    if not os.path.isfile(path):
        parser.error(f"{path}: no such file")
    kinds = ("xdmf2", "xdmf3") if args.reader == "both" else (args.reader,)
    failures = []
    for kind in kinds:
        failures += check_with_reader(kind, path, expect, args.rtol, args.atol)
    for failure in failures:
        print("FAIL " + failure)
    print("OK" if not failures else f"{len(failures)} check(s) failed")
    return 0 if not failures else 1


if __name__ == "__main__":
    sys.exit(main())
