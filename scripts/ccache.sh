# Sourced by scripts/test.sh and scripts/test-extended.sh: ccache (Debian's, installed by
# scripts/install-deps.sh) with a cache of the checkout's own, .ccache/, empty in a fresh clone, so
# that CI's times are cold-cache times. What it saves is within one run: the lean build of the
# mutation check (scripts/mutation/run.py) compiles the release build's files with its flags, in a
# copy laid out as the checkout (build-mutation/source, built in its build/), and base_dir (the
# checkout) makes both sets of paths the same, so those files are cache hits.
ccache_args=()
if command -v ccache >/dev/null; then
  export CCACHE_DIR="$PWD/.ccache" CCACHE_BASEDIR="$PWD" CCACHE_DEPEND=1 CCACHE_NOHASHDIR=1
  unset CCACHE_DISABLE
  ccache_args=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
