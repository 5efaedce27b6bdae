"""Prints where the antcd package goes under an install prefix, relative to that prefix.

Used by python/CMakeLists.txt at configure time. Asks this interpreter's sysconfig, so the answer
follows the distribution's layout: Debian installs local packages under
/usr/local/lib/python3.X/dist-packages (its default 'posix_local' scheme) and its own under
/usr/lib/python3/dist-packages ('deb_system'); other systems use lib/python3.X/site-packages.
"""
import os
import sys
import sysconfig


def main() -> None:
    prefix = os.path.realpath(sys.argv[1])
    scheme = sysconfig.get_default_scheme()
    if scheme == "posix_local":
        if prefix == os.path.realpath(sys.base_prefix) and "deb_system" in sysconfig.get_scheme_names():
            root, path = sys.base_prefix, sysconfig.get_path("platlib", "deb_system")
        else:
            # posix_local is prefix/local/...: relative to base_prefix/local it is the part to keep.
            root, path = os.path.join(sys.base_prefix, "local"), sysconfig.get_path("platlib", scheme)
    else:
        root = prefix
        path = sysconfig.get_path("platlib", scheme, vars={"base": prefix, "platbase": prefix})
    print(os.path.relpath(path, root))


if __name__ == "__main__":
    main()
