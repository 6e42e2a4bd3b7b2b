"""Two-DOF planar robots (motion: translation, pose [x, y] of a point tool): the shipped five-bar
and biglide through Robot.inverse_dynamics with arrays of shape (N, 2), `nocdyn pose X Y`, and
`nocdyn forward-kinematics U1 U2` (poses x, y), `nocdyn.simulate` (columns t, x, y, ...),
`nocdyn.workspace`, `nocdyn.inverse_dynamics` (trajectories keyed x, y), `nocdyn.loads`,
`nocdyn.convert`, `nocdyn.identify` (a point payload: its mass), Python's pose and direct
kinematics over x, y, the drawing, and the other commands over x, y."""

import numpy as np
import pytest

import nocdyn


def _robot(source_dir, name):
    return nocdyn.Robot.load(str(source_dir / "robots" / f"{name}.yaml"))


def _motion(center, n=200):
    t = np.linspace(0.0, 0.5, n)
    a, w = np.array([0.03, 0.04]), np.array([9.0, 13.0])
    P = center + a * np.sin(np.outer(t, w))
    dP = a * w * np.cos(np.outer(t, w))
    ddP = -a * w * w * np.sin(np.outer(t, w))
    return P, dP, ddP


@pytest.mark.parametrize("name, center", [("five-bar", [0.01, 0.32]), ("biglide", [0.0, 0.17])])
def test_batch_of_shape_n_2_matches_one_sample_at_a_time(source_dir, name, center):
    robot = _robot(source_dir, name)
    assert robot.task_dimension == 2
    assert robot.actuators == 2
    P, dP, ddP = _motion(np.array(center))
    u, du, ddu, tau = robot.inverse_dynamics(P, dP, ddP)
    assert u.shape == du.shape == ddu.shape == tau.shape == (len(P), 2)
    assert np.all(np.isfinite(tau)) and np.abs(tau).max() > 0.1
    for k in (0, 57, 133, 199):
        one = robot.inverse_dynamics(P[k], dP[k], ddP[k])
        for batch, sample in zip((u, du, ddu, tau), one):
            np.testing.assert_allclose(batch[k], sample, rtol=1e-11, atol=1e-12)


def test_batch_reads_n_2_arrays_in_place_in_any_order_across_slices(source_dir):
    # the compiled batch lifts (N, 2) through E slice by slice (65536 rows): a batch longer than
    # one slice, read C-ordered, F-ordered and as a strided view, into new and preallocated
    # outputs, gives every row the one-sample result to the last bits
    robot = _robot(source_dir, "five-bar")
    P, dP, ddP = _motion(np.array([0.01, 0.32]), n=70001)
    u, du, ddu, tau = robot.inverse_dynamics(P, dP, ddP)
    for k in (0, 65535, 65536, 70000):
        one = robot.inverse_dynamics(P[k], dP[k], ddP[k])
        for batch, sample in zip((u, du, ddu, tau), one):
            np.testing.assert_allclose(batch[k], sample, rtol=1e-11, atol=1e-12)
    F = [np.asfortranarray(a) for a in (P, dP, ddP)]
    wide = [np.zeros((len(P), 5)) for _ in range(3)]
    for w, a in zip(wide, (P, dP, ddP)):
        w[:, 1:5:2] = a  # columns 1 and 3: a strided view of every other column
    out = tuple(np.empty((len(P), 2), order="F") for _ in range(4))
    for inputs, into in ((F, None), ([w[:, 1:5:2] for w in wide], None), ((P, dP, ddP), out)):
        result = robot.inverse_dynamics(*inputs, out=into)
        for got, want in zip(result, (u, du, ddu, tau)):
            np.testing.assert_array_equal(got, want)
    assert result.tau is out[3]
    with pytest.raises(nocdyn.Error, match="overlaps the input p"):
        robot.inverse_dynamics(P, dP, ddP, out=(P, np.empty_like(P), np.empty_like(P), np.empty_like(P)))
    with pytest.raises(nocdyn.Error, match=r"dp: expected shape \(70001, 2\)"):
        robot.inverse_dynamics(P, dP[:-1], ddP)
    # a sample out of reach: its row NaN, the rest computed (check=False), else the error names it
    P_bad = P.copy()
    P_bad[40000] = [0.0, 0.9]
    bad = robot.inverse_dynamics(P_bad, dP, ddP, check=False)
    assert np.all(np.isnan(bad.tau[40000])) and np.isfinite(bad.tau[39999]).all()
    with pytest.raises(nocdyn.Error, match="sample 40001"):
        robot.inverse_dynamics(P_bad, dP, ddP)
    # an actuator beyond its effort (8 N m): the limit is checked in the kernel
    with pytest.raises(nocdyn.Error, match="sample 1: .*effort"):
        robot.inverse_dynamics(P[:3], dP[:3], 1e4 * np.ones((3, 2)))
    robot.inverse_dynamics(P[:3], dP[:3], 1e4 * np.ones((3, 2)), check_limits=False)


