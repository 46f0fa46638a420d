# Sourced by the build scripts: the compiler cache (Debian's ccache) every
# tree goes through, GCC and clang alike (docs/ci.md "Compiler cache").
# It lives outside the clone (~/.cache/ccache, or $CCACHE_DIR), capped at
# 5 GB, and is keyed so that a fresh clone in another folder hits it: paths
# under the clone are rewritten relative to it (CCACHE_BASEDIR) and the
# working folder is left out of the key (hash_dir = false; the objects keep
# the first build's folder in their line tables only). Precompiled headers
# need the pch_defines and time_macros sloppiness. Without ccache installed,
# GLOBE_CCACHE_ARGS is empty and builds run as before.
GLOBE_CCACHE_ARGS=()
if command -v ccache >/dev/null; then
  export CCACHE_BASEDIR
  CCACHE_BASEDIR=$(pwd -P)
  export CCACHE_NOHASHDIR=true
  export CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime
  export CCACHE_MAXSIZE=${CCACHE_MAXSIZE:-5G}
  GLOBE_CCACHE_ARGS=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
