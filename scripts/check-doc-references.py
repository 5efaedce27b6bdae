#!/usr/bin/python3
"""Checks that docs and code comments name only things that exist (ctest: docs_references).

Docs: README.md, wasm/README.md and docs/*.md (a path resolves from the repository root or from
the document's own folder).

Docs drift when code is renamed or removed: a design note naming a function that is gone, a path
that moved. This finds these references and fails (exit 1, one line per stale reference) when one
no longer resolves:
  - in README.md and docs/*.md, C++ names in backticks, qualified (`World::nearest_pair`,
    `detail::AabbTree`) or called (`nearest_pair()`, `distance(a, b)`): the name (the last
    component) must occur in the sources' code, comments stripped (src, include, apps, python...);
  - in the same files, repository paths (`src/world/nearest.cpp`, `experiments/paper/*.cpp`,
    `tests/ccd/data/degenerate_{vf,ee}.csv`): must exist (globs and {a,b} expanded);
  - in the // comments of C++ sources, qualified names and called snake_case names
    (`detail::narrow_phase`, `search_feature_space()`): must occur in the code.
References that are meant to name something outside this tree or no longer here (a column of
what a refactoring replaced) are listed in ALLOWED with the reason.
Usage: scripts/check-doc-references.py [repository root]
"""
import itertools
import pathlib
import re
import sys

ROOT = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent.parent)
TOP = ("src", "include", "tests", "bench", "docs", "scripts", "python", "apps", "examples",
       "viewer", "fuzz", "learned", "shared", "experiments", "cmake", "wasm")
SOURCES = ("src", "include", "apps", "python", "bench", "tests", "scripts", "viewer/src", "learned",
           "shared", "experiments", "examples", "fuzz", "cmake", "wasm/src", "wasm/test")
CXX = {".cpp", ".hpp", ".h"}
SUFFIXES = {".cpp", ".hpp", ".h", ".py", ".pyi", ".sh", ".js", ".mjs", ".ts", ".cmake", ".txt", ".in"}

ALLOWED = {
    # trimesh's own test file, which antcd.CollisionManager is checked against
    ("README.md", "tests/test_collision.py"),
    # design.md's table of what the shared libraries replaced (files that are gone on purpose)
    ("design.md", "experiments/paper_bench.cpp"),
    ("design.md", "experiments/peers_bench.cpp"),
    ("design.md", "experiments/production_line.*"),
    ("design.md", "experiments/run_result.*"),
    # the npm package the main build writes (not in a fresh clone; the sanitizer builds make none)
    ("javascript.md", "wasm/dist"),
}

CALL_RE = re.compile(r"\b([a-z]\w*)\(")
SNAKE_CALL_RE = re.compile(r"\b([a-z][a-z0-9]*_\w+)\(")
# Namespaces of other libraries: their names are not ours to check.
EXTERNAL = {"std", "torch", "at", "c10", "CLI", "Eigen", "fcl", "tbb", "oneapi", "py", "pybind11",
            "nlohmann", "CGAL", "Assimp", "tinyobj", "emscripten", "benchmark", "testing", "boost"}
# Mathematical notation, not code: fl(x) is a rounded value, h_A(d) a support function.
NOT_CODE = re.compile(r"^(fl|[a-z]_[A-Za-z0-9])$")
PATH_RE = re.compile(r"(?<![\w/.\-])((?:%s)/[\w./*\-]*(?:\{[\w,]+\}[\w./*\-]*)?[\w*])" % "|".join(TOP))
NAME_RE = re.compile(r"\b((?:[A-Za-z_]\w*::)+[A-Za-z_]\w*)")


def expand_braces(path):
    m = re.search(r"\{([^}]*)\}", path)
    if not m:
        return [path]
    return list(itertools.chain.from_iterable(
        expand_braces(path[:m.start()] + alt + path[m.end():]) for alt in m.group(1).split(",")))


def exists(path, *bases):
    """Whether `path` exists under one of `bases` (every {a,b} alternative; a glob matches)."""
    return any(all(any(base.glob(p)) if "*" in p else (base / p).exists()
                   for p in expand_braces(path)) for base in bases)


def strip_comments(text):
    return re.sub(r"//[^\n]*|/\*.*?\*/", "", text, flags=re.S)


def main():
    docs = [ROOT / "README.md", ROOT / "wasm" / "README.md"]
    docs += sorted((ROOT / "docs").glob("*.md"))
    docs = [d for d in docs if d.exists()]
    files = [p for d in SOURCES if (ROOT / d).is_dir() for p in (ROOT / d).rglob("*")
             if p.is_file() and (p.suffix in SUFFIXES or p.name == "CMakeLists.txt")
             and p.resolve() != pathlib.Path(__file__).resolve()]
    texts = {p: p.read_text(errors="ignore") for p in files}
    words = set()
    for p, text in texts.items():
        words.update(re.findall(r"\w+", strip_comments(text) if p.suffix in CXX else text))
    stale = []

    def check_name(where, name):
        if name.split("::")[0] in EXTERNAL:
            return
        last = name.split("::")[-1]
        if last not in words and not NOT_CODE.match(last):
            stale.append(f"{where[1]}: `{name}` is named nowhere in the code")

    for doc in docs:
        text = doc.read_text()
        where = (doc.name, doc.relative_to(ROOT))
        for quoted in re.findall(r"`([^`\n]+)`", text):
            for name in NAME_RE.findall(quoted) + CALL_RE.findall(quoted):
                if (doc.name, name) not in ALLOWED:
                    check_name(where, name)
        for path in sorted(set(PATH_RE.findall(text))):
            if (doc.name, path) not in ALLOWED and not exists(path, ROOT, doc.parent):
                stale.append(f"{doc.relative_to(ROOT)}: {path} does not exist")
    for p, text in texts.items():
        if p.suffix not in CXX:
            continue
        for number, line in enumerate(text.splitlines(), 1):
            comment = line.partition("//")[2]
            for name in NAME_RE.findall(comment) + SNAKE_CALL_RE.findall(comment):
                check_name((p.name, f"{p.relative_to(ROOT)}:{number}"), name)
    for line in stale:
        print(line)
    if stale:
        print(f"check-doc-references: {len(stale)} stale reference(s)", file=sys.stderr)
        return 1
    print(f"check-doc-references: {len(docs)} documents and {len(files)} sources, every "
          "reference resolves")
    return 0


if __name__ == "__main__":
    sys.exit(main())
