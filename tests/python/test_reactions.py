"""Robot.reactions: the (N, limbs, 3, 3) batch against the CLI's reaction columns, the weight
carried at rest, threads and memory orders, and the errors of a bad sample."""

import csv

import numpy as np
import pytest

import nocdyn

GRAVITY = "gravity: [0.0, -9.81]\n"
PLATFORM_MASS = 1.75257  # kg, the paper's platform on every example robot


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    data = np.array([[float(v) for v in row] for row in rows[1:]])
    return {name: data[:, i] for i, name in enumerate(rows[0])}


def robot_with_gravity(source_dir, name):
    return nocdyn.Robot.from_yaml(GRAVITY + (source_dir / "robots" / f"{name}.yaml").read_text())


def motion(robot, n=40):
    p, dp, ddp = nocdyn.Trajectory.paper(1).evaluate(np.arange(n) * 1e-3)
    return p + np.asarray(robot.home), dp, ddp


def test_the_batch_equals_the_cli_reaction_columns(tmp_path, cli, source_dir):
    robot_path = source_dir / "robots" / "3-rrr.yaml"
    out = tmp_path / "id.csv"
    code, _, err = cli("inverse-dynamics", "--robot", robot_path, "--trajectory", "paper1", "--duration", 0.02,
                       "--rate", 1000, "--reactions", "-o", out)
    assert code == 0, err
    table = read_csv(out)
    robot = nocdyn.Robot.load(robot_path)
    p, dp, ddp = nocdyn.Trajectory.paper(1).evaluate(table["t"])
    np.testing.assert_allclose(p, np.column_stack([table["x"], table["y"], table["theta"]]), rtol=0, atol=1e-15)
    r = robot.reactions(p, dp, ddp)
    assert r.shape == (20, 3, 3, 3)
    expected = np.stack([np.column_stack([table[f"limb{j + 1}_j{k + 1}_{c}"] for c in ("fx", "fy", "m")])
                         for j in range(3) for k in range(3)], axis=1).reshape(20, 3, 3, 3)
    peak = np.max(np.abs(expected))
    assert peak > 1.0
    np.testing.assert_allclose(r, expected, rtol=0, atol=1e-12 * peak)
    # one sample: (limbs, 3, 3), the same numbers
    np.testing.assert_array_equal(robot.reactions(p[7], dp[7], ddp[7]), r[7])


@pytest.mark.parametrize("name", ["3-rrr", "3-rpr", "4-rrr", "paper-3prr-general"])
def test_at_rest_the_platform_pivots_carry_the_platforms_weight(source_dir, name):
    robot = robot_with_gravity(source_dir, name)
    p = np.tile(np.asarray(robot.home), (3, 1)) + [[0.0, 0.0, 0.0], [0.002, -0.001, 0.01], [-0.003, 0.002, -0.02]]
    zero = np.zeros_like(p)
    r = robot.reactions(p, zero, zero)
    assert r.shape == (3, robot.limbs, 3, 3)
    # the platform joints are passive revolutes of these robots: their forces hold the platform up
    assert f"mass: {PLATFORM_MASS}" in (source_dir / "robots" / f"{name}.yaml").read_text()
    pivots = r[:, :, 2, :2].sum(axis=1)
    np.testing.assert_allclose(pivots, np.tile([0.0, 9.81 * PLATFORM_MASS], (3, 1)), rtol=0,
                               atol=1e-12 * np.max(np.abs(r)))
    assert np.all(r[:, :, 2, 2] == 0.0), "an R joint's reaction has no couple"


def test_threads_and_memory_orders_give_the_same_numbers(source_dir):
    robot = robot_with_gravity(source_dir, "4-rrr")
    p, dp, ddp = motion(robot, 100)
    one = robot.reactions(p, dp, ddp)
    np.testing.assert_array_equal(robot.reactions(p, dp, ddp, threads=2), one)
    np.testing.assert_array_equal(robot.reactions(np.asfortranarray(p), np.asfortranarray(dp), ddp[:, :]), one)
    # the minimum-norm forces' reactions: 4 limbs of 3 joints
    assert one.shape == (100, 4, 3, 3) and np.all(np.isfinite(one))


def test_a_sample_out_of_reach_is_the_inverse_dynamics_error(source_dir):
    robot = nocdyn.Robot.load(source_dir / "robots" / "3-rrr.yaml")
    p, dp, ddp = motion(robot, 5)
    p[3, 1] = 0.5
    with pytest.raises(nocdyn.Error) as reactions_error:
        robot.reactions(p, dp, ddp)
    with pytest.raises(nocdyn.Error) as id_error:
        robot.inverse_dynamics(p, dp, ddp)
    assert str(reactions_error.value).startswith("sample 4: ")  # row 3, numbered from 1
    assert str(reactions_error.value) == str(id_error.value)
    r = robot.reactions(p, dp, ddp, check=False)
    assert np.all(np.isnan(r[3])) and np.all(np.isfinite(r[[0, 1, 2, 4]]))
    with pytest.raises(nocdyn.Error, match="dp: expected shape"):
        robot.reactions(p, dp[:4], ddp)
