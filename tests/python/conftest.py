"""Fixtures of the Python package's tests: the source tree, the CLI, the golden files.

ctest sets NOCDYN_CLI (the built `nocdyn` binary), NOCDYN_SOURCE_DIR and NOCDYN_GOLDEN_DIR and
PYTHONPATH=<build>/python; run by hand:
    PYTHONPATH=build/python NOCDYN_CLI=build/nocdyn /usr/bin/python3 -m pytest tests/python
"""

import os
import pathlib
import subprocess

import pytest

import nocdyn

def skip_or_fail_in_ci(reason):
    """Skips the test for a missing tool or file; under CI=true (.ci/run) fails it instead, so
    that CI cannot pass with tests that did not run."""
    if os.environ.get("CI") == "true":
        pytest.fail(f"{reason} (CI=true: a test that would skip fails instead)")
    pytest.skip(reason)


SOURCE_DIR = pathlib.Path(os.environ.get("NOCDYN_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


@pytest.fixture(scope="session")
def source_dir():
    return SOURCE_DIR


@pytest.fixture(scope="session")
def paper_robot():
    return nocdyn.Robot.load(SOURCE_DIR / "robots" / "paper-3prr.yaml")


@pytest.fixture(scope="session")
def cli():
    """Runs the nocdyn CLI: returns (exit code, stdout, stderr)."""
    path = os.environ.get("NOCDYN_CLI")
    if not path or not os.path.exists(path):
        skip_or_fail_in_ci("NOCDYN_CLI does not name the built nocdyn binary (ctest sets it)")

    def run(*args):
        done = subprocess.run([path, *map(str, args)], capture_output=True, text=True, timeout=60)
        return done.returncode, done.stdout, done.stderr

    return run


@pytest.fixture(scope="session")
def golden_dir():
    path = pathlib.Path(os.environ.get("NOCDYN_GOLDEN_DIR", SOURCE_DIR.parent / "shared" / "golden"))
    if not (path / "paper_trajectory1.csv").exists():
        skip_or_fail_in_ci(f"no golden files in {path} (NOCDYN_GOLDEN_DIR)")
    return path
