#!/usr/bin/python3
"""Meshes a case with `needlefem mesh` and checks the result against independent references.

- exit code 0, no inverted tetrahedra (det J > 0 at nodes and quadrature points);
- tip volume of the OpenCASCADE model vs the analytic volume (geometry/needle_tip): rel <= 0.5 %;
- cavity removed from the tissue mesh (cube minus tissue mesh volume) vs analytic: rel <= 1 %;
- every named surface a later stage needs is present;
- the mesh written to HDF5 for ParaView (VTK node order) has, tet by tet, the volume that the
  report computed from the .msh (gmsh order), integrated here independently with numpy;
- the named surfaces are complete and oriented outward: by the divergence theorem the flux of x
  through the tissue boundary (entry + fixed + cavity; or the six block faces) and through
  needle_surface, divided by 3, equals the region volumes (TRI6 integrated exactly, degree 5);
- optionally: the same case meshed twice gives the same mesh (determinism: the second from the
  mesh cache), and
  the generated .msh fed back as scene.mesh_file gives the same mesh (user-supplied meshes).
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np

REQUIRED_SURFACES = {
    "brain-tip": ["entry", "fixed", "cavity", "needle_rear", "needle_surface", "x_min", "x_max", "y_min", "y_max",
                  "z_max"],
    "block": ["x_min", "x_max", "y_min", "y_max", "z_min", "z_max"],
}

failures = []


def check(condition, message):
    print(("ok: " if condition else "FAIL: ") + message)
    if not condition:
        failures.append(message)


def run_mesh(exe, case, out, extra):
    result = subprocess.run([exe, "mesh", case, "--out", str(out)] + extra, capture_output=True, text=True)
    print(result.stdout.strip())
    check(result.returncode == 0, f"needlefem mesh exits 0 (got {result.returncode}: {result.stderr.strip()})")
    return json.loads((out / "mesh_report.json").read_text())


def tet10_volumes_vtk_order(points, cells):
    """Volumes of TET10s given in VTK node order (edges 01 12 02 03 13 23): det J of the
    quadratic map is cubic, integrated exactly by Keast's 15-point degree-5 rule."""
    a1, w1 = 0.25, 0.030283678097089
    a2, w2 = 0.333333333333333, 0.006026785714286
    b2 = 0.0
    a3, w3 = 0.090909090909091, 0.011645249086029
    b3 = 0.727272727272727
    a4, w4 = 0.066550153573664, 0.010949141561386
    b4 = 0.433449846426336
    pts, wts = [(a1, a1, a1)], [w1]
    for a, b, w in ((a2, b2, w2), (a3, b3, w3)):
        for p in ((a, a, a), (b, a, a), (a, b, a), (a, a, b)):
            pts.append(p)
            wts.append(w)
    for p in ((a4, a4, b4), (a4, b4, a4), (b4, a4, a4), (a4, b4, b4), (b4, a4, b4), (b4, b4, a4)):
        pts.append(p)
        wts.append(w4)
    wts = np.array(wts)
    assert abs(wts.sum() - 1 / 6) < 1e-12
    edges = [(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3)]  # VTK quadratic tetra
    x = points[cells]  # [tets, 10, 3]
    volumes = np.zeros(len(cells))
    for (u, v, w), weight in zip(pts, wts):
        L = np.array([1 - u - v - w, u, v, w])
        dL = np.array([[-1, -1, -1], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
        dN = np.zeros((10, 3))
        for i in range(4):
            dN[i] = (4 * L[i] - 1) * dL[i]
        for k, (i, j) in enumerate(edges):
            dN[4 + k] = 4 * (dL[i] * L[j] + L[i] * dL[j])
        J = np.einsum("eni,nj->eij", x, dN)
        volumes += weight * np.linalg.det(J)
    return volumes


def enclosed_volume(points, faces):
    """(1/3) * flux of the position vector through TRI6/TRI3 faces (gmsh order 0 1 2 (01) (12) (20)):
    x . (dx/dxi x dx/deta) is a degree-4 polynomial on TRI6, so the 7-point degree-5 rule is exact."""
    a, b, c, d = 0.059715871789770, 0.470142064105115, 0.797426985353087, 0.101286507323456
    rule = [((1 / 3, 1 / 3), 0.225)] + [((p, q), 0.132394152788506) for p, q in ((a, b), (b, a), (b, b))] + \
           [((p, q), 0.125939180544827) for p, q in ((c, d), (d, c), (d, d))]
    x = points[faces]
    total = 0.0
    for (u, v), w in rule:
        L = np.array([1 - u - v, u, v])
        dL = np.array([[-1, -1], [1, 0], [0, 1]], dtype=float)
        if faces.shape[1] == 6:
            dN = np.vstack([(4 * L[i] - 1) * dL[i] for i in range(3)] +
                           [4 * (dL[i] * L[j] + L[i] * dL[j]) for i, j in ((0, 1), (1, 2), (2, 0))])
            N = np.concatenate([L * (2 * L - 1), [4 * L[0] * L[1], 4 * L[1] * L[2], 4 * L[2] * L[0]]])
        else:
            dN, N = dL, L
        pos = np.einsum("fnk,n->fk", x, N)
        tangents = np.einsum("fnk,nj->fkj", x, dN)
        normal = np.cross(tangents[:, :, 0], tangents[:, :, 1])
        total += 0.5 * w * np.einsum("fk,fk->", pos, normal)
    return total / 3


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--exe", required=True)
    parser.add_argument("--case", required=True)
    parser.add_argument("--out", required=True, type=Path)
    parser.add_argument("--set", action="append", default=[])
    parser.add_argument("--determinism", action="store_true")
    parser.add_argument("--user-mesh", action="store_true")
    args = parser.parse_args()
    extra = [a for s in args.set for a in ("--set", s)]
    if args.determinism:  # a mesh cache of its own, empty: the first meshing is gmsh's
        cache = args.out.parent / (args.out.name + "_cache")
        shutil.rmtree(cache, ignore_errors=True)
        os.environ["NEEDLEFEM_MESH_CACHE"] = str(cache)

    report = run_mesh(args.exe, args.case, args.out, extra)
    scene = report["case"]["scene"]["kind"]
    check(report["inverted_tets"] == 0, f"no inverted tets ({report['inverted_tets']})")
    for name in REQUIRED_SURFACES[scene]:
        check(report["surfaces"].get(name, 0) > 0, f"surface '{name}' has faces ({report['surfaces'].get(name, 0)})")
    if scene == "brain-tip":
        needle = report["needle"]
        cad = needle["cad_volume"]["relative_difference"]
        cavity = needle["cavity_volume_removed_from_mesh"]["relative_difference"]
        check(abs(cad) <= 5e-3, f"CAD tip volume vs analytic: {cad:+.2e} (limit 0.5 %)")
        check(abs(cavity) <= 1e-2, f"cavity removed from the mesh vs analytic: {cavity:+.2e} (limit 1 %)")

    with h5py.File(args.out / "mesh.h5", "r") as f:
        points = f["/mesh/coordinates_mm"][...] * 1e-3
        cells = f["/mesh/tets"][...]
        regions = f["/mesh/region"][...]
        names = [n.decode() if isinstance(n, bytes) else n for n in f["/mesh/region"].attrs["names"]]
    check(len(cells) == report["tets"] and len(points) == report["nodes"], "HDF5 mesh has the report's counts")
    volumes = tet10_volumes_vtk_order(points, cells) if cells.shape[1] == 10 else None
    if volumes is not None:
        check(volumes.min() > 0, f"every written tet has positive volume in VTK order (min {volumes.min():.3e} m^3)")
        for index, name in enumerate(names):
            written = volumes[regions == index].sum() * 1e9
            reported = report["regions"][name]["volume_mm3"]
            check(abs(written - reported) <= 1e-10 * reported,
                  f"region {name}: written-mesh volume {written:.12g} mm^3 = report {reported:.12g} mm^3")

    with h5py.File(args.out / "mesh.h5", "r") as f:
        surfaces = {name: f["/mesh/surfaces"][name][...] for name in f["/mesh/surfaces"]}
    tissue_boundary = ["entry", "fixed", "cavity"] if scene == "brain-tip" else REQUIRED_SURFACES["block"]
    tissue_volume = sum(q["volume_mm3"] for name, q in report["regions"].items() if name.startswith("tissue"))
    enclosed = enclosed_volume(points, np.vstack([surfaces[n] for n in tissue_boundary])) * 1e9
    check(abs(enclosed - tissue_volume) <= 1e-9 * tissue_volume,
          f"tissue boundary is closed and outward: flux volume {enclosed:.12g} = tissue {tissue_volume:.12g} mm^3")
    if "needle_surface" in surfaces:
        needle_volume = report["regions"]["needle"]["volume_mm3"]
        enclosed = enclosed_volume(points, surfaces["needle_surface"]) * 1e9
        check(abs(enclosed - needle_volume) <= 1e-9 * needle_volume,
              f"needle_surface is closed and outward: flux volume {enclosed:.12g} = needle {needle_volume:.12g} mm^3")

    if args.determinism:
        again = args.out.parent / (args.out.name + "_again")
        second = run_mesh(args.exe, args.case, again, extra)
        # Bit for bit: gmsh's high-order optimiser works in the order of memory addresses, and two
        # meshings differ in the last digits of ~1200 curved nodes of the default tip; the scene is
        # meshed once and the second `mesh` reads it from the mesh cache (mesh/mesh_cache.hpp).
        sources = (report["mesh_cache"]["source"], second["mesh_cache"]["source"])
        check(sources == ("miss", "hit") and report["mesh_cache"]["key"] == second["mesh_cache"]["key"],
              f"meshed once, then read from the cache under the same key ({sources})")
        check((args.out / "mesh.msh").read_bytes() == (again / "mesh.msh").read_bytes(), "the same mesh.msh bytes")
        with h5py.File(args.out / "mesh.h5", "r") as f, h5py.File(again / "mesh.h5", "r") as g:
            same_tets = np.array_equal(f["/mesh/tets"][...], g["/mesh/tets"][...])
            drift = np.abs(f["/mesh/coordinates_mm"][...] - g["/mesh/coordinates_mm"][...]).max()
        check(same_tets and drift == 0.0, f"meshing twice gives the same mesh (connectivity identical, "
              f"coordinates within {drift:.1e} mm)")
    if args.user_mesh:
        reused = args.out.parent / (args.out.name + "_user")
        user = run_mesh(args.exe, args.case, reused, extra + ["--set", f"scene.mesh_file={(args.out / 'mesh.msh').resolve()}"])
        check(user["user_mesh"] and user["nodes"] == report["nodes"] and user["tets"] == report["tets"],
              f"the .msh fed back as scene.mesh_file gives the same mesh ({user['nodes']} nodes, {user['tets']} tets)")
    print(f"{len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