def test_power_balance_along_a_five_bar_motion(source_dir):
    # tau . du = dE/dt with no gravity (the horizontal five-bar): the kinetic energy from
    # E(t) = integral of the power, checked as the power's integral over a period vanishing
    robot = _robot(source_dir, "five-bar")
    t = np.linspace(0.0, 2.0 * np.pi / 3.0, 4001)  # one common period of w = 3 and 6
    a = np.array([0.03, 0.02])
    c = np.array([0.0, 0.3])
    P = c + np.stack([a[0] * np.sin(3.0 * t), a[1] * np.sin(6.0 * t)], axis=1)
    dP = np.stack([3.0 * a[0] * np.cos(3.0 * t), 6.0 * a[1] * np.cos(6.0 * t)], axis=1)
    ddP = np.stack([-9.0 * a[0] * np.sin(3.0 * t), -36.0 * a[1] * np.sin(6.0 * t)], axis=1)
    _, du, _, tau = robot.inverse_dynamics(P, dP, ddP)
    power = np.sum(tau * du, axis=1)
    # the kinetic energy returns to its start after a period: the work done is zero
    work = np.trapezoid(power, t) if hasattr(np, "trapezoid") else np.trapz(power, t)
    assert abs(work) < 1e-6 * np.abs(power).max() * t[-1]


def test_biglide_holds_its_weight_as_virtual_work_says(source_dir):
    robot = _robot(source_dir, "biglide")
    zero = np.zeros(2)
    _, _, _, tau = robot.inverse_dynamics(np.array([0.0, 0.2]), zero, zero)
    expected = 9.81 * (0.5 + 0.2) * 0.15 / (2.0 * 0.2)  # g (m_tool + m_link) s / (2 y)
    np.testing.assert_allclose(tau, [expected, -expected], rtol=1e-12)


def test_wrong_shapes_and_matrices_are_refused(source_dir):
    robot = _robot(source_dir, "five-bar")
    with pytest.raises(nocdyn.Error, match=r"\(N, 2\)"):
        robot.inverse_dynamics(np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((3, 3)))
    with pytest.raises(nocdyn.Error, match="matrices"):
        robot.inverse_dynamics(np.array([0.0, 0.3]), np.zeros(2), np.zeros(2), matrices=True)
    with pytest.raises(nocdyn.Error, match="sample 1"):
        robot.inverse_dynamics(np.array([[0.0, 0.9]]), np.zeros((1, 2)), np.zeros((1, 2)))


def test_pose_prints_x_y(cli, source_dir):
    code, out, err = cli("pose", "0.05", "0.25", "--robot", source_dir / "robots" / "five-bar.yaml")
    assert code == 0, err
    assert "pose x = 0.05 m, y = 0.25 m" in out
    assert "columns: x, y)" in out
    code, out, err = cli("pose", "0.0", "0.2", "--robot", source_dir / "robots" / "biglide.yaml", "--json")
    assert code == 0, err
    import json

    report = json.loads(out)
    assert set(report["pose"]) == {"x", "y"}
    np.testing.assert_allclose(report["tau"], [2.575125, -2.575125], rtol=1e-12)
    code, _, err = cli("pose", "0.0", "0.3", "0.1", "--robot", source_dir / "robots" / "five-bar.yaml")
    assert code != 0 and "no theta" in err
    code, _, err = cli("pose", "0.0", "0.0", "--robot", source_dir / "robots" / "3-rrr.yaml")
    assert code != 0 and "THETA" in err


@pytest.mark.parametrize("name, tool", [("five-bar", [0.03, 0.31]), ("biglide", [-0.02, 0.18])])
def test_forward_kinematics_gives_both_tool_points_x_y(cli, source_dir, name, tool):
    import json

    robot = _robot(source_dir, name)
    u = robot.inverse_dynamics(np.array(tool), np.zeros(2), np.zeros(2))[0]
    path = source_dir / "robots" / f"{name}.yaml"
    code, out, err = cli("forward-kinematics", repr(u[0]), repr(u[1]), "--robot", path, "--all-branches", "--json")
    assert code == 0, err
    report = json.loads(out)
    assert report["solutions_all_branches"] == 2
    poses = np.array([[s["pose"]["x"], s["pose"]["y"]] for s in report["solutions"]])
    assert all(set(s["pose"]) == {"x", "y"} for s in report["solutions"])
    assert tuple(poses[0]) < tuple(poses[1])  # listed by x, then y
    # the tool point that gave u is one of them, in the working mode
    hit = np.argmin(np.linalg.norm(poses - tool, axis=1))
    np.testing.assert_allclose(poses[hit], tool, atol=1e-12)
    assert report["solutions"][hit]["working"]
    code, out, err = cli("forward-kinematics", repr(u[0]), repr(u[1]), "--robot", path)
    assert code == 0, err
    assert f"x = {tool[0] * 1e3:+.9f} mm, y = {tool[1] * 1e3:+.9f} mm" in out
    assert "theta" not in out


def test_the_stiffness_of_a_two_dof_robot_is_2_by_2_over_x_y(cli, source_dir, tmp_path):
    # drive springs k at both motors, every other joint free: K = A^T diag(k) A with A the
    # report's 2 x 2 actuation map over x, y, and the frequencies from det(K - w^2 I) = 0 with
    # I = E^T I E the report's inertia (horizontal five-bar: no gravity preload)
    import json

    text = (source_dir / "robots" / "five-bar.yaml").read_text()
    stiff = tmp_path / "stiff-five-bar.yaml"
    stiff.write_text(text.replace("effort: 8.0, velocity: 30.0}}", "effort: 8.0, velocity: 30.0}, stiffness: 5000.0}"))
    code, out, err = cli("pose", "0.02", "0.3", "--robot", stiff, "--json")
    assert code == 0, err
    report = json.loads(out)
    A, inertia = np.array(report["A"]), np.array(report["I"])
    K = np.array(report["stiffness"]["matrix"])
    assert K.shape == (2, 2) and report["stiffness"]["coordinates"] == ["x [m]", "y [m]"]
    np.testing.assert_allclose(K, 5000.0 * A.T @ A, rtol=1e-10)
    w2 = np.sort(np.linalg.eigvals(np.linalg.solve(inertia, K)).real)
    np.testing.assert_allclose(report["natural_frequencies"], np.sqrt(w2) / (2 * np.pi), rtol=1e-9)
    assert report["first_frequency"]["value"] == report["natural_frequencies"][0]
    code, out, err = cli("pose", "0.02", "0.3", "--robot", stiff)
    assert code == 0, err
    assert "rows and columns: x [m] y [m])" in out and "rows: x, y)" in out


