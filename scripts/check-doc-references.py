#!/usr/bin/python3
"""Checks that README.md and docs/*.md name only things that exist (ctest: docs_references).

Docs drift when code is renamed or removed: a design note naming a function that is gone, a path
that moved. This finds two kinds of reference and fails (exit 1, one line per stale reference)
when one no longer resolves:
  - qualified C++ names in backticks (`World::nearest_pair`, `detail::AabbTree`): the last
    component must occur as a word somewhere in the sources (src, include, apps, python, ...);
  - repository paths (`src/world/nearest.cpp`, `experiments/paper/*.cpp`,
    `tests/ccd/data/degenerate_{vf,ee}.csv`): must exist (globs and {a,b} expanded).
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
       "viewer", "fuzz", "learned", "shared", "experiments", "cmake")
SOURCES = ("src", "include", "apps", "python", "bench", "tests", "scripts", "viewer/src", "learned",
           "shared", "experiments", "examples", "fuzz", "cmake")
SUFFIXES = {".cpp", ".hpp", ".h", ".py", ".pyi", ".sh", ".js", ".mjs", ".ts", ".cmake", ".txt", ".in"}

ALLOWED = {
    # trimesh's own test file, which antcd.CollisionManager is checked against
    ("README.md", "tests/test_collision.py"),
    # design.md's table of what the shared libraries replaced (files that are gone on purpose)
    ("design.md", "experiments/paper_bench.cpp"),
    ("design.md", "experiments/peers_bench.cpp"),
    ("design.md", "experiments/production_line.*"),
    ("design.md", "experiments/run_result.*"),
}

PATH_RE = re.compile(r"(?<![\w/.\-])((?:%s)/[\w./*\-]*(?:\{[\w,]+\}[\w./*\-]*)?[\w*])" % "|".join(TOP))
NAME_RE = re.compile(r"\b((?:[A-Za-z_]\w*::)+[A-Za-z_]\w*)")


def expand_braces(path):
    m = re.search(r"\{([^}]*)\}", path)
    if not m:
        return [path]
    return list(itertools.chain.from_iterable(
        expand_braces(path[:m.start()] + alt + path[m.end():]) for alt in m.group(1).split(",")))


def exists(path):
    return all(any(ROOT.glob(p)) if "*" in p else (ROOT / p).exists() for p in expand_braces(path))


def main():
    docs = [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))
    code = "\n".join(p.read_text(errors="ignore") for d in SOURCES if (ROOT / d).is_dir()
                     for p in (ROOT / d).rglob("*") if p.is_file() and p.suffix in SUFFIXES)
    words = set(re.findall(r"\w+", code))
    stale = []
    for doc in docs:
        text = doc.read_text()
        for quoted in re.findall(r"`([^`\n]+)`", text):
            for name in NAME_RE.findall(quoted):
                if name.split("::")[-1] not in words and (doc.name, name) not in ALLOWED:
                    stale.append(f"{doc.relative_to(ROOT)}: `{name}` is named nowhere in the sources")
        for path in sorted(set(PATH_RE.findall(text))):
            if (doc.name, path) not in ALLOWED and not exists(path):
                stale.append(f"{doc.relative_to(ROOT)}: {path} does not exist")
    for line in stale:
        print(line)
    if stale:
        print(f"check-doc-references: {len(stale)} stale reference(s)", file=sys.stderr)
        return 1
    print(f"check-doc-references: {len(docs)} documents, every reference resolves")
    return 0


if __name__ == "__main__":
    sys.exit(main())
