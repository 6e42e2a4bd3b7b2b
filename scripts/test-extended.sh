#!/usr/bin/env bash
# The slower checks, after scripts/test.sh (which built build/ and ran every test there):
# - the mutation check (scripts/mutation/): deliberate errors in the core formulas, each of
#   which some test must catch; its own build without Simbody and MuJoCo (the release build's
#   flags, so that ccache gives it what scripts/test.sh compiled, but the cloned kernels' files
#   once, for AVX2: -DNOCDYN_CPU_DISPATCH=OFF), one file rebuilt per error;
# - the whole suite again under AddressSanitizer and UndefinedBehaviorSanitizer;
# - a short libFuzzer run (clang, ASan, UBSan) of each file reader over its committed corpus.
# .ci/run runs both scripts. Every option is set explicitly, and ctest fails when it finds no test.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
jobs="$(nproc)"
# Each stage's share of the CI budget (.ci/run: 28 of its 40 minutes for this script): a stage
# that takes longer prints a warning, so that the change that slows it is seen at once.
stage() {  # stage <name> <seconds taken> <seconds allowed>
  if (($2 > $3)); then
    echo "test-extended.sh: WARNING: $1 took $2 s, above its share of the CI budget ($3 s)" >&2
  else
    echo "test-extended.sh: $1 took $2 s (its share: $3 s)"
  fi
}
# Ninja for a new build tree (scripts/test.sh says why).
command -v ninja >/dev/null && export CMAKE_GENERATOR=Ninja

# The mutation check runs beside the sanitizer build: after its own build it compiles one file
# and runs a few test binaries at a time, on one core, and the sanitizer build takes the other.
# Its output is printed when it ends; it is stopped (its whole process group) if this script
# stops first. It ends before the fuzzers start, whose runs are limited in time, not in work.
mutation_log="$(mktemp)"
setsid -w python3 scripts/mutation/run.py --jobs "$jobs" >"$mutation_log" 2>&1 &
mutation_pid=$!
trap 'kill -- -"$mutation_pid" 2>/dev/null || true; rm -f "$mutation_log"' EXIT
start=$SECONDS

# The Python package is not built here: an interpreter cannot load an ASan-instrumented module
# without LD_PRELOAD of the ASan runtime (its tests run in the release build). GCC, as the
# release build: clang 14 compiles the same instrumented files in about 60 % of GCC's time
# (src/analysis/stiffness.cpp: 72 s against 121 s) but its -O1 code ran the suite 2.5 times
# slower (DirectKinematics.EverySolutionIsVerifiedAndNoneIsMissed: 180 s against 12 s).
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DNOCDYN_BUILD_TESTS=ON -DNOCDYN_BUILD_VALIDATION=ON \
  -DNOCDYN_BUILD_BENCHMARKS=OFF -DNOCDYN_SANITIZE=ON -DNOCDYN_FUZZ=OFF -DNOCDYN_BUILD_PYTHON=OFF -DNOCDYN_CPU_DISPATCH=ON
cmake --build build-sanitize -j"$jobs"
echo "test-extended.sh: sanitizer build done at $((SECONDS - start)) s"
stage "the sanitizer build" $((SECONDS - start)) 900
tests_start=$SECONDS
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-sanitize --output-on-failure --no-tests=error -j"$jobs" | tee build-sanitize/ctest-summary.log
sanitizer_tests=$(grep -Eo 'tests passed, 0 tests failed out of [0-9]+' build-sanitize/ctest-summary.log | grep -Eo '[0-9]+$')
echo "test-extended.sh: sanitizer tests done at $((SECONDS - start)) s ($sanitizer_tests tests passed)"
stage "the sanitizer tests" $((SECONDS - tests_start)) 540

mutation_status=0
wait "$mutation_pid" || mutation_status=$?
cat "$mutation_log"
# its own time, from its start to its end ("mutation: N s in all"), which may come before the
# sanitizer tests end; the time waited here when it printed none (it failed before its end)
mutation_seconds=$(grep -Eo '^mutation: [0-9]+ s in all' "$mutation_log" | grep -Eo '[0-9]+' || echo $((SECONDS - start)))
echo "test-extended.sh: mutation check done at $((SECONDS - start)) s (its own run: $mutation_seconds s)"
stage "the mutation check (beside the sanitizer build and tests)" "$mutation_seconds" 1440
fuzz_start=$SECONDS
if ((mutation_status != 0)); then
  echo "test-extended.sh: the mutation check failed (exit code $mutation_status)" >&2
  exit 1
fi

# The file readers under libFuzzer (clang, ASan, UBSan): only the library's readers and the
# harnesses are built; each harness runs briefly over its committed seed corpus (fuzz/).
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DNOCDYN_BUILD_TESTS=OFF -DNOCDYN_BUILD_VALIDATION=OFF -DNOCDYN_BUILD_BENCHMARKS=OFF \
  -DNOCDYN_SANITIZE=OFF -DNOCDYN_FUZZ=ON -DNOCDYN_BUILD_PYTHON=OFF -DNOCDYN_CPU_DISPATCH=ON
cmake --build build-fuzz -j"$jobs" --target nocdyn_fuzzers
ctest --test-dir build-fuzz --output-on-failure --no-tests=error -L fuzz -j"$jobs" | tee build-fuzz/ctest-summary.log
harnesses=$(grep -Eo 'tests passed, 0 tests failed out of [0-9]+' build-fuzz/ctest-summary.log | grep -Eo '[0-9]+$')
echo "test-extended.sh: fuzz done at $((SECONDS - start)) s ($harnesses harnesses)"
stage "the fuzz build and runs" $((SECONDS - fuzz_start)) 240
echo "test-extended.sh: mutation check ($(grep -Eo '^[0-9]+/[0-9]+ mutations caught' "$mutation_log")), lean build, $sanitizer_tests sanitizer tests and $harnesses fuzz harnesses passed"