@pytest.mark.parametrize("name, center", [("five-bar", [0.01, 0.32]), ("biglide", [0.0, 0.17])])
def test_linearize_over_x_y_agrees_with_finite_differences_of_the_inverse_dynamics(source_dir, name, center):
    # the state [x, y, dx/dt, dy/dt]; with square actuation, tau_id(p, dp, ddp) = tau gives
    # d(ddp)/d(tau) = (d tau_id / d ddp)^-1 and d(ddp)/d(p, dp) = -B_l d tau_id / d(p, dp)
    robot = _robot(source_dir, name)
    p, dp = np.array(center), np.array([0.2, -0.3])
    tau = robot.inverse_dynamics(p, dp, np.array([1.0, -2.0])).tau
    A, B, C, D = robot.linearize(p, dp, tau, output="acceleration")
    assert A.shape == (4, 4) and B.shape == (4, 2) and C.shape == (2, 4) and D.shape == (2, 2)
    np.testing.assert_array_equal(A[:2], np.hstack([np.zeros((2, 2)), np.eye(2)]))
    np.testing.assert_array_equal(B[:2], np.zeros((2, 2)))
    np.testing.assert_array_equal(C, A[2:])
    np.testing.assert_array_equal(D, B[2:])

    def tau_id(p_, dp_, ddp_):
        return robot.inverse_dynamics(p_, dp_, ddp_).tau

    ddp = np.array([1.0, -2.0])
    h = 1e-6
    dtau = {"ddp": np.zeros((2, 2)), "p": np.zeros((2, 2)), "dp": np.zeros((2, 2))}
    for i in range(2):
        e = h * np.eye(2)[i]
        dtau["ddp"][:, i] = (tau_id(p, dp, ddp + e) - tau_id(p, dp, ddp - e)) / (2 * h)
        dtau["p"][:, i] = (tau_id(p + e, dp, ddp) - tau_id(p - e, dp, ddp)) / (2 * h)
        dtau["dp"][:, i] = (tau_id(p, dp + e, ddp) - tau_id(p, dp - e, ddp)) / (2 * h)
    B_l = np.linalg.inv(dtau["ddp"])
    np.testing.assert_allclose(B[2:], B_l, rtol=1e-6, atol=1e-9 * np.abs(B_l).max())
    for block, key in ((A[2:, :2], "p"), (A[2:, 2:], "dp")):
        expected = -B_l @ dtau[key]
        np.testing.assert_allclose(block, expected, rtol=1e-5, atol=1e-6 * np.abs(expected).max())
    # the actuators' output: du = A_p E dp, so C's rate columns vanish and its position columns
    # are the actuation Jacobian over x, y (finite differences of u)
    _, _, C_u, D_u = robot.linearize(p, dp, tau, output="actuators")
    J = np.column_stack([(robot.inverse_dynamics(p + h * e, dp, ddp).u - robot.inverse_dynamics(p - h * e, dp, ddp).u)
                         / (2 * h) for e in np.eye(2)])
    np.testing.assert_allclose(C_u[:, :2], J, rtol=1e-6, atol=1e-9)
    np.testing.assert_array_equal(C_u[:, 2:], np.zeros((2, 2)))
    np.testing.assert_array_equal(D_u, np.zeros((2, 2)))
    with pytest.raises(nocdyn.Error, match="expected shape \\(2,\\) for a two-DOF robot"):
        robot.linearize(np.array([0.0, 0.3, 0.0]), np.zeros(3), tau)
    with pytest.raises(nocdyn.Error, match="declares no joint or drive stiffness"):
        robot.linearize(p, dp, tau, compliance="lumped")


def test_robot_reactions_and_payload_of_a_five_bar_over_x_y(source_dir):
    # reactions on (N, 2) samples: those of the command line's --reactions columns (which the
    # Newton-Euler balance of tests/twodof_forces_cli_test.cpp checks)
    robot = _robot(source_dir, "five-bar")
    eight = str(source_dir / "trajectories" / "five-bar-figure-eight.yaml")
    forces = nocdyn.inverse_dynamics(eight, robot=robot, rate=400.0, reactions=True)
    p, dp, ddp = (a[:, :2] for a in nocdyn.Trajectory.load(eight).evaluate(forces["t"]))
    reactions = robot.reactions(p, dp, ddp)
    assert reactions.shape == (len(p), 2, 3, 3)
    for limb in (1, 2):
        for joint in (1, 2, 3):
            for k, axis in enumerate(("fx", "fy", "m")):
                np.testing.assert_allclose(reactions[:, limb - 1, joint - 1, k],
                                           forces[f"limb{limb}_j{joint}_{axis}"], rtol=0, atol=1e-12)
    np.testing.assert_array_equal(robot.reactions(p[7], dp[7], ddp[7]), reactions[7])
    # a payload is a point mass at the tool: the same as a heavier tool in the file
    heavier = nocdyn.Robot.from_yaml((source_dir / "robots" / "five-bar.yaml").read_text().replace(
        "platform: {mass: 0.3}", "platform: {mass: 0.5}"))
    np.testing.assert_allclose(robot.with_payload(0.2).inverse_dynamics(p, dp, ddp).tau,
                               heavier.inverse_dynamics(p, dp, ddp).tau, rtol=1e-13, atol=1e-13)
    with pytest.raises(nocdyn.Error, match="a point mass at its tool point: com must be"):
        robot.with_payload(0.2, com=(0.01, 0.0))


