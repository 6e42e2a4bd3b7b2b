"""Exact derivatives from Python: Robot.inverse_dynamics_derivatives, Robot.actuator_derivatives and
Robot.linearize against central finite differences of Robot.inverse_dynamics and of the forward
dynamics' linearisation, and nocdyn.frequency_response against the numbers of docs/frequency-response.md."""

import numpy as np
import pytest

import nocdyn


@pytest.fixture(scope="module")
def robots():
    return [nocdyn.Robot.example(name) for name in ("paper-3prr", "3-rrr", "4-rrr")]


def sample(robot, k=0):
    t = 0.013 + 0.017 * k
    p = robot.home + np.array([0.002 * np.cos(7 * t), -0.001 * np.sin(13 * t), 0.02 * np.sin(10 * t)])
    dp = np.array([-0.02 * np.sin(7 * t), 0.015 * np.cos(13 * t), 0.3 * np.cos(10 * t)])
    ddp = np.array([-0.14 * np.cos(7 * t), -0.2 * np.sin(13 * t), -3.0 * np.sin(10 * t)])
    return p, dp, ddp


def central(f, x, h):
    """Five-point derivatives of f (an array) by each coordinate of x: shape f.shape + (3,)."""
    columns = []
    for i in range(3):
        e = np.zeros(3)
        e[i] = h
        columns.append((-f(x + 2 * e) + 8 * f(x + e) - 8 * f(x - e) + f(x - 2 * e)) / (12 * h))
    return np.stack(columns, axis=-1)


def test_inverse_dynamics_derivatives_equal_finite_differences(robots):
    for robot in robots:
        p, dp, ddp = sample(robot)
        d_p, d_dp, d_ddp = robot.inverse_dynamics_derivatives(p, dp, ddp)
        n = robot.actuators
        assert d_p.shape == d_dp.shape == d_ddp.shape == (n, 3)
        tau = lambda p_, dp_, ddp_: robot.inverse_dynamics(p_, dp_, ddp_).tau  # noqa: E731
        for exact, fd in ((d_p, central(lambda x: tau(x, dp, ddp), p, 1e-5)),
                          (d_dp, central(lambda x: tau(p, x, ddp), dp, 1e-4)),
                          (d_ddp, central(lambda x: tau(p, dp, x), ddp, 1e-2))):
            scale = np.abs(exact).max()
            assert np.abs(exact - fd).max() <= 1e-7 * scale, (robot.name, exact, fd)


def test_batch_derivatives_are_the_samples_stacked(robots):
    robot = robots[2]  # redundant
    samples = [sample(robot, k) for k in range(6)]
    p, dp, ddp = (np.array([s[i] for s in samples]) for i in range(3))
    d_p, d_dp, d_ddp = robot.inverse_dynamics_derivatives(p, dp, ddp)
    assert d_p.shape == (6, robot.actuators, 3)
    for k, (pk, dpk, ddpk) in enumerate(samples):
        one = robot.inverse_dynamics_derivatives(pk, dpk, ddpk)
        for batch, single in zip((d_p, d_dp, d_ddp), one):
            np.testing.assert_array_equal(batch[k], single)


def test_batch_with_a_sample_out_of_reach_names_it(robots):
    robot = robots[0]
    p = np.array([robot.home, robot.home + [1.0, 0.0, 0.0]])
    with pytest.raises(nocdyn.Error, match="sample 1"):
        robot.inverse_dynamics_derivatives(p, np.zeros((2, 3)), np.zeros((2, 3)))


