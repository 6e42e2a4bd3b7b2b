"""One vocabulary for Python and the command line: a pose is [x, y, theta] (the CSV tables'
column order), limbs, joints and actuators are numbered from 1, and Robot.inverse_dynamics checks
the joint ranges, velocities and efforts as `nocdyn inverse-dynamics` does."""

import csv
import pathlib

import numpy as np
import pytest

import nocdyn


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    data = np.array([[float(v) for v in row] for row in rows[1:]])
    return rows[0], data


def columns(header, data, names):
    return data[:, [header.index(name) for name in names]]


def test_the_cli_csvs_pose_columns_in_file_order_give_its_forces(tmp_path, cli, source_dir):
    """The pose columns of a CSV written by `nocdyn inverse-dynamics`, taken in the file's order
    x, y, theta, with the rates and accelerations of the same trajectory (the CSV has none), go
    into Robot.inverse_dynamics unchanged and give the CSV's forces to 1e-12 of each column's
    peak (measured: 2.1e-15; the batch's lean kernel against the CLI's full path)."""
    robot_path = source_dir / "robots" / "3-rrr.yaml"
    out = tmp_path / "id.csv"
    code, _, err = cli("inverse-dynamics", "--robot", robot_path, "--trajectory", "paper1", "--duration", 0.05,
                       "--output", out)
    assert code == 0, err
    header, data = read_csv(out)
    pose = [name for name in header if name in ("x", "y", "theta")]
    assert pose == ["x", "y", "theta"], header
    P = columns(header, data, pose)
    t = data[:, header.index("t")]
    P_traj, dP, ddP = nocdyn.Trajectory.paper(1).evaluate(t)
    np.testing.assert_array_equal(P_traj, P)  # the trajectory's columns are the file's, in its order
    robot = nocdyn.Robot.load(robot_path)
    n = robot.actuators
    tau_csv = columns(header, data, [f"tau{i + 1}" for i in range(n)])
    u_csv = columns(header, data, [f"u{i + 1}" for i in range(n)])
    peak = np.max(np.abs(tau_csv), axis=0)
    assert np.all(peak > 0.1)
    batch = robot.inverse_dynamics(P, dP, ddP)
    assert np.all(np.abs(batch.tau - tau_csv) <= 1e-12 * peak)
    np.testing.assert_allclose(batch.u, u_csv, rtol=0, atol=1e-15)
    # one sample at a time: the same pose order through the single-sample path
    for k in range(0, len(t), 97):
        one = robot.inverse_dynamics(P[k], dP[k], ddP[k])
        assert np.all(np.abs(one.tau - tau_csv[k]) <= 1e-12 * peak)
    # Fortran order: the gathers' other branch reads the same columns
    fortran = robot.inverse_dynamics(*(np.asfortranarray(a) for a in (P, dP, ddP)))
    np.testing.assert_array_equal(fortran.tau, batch.tau)
    # the command line's own code from Python writes the same columns in the same order
    sampled = nocdyn.inverse_dynamics(nocdyn.Trajectory.paper(1), robot=robot, rate=10000, duration=0.05)
    np.testing.assert_array_equal(np.column_stack([sampled["x"], sampled["y"], sampled["theta"]]), P)
    # and a swapped order gives other forces: the test sees the order
    swapped = robot.inverse_dynamics(P[:, [2, 0, 1]], dP[:, [2, 0, 1]], ddP[:, [2, 0, 1]], check=False,
                                     check_limits=False)
    assert not np.allclose(swapped.tau, tau_csv, rtol=0, atol=1e-3 * peak.max(), equal_nan=False)


def test_column_zero_of_a_pose_is_x():
    """Moving the pose's column 0 moves C along x: the direct kinematics of the actuator values
    gives the pose back with x changed, and the home pose of the paper's robot is its file's."""
    robot = nocdyn.Robot.paper()
    p = robot.home + np.array([0.003, -0.001, 0.02])
    u = robot.inverse_dynamics(p, np.zeros(3), np.zeros(3)).u
    poses = [m["pose"] for m in robot.forward_kinematics(u) if m["working"]]
    assert any(np.max(np.abs(q - p)) <= 1e-9 for q in poses)
    # d u / d x of the paper's 3-PRR at home: actuator 1's rail is along x (phi_1 = 0, eq. 8)
    d_p, _, _ = robot.inverse_dynamics_derivatives(robot.home, np.zeros(3), np.zeros(3))
    A, _ = robot.linearize(robot.home, np.zeros(3), np.zeros(3))
    np.testing.assert_array_equal(A[:3, 3:], np.eye(3))
    h = 1e-7
    du_dx = (robot.inverse_dynamics(robot.home + [h, 0, 0], np.zeros(3), np.zeros(3)).u -
             robot.inverse_dynamics(robot.home - [h, 0, 0], np.zeros(3), np.zeros(3)).u) / (2 * h)
    assert du_dx[0] == pytest.approx(1.0, abs=1e-6)
    theta = nocdyn.Trajectory.harmonic(offset=(0.0, 0.0, 0.01)).evaluate([0.0])[0]
    np.testing.assert_array_equal(theta, [[0.0, 0.0, 0.01]])
    assert d_p.shape == (3, 3)