def _circle_intersections(a, ra, b, rb):
    """The two points at distance ra from a and rb from b (the five-bar's forearms meet there)."""
    d = np.linalg.norm(b - a)
    along = (ra**2 - rb**2 + d**2) / (2 * d)
    h = np.sqrt(ra**2 - along**2)
    e = (b - a) / d
    mid = a + along * e
    n = np.array([-e[1], e[0]])
    return mid + h * n, mid - h * n


def test_python_pose_and_direct_kinematics_of_a_five_bar_are_over_x_y(source_dir):
    # the two tool points of the motors' angles u: the intersections of the circles of the
    # forearm's length about the two elbows (closed form), found by Robot.forward_kinematics,
    # nocdyn.forward_kinematics and nocdyn.pose without theta
    robot = _robot(source_dir, "five-bar")
    assert robot.home.shape == (2,)
    np.testing.assert_allclose(robot.home, [0.0, 0.35])
    tool = np.array([0.05, 0.25])
    report = nocdyn.pose(*tool, robot=robot)
    np.testing.assert_array_equal(report.pose, tool)
    assert report.A.shape == (2, 2)
    u = report.u
    motors, arm, forearm = np.array([[-0.1, 0.0], [0.1, 0.0]]), np.hypot(0.1, 0.2), 0.25
    elbows = [m + arm * np.array([np.cos(a), np.sin(a)]) for m, a in
              zip(motors, np.arctan2([0.2, 0.2], [-0.1, 0.1]) + u)]  # the file's elbows at u = 0
    expected = sorted(tuple(p) for p in _circle_intersections(elbows[0], forearm, elbows[1], forearm))
    modes = nocdyn.forward_kinematics(u, robot=robot, all_branches=True)
    assert modes.poses.shape == (2, 2)
    np.testing.assert_allclose(sorted(map(tuple, modes.poses)), expected, atol=1e-12)
    found = sorted(tuple(m["pose"]) for m in robot.forward_kinematics(u))
    np.testing.assert_allclose(found, expected, atol=1e-12)
    # the state from u and du: the working mode nearest home, and du = A dp
    du = np.array([0.3, -0.2])
    state = robot.state_from_actuators(u, du)
    assert state["p"].shape == state["dp"].shape == (2,)
    nearest = min(expected, key=lambda p: np.linalg.norm(np.array(p) - robot.home))
    np.testing.assert_allclose(state["p"], nearest, atol=1e-12)
    A = nocdyn.pose(*state["p"], robot=robot).A
    np.testing.assert_allclose(A @ state["dp"], du, rtol=1e-10)


def test_a_two_dof_robot_is_drawn_at_its_tool_point(source_dir):
    for name in ("five-bar", "biglide"):
        robot = _robot(source_dir, name)
        svg = robot.svg()
        assert svg == robot._repr_svg_() and svg.startswith("<svg")
        assert svg.count('fill="#2ca02c"') == 4  # the two actuated joints and their labels
        assert ">u1</text>" in svg and ">u2</text>" in svg
        assert f"{name}: 2 limbs, 2 actuators" in svg
        assert robot.svg([0.01, robot.home[1] - 0.02]) != svg
        with pytest.raises(ValueError, match=r"expected 2 values \[x, y\]"):
            robot.svg([0.0, 0.3, 0.0])


def test_simulate_gives_x_y_and_inverse_dynamics_gives_the_forces_back(source_dir):
    # the biglide under forces about its holding forces at home: the motion's inverse dynamics
    # (rates and accelerations by differences of the simulated x, y) gives the forces back
    robot = _robot(source_dir, "biglide")
    hold = robot.inverse_dynamics(np.array([0.0, 0.2]), np.zeros(2), np.zeros(2))[3]
    t = np.linspace(0.0, 0.2, 201)
    tau = hold + np.column_stack([0.8 * np.sin(2 * np.pi * 4 * t), -0.5 * np.sin(2 * np.pi * 6 * t)])
    motion = nocdyn.simulate({"t": t, "tau1": tau[:, 0], "tau2": tau[:, 1]},
                             robot=str(source_dir / "robots" / "biglide.yaml"), rate=10000)
    assert list(motion.columns) == ["t", "x", "y", "u1", "u2", "du1", "du2", "tau1", "tau2", "kinetic"]
    xy = np.column_stack([motion["x"], motion["y"]])
    assert np.ptp(xy[:, 0]) > 1e-3 and np.ptp(xy[:, 1]) > 1e-4
    k, h = np.arange(10, len(xy) - 10, 97), 1e-3  # samples 10 apart at 10 kHz
    P = xy[k]
    dP = (xy[k + 10] - xy[k - 10]) / (2 * h)
    ddP = (xy[k + 10] - 2 * P + xy[k - 10]) / h**2
    applied = np.column_stack([motion["tau1"], motion["tau2"]])[k]
    back = robot.inverse_dynamics(P, dP, ddP)[3]
    np.testing.assert_allclose(back, applied, atol=1e-3 * np.abs(applied).max())


