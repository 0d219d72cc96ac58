#!/usr/bin/python3
"""Every case key the scene mesher reads is part of the mesh cache's key (the keys
mesh_cache_key_text in solver/mesh/mesh_cache.cpp names), or is one the cache handles otherwise: a
key missing there would let a changed value find the mesh of the old one.

Reads the sources: the keys read as c.text("..."), c.real("..."), ... or parse_choice(c, "...")
in the parsers of the mesher's spec and in the mesher's own files.

usage: check_mesh_cache_keys.py SOURCE_DIR
"""
import re
import sys
from pathlib import Path

# The files whose case reads decide the scene mesh: the parser of the mesher's spec
# (case/specs/mesh_spec.cpp) with the spec parsers it includes (the needle tip and tissue cube, the
# scene kind), and every source of solver/mesh/ but the cache itself (the scene mesher, its size
# field, the CAD tip it imports), which take the spec and should read no key themselves. A parser
# the mesh spec starts to include, or a file split out of the mesher, is read without being listed
# here.
SPEC_INCLUDE = re.compile(r'#include "(case/specs/[a-z_]+)\.hpp"')


def mesher_files(source):
    parser = source / "solver/case/specs/mesh_spec.cpp"
    specs = {parser}
    for header in [source / "solver/case/specs/mesh_spec.hpp", parser]:
        specs |= {source / "solver" / (name + ".cpp") for name in SPEC_INCLUDE.findall(header.read_text())}
    mesh = sorted(p for p in (source / "solver/mesh").glob("*.cpp") if p.name != "mesh_cache.cpp")
    return sorted(p for p in specs if p.exists()) + mesh
# Keys those files read that the key leaves out, and why.
HANDLED_OTHERWISE = {
    "scene.mesh_file": "bypasses the cache",
    "needle.export_file": "bypasses the cache (written while meshing)",
    "needle.cad_file": "keyed by the file's bytes",
    "needle.cad_facet_um": "the contact needle's triangulation (cad_tip.cpp), not the scene mesh",
    "needle.cad_facet_deg": "the contact needle's triangulation (cad_tip.cpp), not the scene mesh",
    "mesh.partitions": "partitions the mesh once meshed (`needlefem mesh`), not the scene mesh",
}
READ = re.compile(r'(?:\bc\.(?:text|real|reals|integer|flag|texts|path|given|has|maybe_real|maybe_integer)\(|\bparse_choice\(c, )'
                  r'"([a-z_0-9.]+)"')


def main():
    source = Path(sys.argv[1])
    cache = (source / "solver/mesh/mesh_cache.cpp").read_text()
    start = cache.index("std::string mesh_cache_key_text(")
    listed = set(re.findall(r'"([a-z_]+\.[a-z_0-9]+)"', cache[start:cache.index("\n}\n", start)]))
    read = set()
    for path in mesher_files(source):
        read |= set(READ.findall(path.read_text()))
    missing = sorted(read - listed - set(HANDLED_OTHERWISE))
    unread = sorted(listed - read)
    print(f"{len(read)} keys read by the mesher, {len(listed)} in the cache key")
    for key in missing:
        print(f"FAIL: the mesher reads '{key}', which the mesh cache's key leaves out")
    for key in unread:
        print(f"FAIL: the mesh cache's key holds '{key}', which the mesher does not read")
    return 1 if missing or unread else 0


if __name__ == "__main__":
    sys.exit(main())