def test_actuator_info_numbers_limbs_and_joints_from_1_as_the_cli(tmp_path, cli, source_dir):
    """3-RPR: actuator a + 1 is the leg, joint 2 of limb a + 1; the CLI names the same joint
    'limb 1, joint 2' when its range is exceeded."""
    robot = nocdyn.Robot.example("3-rpr")
    info = robot.actuator_info()
    assert [(a["limb"], a["joint"], a["type"]) for a in info] == [(1, 2, "P"), (2, 2, "P"), (3, 2, "P")]
    paper = nocdyn.Robot.paper()
    assert [(a["limb"], a["joint"]) for a in paper.actuator_info()] == [(1, 1), (2, 1), (3, 1)]
    # the leg of limb 1 beyond its 30 mm: the same numbers in the CLI's message and in Python's
    upper = info[0]["upper"]
    p = np.array([0.0, -0.05, 0.0])  # C 50 mm towards limb 1's base pivot shortens its leg
    with pytest.raises(nocdyn.Error, match=r"joint range exceeded: limb 1, joint 2: ") as error:
        robot.inverse_dynamics(p, np.zeros(3), np.zeros(3))
    u = robot.inverse_dynamics(p, np.zeros(3), np.zeros(3), check_limits=False).u
    assert abs(u[0]) > upper
    trajectory = tmp_path / "still.yaml"
    trajectory.write_text(f"name: still\nduration: 0.001\nx: {{offset: {p[0]!r}, harmonics: []}}\n"
                          f"y: {{offset: {p[1]!r}, harmonics: []}}\n")
    code, _, err = cli("inverse-dynamics", "--robot", source_dir / "robots" / "3-rpr.yaml", "--trajectory",
                       trajectory, "--output", tmp_path / "out.csv")
    assert code != 0
    assert f"t = 0 s: {error.value}" in err


def test_envelope_numbers_from_1_and_0_where_not_applicable(paper_robot):
    table = nocdyn.envelope(robot=paper_robot, min_frequency=5, max_frequency=50, points=2, progress=False)
    points = [{column: table[column][k] for column in table.columns} for k in range(len(table))]
    for point in points:
        for key in ("limb", "joint", "actuator"):
            assert int(point[key]) == point[key] and 0 <= point[key] <= 3
        if point["limit"] in ("range", "effort"):
            assert point["limb"] >= 1 and point["joint"] >= 1 and point["actuator"] >= 1
        if point["limit"] == "none":
            assert point["limb"] == point["joint"] == point["actuator"] == 0
    assert any(point["limit"] in ("range", "effort") for point in points)


def still_trajectory_error(robot, p):
    """The command line's reason (from its own sampling code) at the constant pose p."""
    still = nocdyn.Trajectory.harmonic(offset=tuple(p), duration=1e-3)
    with pytest.raises(nocdyn.Error) as error:
        nocdyn.inverse_dynamics(still, robot=robot, rate=10000)
    message = str(error.value)
    assert message.startswith("t = 0 s: ")
    return message[len("t = 0 s: "):]


