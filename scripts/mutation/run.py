#!/usr/bin/env python3
"""Mutation check: does the test suite catch deliberate errors in the core formulas?

Each mutation of mutations.txt (a textual search and replace in one source file) is applied to
a copy of the source tree, which is built once without Simbody and MuJoCo (Release, with the flags of
scripts/test.sh's build, so that with ccache and the checkout's cache .ccache/ every file that the
release build compiled is a cache hit: the copy is laid out as the checkout, its build folder
inside it, and ccache's base_dir makes both paths the same; the files it mutates are compiled at
-O1 instead, since each is compiled again for every mutation), and rebuilt for each mutation (only
what the changed file touches). The core test binaries then
run in turn, each stopping at its first failing test: the first failing test caught the mutation,
and the binaries after it are neither relinked nor run. The binary named by the mutation's
"test:" line (or the one that caught the previous mutation of its file) goes first, then the
others in the order of TESTS. The check passes only when every mutation is caught, and when every searched text is
found exactly once (a mutation whose code has moved must be updated, not skipped). The last
line printed is "N/N mutations caught".

Usage: scripts/mutation/run.py [--build-dir DIR] [--golden-dir DIR] [--jobs N] [--only SUBSTRING] [--all]
(--golden-dir: the golden values' folder, by default tests/data/golden, a copy of the independent references.)
(--all also runs the extended mutations, of shared headers that rebuild many files: several
minutes more; their searched texts are checked on every run.)
"""

import argparse
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
LIST = Path(__file__).resolve().parent / "mutations.txt"

# The core test binaries of the general model, each run until its first failing test
# (--gtest_fail_fast): a few seconds for all of them unmutated. None needs Simbody, MuJoCo or
# the CLI. (The tests of the hand-derived 3-PRR model, src/prr3, see none of the mutated files.)
TESTS = [
    "lagrange_test",
    "golden_test",
    "model_test",
    "forward_dynamics_robots_test",
    "identification_test",
    "reactions_test",
    "batch_test",
    "derivatives_test",
    "excitation_gradient_test",
    "twodof_test",
    "spatial_dynamics_test",
]
# A test binary that runs longer than this under a mutation (a loop that no longer converges)
# counts as failing.
TIMEOUT = 120

# Folders of the repository the build needs (the copy leaves out build trees and the like).
IGNORED = shutil.ignore_patterns("node_modules", "__pycache__")
COPIED = ["CMakeLists.txt", "cmake", "include", "src", "app", "apps", "render", "tests", "bench/baseline", "robots", "trajectories", "data"]


class Mutation:
    def __init__(self, description, path):
        self.description = description
        self.path = path
        self.pairs = []  # (search, replace)
        self.extended = False  # run only with --all
        self.first = None  # the test binary run (and relinked) first: "test: <binary> [<gtest filter>]"
        self.filter = None  # the tests of that binary run before the rest of it


def parse(text):
    mutations = []
    for number, line in enumerate(text.splitlines(), 1):
        if line.startswith("## "):
            mutations.append(Mutation(line[3:].strip(), None))
        elif line.startswith("file:"):
            mutations[-1].path = line[5:].strip()
        elif line.strip() == "run: extended":
            mutations[-1].extended = True
        elif line.startswith("test:"):
            words = line[5:].split()
            if not words or len(words) > 2 or words[0] not in TESTS:
                sys.exit(f"{LIST}:{number}: '{line}' does not name one of the core test binaries (and a filter)")
            mutations[-1].first = words[0]
            mutations[-1].filter = words[1] if len(words) == 2 else None
        elif line.startswith("- "):
            mutations[-1].pairs.append([line[2:].strip(), None])
        elif line.startswith("+ "):
            if not mutations or not mutations[-1].pairs or mutations[-1].pairs[-1][1] is not None:
                sys.exit(f"{LIST}:{number}: '+' without its '-'")
            mutations[-1].pairs[-1][1] = line[2:].strip()
        elif line.strip() and not line.startswith("#"):
            sys.exit(f"{LIST}:{number}: unexpected line: {line}")
    for m in mutations:
        if not m.path or not m.pairs or any(r is None for _, r in m.pairs):
            sys.exit(f"{LIST}: incomplete mutation '{m.description}'")
    return mutations


def run(command, cwd=None, log=None, timeout=None):
    """Runs command; returns (exit code, output). A timeout is exit code None."""
    try:
        done = subprocess.run(command, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                              timeout=timeout)
    except subprocess.TimeoutExpired as e:
        out = e.stdout if isinstance(e.stdout, str) else (e.stdout or b"").decode(errors="replace")
        return None, out
    if log is not None:
        log.write(done.stdout)
        log.flush()
    return done.returncode, done.stdout


