"""Two-DOF planar robots (motion: translation, pose [x, y] of a point tool): the shipped five-bar
and biglide through Robot.inverse_dynamics with arrays of shape (N, 2), `nocdyn pose X Y`, and
`nocdyn forward-kinematics U1 U2` (poses x, y), `nocdyn.simulate` (columns t, x, y, ...),
`nocdyn.workspace`, `nocdyn.identify` (a point payload: its mass), and the one-line refusal of the
commands that do not take them yet."""

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


@pytest.mark.parametrize("command", [["inverse-dynamics", "--trajectory", "paper1"],
                                     ["loads", "--trajectory", "paper1"], ["control", "--trajectory", "paper1"],
                                     ["envelope"], ["frequency-response"], ["convert"]])
def test_other_commands_refuse_two_dof_robots_in_one_line(cli, source_dir, tmp_path, command):
    forces = tmp_path / "forces.csv"
    forces.write_text("t,tau1,tau2\n0,0,0\n0.1,0,0\n")
    command = [str(forces) if c == "FORCES" else c for c in command]
    code, out, err = cli(*command, "--robot", source_dir / "robots" / "five-bar.yaml")
    assert code != 0
    assert "five-bar.yaml: a two-DOF robot (motion: translation" in err
    assert len(err.strip().splitlines()) == 1, err


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


def test_robot_methods_that_do_not_take_two_dof_robots_refuse_them(source_dir):
    robot = _robot(source_dir, "five-bar")
    p, z = np.array([0.0, 0.3, 0.0]), np.zeros(3)
    calls = {
        "svg": lambda: robot.svg(),
        "with_payload": lambda: robot.with_payload(0.1),
        "forward_kinematics": lambda: robot.forward_kinematics(np.zeros(2)),
        "state_from_actuators": lambda: robot.state_from_actuators(np.zeros(2)),
        "inverse_dynamics_derivatives": lambda: robot.inverse_dynamics_derivatives(p, z, z),
        "reactions": lambda: robot.reactions(p, z, z),
    }
    for name, call in calls.items():
        with pytest.raises(nocdyn.Error, match=f"{name}: a two-DOF robot"):
            call()
    assert robot._repr_svg_() is None


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
    e = nocdyn.excite(robot=path, friction=True, duration=1, frequency=1, harmonics=3, random=10, evaluations=30)
    assert e.trajectory.harmonics("theta") == (0.0, [])  # (offset, harmonics): at home, still
    assert len(e.trajectory.harmonics("x")[1]) > 0 and len(e.trajectory.harmonics("y")[1]) > 0
    designed = [line for line in e.text.splitlines() if line.startswith("designed: {condition_number: ")]
    assert len(designed) == 1
    assert 1.0 <= float(designed[0].split("condition_number: ")[1].split(",")[0]) < 100.0
    trajectory = tmp_path / "excitation.yaml"
    trajectory.write_text(e.yaml)
    page = nocdyn.animate(str(trajectory), robot=path, rate=100).html
    assert '"stride":14' in page
