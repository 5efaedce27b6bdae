#!/usr/bin/env python3
"""The layer check (docs/design.md, "Layers"): no file of the library includes a header of a layer
above its own, and the libraries include only what they link.

Every folder of src/ is a layer, ranked below; a public header include/antcd/<name>.hpp belongs to
the layer that implements it (HEADER_LAYER). A file of layer L may include the public and private
headers of layers ranked below L and of L itself; layers of one rank (io and random) must not
include each other. Public headers are checked the same way, and the front ends (apps/, python/,
wasm/) may not include private headers of src/ at all (they are the libraries' callers, not parts
of them). Every public header must be installed by exactly one library (its antcd_library_headers
list in src/CMakeLists.txt).

Usage: scripts/check-layers.py [REPO]   exits 1 naming each upward include, 0 when there is none.
"""
import pathlib
import re
import sys

# Bottom to top. util holds the core's header-only helpers and file helpers: every layer uses it.
RANKS = {
    "base": 0, "util": 1, "geometry": 2, "mesh": 3, "bvh": 4, "points": 5, "exact": 6,
    "distance": 7, "penetration": 8, "ccd": 9, "self": 10, "world": 11,
    # Libraries on top of the core (each its own target): the file readers, the paper's random
    # detection, then scenes (which use both).
    "io": 12, "random": 12, "scene": 13,
}
HEADER_LAYER = {
    "math": "base", "error": "base", "export": "base", "tolerances": "base", "version": "base",
    "pose": "base", "file": "util",
    "geometry": "geometry", "mesh": "mesh", "bvh": "bvh", "points": "points", "collide": "exact",
    "distance": "distance", "penetration": "penetration", "sweep": "ccd", "ccd": "ccd", "deform_ccd": "ccd",
    "self": "self", "world": "world",
    "load": "io", "csv": "io", "io_export": "io",
    "random": "random", "random_features": "random", "random_search": "random", "method": "random",
    "rng": "random", "random_export": "random",
    "scene": "scene", "scene_export": "scene",
}
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^">]+)[">]')


def layer_of_include(target):
    """The layer of an included path, or None for a header outside antcd (std, Eigen, ...)."""
    parts = target.split("/")
    if parts[0] == "antcd" and len(parts) == 2 and parts[1].endswith(".hpp"):
        name = parts[1][:-4]
        return HEADER_LAYER.get(name, "?" + name)
    if len(parts) == 2 and parts[0] in RANKS:
        return parts[0]  # a private header, "layer/file.hpp"
    return None


def allowed(own, other):
    if other == own:
        return True
    if other.startswith("?"):
        return False
    return RANKS[other] < RANKS[own]


def main():
    repo = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent.parent)
    problems = []
    checked = 0
    files = [(f, f.relative_to(repo / "src").parts[0]) for f in sorted((repo / "src").glob("*/*.[ch]pp"))]
    for f in sorted((repo / "include" / "antcd").glob("*.hpp")):
        files.append((f, HEADER_LAYER.get(f.stem, "?" + f.stem)))
    for f, own in files:
        if own.startswith("?"):
            problems.append(f"{f.relative_to(repo)}: a public header of no layer (add it to HEADER_LAYER)")
            continue
        if own not in RANKS:
            problems.append(f"{f.relative_to(repo)}: folder src/{own} is no layer (add it to RANKS)")
            continue
        checked += 1
        for number, line in enumerate(f.read_text(encoding="utf-8").splitlines(), 1):
            m = INCLUDE.match(line)
            if not m:
                continue
            other = layer_of_include(m.group(2))
            if other is not None and not allowed(own, other):
                problems.append(f"{f.relative_to(repo)}:{number}: layer {own} includes {m.group(2)} "
                                f"(layer {other.lstrip('?')}, not below it)")
    for front in ("apps", "python", "wasm"):
        for f in sorted((repo / front).rglob("*.[ch]pp")):
            if "node_modules" in f.parts:
                continue
            checked += 1
            for number, line in enumerate(f.read_text(encoding="utf-8").splitlines(), 1):
                m = INCLUDE.match(line)
                if m and m.group(1) == '"' and m.group(2).split("/")[0] in RANKS:
                    problems.append(f"{f.relative_to(repo)}:{number}: the front end includes the "
                                    f"library's private header {m.group(2)}")
    # Every public header is installed by exactly one library (antcd_library_headers in
    # src/CMakeLists.txt), or an installed package would lack it.
    cmake = (repo / "src" / "CMakeLists.txt").read_text(encoding="utf-8")
    listed = []
    for m in re.finditer(r"antcd_library_headers\(\s*(\w+)([^)]*)\)", cmake):
        listed += m.group(2).split()
    for f in sorted((repo / "include" / "antcd").glob("*.hpp")):
        if listed.count(f.name) != 1:
            problems.append(f"include/antcd/{f.name}: installed by {listed.count(f.name)} libraries "
                            "(list it once in an antcd_library_headers call of src/CMakeLists.txt)")
    for p in problems:
        print(p)
    if problems:
        print(f"check-layers: {len(problems)} problem(s): includes against the layers of "
              "docs/design.md, or public headers no library installs",
              file=sys.stderr)
        return 1
    print(f"check-layers: {checked} files, no upward include")
    return 0


if __name__ == "__main__":
    sys.exit(main())