def copy_tree(destination):
    if destination.exists():
        # keep timestamps of unchanged files so that a rebuild stays incremental
        for name in COPIED:
            source = ROOT / name
            if source.is_dir():
                shutil.copytree(source, destination / name, dirs_exist_ok=True, copy_function=copy_if_changed,
                                ignore=IGNORED)
            else:
                copy_if_changed(source, destination / name)
    else:
        destination.mkdir(parents=True)
        for name in COPIED:
            source = ROOT / name
            if source.is_dir():
                shutil.copytree(source, destination / name, ignore=IGNORED)
            else:
                shutil.copy2(source, destination / name)


def copy_if_changed(source, destination):
    source, destination = Path(source), Path(destination)
    if destination.exists() and destination.read_bytes() == source.read_bytes():
        return destination
    # a new modification time (not copy2's): a source older than the build's last compile of it
    # would otherwise leave a stale object behind
    shutil.copy(source, destination)
    return destination


def lean_cli_check(cli, work, log, golden_dir):
    """The lean build's command line on the paper robot: a pose, an inverse-dynamics table whose forces
    match the golden file's at t = 0, and `validate` refused with its reason (no engines). Returns the
    failures, each one line."""
    failures = []
    code, out = run([str(cli), "pose", "0", "0", "0"], log=log, timeout=TIMEOUT)
    if code != 0 or "u" not in out:
        failures.append(f"`nocdyn pose 0 0 0` exited with {code}")
    table = work / "lean-paper1.csv"
    code, out = run([str(cli), "inverse-dynamics", "--trajectory", "paper1", "--duration", "0.01", "--rate", "100",
                     "-o", str(table)], log=log, timeout=TIMEOUT)
    if code != 0 or not table.exists():
        failures.append(f"`nocdyn inverse-dynamics --trajectory paper1` exited with {code}")
    else:
        rows = [line.split(",") for line in table.read_text().splitlines() if line and not line.startswith("#")]
        header, first = rows[0], [float(v) for v in rows[1]]
        golden_rows = [line.split(",") for line in (golden_dir / "paper_trajectory1.csv").read_text().splitlines()
                       if line and not line.startswith("#")]
        golden = dict(zip(golden_rows[0], (float(v) for v in golden_rows[1])))
        for column in ("tau1", "tau2", "tau3"):
            ours = first[header.index(column)]
            if abs(ours - golden[column]) > 1e-9 * max(1.0, abs(golden[column])):
                failures.append(f"{column} at t = 0 is {ours!r}, the golden value {golden[column]!r}")
    code, out = run([str(cli), "validate"], log=log, timeout=TIMEOUT)
    if code == 0:
        failures.append("`nocdyn validate` succeeded without the engines")
    return failures


def mutated_sources(mutations):
    """The library's source files (src/*/*.cpp) that the mutations recompile: each mutated .cpp,
    and those that include a mutated header, directly or through another of src/'s headers."""
    paths = {m.path for m in mutations}
    headers = {Path(p).name for p in paths if p.endswith(".hpp")}
    sources = {p for p in paths if p.endswith(".cpp")}
    files = {f: f.read_text(errors="replace") for f in sorted((ROOT / "src").glob("*/*.[ch]pp"))}

    def includes(text, names):
        return any(re.search(rf'^#include "(?:[^"]*/)?{re.escape(n)}"', text, re.MULTILINE) for n in names)

    for _ in range(len(files)):  # the headers that include a mutated one, to a fixed point
        more = {f.name for f, text in files.items() if f.suffix == ".hpp" and includes(text, headers)} - headers
        if not more:
            break
        headers |= more
    sources |= {str(f.relative_to(ROOT)) for f, text in files.items() if f.suffix == ".cpp" and includes(text, headers)}
    return sorted(sources)


def failing_test(output):
    match = re.search(r"^\[  FAILED  \] ([^\s,]+)", output, re.MULTILINE)
    return match.group(1) if match else None


