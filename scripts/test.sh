#!/usr/bin/env bash
# Every test from a fresh Debian 12 machine: install what is missing, build everything
# (library, CLI, Python package, validation engines, benchmarks, tests) in Release and run the
# whole suite (ctest: unit, identities, golden values, engines, CLI, Python, docs, browser, lint).
# The slower checks of the same code (the mutation check, the suite again under AddressSanitizer
# and UndefinedBehaviorSanitizer, libFuzzer runs of the readers) are scripts/test-extended.sh,
# which .ci/run adds. Every option is set explicitly: a cache left in build/ by
# scripts/reproduce.sh (tests off) must not turn the tests off here, and ctest fails when it
# finds no test.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
jobs="$(nproc)"
# Ninja for a new build tree (an existing one keeps its generator): it compiles a target's files
# as soon as their inputs exist, where make waits for every library below it to be linked, so
# that both cores stay busy through the layered library.
command -v ninja >/dev/null && export CMAKE_GENERATOR=Ninja
source scripts/ccache.sh

cmake -S . -B build "${ccache_args[@]}" -DCMAKE_BUILD_TYPE=Release -DNOCDYN_BUILD_TESTS=ON -DNOCDYN_BUILD_VALIDATION=ON \
  -DNOCDYN_BUILD_BENCHMARKS=ON -DNOCDYN_SANITIZE=OFF -DNOCDYN_FUZZ=OFF -DNOCDYN_BUILD_PYTHON=ON -DNOCDYN_CPU_DISPATCH=ON
start=$SECONDS
cmake --build build -j"$jobs"
echo "test.sh: release build done in $((SECONDS - start)) s"
# playwright-core (the driver only; the browser is Debian's chromium) for ctest -L browser
npm ci --prefix tests/browser --no-audit --no-fund
start=$SECONDS
ctest --test-dir build --output-on-failure --no-tests=error -j"$jobs" | tee build/ctest-summary.log
echo "test.sh: $(grep -Eo 'tests passed, 0 tests failed out of [0-9]+' build/ctest-summary.log | grep -Eo '[0-9]+$') tests passed (release build), in $((SECONDS - start)) s"
