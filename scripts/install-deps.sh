#!/usr/bin/env bash
# Installs every Debian 12 package nocdyn needs to build, test, validate, benchmark and plot.
# Run as root (or with sudo). Safe to run again: apt-get skips what is already installed.
set -euo pipefail
packages=(
  g++ make cmake pkg-config            # toolchain (CMake >= 3.25)
  ninja-build                          # the builds of scripts/test*.sh (CMAKE_GENERATOR=Ninja)
  ccache                               # the mutation check: a file put back is not compiled again
  lld                                  # LLVM's linker: the tests' links in under half of GNU ld's time
  libeigen3-dev                        # linear algebra
  libyaml-cpp-dev                      # robot and trajectory files
  libmuparser-dev                      # arithmetic expressions in parametric robot files
  libcli11-dev                         # command line
  nlohmann-json3-dev                   # `nocdyn pose --json`
  libboost-dev                         # Boost.Odeint (forward dynamics)
  libsimbody-dev                       # reference multibody engine (validation)
  libmujoco-dev libqhull-dev           # second multibody engine (validation)
  libgtest-dev libgmock-dev            # tests
  libbenchmark-dev                     # benchmarks
  chromium nodejs                      # browser tests of the animation page (ctest -L browser; npm ci)
  libjs-three                          # three.js, inlined into the 3-D animation page of a spatial robot
  gnuplot-nox                          # figures (PNG via pngcairo, SVG)
  clang libclang-rt-dev                # libFuzzer harnesses of the file readers (fuzz/)
  clang-format clang-tidy              # style and static checks (ctest -L lint)
  python3-dev python3-pybind11 python3-numpy   # the Python package (python/), /usr/bin/python3
  python3-pytest python3-matplotlib            # its tests (ctest -L python) and examples/quickstart.py
  python3-hypothesis                           # the property-based tests of the Python surface
  python3-scipy python3-optuna                 # design sweeps: Sobol/LHS (scipy.stats.qmc), NSGA-II/TPE
  python3-dask python3-distributed             # design sweeps on a Dask cluster (nocdyn.designs)
  python3-tqdm python3-pandas                  # progress bars and to_pandas() of the Python package
  python3-venv python3-pip                     # the test of `pip install .` (ctest -L pip)
  python3-sphinx python3-myst-parser           # the user guide, docs/ (ctest -L docs)
  locales                                      # a decimal-comma locale built by the tests (numbers as text)
  calculix-ccx                                 # finite-element check of the stiffness and modes (ctest -L validation)
  doxygen python3-breathe                      # its C++ API page (docs/cpp-api.md, docs/Doxyfile)
  phcpack                                      # every assembly mode of a hexapod (polynomial homotopy, `phc`)
)
# npm fetches playwright-core for the browser tests: Debian's package, unless the installed
# Node.js already brings its own (NodeSource's nodejs provides and conflicts with Debian's npm)
command -v npm >/dev/null 2>&1 || packages+=(npm)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "install-deps: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
# clang-tidy 22 (bookworm-security) skips the AST matching in system headers, Eigen's above all: the
# lint's checks run in about a fifth of clang-tidy 14's time (tests/CMakeLists.txt takes it first).
# Where the archive does not carry it, the lint runs the same checks with clang-tidy 14.
if ! command -v clang-tidy-22 >/dev/null 2>&1; then
  export DEBIAN_FRONTEND=noninteractive
  candidate="$(apt-cache policy clang-tidy-22 2>/dev/null | awk '/Candidate:/ {print $2}')"
  if [[ -z "$candidate" ]]; then
    apt-get update -qq
    candidate="$(apt-cache policy clang-tidy-22 2>/dev/null | awk '/Candidate:/ {print $2}')"
  fi
  if [[ -n "$candidate" && "$candidate" != "(none)" ]]; then
    apt-get install -y -qq --no-install-recommends clang-tidy-22
  else
    echo "install-deps: clang-tidy-22 is not in the archive; the lint uses clang-tidy (14), slower" >&2
  fi
fi
