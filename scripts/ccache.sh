# Sourced by scripts/test.sh and scripts/test-extended.sh: ccache (Debian's, installed by
# scripts/install-deps.sh) with a cache of the checkout's own, .ccache/, empty in a fresh clone, so
# that CI's times are cold-cache times. What it saves: a second run of the same checkout, and in
# the mutation check (scripts/mutation/run.py, the same cache) each file put back after its
# mutation (its build compiles at -O1, so it shares nothing with the release build).
ccache_args=()
if command -v ccache >/dev/null; then
  export CCACHE_DIR="$PWD/.ccache" CCACHE_BASEDIR="$PWD" CCACHE_DEPEND=1 CCACHE_NOHASHDIR=1
  unset CCACHE_DISABLE
  ccache_args=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
