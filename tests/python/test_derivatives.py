"""Exact derivatives from Python: Robot.inverse_dynamics_derivatives, Robot.actuator_derivatives and
Robot.linearize against central finite differences of Robot.inverse_dynamics and of the forward
dynamics' linearisation, and nocdyn.frequency_response against the numbers of docs/frequency-response.md."""

import numpy as np
import pytest
from conftest import SOURCE_DIR

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
    with pytest.raises(nocdyn.Error, match="^sample 2: "):  # row 1, numbered from 1
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
    result = nocdyn.frequency_response(min_frequency=1.0, max_frequency=1000.0, points=4)
    assert result.columns[0] == "f"
    col = {c: i for i, c in enumerate(result.columns)}
    assert np.allclose(result.data[:, col["ddtheta_tau1_db"]], 6.2490, atol=5e-4)
    assert np.allclose(result.data[:, col["ddx_tau1_db"]], -15.8739, atol=5e-4)
    assert "beyond the grid" in result.text


def test_closed_loop_response_of_the_paper_robot_is_the_guide_s():
    nominal = nocdyn.frequency_response(closed_loop=True, min_frequency=0.1, max_frequency=4000.0, points=400)
    col = {c: i for i, c in enumerate(nominal.columns)}
    assert np.all(np.abs(nominal.data[:, col["x_db"]]) < 0.1)
    assert "beyond the grid  12.4481  75.9941" in nominal.text
    loaded = nocdyn.frequency_response(closed_loop=True, payload_mass=5.0, min_frequency=0.1, max_frequency=4000.0,
                                       points=400)
    assert "x  0.0019  -5.1516  10.5627  7.2248  67.3268" in loaded.text
    col = {c: i for i, c in enumerate(loaded.columns)}
    assert loaded.data[-1, col["y_db"]] == pytest.approx(-5.1516, abs=1e-3)


def test_closed_loop_on_the_compliant_robot_has_its_resonance_and_usable_band():
    robot = str(SOURCE_DIR / "robots" / "paper-3prr-compliant.yaml")
    # the default pose feedback cannot be closed around the 2 %-damped 41 Hz mode
    with pytest.raises(ValueError, match="unstable closed loop.*lumped compliant plant"):
        nocdyn.frequency_response(robot=robot, closed_loop=True, min_frequency=0.1, max_frequency=1000.0, points=50)
    loop = nocdyn.frequency_response(robot=robot, closed_loop=True, natural_frequency=0.5, min_frequency=0.1,
                                     max_frequency=1000.0, points=400)
    assert "# plant: the lumped compliant model" in loop.text
    assert "band  x  12.3109  32.6503  41.3563" in loop.text
    col = {c: i for i, c in enumerate(loop.columns)}
    assert abs(loop.data[0, col["x_db"]]) < 1e-3
    wider = nocdyn.frequency_response(robot=robot, closed_loop=True, natural_frequency=0.5, min_frequency=0.1,
                                      max_frequency=1000.0, points=400, amplification=1.5)
    assert "[0.6667, 1.5000]" in wider.text
    rigid = nocdyn.frequency_response(robot=robot, closed_loop=True, compliance="rigid", min_frequency=0.1,
                                      max_frequency=1000.0, points=50)
    assert "band  x  beyond the grid" in rigid.text
    with pytest.raises(ValueError, match="^amplification: does not apply to the plant"):
        nocdyn.frequency_response(robot=robot, amplification=1.5, points=3)


def _compliant():
    return nocdyn.Robot.load(SOURCE_DIR / "robots" / "paper-3prr-compliant.yaml")


def _held(robot, p, dp=np.zeros(3)):
    """The forces that hold the state (p, dp) without acceleration: the CLI's operating point."""
    return robot.inverse_dynamics(p, dp, np.zeros(3)).tau


def test_compliant_linearize_is_the_command_line_s_lumped_plant():
    robot = _compliant()
    p = robot.home
    lin = robot.linearize(p, np.zeros(3), _held(robot, p), output="acceleration")
    assert lin.model == "lumped" and lin.inputs == ("uc", "uc", "uc")
    A, B, C, D = lin
    assert A.shape == (6, 6) and B.shape == (6, 3) and C.shape == (3, 6) and D.shape == (3, 3)
    table = nocdyn.frequency_response(robot=robot, min_frequency=5.0, max_frequency=500.0, points=7)
    assert "(lumped compliant model)" in table.text
    col = {c: i for i, c in enumerate(table.columns)}
    for k, f in enumerate(table.data[:, 0]):
        s = 2j * np.pi * f
        H = C @ np.linalg.solve(s * np.eye(6) - A, B) + D
        for o, axis in enumerate(("x", "y", "theta")):
            for i in range(3):
                h = H[o, i]
                # the CSV's magnitude is printed to 6 significant figures or so: compare in dB
                assert 20 * np.log10(abs(h)) == pytest.approx(table.data[k, col[f"dd{axis}_uc{i + 1}_db"]], abs=1e-6)
                phase = np.degrees(np.angle(h))
                wrapped = (phase - table.data[k, col[f"dd{axis}_uc{i + 1}_deg"]] + 180.0) % 360.0 - 180.0
                assert abs(wrapped) < 1e-6


