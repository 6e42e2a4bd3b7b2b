#!/usr/bin/env bash
# Every test from a fresh Debian 12 machine: install what is missing, build everything
# (library, CLI, validation engines, benchmarks, tests), run the whole suite, then build
# and run it again under AddressSanitizer and UndefinedBehaviorSanitizer, then a short
# libFuzzer run of each file reader (clang). Between the release and the sanitizer builds the
# mutation check makes sure that the tests catch deliberate errors in the core formulas.
# Every option is set explicitly: a cache left in build/ by scripts/reproduce.sh (tests off)
# must not turn the tests off here, and ctest fails when it finds no test.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
jobs="$(nproc)"

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DNOCDYN_BUILD_TESTS=ON -DNOCDYN_BUILD_VALIDATION=ON \
  -DNOCDYN_BUILD_BENCHMARKS=ON -DNOCDYN_SANITIZE=OFF -DNOCDYN_FUZZ=OFF -DNOCDYN_BUILD_PYTHON=ON
cmake --build build -j"$jobs"
# playwright-core (the driver only; the browser is Debian's chromium) for ctest -L browser
npm ci --prefix tests/browser --no-audit --no-fund
ctest --test-dir build --output-on-failure --no-tests=error -j"$jobs"

# The mutation check (scripts/mutation/): deliberate errors in the core formulas, each of which
# some test must catch; its own -O1 build without Simbody and MuJoCo, one file rebuilt per error.
python3 scripts/mutation/run.py --jobs "$jobs"

# The Python package is not built here: an interpreter cannot load an ASan-instrumented module
# without LD_PRELOAD of the ASan runtime (its tests run in the release build above).
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DNOCDYN_BUILD_TESTS=ON -DNOCDYN_BUILD_VALIDATION=ON \
  -DNOCDYN_BUILD_BENCHMARKS=OFF -DNOCDYN_SANITIZE=ON -DNOCDYN_FUZZ=OFF -DNOCDYN_BUILD_PYTHON=OFF
cmake --build build-sanitize -j"$jobs"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-sanitize --output-on-failure --no-tests=error -j"$jobs"

# The file readers under libFuzzer (clang, ASan, UBSan): only the library's readers and the
# harnesses are built; each harness runs briefly over its committed seed corpus (fuzz/).
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DNOCDYN_BUILD_TESTS=OFF -DNOCDYN_BUILD_VALIDATION=OFF -DNOCDYN_BUILD_BENCHMARKS=OFF \
  -DNOCDYN_SANITIZE=OFF -DNOCDYN_FUZZ=ON -DNOCDYN_BUILD_PYTHON=OFF
cmake --build build-fuzz -j"$jobs" --target nocdyn_fuzzers
ctest --test-dir build-fuzz --output-on-failure --no-tests=error -L fuzz -j"$jobs"
echo "test.sh: all tests passed (release, mutation, sanitizer and fuzz builds)"