def has_avx2():
    """Whether this CPU runs x86-64-v3 code (AVX2, FMA, BMI2), which a build without the kernels'
    clones is compiled for."""
    try:
        flags = Path("/proc/cpuinfo").read_text(errors="replace").split()
    except OSError:
        return False
    return all(f in flags for f in ("avx2", "fma", "bmi2", "movbe", "f16c"))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build-dir", default=str(ROOT / "build-mutation"))
    parser.add_argument("--golden-dir", default=str(ROOT / "tests" / "data" / "golden"),
                        help="folder of the golden values (NOCDYN_GOLDEN_DIR)")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--only", default=None, help="run only the mutations whose description contains this")
    parser.add_argument("--all", action="store_true", help="run the extended mutations too (slower)")
    args = parser.parse_args()
    if not Path(args.golden_dir).is_dir():
        print(f"mutation: the golden folder {args.golden_dir} does not exist (--golden-dir)", file=sys.stderr)
        return 1

    start = time.monotonic()
    mutations = parse(LIST.read_text())
    work = Path(args.build_dir).resolve()
    source = work / "source"
    build = source / "build"  # as build/ in the checkout: the same relative paths for ccache
    copy_tree(source)
    log = open(work / "mutation.log", "w")

    # Every searched text must be found exactly once before anything is built.
    problems = []
    for m in mutations:
        path = source / m.path
        if not path.exists():
            problems.append(f"'{m.description}': {m.path} does not exist")
            continue
        text = path.read_text()
        for search, _ in m.pairs:
            count = text.count(search)
            if count != 1:
                problems.append(f"'{m.description}': {m.path} has {count} occurrences of: {search}")
    if problems:
        for p in problems:
            print(f"mutation: NOT APPLIED {p}")
        print(f"0/{len(mutations)} mutations caught (the list no longer matches the code)")
        return 1
    # every text is checked above; only these are built and tested
    left_out = [m for m in mutations if m.extended and not args.all]
    mutations = [m for m in mutations if m not in left_out and (not args.only or args.only in m.description)]

    generator = ["-G", "Ninja"] if shutil.which("ninja") else []
    # ccache with the checkout's cache (scripts/ccache.sh: .ccache/, base_dir the checkout): the
    # unmutated build takes what scripts/test.sh's release build compiled, and a file mutated and
    # then put back is compiled again as a copy.
    launcher = []
    if shutil.which("ccache"):
        launcher = ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"]
        os.environ["CCACHE_DIR"] = str(ROOT / ".ccache")  # as scripts/ccache.sh
        os.environ["CCACHE_BASEDIR"] = str(ROOT)
        os.environ.pop("CCACHE_DISABLE", None)
        os.environ["CCACHE_DEPEND"] = "1"  # no preprocessor run on a miss: the compiler's -MD list
        os.environ["CCACHE_NOHASHDIR"] = "1"
    configure = ["cmake", "-S", str(source), "-B", str(build), *generator, *launcher, "-DCMAKE_BUILD_TYPE=Release",
                 "-DCMAKE_CXX_FLAGS=", "-DNOCDYN_BUILD_TESTS=ON", "-DNOCDYN_BUILD_VALIDATION=OFF", "-DNOCDYN_BUILD_BENCHMARKS=OFF",
                 "-DNOCDYN_BUILD_PYTHON=OFF", "-DNOCDYN_SANITIZE=OFF", "-DNOCDYN_FUZZ=OFF",
                 # the cloned kernels' files built once, for the AVX2 clone this machine runs
                 # (CMakeLists.txt): a mutation in them, or in a header they include, recompiles
                 # in about half the time
                 f"-DNOCDYN_CPU_DISPATCH={'OFF' if has_avx2() else 'ON'}",
                 # those files, which no release object stands for, at -O1: a mutation in them
                 # (batch_chunk.hpp, the lean kernel) recompiles in about 40 % of -O3's time
                 "-DNOCDYN_CHECK_FLAGS=-O1",
                 # and the library's files mutated here, which each mutation recompiles
                 f"-DNOCDYN_CHECK_SOURCES={';'.join(mutated_sources(mutations))}",
                 # the glue (application layer, command line, rendering) at -O0: only the lean
                 # check below runs it, three short commands (CMakeLists.txt: NOCDYN_GLUE_FLAGS)
                 "-DNOCDYN_GLUE_FLAGS=-O0",
                 f"-DNOCDYN_GOLDEN_DIR={Path(args.golden_dir).resolve()}"]
    build_targets = ["cmake", "--build", str(build), "-j", str(args.jobs), "--target"]
    build_command = [*build_targets, *TESTS]
    code, out = run(configure, log=log)
    if code != 0:
        print(out)
        print(f"0/{len(mutations)} mutations caught (the configuration failed)")
        return 1
    # This build is also CI's check of the lean configuration (no Simbody, no MuJoCo, no Python):
    # the command line is built and run in it once, before the mutations.
    code, out = run([*build_command, "nocdyn_cli"], log=log)
    if code != 0:
        print(out[-5000:])
        print(f"0/{len(mutations)} mutations caught (the unmutated build failed)")
        return 1
    lean_failures = lean_cli_check(build / "nocdyn", work, log, Path(args.golden_dir))
    if lean_failures:
        for failure in lean_failures:
            print(f"mutation: the lean build's command line: {failure}")
        print(f"0/{len(mutations)} mutations caught (the lean build's command line fails)")
        return 1
    print("mutation: the lean build (-DNOCDYN_BUILD_VALIDATION=OFF -DNOCDYN_BUILD_PYTHON=OFF) built the command line "
          "and its checks passed", flush=True)
    env_dir = build / "tests" / "scratch"
    env_dir.mkdir(parents=True, exist_ok=True)
    os.environ["TEST_TMPDIR"] = str(env_dir) + "/"

    def run_tests(binaries=TESTS, first_only=False, gtest_filter=None):
        """The first failing test of each binary that fails (binary -> test), in the order given;
        with first_only, the binaries after the first that fails are not run (one suffices to
        catch a mutation); with gtest_filter, only those tests of each binary run."""
        failures = {}
        for test in binaries:
            if first_only and failures:
                break
            selected = [f"--gtest_filter={gtest_filter}"] if gtest_filter else []
            code, out = run([str(build / "tests" / test), "--gtest_fail_fast", "--gtest_brief=1", *selected],
                            cwd=build / "tests", log=log, timeout=TIMEOUT)
            if code is None:
                failures[test] = f"{test} (timed out after {TIMEOUT} s)"
            elif code != 0:
                failures[test] = failing_test(out) or f"{test} (exit code {code})"
        return failures

    baseline = time.monotonic()
    failures = run_tests()
    if failures:
        print(f"mutation: the unmutated source already fails {', '.join(failures.values())} "
              f"(see {work / 'mutation.log'})")
        print(f"0/{len(mutations)} mutations caught (the unmutated tests fail)")
        return 1
    print(f"mutation: build {baseline - start:.0f} s, unmutated tests {time.monotonic() - baseline:.0f} s", flush=True)

    caught = 0
    catcher = {}  # file -> the binary that caught the last mutation of it
    originals = {}
    try:
        for number, m in enumerate(mutations, 1):
            t0 = time.monotonic()
            path = source / m.path
            original = originals.setdefault(m.path, path.read_text())
            # the other files back as they were, this one mutated
            for other, text in originals.items():
                if other != m.path and (source / other).read_text() != text:
                    (source / other).write_text(text)
            log.write(f"\n=== mutation {number} [{m.path}]: {m.description}\n")
            mutated = original
            for search, replace in m.pairs:
                mutated = mutated.replace(search, replace, 1)
            path.write_text(mutated)
            # The binary named by the block's "test:" line (its tests that the line names first,
            # then the others), or the one that caught the previous mutation of this file, is
            # relinked and run first: when it catches the mutation the other binaries are neither
            # relinked nor run. Otherwise every binary is, in order.
            first = m.first or catcher.get(m.path)
            failures = {}
            code, out = run([*build_targets, first] if first else build_command, log=log)
            if code == 0 and first:
                failures = run_tests([first], gtest_filter=m.filter)
                if not failures and m.filter:
                    failures = run_tests([first], gtest_filter=f"-{m.filter}")
                if not failures:
                    code, out = run(build_command, log=log)
            if code == 0 and not failures:
                failures = run_tests([t for t in TESTS if t != first], first_only=True)
            if code != 0:
                verdict = "DOES NOT COMPILE (fix the mutation)"
            elif failures:
                caught += 1
                binary, test = next(iter(failures.items()))
                catcher[m.path] = binary
                verdict = f"caught by {test}"
                if m.first and binary != m.first:
                    verdict += f" (not by {m.first}, its 'test:' line: update it)"
            else:
                verdict = "NOT CAUGHT"
            print(f"mutation {number:2d} [{m.path}] {m.description}: {verdict} ({time.monotonic() - t0:.0f} s)",
                  flush=True)
    finally:
        for other, text in originals.items():
            (source / other).write_text(text)
    print(f"mutation: {time.monotonic() - start:.0f} s in all, log in {work / 'mutation.log'}")
    if left_out:
        print(f"mutation: {len(left_out)} extended mutations found in the code but not run (--all runs them)")
    print(f"{caught}/{len(mutations)} mutations caught")
    return 0 if caught == len(mutations) else 1


if __name__ == "__main__":
    sys.exit(main())