def test_compliant_linearize_at_rest_has_the_lumped_natural_frequencies_and_stiffness():
    robot = _compliant()  # no gravity: at rest df/dp = 0, so -M_p A_21 = K
    for p in (robot.home, robot.home + [0.003, -0.002, 0.01]):
        A, B = robot.linearize(p, np.zeros(3), _held(robot, p))
        eigen = np.linalg.eigvals(A)
        # the modes' damping (damping_ratio) moves each pair to -zeta w +- j w sqrt(1 - zeta^2):
        # its modulus is the natural frequency w
        f = np.sort(np.abs(eigen[eigen.imag > 0]) / (2 * np.pi))
        np.testing.assert_allclose(f, robot.natural_frequencies(p), rtol=1e-9)
        # the rigid model at the same point has no stiffness term: the difference of the
        # acceleration rows by the pose is -M_p^-1 K
        rigid_A, _ = robot.linearize(p, np.zeros(3), _held(robot, p), compliance="rigid")
        M_inv_K = rigid_A[3:, :3] - A[3:, :3]
        K = robot.stiffness(p)
        # M_p^-1 K has the eigenvalues w^2 of K v = w^2 M_p v
        w2 = np.sort(np.linalg.eigvals(M_inv_K).real)
        np.testing.assert_allclose(np.sqrt(w2) / (2 * np.pi), robot.natural_frequencies(p), rtol=1e-9)
        assert np.abs(K).max() > 1e3  # the stiffness is there


def test_compliant_drives_follow_their_commanded_positions_at_dc():
    # a constant commanded position u_c relaxes every spring once the drives are at u_c: the
    # static gain from the commands to the actuator variables is the identity, whatever K is
    robot = _compliant()
    p = robot.home + [0.002, 0.001, -0.005]
    A, B, C, D = robot.linearize(p, np.zeros(3), _held(robot, p), output="actuators")
    static = -C @ np.linalg.solve(A, B) + D
    np.testing.assert_allclose(static, np.eye(3), atol=1e-9)
    # the rigid model from forces has no such gain: its A is singular at rest without gravity
    rigid = robot.linearize(p, np.zeros(3), _held(robot, p), output="actuators", compliance="rigid")
    assert rigid.inputs == ("tau",) * 3 and rigid.model == "rigid"
    assert np.linalg.matrix_rank(rigid.A) < 6


def test_linearize_compliance_choices():
    rigid_robot = nocdyn.Robot.example("paper-3prr")
    p = rigid_robot.home
    tau = _held(rigid_robot, p)
    auto = rigid_robot.linearize(p, np.zeros(3), tau)
    rigid = rigid_robot.linearize(p, np.zeros(3), tau, compliance="rigid")
    assert auto.model == rigid.model == "rigid" and auto.inputs == ("tau",) * 3
    for a, b in zip(auto, rigid):
        np.testing.assert_array_equal(a, b)
    A, B = auto  # still a pair when no output is asked for
    np.testing.assert_array_equal(A, auto.A)
    with pytest.raises(nocdyn.Error, match="declares no joint or drive stiffness"):
        rigid_robot.linearize(p, np.zeros(3), tau, compliance="lumped")
    with pytest.raises(nocdyn.Error, match="compliance"):
        rigid_robot.linearize(p, np.zeros(3), tau, compliance="elastic")
    # a compliant file: "auto" is "lumped", and "rigid" the rigid model of the same bodies
    robot = _compliant()
    tau = _held(robot, robot.home)
    for a, b in zip(robot.linearize(robot.home, np.zeros(3), tau),
                    robot.linearize(robot.home, np.zeros(3), tau, compliance="lumped")):
        np.testing.assert_array_equal(a, b)
    rigid = robot.linearize(robot.home, np.zeros(3), tau, compliance="rigid")
    np.testing.assert_array_equal(rigid.A[3:, :3], np.zeros((3, 3)))  # at rest, no gravity


def test_actuator_derivatives_batch_is_the_samples_stacked_and_threads_change_nothing(robots):
    for robot in robots:
        samples = [sample(robot, k) for k in range(40)]
        p, dp, ddp = (np.array([s[i] for s in samples]) for i in range(3))
        batch = robot.actuator_derivatives(p, dp, ddp)
        threaded = robot.actuator_derivatives(p, dp, ddp, threads=2)
        n = robot.actuators
        for name in batch._fields:
            expected = (40, n) if name in ("u", "du", "ddu") else (40, n, 3)
            assert getattr(batch, name).shape == expected, name
            assert getattr(batch, name).tobytes() == getattr(threaded, name).tobytes(), name
        for k, (pk, dpk, ddpk) in enumerate(samples):
            one = robot.actuator_derivatives(pk, dpk, ddpk)
            for name in batch._fields:
                np.testing.assert_array_equal(getattr(batch, name)[k], getattr(one, name), err_msg=name)
        # F-ordered and strided inputs read in place give the same numbers
        wide = np.zeros((40, 6))
        wide[:, ::2] = dp
        again = robot.actuator_derivatives(np.asfortranarray(p), wide[:, ::2], np.asfortranarray(ddp))
        for name in batch._fields:
            np.testing.assert_array_equal(getattr(again, name), getattr(batch, name))


def test_actuator_derivatives_batch_names_a_failed_sample_or_leaves_it_nan(robots):
    robot = robots[0]
    p = np.array([robot.home, robot.home + [1.0, 0.0, 0.0], robot.home])
    zeros = np.zeros((3, 3))
    with pytest.raises(nocdyn.Error, match=r"^sample 2: .*\(1 of 3 samples failed\)"):
        robot.actuator_derivatives(p, zeros, zeros)
    d = robot.actuator_derivatives(p, zeros, zeros, check=False)
    assert np.isnan(d.u[1]).all() and np.isnan(d.ddu_p[1]).all()
    assert np.isfinite(d.u[[0, 2]]).all() and np.isfinite(d.ddu_p[[0, 2]]).all()
    with pytest.raises(nocdyn.Error):
        robot.actuator_derivatives(p, np.zeros((2, 3)), zeros)