def test_actuator_derivatives_equal_finite_differences(robots):
    for robot in robots:  # a 3-PRR, a 3-RRR and a redundant 4-RRR
        for k in range(3):
            p, dp, ddp = sample(robot, k)
            d = robot.actuator_derivatives(p, dp, ddp)
            n = robot.actuators
            values = robot.inverse_dynamics(p, dp, ddp)
            for name in ("u", "du", "ddu"):
                np.testing.assert_allclose(getattr(d, name), getattr(values, name), rtol=0, atol=1e-12)
            assert d.u_p.shape == d.ddu_ddp.shape == (n, 3)

            def of(name, p_=p, dp_=dp, ddp_=ddp):
                return getattr(robot.inverse_dynamics(p_, dp_, ddp_), name)

            for exact, fd in ((d.u_p, central(lambda x: of("u", p_=x), p, 1e-5)),
                              (d.du_p, central(lambda x: of("du", p_=x), p, 1e-5)),
                              (d.du_dp, central(lambda x: of("du", dp_=x), dp, 1e-4)),
                              (d.ddu_p, central(lambda x: of("ddu", p_=x), p, 1e-5)),
                              (d.ddu_dp, central(lambda x: of("ddu", dp_=x), dp, 1e-4)),
                              (d.ddu_ddp, central(lambda x: of("ddu", ddp_=x), ddp, 1e-2))):
                scale = np.abs(exact).max()
                assert np.abs(exact - fd).max() <= 1e-7 * scale, (robot.name, exact, fd)
            # du and ddu are linear in dp and ddp through the same map A S(c)
            np.testing.assert_allclose(d.du_dp, d.u_p, rtol=0, atol=1e-12 * np.abs(d.u_p).max())
            np.testing.assert_allclose(d.ddu_ddp, d.u_p, rtol=0, atol=1e-12 * np.abs(d.u_p).max())
            # the pose order is [x, y, theta]: a rotation moves a prismatic or revolute actuator
            # as the theta column says
            h = 1e-6
            step = np.array([0.0, 0.0, h])
            assert np.abs((of("u", p_=p + step) - of("u", p_=p - step)) / (2 * h) - d.u_p[:, 2]).max() \
                <= 1e-6 * np.abs(d.u_p).max()


def test_actuator_derivatives_of_a_pose_out_of_reach_raise(robots):
    robot = robots[0]
    with pytest.raises(nocdyn.Error):
        robot.actuator_derivatives(robot.home + [1.0, 0.0, 0.0], np.zeros(3), np.zeros(3))


def test_linearize_is_the_forward_dynamics_jacobian(robots):
    for robot in robots:
        p, dp, ddp = sample(robot, 2)
        tau = robot.inverse_dynamics(p, dp, ddp).tau
        A, B = robot.linearize(p, dp, tau)
        n = robot.actuators
        assert A.shape == (6, 6) and B.shape == (6, n)
        np.testing.assert_array_equal(A[:3, 3:], np.eye(3))
        # the acceleration rows d ddp/d(p, dp), checked through the inverse dynamics: the
        # minimum-norm forces of the motion under tau are P(p) tau, P the projector onto the
        # range of A_p (the identity with three actuators), so tau_id(p, dp, ddp(p, dp, tau)) =
        # P(p) tau: its derivative by dp is 0, and by p too when n = 3
        d_p, d_dp, d_ddp = robot.inverse_dynamics_derivatives(p, dp, ddp)
        assert np.abs(d_ddp @ A[3:, 3:] + d_dp).max() <= 1e-9 * np.abs(d_dp).max()
        if n == 3:
            assert np.abs(d_ddp @ A[3:, :3] + d_p).max() <= 1e-9 * np.abs(d_p).max()
        # B's acceleration rows map tau to ddp: M_p^-1 A_p^T, so d_ddp B is the projector onto
        # the minimum-norm forces (the identity with three actuators)
        P = d_ddp @ B[3:]
        np.testing.assert_allclose(P @ P, P, atol=1e-9)
        if n == 3:
            np.testing.assert_allclose(P, np.eye(3), atol=1e-9)
        A4, B4, C, D = robot.linearize(p, dp, tau, output="acceleration")
        np.testing.assert_array_equal(C, A4[3:])
        np.testing.assert_array_equal(D, B4[3:])


def test_frequency_response_of_the_paper_robot_is_the_guide_s(tmp_path):
    result = nocdyn.frequency_response(f_min=1.0, f_max=1000.0, points=4)
    assert result.columns[0] == "f"
    col = {c: i for i, c in enumerate(result.columns)}
    assert np.allclose(result.data[:, col["ddtheta_tau1_db"]], 6.2490, atol=5e-4)
    assert np.allclose(result.data[:, col["ddx_tau1_db"]], -15.8739, atol=5e-4)
    assert "beyond the grid" in result.text


def test_closed_loop_response_of_the_paper_robot_is_the_guide_s():
    nominal = nocdyn.frequency_response(closed_loop=True, f_min=0.1, f_max=4000.0, points=400)
    col = {c: i for i, c in enumerate(nominal.columns)}
    assert np.all(np.abs(nominal.data[:, col["x_db"]]) < 0.1)
    assert "beyond the grid  12.4481  75.9941" in nominal.text
    loaded = nocdyn.frequency_response(closed_loop=True, payload=5.0, f_min=0.1, f_max=4000.0, points=400)
    assert "x  0.0019  -5.1516  10.5627  7.2248  67.3268" in loaded.text
    col = {c: i for i, c in enumerate(loaded.columns)}
    assert loaded.data[-1, col["y_db"]] == pytest.approx(-5.1516, abs=1e-3)