def test_workspace_of_the_five_bar_is_its_tool_points_region(source_dir):
    ws = nocdyn.workspace(robot=str(source_dir / "robots" / "five-bar.yaml"), resolution=41)
    assert ws.text.startswith("The feasible region of the tool point C")
    assert 0.1 < ws.area < 0.3  # [m^2]: 0.200 at resolution 201
    with pytest.raises(nocdyn.Error, match="has no theta"):
        nocdyn.workspace(robot=str(source_dir / "robots" / "five-bar.yaml"), theta=0.1)


def test_a_compliant_two_dof_robot_names_its_first_resonance_and_its_refusals(cli, source_dir, tmp_path):
    import json

    text = (source_dir / "robots" / "five-bar.yaml").read_text()
    stiff = tmp_path / "stiff-five-bar.yaml"
    stiff.write_text(text.replace("effort: 8.0, velocity: 30.0}}", "effort: 8.0, velocity: 30.0}, stiffness: 5000.0}"))
    code, out, err = cli("pose", "0.0", "0.35", "--robot", stiff, "--json")
    assert code == 0, err
    first = json.loads(out)["first_frequency"]["value"]
    assert 10.0 < first < 1000.0
    # simulate's rigid plant names the first resonance of the task's modes at home
    forces = tmp_path / "forces.csv"
    forces.write_text("t,tau1,tau2\n0,0,0\n0.01,0,0\n")
    code, out, err = cli("simulate", "--robot", stiff, "--forces", forces, "--rate", "100")
    assert code == 0, err
    assert f"(first resonance at home {first:.4g} Hz) is not modelled" in err
    # the first natural frequency map and elastic bodies of a two-DOF robot: refused in one line
    code, _, err = cli("workspace", "--robot", stiff, "--first-frequency", "--resolution", "21")
    assert code != 0 and "first natural frequency map of a two-DOF robot" in err
    assert len(err.strip().splitlines()) == 1, err
    elastic = tmp_path / "elastic-five-bar.yaml"
    elastic.write_text(text.replace("{mass: 0.15, inertia: 7.8125e-4, com: [-0.1, 0.275]}",
                                    "{mass: 0.15, inertia: 7.8125e-4, com: [-0.1, 0.275], "
                                    "elastic: {EA: 1.0e6, EI: 20.0}}"))
    code, _, err = cli("pose", "0.0", "0.35", "--robot", elastic)
    assert code != 0 and "elastic bodies of a two-DOF robot" in err, err
    assert len(err.strip().splitlines()) == 1, err


def test_robot_stiffness_and_natural_frequencies_of_a_two_dof_robot_are_over_x_y(cli, source_dir, tmp_path):
    import json

    text = (source_dir / "robots" / "five-bar.yaml").read_text()
    stiff = tmp_path / "stiff-five-bar.yaml"
    stiff.write_text(text.replace("effort: 8.0, velocity: 30.0}}", "effort: 8.0, velocity: 30.0}, stiffness: 5000.0}"))
    robot = nocdyn.Robot.load(str(stiff))
    K = robot.stiffness([0.02, 0.3])
    f, shapes = robot.natural_frequencies([0.02, 0.3], modes=True)
    code, out, err = cli("pose", "0.02", "0.3", "--robot", stiff, "--json")
    assert code == 0, err
    report = json.loads(out)
    np.testing.assert_allclose(K, report["stiffness"]["matrix"], rtol=1e-14)
    np.testing.assert_allclose(f, report["natural_frequencies"], rtol=1e-14)
    assert K.shape == (2, 2) and f.shape == (2,) and shapes.shape == (2, 2)
    with pytest.raises(nocdyn.Error, match=r"\[x, y\]"):
        robot.stiffness([0.02, 0.3, 0.0])
    with pytest.raises(nocdyn.Error, match="elastodynamic modes of a two-DOF robot"):
        robot.natural_frequencies([0.02, 0.3], model="elastodynamic")
    with pytest.raises(nocdyn.Error, match="declares no compliance"):
        _robot(source_dir, "five-bar").stiffness([0.02, 0.3])


def test_inverse_dynamics_job_equals_robot_inverse_dynamics_on_x_y(source_dir):
    # the job (nocdyn.inverse_dynamics, the command line's) on the shipped figure eight, keyed x, y,
    # against Robot.inverse_dynamics with (N, 2) arrays at the same samples
    robot = _robot(source_dir, "five-bar")
    trajectory = nocdyn.Trajectory.load(str(source_dir / "trajectories" / "five-bar-figure-eight.yaml"))
    table = nocdyn.inverse_dynamics(trajectory, robot=robot, rate=400.0)
    assert table.columns == ["t", "x", "y", "u1", "u2", "du1", "du2", "ddu1", "ddu2", "tau1", "tau2", "kinetic"]
    assert len(table) == 200
    p, dp, ddp = trajectory.evaluate(table["t"])
    np.testing.assert_array_equal(table.data[:, 1:3], p[:, :2])
    u, du, ddu, tau = robot.inverse_dynamics(p[:, :2], dp[:, :2], ddp[:, :2])
    for name, want in (("u", u), ("du", du), ("ddu", ddu), ("tau", tau)):
        np.testing.assert_allclose(table.group(name), want, rtol=0, atol=1e-12)
    assert np.abs(tau).max() > 0.05
    # a trajectory built in code, keyed x, y, about the biglide's home
    biglide = _robot(source_dir, "biglide")
    line = nocdyn.Trajectory.harmonic(x=[(0.03, 3.0, 0.0)], y=[(0.01, 6.0, 0.5)], offset=(0.0, 0.2, 0.0),
                                      duration=0.2)
    table = nocdyn.inverse_dynamics(line, robot=biglide, rate=500.0)
    p, dp, ddp = line.evaluate(table["t"])
    tau = biglide.inverse_dynamics(p[:, :2], dp[:, :2], ddp[:, :2]).tau
    np.testing.assert_allclose(table.group("tau"), tau, rtol=0, atol=1e-12)
    # a theta that moves has no meaning for a two-DOF robot
    turning = nocdyn.Trajectory.harmonic(x=[(0.01, 2.0, 0.0)], theta=[(0.01, 2.0, 0.0)], offset=(0.0, 0.35, 0.0))
    with pytest.raises(nocdyn.Error, match="theta: not 0 throughout"):
        nocdyn.inverse_dynamics(turning, robot=robot, rate=400.0)


