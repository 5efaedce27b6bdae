"""The pip path end to end (ctest python_wheel): build the wheel with `python3 -m build --wheel
--no-isolation` reusing the CMake build tree (ANTCD_CMAKE_BUILD_DIR: nothing is compiled again),
install it into a fresh `venv --system-site-packages`, check that the installed extension loads the
libantcd shipped beside it (relative RUNPATH), then run the pytest suite against the installed
package from outside the source tree.

Usage: python3 wheel_check.py --source DIR --cmake-build DIR --work DIR
"""
import argparse
import os
import shutil
import subprocess
import sys
from pathlib import Path

PROBE = """
import antcd, os, sys
package = os.path.dirname(os.path.realpath(antcd.__file__))
assert package.startswith(os.path.realpath(sys.prefix)), f"antcd imported from {package}, not the venv"
libs = {line.split()[-1] for line in open("/proc/self/maps") if "/libantcd" in line}
assert libs and all(os.path.dirname(os.path.realpath(p)) == package for p in libs), libs
print("installed antcd", antcd.__version__, "at", package, "with", *sorted(libs))
"""


def run(command, **kwargs):
    print("wheel_check:", " ".join(str(c) for c in command), flush=True)
    subprocess.run([str(c) for c in command], check=True, **kwargs)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--source", type=Path, required=True)
    parser.add_argument("--cmake-build", type=Path, required=True)
    parser.add_argument("--work", type=Path, required=True)
    args = parser.parse_args()

    shutil.rmtree(args.work, ignore_errors=True)
    args.work.mkdir(parents=True)
    env = dict(os.environ, ANTCD_CMAKE_BUILD_DIR=str(args.cmake_build.resolve()))
    env.pop("PYTHONPATH", None)
    dist = args.work / "dist"
    run([sys.executable, "-m", "build", "--wheel", "--no-isolation", "-o", dist, args.source],
        env=env, cwd=args.source)
    wheels = sorted(dist.glob("antcd-*.whl"))
    assert len(wheels) == 1, f"expected one wheel in {dist}, got {wheels}"

    venv = args.work / "venv"
    run([sys.executable, "-m", "venv", "--system-site-packages", venv])
    python = venv / "bin" / "python"
    run([python, "-m", "pip", "install", "--no-deps", "--no-index", "--no-cache-dir", wheels[0]],
        env=env)
    run([python, "-c", PROBE], env=env, cwd=args.work)
    run([python, "-m", "pytest", "-q", "-p", "no:cacheprovider", args.source / "python" / "tests"],
        env=dict(env, PYTHONDONTWRITEBYTECODE="1"), cwd=args.work)


if __name__ == "__main__":
    main()