def test_check_limits_refuses_a_range_a_velocity_and_an_effort_as_the_cli(paper_robot):
    """check_limits (default True) raises the command line's reason for one sample and names the
    first sample of a batch; check_limits=False computes the numbers regardless."""
    robot = paper_robot
    z = np.zeros(3)
    beyond = robot.home + [0.02, 0.0, 0.0]  # actuator 1 at 20 mm on a 12.45 mm range
    with pytest.raises(nocdyn.Error) as error:
        robot.inverse_dynamics(beyond, z, z)
    assert str(error.value) == still_trajectory_error(robot, beyond)
    assert str(error.value).startswith("joint range exceeded: limb 1, joint 1: q = 0.02")
    u = robot.inverse_dynamics(beyond, z, z, check_limits=False).u
    assert u[0] == pytest.approx(0.02, abs=1e-15)
    # a batch: the first sample beyond, the same reason
    P = np.tile(robot.home, (9, 1))
    P[:, 0] = np.linspace(0.0, 0.004, 9)
    P[5] = beyond
    P[7] = beyond
    Z = np.zeros_like(P)
    with pytest.raises(nocdyn.Error) as batch_error:
        robot.inverse_dynamics(P, Z, Z)
    assert str(batch_error.value) == f"sample 6: {error.value}"
    unchecked = robot.inverse_dynamics(P, Z, Z, check_limits=False)
    assert np.all(np.isfinite(unchecked.u)) and unchecked.u[5, 0] == pytest.approx(0.02, abs=1e-15)
    # an effort: 262 N at most, an acceleration of 1000 m/s^2 needs more
    ddp = np.array([1000.0, 0.0, 0.0])
    with pytest.raises(nocdyn.Error, match=r"^actuator effort limit exceeded: actuator 1 \(limb 1, joint 1\)") as effort:
        robot.inverse_dynamics(robot.home, z, ddp)
    Zdd = np.zeros_like(P[:4])
    Zdd[2] = ddp
    with pytest.raises(nocdyn.Error) as batch_effort:
        robot.inverse_dynamics(np.tile(robot.home, (4, 1)), Z[:4], Zdd)
    assert str(batch_effort.value) == f"sample 3: {effort.value}"
    # a velocity: the 3-RPR's legs at most 1 m/s
    rpr = nocdyn.Robot.example("3-rpr")
    fast = np.array([0.0, 2.0, 0.0])
    with pytest.raises(nocdyn.Error, match=r"^joint velocity limit exceeded: limb 1, joint 2: ") as velocity:
        rpr.inverse_dynamics(rpr.home, fast, z)
    with pytest.raises(nocdyn.Error) as batch_velocity:
        rpr.inverse_dynamics(np.tile(rpr.home, (3, 1)), np.array([z, z, fast]), np.zeros((3, 3)))
    assert str(batch_velocity.value) == f"sample 3: {velocity.value}"
    # the reactions check the same limits by the full path
    with pytest.raises(nocdyn.Error) as reactions_error:
        robot.reactions(P, Z, Z)
    assert str(reactions_error.value) == f"sample 6: {error.value}"
    assert np.all(np.isfinite(robot.reactions(P, Z, Z, check_limits=False)))


def test_a_passive_joints_range_is_checked_by_the_full_path_in_a_batch(source_dir):
    """A range on a passive joint (limb 1's base pivot of a 3-RPR): the batch's check from u, du,
    tau cannot see it, so it takes the full path at every sample, with the single sample's reason."""
    text = (source_dir / "robots" / "3-rpr.yaml").read_text()
    limited = text.replace("{type: R, point: [0.0, -0.2]}",
                           "{type: R, point: [0.0, -0.2], limits: {lower: -0.01, upper: 0.01}}", 1)
    assert limited != text
    robot = nocdyn.Robot.from_yaml(limited, "limited.yaml")
    z = np.zeros(3)
    beyond = robot.home + [0.005, 0.0, 0.0]
    with pytest.raises(nocdyn.Error, match=r"^joint range exceeded: limb 1, joint 1: ") as error:
        robot.inverse_dynamics(beyond, z, z)
    P = np.tile(robot.home, (6, 1))
    P[4] = beyond
    with pytest.raises(nocdyn.Error) as batch_error:
        robot.inverse_dynamics(P, np.zeros_like(P), np.zeros_like(P))
    assert str(batch_error.value) == f"sample 5: {error.value}"
    free = robot.inverse_dynamics(P, np.zeros_like(P), np.zeros_like(P), check_limits=False)
    reference = nocdyn.Robot.from_yaml(text).inverse_dynamics(P, np.zeros_like(P), np.zeros_like(P))
    np.testing.assert_array_equal(free.u, reference.u)


def test_the_vocabulary_is_stated_where_poses_are_taken():
    sentence = "a pose is [x, y, theta]"
    assert sentence in nocdyn.Robot.__doc__
    for method in ("inverse_dynamics", "inverse_dynamics_derivatives", "actuator_derivatives", "linearize", "reactions",
                   "regressor", "forward_kinematics", "state_from_actuators", "stiffness", "natural_frequencies"):
        assert sentence in getattr(nocdyn.Robot, method).__doc__, method
    assert sentence in nocdyn.Trajectory.evaluate.__doc__ and sentence in nocdyn.Trajectory.harmonic.__doc__
    docs = pathlib.Path(__file__).resolve().parents[2] / "docs" / "python.md"
    assert "## Vocabulary" in docs.read_text()