def test_loads_and_convert_take_the_five_bar(source_dir, tmp_path):
    path = str(source_dir / "robots" / "five-bar.yaml")
    eight = str(source_dir / "trajectories" / "five-bar-figure-eight.yaml")
    loads = nocdyn.loads(eight, robot=path, rate=400.0)
    assert "peak_force_theta" not in loads.columns and "peak_force_x" in loads.columns
    assert len(loads) == 6 and np.all(loads["peak_force"] > 0.1)
    # the peaks: the largest reaction of the same samples' inverse dynamics with --reactions
    forces = nocdyn.inverse_dynamics(eight, robot=path, rate=400.0, reactions=True)
    for limb, joint, peak in zip(loads["limb"], loads["joint"], loads["peak_force"]):
        fx, fy = forces[f"limb{limb}_j{joint}_fx"], forces[f"limb{limb}_j{joint}_fy"]
        np.testing.assert_allclose(peak, np.hypot(fx, fy).max(), rtol=1e-12)
    text = nocdyn.convert(path, output=str(tmp_path / "general.yaml"))
    assert "motion: translation" in text
    back = nocdyn.Robot.load(str(tmp_path / "general.yaml"))
    P, dP, ddP = _motion(np.array([0.01, 0.32]))
    np.testing.assert_array_equal(back.inverse_dynamics(P, dP, ddP).tau,
                                  _robot(source_dir, "five-bar").inverse_dynamics(P, dP, ddP).tau)


def test_shake_plays_one_record_on_y_of_a_five_bar_as_the_command_does(cli, source_dir, tmp_path):
    record, robot = source_dir / "data" / "elcentro_1940_ns.AT2", source_dir / "robots" / "five-bar.yaml"
    quick = {"window": 1, "plant": "nocdyn", "rate": 2000}
    r = nocdyn.shake(str(record), robot=str(robot), axis="y", **quick)
    assert list(r.columns) == ["t", "x", "y", "ax", "ay", "ax_achieved", "ay_achieved", "x_achieved", "y_achieved",
                               "u1", "u2", "tau1", "tau2"]
    np.testing.assert_array_equal(r["x"], 0.0)  # x is not driven: its target holds home
    assert set(r.metrics["metrics"]) == {"ay"}
    # the same replay through the command line: the same numbers (the sensors' noise is seeded)
    code, _, err = cli("shake", "--robot", robot, "--record", record, "--axis", "y", "--window", "1", "--plant",
                       "nocdyn", "--rate", "2000", "--out-dir", tmp_path / "cli")
    assert code == 0, err
    import json

    metrics = json.loads((tmp_path / "cli" / "shake.json").read_text())["metrics"]["ay"]
    assert r.metrics["metrics"]["ay"]["rms_error_percent"] == metrics["rms_error_percent"]
    assert 5.0 < metrics["rms_error_percent"] < 20.0  # the 0.5 kg payload unknown (measured 15.5 %)
    with pytest.raises(nocdyn.Error, match="record_theta: a two-DOF robot"):
        nocdyn.shake(str(record), robot=str(robot), record_theta=str(record), **quick)


def test_design_sweeps_a_five_bar_family_over_x_y(source_dir):
    family = str(source_dir / "examples" / "design_fivebar" / "family.yaml")
    designs = nocdyn.design(["b=0.25:0.25"], ["workspace_area", "moving_mass"], robot=family, samples=1,
                            resolution=31)
    workspace = nocdyn.workspace(robot=str(source_dir / "robots" / "five-bar.yaml"), resolution=31)
    assert designs.feasible.all()
    assert designs.column("workspace_area")[0] == pytest.approx(workspace.area, rel=1e-9)
    assert designs.column("moving_mass")[0] == pytest.approx(1.1, rel=1e-12)
    with pytest.raises(nocdyn.Error, match="envelope_theta@20.*has no theta"):
        nocdyn.design(["b=0.2:0.3"], ["envelope_theta@20"], robot=family, samples=2, resolution=21)


def test_shake_takes_a_records_component_files_as_one_record(source_dir):
    folder = source_dir / "data" / "records3"
    components = [str(folder / f"RSN1690_NORTH151_SYL{c}.AT2") for c in ("-UP", "360-hor2", "090-hor1")]
    quick = {"window": 1, "plant": "nocdyn", "rate": 2000}
    with pytest.warns(RuntimeWarning, match="SYL-UP.AT2: the vertical component is not replayed"):
        r = nocdyn.shake(components, robot=str(source_dir / "robots" / "five-bar.yaml"), **quick)
    assert set(r.metrics["metrics"]) == {"ax", "ay"}  # x east (090), y north (360): both driven
    assert np.ptp(r["ax"]) > 0.02 and np.ptp(r["ay"]) > 0.02  # [m/s^2] in the first second
    # two records' components are a suite, which returns no samples: refused before it runs
    both = components + [str(folder / "RSN6_IMPVALL.I_I-ELC180-hor1.AT2"),
                         str(folder / "RSN6_IMPVALL.I_I-ELC270-hor2.AT2")]
    with pytest.raises(ValueError, match="is a suite of records"):
        nocdyn.shake(both, robot=str(source_dir / "robots" / "five-bar.yaml"), **quick)


