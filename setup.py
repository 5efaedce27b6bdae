"""The PEP 517 build of the `antcd` Python package (pyproject.toml): setuptools drives CMake.

`pip install --no-build-isolation .` and `python3 -m build --wheel --no-isolation` build the CMake
target antcd_python, then put into the wheel the package CMake assembles (build/python/antcd: the
extension _antcd, the pure-Python files, the type stubs) together with the shared libantcd, and
make the extension find libantcd beside it (RUNPATH $ORIGIN), wherever the wheel is installed.

Environment:
  ANTCD_CMAKE_BUILD_DIR   an existing, configured CMake build tree of this source tree to reuse:
                          only antcd_python is brought up to date there (nothing recompiles when it
                          is current). Unset: the tree build/wheel is configured (Release, no
                          tests, no apps; ccache when installed) and built.
  CMAKE_BUILD_PARALLEL_LEVEL  build jobs (default 2).
"""
import os
import re
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = Path(__file__).resolve().parent
PACKAGE_FILES = ("__init__.py", "cluster.py", "collision.py", "py.typed", "__init__.pyi")


def project_version():
    match = re.search(r"project\(antcd VERSION ([0-9.]+)", (SOURCE / "CMakeLists.txt").read_text())
    if not match:
        raise RuntimeError("antcd: no 'project(antcd VERSION x.y.z' in CMakeLists.txt")
    return match.group(1)


def run(*command):
    print("antcd:", " ".join(str(c) for c in command), flush=True)
    subprocess.run([str(c) for c in command], check=True)


class CMakeBuild(build_ext):
    """Builds the one 'extension' (antcd._antcd) by CMake and copies the package into build_lib."""

    def run(self):
        given = os.environ.get("ANTCD_CMAKE_BUILD_DIR")
        if given:
            tree = Path(given).resolve()
            if not (tree / "CMakeCache.txt").is_file():
                raise RuntimeError(f"ANTCD_CMAKE_BUILD_DIR={given}: not a configured CMake build tree "
                                   "(no CMakeCache.txt)")
        else:
            tree = SOURCE / "build" / "wheel"
            if not (tree / "CMakeCache.txt").is_file():
                configure = ["cmake", "-S", SOURCE, "-B", tree, "-DCMAKE_BUILD_TYPE=Release",
                             "-DANTCD_BUILD_TESTS=OFF", "-DANTCD_BUILD_APPS=OFF",
                             "-DANTCD_BUILD_LEARNED=OFF", "-DANTCD_BUILD_BENCHMARKS=OFF",
                             "-DANTCD_BUILD_PYTHON=ON", f"-DPython3_EXECUTABLE={sys.executable}"]
                if shutil.which("ccache"):
                    configure.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
                run(*configure)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", "2")
        run("cmake", "--build", tree, "--target", "antcd_python", "-j", jobs)

        built = tree / "python" / "antcd"
        suffix = sysconfig.get_config_var("EXT_SUFFIX")
        extension = built / f"_antcd{suffix}"
        if not extension.is_file():
            found = sorted(p.name for p in built.glob("_antcd*"))
            raise RuntimeError(f"antcd: {extension} missing (the CMake tree {tree} built {found}: "
                               f"configured for another Python than {sys.executable}?)")
        target = Path(self.build_lib) / "antcd"
        target.mkdir(parents=True, exist_ok=True)
        for name in PACKAGE_FILES:
            shutil.copyfile(built / name, target / name)
        shutil.copyfile(extension, target / extension.name)

        # The shared antcd libraries the extension links (none with BUILD_SHARED_LIBS=OFF), under
        # their SONAMEs, the names the loader looks for; each file that has a (build-tree) RUNPATH
        # gets $ORIGIN instead, so that they find one another beside the extension.
        needed = subprocess.run(["ldd", str(extension)], check=True, capture_output=True,
                                text=True).stdout
        shipped = [target / extension.name]
        for line in needed.splitlines():
            match = re.match(r"\s*(libantcd[^ ]*\.so[^ ]*) => (\S+)", line)
            if match:
                shutil.copyfile(match.group(2), target / match.group(1))
                shipped.append(target / match.group(1))
        script = "".join(
            f'unset(runpath)\nunset(rpath)\nfile(READ_ELF "{path}" RUNPATH runpath RPATH rpath)\n'
            f'if(runpath OR rpath)\n  file(RPATH_SET FILE "{path}" NEW_RPATH "$ORIGIN")\nendif()\n'
            for path in shipped)
        set_rpath = tree / "antcd_set_rpath.cmake"
        set_rpath.write_text(script)
        run("cmake", "-P", set_rpath)

(SOURCE / "build").mkdir(exist_ok=True)
setup(
    version=project_version(),
    ext_modules=[Extension("antcd._antcd", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' own scratch folders inside the (git-ignored) build folder, not in the source root.
    options={"build": {"build_base": "build/setuptools"}, "egg_info": {"egg_base": "build"}},
)
