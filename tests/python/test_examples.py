"""The notebooks of examples/ (jupytext-style scripts, `# %%` cells) run from start to end, in
a temporary folder, in their quick form (NOCDYN_EXAMPLE_QUICK=1: shorter experiments)."""

import os
import subprocess
import sys

import pytest

from conftest import SOURCE_DIR

EXAMPLES = ["paper_figures.py", "own_robot.py", "five_bar.py", "hexapod.py", "identification.py",
            "el_centro.py"]


@pytest.mark.parametrize("name", EXAMPLES)
def test_example_runs(name, tmp_path):
    script = SOURCE_DIR / "examples" / name
    assert "# %%" in script.read_text()
    env = dict(os.environ, NOCDYN_EXAMPLE_OUT=str(tmp_path), NOCDYN_EXAMPLE_QUICK="1", MPLBACKEND="Agg",
               NOCDYN_SOURCE_DIR=str(SOURCE_DIR))
    # the package this test imports, whatever the folder the example runs in
    env["PYTHONPATH"] = os.pathsep.join(os.path.abspath(p) for p in env.get("PYTHONPATH", "").split(os.pathsep) if p)
    done = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=180, env=env,
                          cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    if name == "paper_figures.py":
        for figure in ("paper_fig5.png", "paper_fig6.png"):
            assert (tmp_path / figure).read_bytes()[:4] == b"\x89PNG"
        assert "trajectory 1: 2000 samples" in done.stdout
    if name == "own_robot.py":
        assert (tmp_path / "3-rrr.svg").read_text().startswith("<svg") and "assembly modes" in done.stdout
    if name == "five_bar.py":
        assert (tmp_path / "five-bar.svg").read_text().startswith("<svg")
        assert (tmp_path / "five-bar-workspace.png").read_bytes()[:4] == b"\x89PNG"
        assert "checked: the workspace, both tool points, the efforts, the power balance and the motion" in done.stdout
    if name == "hexapod.py":
        assert "every check passed" in done.stdout and "real assembly modes" in done.stdout, done.stdout
    if name == "identification.py":
        assert "payload: {mass: 0.4" in done.stdout or "payload: {mass: 0.5" in done.stdout, done.stdout
    if name == "el_centro.py":
        assert (tmp_path / "el-centro" / "shake.json").exists() and "time scale L" in done.stdout


# The design studies (argparse scripts): each checks its own claims and exits non-zero when one fails.
DESIGN_EXAMPLES = ["design_3rrr/optimise_vs_grid.py", "design_vibration_generator/run.py"]


@pytest.mark.parametrize("name", DESIGN_EXAMPLES)
def test_design_example_checks_its_claims(name, tmp_path):
    script = SOURCE_DIR / "examples" / name
    env = dict(os.environ, NOCDYN_EXAMPLE_OUT=str(tmp_path), NOCDYN_EXAMPLE_QUICK="1", MPLBACKEND="Agg")
    env["PYTHONPATH"] = os.pathsep.join(os.path.abspath(p) for p in env.get("PYTHONPATH", "").split(os.pathsep) if p)
    done = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=180, env=env,
                          cwd=tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    if name.startswith("design_3rrr"):
        assert "grid 20 x 20: 400 evaluations, best area 22140.73 mm^2" in done.stdout, done.stdout
        assert "optimiser >= grid: True" in done.stdout and "the claims hold" in done.stdout, done.stdout
    else:
        assert (tmp_path / "design_vibration_generator" / "pareto.png").read_bytes()[:4] == b"\x89PNG"
        assert "on the front reach at least the prototype's three envelopes" in done.stdout, done.stdout


def test_a_design_example_fails_when_its_claim_is_off(tmp_path):
    """Ten trials cannot reach the grid's best: the comparison says so and exits non-zero."""
    env = dict(os.environ, NOCDYN_EXAMPLE_QUICK="1")
    env["PYTHONPATH"] = os.pathsep.join(os.path.abspath(p) for p in env.get("PYTHONPATH", "").split(os.pathsep) if p)
    done = subprocess.run([sys.executable, str(SOURCE_DIR / "examples" / "design_3rrr" / "optimise_vs_grid.py"),
                           "--trials", "10"], capture_output=True, text=True, timeout=180, env=env, cwd=tmp_path)
    assert done.returncode != 0 and "below the grid's" in done.stderr, done.stderr