def test_envelope_frequency_response_and_control_of_a_two_dof_robot_are_over_x_y(cli, source_dir, tmp_path):
    import json

    five_bar = source_dir / "robots" / "five-bar.yaml"
    table = nocdyn.envelope(robot=str(five_bar), points=2, min_frequency=1.0, max_frequency=50.0)
    assert sorted(set(table["axis"])) == ["x", "y"] and len(table["axis"]) == 4
    # with springs at the motors the band's third bound is the task's first mode (pose's number)
    text = five_bar.read_text()
    stiff = tmp_path / "stiff-five-bar.yaml"
    stiff.write_text(text.replace("effort: 8.0, velocity: 30.0}}", "effort: 8.0, velocity: 30.0}, stiffness: 5000.0}"))
    code, out, err = cli("pose", "0.0", "0.35", "--robot", stiff, "--json")
    assert code == 0, err
    first = json.loads(out)["first_frequency"]["value"]
    band = nocdyn.envelope(robot=str(stiff), points=2, min_frequency=1.0, max_frequency=50.0)
    assert band.first_natural_frequency == pytest.approx(first, rel=1e-12)
    assert sorted(band.band_end) == ["x", "y"]
    assert all(0.0 < f < first for f in band.band_end.values())
    # the plant over x, y: 2 x 2 channels; a theta value refused
    plant = nocdyn.frequency_response(robot=str(five_bar), pose=[0.02, 0.3], points=3, compliance="rigid")
    assert [c for c in plant.columns if c.endswith("_db")] == ["ddx_tau1_db", "ddx_tau2_db", "ddy_tau1_db",
                                                                "ddy_tau2_db"]
    with pytest.raises(nocdyn.Error, match="no theta"):
        nocdyn.frequency_response(robot=str(five_bar), pose=[0.0, 0.3, 0.0], points=3)
    circle = tmp_path / "circle.yaml"
    circle.write_text("duration: 0.2\nx: {harmonics: [{amplitude: 0.01, frequency: 2, phase: 1.5707963267948966}]}\n"
                      "y: {offset: 0.35, harmonics: [{amplitude: 0.01, frequency: 2}]}\n")
    run = nocdyn.control(str(circle), robot=str(five_bar), plant="nocdyn", rate=2000.0, natural_frequency=20.0)
    assert list(run.columns[:7]) == ["t", "x_d", "y_d", "x", "y", "e_x", "e_y"]
    assert np.abs(run["e_x"]).max() < 1e-5 and np.abs(run["e_y"]).max() < 1e-5
    with pytest.raises(nocdyn.Error, match="plant nocdyn"):
        nocdyn.control(str(circle), robot=str(five_bar), plant="simbody")
    # no plant given: nocdyn's, the same run
    default = nocdyn.control(str(circle), robot=str(five_bar), rate=2000.0, natural_frequency=20.0)
    np.testing.assert_array_equal(default["e_x"], run["e_x"])
    code, out, err = cli("control", "--robot", five_bar, "--trajectory", circle, "--rate", "2000")
    assert code == 0, err
    assert "on the nocdyn forward dynamics plant" in out


def test_identify_gives_a_point_payloads_mass_within_its_standard_deviation(source_dir, tmp_path):
    # the five-bar's log with 0.2 kg more at its tool point (exact u, du, ddu from the loaded
    # robot's inverse dynamics, forces with Gaussian noise), identified against the shipped file
    text = (source_dir / "robots" / "five-bar.yaml").read_text()
    assert "platform: {mass: 0.3}" in text
    loaded = tmp_path / "five-bar-loaded.yaml"
    loaded.write_text(text.replace("platform: {mass: 0.3}", "platform: {mass: 0.5}"))
    robot = nocdyn.Robot.load(str(loaded))
    t = np.linspace(0.0, 0.5, 1000)  # the times of _motion's samples
    P, dP, ddP = _motion(np.array([0.0, 0.35]), len(t))
    P, dP, ddP = (np.ascontiguousarray(a) for a in (P, dP, ddP))
    u, du, ddu, tau = robot.inverse_dynamics(P, dP, ddP)
    tau = tau + 2e-3 * np.random.default_rng(5).standard_normal(tau.shape)
    columns = {"t": t}
    for name, values in (("u", u), ("du", du), ("ddu", ddu), ("tau", tau)):
        for a in range(2):
            columns[f"{name}{a + 1}"] = values[:, a]
    result = nocdyn.identify(columns, robot=str(source_dir / "robots" / "five-bar.yaml"))
    e = result.payload_estimate
    assert 0.0 < e.mass_sd < 2e-3
    assert abs(e.mass - 0.2) <= 3 * e.mass_sd, (e.mass, e.mass_sd)
    assert result.payload["mass"] == e.mass
    assert list(e.com) == [0.0, 0.0] and e.inertia == 0.0  # a point mass: not identified
    assert e.covariance.shape == (1, 1)
    assert "payload: {mass: " in result.text and "com:" not in result.text
    assert "point mass at the tool point" in result.text
    with pytest.raises(nocdyn.Error, match="only its mass is identified"):
        nocdyn.identify(columns, robot=str(source_dir / "robots" / "five-bar.yaml"), prior={"com_x": (-0.01, 0.01)})


