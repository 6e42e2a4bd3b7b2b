"""Robot.stiffness and Robot.natural_frequencies: the compliance of the robot file seen from Python."""

import re

import numpy as np
import pytest

import nocdyn

K_DRIVE = (1.0e5, 2.0e5, 3.0e5)  # N/m


def prr_with_drive_springs(source_dir, k=K_DRIVE):
    """The paper's 3-PRR with drive spring k[j] on limb j's slider (links rigid)."""
    values = iter(k)
    text = re.sub("actuated: true,", lambda _: f"actuated: true, stiffness: {next(values)!r},",
                  (source_dir / "robots" / "paper-3prr-general.yaml").read_text())
    return nocdyn.Robot.from_yaml(text, "prr-springs.yaml")


def test_drive_springs_alone_give_the_finite_difference_jacobian_transpose_diag_k_jacobian(source_dir):
    robot = prr_with_drive_springs(source_dir)
    p = np.array([0.002, -0.001, 0.02])  # [x, y, theta]
    h = np.array([1e-7, 1e-7, 1e-6])
    jacobian = np.empty((3, 3))
    for c in range(3):
        step = np.zeros(3)
        step[c] = h[c]
        zero = np.zeros(3)
        up = robot.inverse_dynamics(p + step, zero, zero).u
        down = robot.inverse_dynamics(p - step, zero, zero).u
        jacobian[:, c] = (up - down) / (2 * h[c])
    expected = jacobian.T @ np.diag(K_DRIVE) @ jacobian
    K = robot.stiffness(p)
    # the pose's order, the command line's stiffness report's
    assert robot.stiffness_coordinates == ("x [m]", "y [m]", "theta [rad]")
    assert list(robot.stiffness_coordinates) == robot._core._stiffness(p)["coordinates"]
    scale = np.diag([1.0, 1.0, 1 / 0.1])
    assert np.linalg.norm(scale @ (K - expected) @ scale) < 1e-7 * np.linalg.norm(scale @ expected @ scale)
    assert np.allclose(K, K.T, rtol=0, atol=1e-12 * np.abs(K).max())


def test_lumped_frequencies_ascend_and_their_shapes_solve_the_eigenproblem(source_dir):
    robot = prr_with_drive_springs(source_dir)
    p = (0.001, 0.0, 0.0)
    f, shapes = robot.natural_frequencies(p, modes=True)
    assert f.shape == (3,) and shapes.shape == (3, 3)
    assert 0 < f[0] < f[1] < f[2]
    K = robot.stiffness(p)
    # K v = w^2 M v with v^T M v = 1: v^T K v = w^2
    for i in range(3):
        w = 2 * np.pi * f[i]
        assert shapes[:, i] @ K @ shapes[:, i] == pytest.approx(w * w, rel=1e-10)
    assert np.array_equal(robot.natural_frequencies(p), f)


def test_elastodynamic_frequencies_equal_the_lumped_ones_with_rigid_links(source_dir):
    robot = prr_with_drive_springs(source_dir)
    p = (-0.002, 0.001, 0.01)
    lumped = robot.natural_frequencies(p)
    elastic, shapes = robot.natural_frequencies(p, modes=True, model="elastodynamic")
    assert elastic.shape == (3,) and shapes.shape == (3, 3)
    assert np.allclose(elastic, lumped, rtol=1e-10, atol=0)


def test_a_rigid_robot_and_an_unknown_model_are_errors(source_dir):
    with pytest.raises(nocdyn.Error, match="declares no compliance"):
        nocdyn.Robot.example("paper-3prr-general").stiffness((0, 0, 0))
    robot = prr_with_drive_springs(source_dir)
    with pytest.raises(nocdyn.Error, match="lumped"):
        robot.natural_frequencies((0, 0, 0), model="fem")
    with pytest.raises(nocdyn.Error, match="out of reach"):
        robot.stiffness((0.5, 0, 0))


def test_a_force_actuator_leaves_a_named_free_direction_with_a_zero_frequency(source_dir):
    robot = prr_with_drive_springs(source_dir, k=(0.0, 2.0e5, 3.0e5))
    f = robot.natural_frequencies((0, 0, 0))
    assert f[0] == 0.0 and f[1] > 1.0
    K = robot.stiffness((0, 0, 0))
    assert np.linalg.matrix_rank(np.diag([1.0, 1.0, 10.0]) @ K, tol=1e-9 * np.abs(K).max()) == 2
