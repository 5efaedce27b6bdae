# Sourced by scripts/test.sh, sanitize.sh and fuzz.sh: compile through ccache (Debian package
# ccache, which scripts/install-deps.sh installs) when it is there. CMake picks the launcher up from
# the environment when it configures a new build folder. Paths are hashed relative to the
# repository, so every clone on a machine (a developer's tree, each CI clone) shares one cache;
# a cold cache builds as before. ANTCD_NO_CCACHE=1 turns it off.
if [ "${ANTCD_NO_CCACHE:-0}" != 1 ] && command -v ccache >/dev/null 2>&1; then
  export CMAKE_CXX_COMPILER_LAUNCHER="${CMAKE_CXX_COMPILER_LAUNCHER:-ccache}"
  export CMAKE_C_COMPILER_LAUNCHER="${CMAKE_C_COMPILER_LAUNCHER:-ccache}"
  CCACHE_BASEDIR="$(pwd)"
  export CCACHE_BASEDIR
  # Debug builds (the sanitizers) would otherwise hash the build folder's absolute path.
  export CCACHE_NOHASHDIR=1
fi
