"""nocdyn.validate on a spatial robot file (the same job as the command line's `validate`):
nocdyn's actuator forces along the trajectory against the Simbody and MuJoCo spatial models',
the table the CLI writes."""

import numpy as np
import pytest

import nocdyn
from nocdyn import _nocdyn

pytestmark = pytest.mark.skipif(not hasattr(_nocdyn, "_run_validate"),
                                reason="validate is built with Simbody and MuJoCo only")


def _delta(source_dir):
    return str(source_dir / "robots" / "delta.yaml"), str(source_dir / "trajectories" / "delta-pick.yaml")


def test_a_spatial_robot_path_agrees_with_both_engines(source_dir):
    robot, trajectory = _delta(source_dir)
    table = nocdyn.validate(trajectory, robot=robot, rate=100)
    n = 3
    prefixes = ("u", "tau", "simbody_tau", "mujoco_tau", "simbody_dtau", "mujoco_dtau")
    assert table.columns == ["t", "x", "y", "z", *[f"{p}{a + 1}" for p in prefixes for a in range(n)]]
    data = np.asarray(table.data)
    assert data.shape == (100, 4 + 6 * n)
    tau = data[:, 4 + n:4 + 2 * n]
    peak = np.max(np.abs(tau), axis=0)
    assert np.all(peak > 1.0)
    for e, engine in enumerate(("simbody", "mujoco")):
        theirs = data[:, 4 + (2 + e) * n:4 + (3 + e) * n]
        dtau = data[:, 4 + (4 + e) * n:4 + (5 + e) * n]
        relative = np.max(np.abs(theirs - tau), axis=0) / peak
        assert np.all(relative < 1e-9), (engine, relative)
        assert np.allclose(dtau, theirs - tau, rtol=0.0, atol=1e-12 * peak.max())
    assert "| Simbody | 3 |" in table.text and "| MuJoCo | 3 |" in table.text
    assert "relative to our peak abs(tau): Simbody " in table.text and ", MuJoCo " in table.text
    # nocdyn's columns are inverse-dynamics' own
    computed = nocdyn.inverse_dynamics(trajectory, robot=robot, rate=100)
    columns = computed.columns
    ours = np.asarray(computed.data)
    for name in ("t", "x", "z", "u1", "u3", "tau1", "tau2", "tau3"):
        assert np.allclose(data[:, table.columns.index(name)], ours[:, columns.index(name)], rtol=0.0,
                           atol=1e-12 * max(1.0, np.max(np.abs(ours[:, columns.index(name)]))))


def test_one_engine_alone(source_dir, tmp_path, cli):
    robot = str(source_dir / "robots" / "stewart.yaml")
    trajectory = str(source_dir / "trajectories" / "stewart-sway.yaml")
    both = nocdyn.validate(trajectory, robot=robot, rate=50)
    mujoco = nocdyn.validate(trajectory, robot=robot, rate=50, engine="mujoco")
    n = 6
    assert mujoco.columns == ["t", "x", "y", "z", "roll", "pitch", "yaw",
                              *[f"{p}{a + 1}" for p in ("u", "tau", "mujoco_tau", "mujoco_dtau") for a in range(n)]]
    assert "| MuJoCo | 6 |" in mujoco.text and "| Simbody |" not in mujoco.text
    a, b = np.asarray(mujoco.data), np.asarray(both.data)
    for name in mujoco.columns:
        assert np.array_equal(a[:, mujoco.columns.index(name)], b[:, both.columns.index(name)]), name
    tau = a[:, 7 + n:7 + 2 * n]
    assert np.max(np.abs(a[:, 7 + 3 * n:])) < 1e-9 * np.max(np.abs(tau))
    code, _, err = cli("validate", "--robot", robot, "--trajectory", trajectory, "--rate", 50, "--engine", "mujoco",
                       "-o", tmp_path / "v.csv")
    assert code == 0, err
    assert (tmp_path / "v.csv").read_text().splitlines()[0] == ",".join(mujoco.columns)
    assert np.allclose(np.loadtxt(tmp_path / "v.csv", delimiter=",", skiprows=1), a, rtol=1e-15, atol=0.0)
    with pytest.raises(nocdyn.Error, match="engine: .*expected both, simbody or mujoco"):
        nocdyn.validate(trajectory, robot=robot, rate=50, engine="adams")
    code, _, err = cli("validate", "--robot", robot, "--trajectory", trajectory, "--engine", "adams")
    assert code != 0 and "--engine" in err


def test_python_gives_the_command_lines_table(source_dir, tmp_path, cli):
    robot, trajectory = _delta(source_dir)
    table = nocdyn.validate(trajectory, robot=robot, rate=100)
    data = np.asarray(table.data)
    code, _, err = cli("validate", "--robot", robot, "--trajectory", trajectory, "--rate", 100, "-o",
                       tmp_path / "v.csv")
    assert code == 0, err
    written = np.loadtxt(tmp_path / "v.csv", delimiter=",", skiprows=1)
    assert (tmp_path / "v.csv").read_text().splitlines()[0] == ",".join(table.columns)
    assert np.allclose(written, data, rtol=1e-15, atol=0.0)
    # and its report: the samples and the agreement table
    assert table.text.startswith("nocdyn validate: delta, delta-pick, 100 samples\n| engine | actuator |")
    assert table.text in err


def test_a_bad_spatial_trajectory_is_one_clear_error(source_dir):
    with pytest.raises(nocdyn.Error, match=r"delta-pick\.yaml:5: roll: missing"):
        nocdyn.validate(str(source_dir / "trajectories" / "delta-pick.yaml"),
                        robot=str(source_dir / "robots" / "stewart.yaml"))
    with pytest.raises(ValueError, match="validate takes a spatial robot file's path"):
        nocdyn.validate(str(source_dir / "trajectories" / "delta-pick.yaml"),
                        robot=nocdyn.Robot.load(source_dir / "robots" / "delta.yaml"))