@pytest.mark.parametrize("name, center", [("five-bar", [0.01, 0.32]), ("biglide", [0.0, 0.17])])
def test_regressor_times_the_standard_parameters_is_the_inverse_dynamics(source_dir, name, center):
    robot = _robot(source_dir, name)
    P, dP, ddP = _motion(np.array(center), 50)
    tau = robot.inverse_dynamics(P, dP, ddP)[3]
    Y = robot.regressor(P, dP, ddP)
    assert Y.shape == (50 * 2, len(robot.parameter_names()))
    np.testing.assert_allclose(Y @ robot.standard_parameters(), tau.reshape(-1), rtol=0, atol=1e-12 * np.abs(tau).max())
    np.testing.assert_array_equal(robot.regressor(P[7], dP[7], ddP[7]), Y[14:16])
    inert = [robot.parameter_names().index(f"platform.{c}") for c in ("mc_x", "mc_y", "I_O")]
    assert np.all(Y[:, inert] == 0.0)


def test_excite_moves_x_y_and_animate_draws_it(source_dir, tmp_path):
    # the design for the five-bar's point payload and its motors' friction: x, y harmonics only,
    # a finite condition number reported; its animation's frames hold 2 limbs x 3 joints + C
    path = str(source_dir / "robots" / "five-bar.yaml")
    e = nocdyn.excite(robot=path, friction=True, duration=1, base_frequency=1, harmonics=3, random_shapes=10, evaluations=30)
    assert e.trajectory.harmonics("theta") == (0.0, [])  # (offset, harmonics): at home, still
    assert len(e.trajectory.harmonics("x")[1]) > 0 and len(e.trajectory.harmonics("y")[1]) > 0
    designed = [line for line in e.text.splitlines() if line.startswith("designed: {condition_number: ")]
    assert len(designed) == 1
    assert 1.0 <= float(designed[0].split("condition_number: ")[1].split(",")[0]) < 100.0
    trajectory = tmp_path / "excitation.yaml"
    trajectory.write_text(e.yaml)
    page = nocdyn.animate(str(trajectory), robot=path, rate=100).html
    assert '"stride":14' in page


def test_the_docs_table_of_commands_by_family_names_every_command(source_dir):
    import re

    text = (source_dir / "docs" / "commands" / "index.md").read_text()
    table = text[text.index("## Commands by robot family"):text.index("```{toctree}")]
    listed = {name for row in table.splitlines() if row.startswith("| `")
              for name in re.findall(r"`([a-z-]+)`", row.split("|")[1])}
    assert listed == set(nocdyn.COMMANDS)


def _three_armed_five_bar(source_dir):
    """The five-bar with a third arm on a motor below the tool: three actuators on two
    coordinates (minimum-norm torques)."""
    text = (source_dir / "robots" / "five-bar.yaml").read_text()
    third = """  - name: middle
    joints:
      - {type: R, point: [0.0, -0.1], actuated: true,
         limits: {lower: -1.5, upper: 1.5, effort: 8.0, velocity: 30.0}}
      - {type: R, point: [0.15, 0.15]}
      - {type: R, point: [0.0, 0.35]}
    bodies:
      - {mass: 0.25, inertia: 2.0e-3, com: [0.075, 0.025]}
      - {mass: 0.15, inertia: 7.8125e-4, com: [0.075, 0.25]}
"""
    return nocdyn.Robot.from_yaml(text.rstrip("\n") + "\n" + third)


@pytest.mark.parametrize("name", ["five-bar", "biglide", "three-armed"])
def test_derivatives_of_a_two_dof_robot_are_its_finite_differences_over_x_y(source_dir, name):
    robot = _three_armed_five_bar(source_dir) if name == "three-armed" else _robot(source_dir, name)
    center = np.array([0.0, 0.17]) if name == "biglide" else np.array([0.02, 0.3])
    P, dP, ddP = _motion(center, n=5)
    d_p, d_dp, d_ddp = robot.inverse_dynamics_derivatives(P, dP, ddP)
    n = robot.actuators
    assert d_p.shape == d_dp.shape == d_ddp.shape == (5, n, 2)
    actuators = robot.actuator_derivatives(P[2], dP[2], ddP[2])
    assert actuators.u_p.shape == (n, 2)
    h = 1e-6
    for k in range(5):
        one = robot.inverse_dynamics_derivatives(P[k], dP[k], ddP[k])
        for batch, sample in zip((d_p, d_dp, d_ddp), one):
            np.testing.assert_array_equal(batch[k], sample)
        for which, exact in enumerate((d_p[k], d_dp[k], d_ddp[k])):
            for j in range(2):
                step = np.zeros(2)
                step[j] = h
                plus = [P[k].copy(), dP[k].copy(), ddP[k].copy()]
                minus = [P[k].copy(), dP[k].copy(), ddP[k].copy()]
                plus[which] += step
                minus[which] -= step
                difference = (robot.inverse_dynamics(*plus).tau - robot.inverse_dynamics(*minus).tau) / (2 * h)
                scale = max(1.0, np.abs(difference).max())
                np.testing.assert_allclose(exact[:, j], difference, rtol=0, atol=1e-6 * scale)
    # d u/d p of the actuator variables: A over x, y (du = A dp)
    np.testing.assert_allclose(actuators.u_p, nocdyn.pose(*P[2], robot=robot).A, rtol=1e-12, atol=1e-12)
