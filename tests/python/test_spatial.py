"""Spatial robots from Python: nocdyn.Robot.load of a spatial file gives a SpatialRobot whose
inverse_dynamics takes (N, 6) or (N, 3) samples (the identities themselves are checked in C++,
tests/spatial_dynamics_test.cpp)."""

import pathlib
import re
import shutil
import tempfile

import numpy as np
import pytest

import nocdyn
from conftest import skip_or_fail_in_ci


def _load(source_dir, name):
    return nocdyn.Robot.load(source_dir / "robots" / f"{name}.yaml")


@pytest.mark.parametrize("name, d", [("stewart", 6), ("hexa-6rus", 6), ("delta", 3)])
def test_a_spatial_file_loads_as_a_spatial_robot_with_its_pose_coordinates(source_dir, name, d):
    robot = _load(source_dir, name)
    assert isinstance(robot, nocdyn.SpatialRobot)
    assert robot.task_dimension == d and robot.actuators == d
    assert robot.coordinates == ["x", "y", "z", "roll", "pitch", "yaw"][:d]
    assert robot.home.shape == (d,)
    text = (source_dir / "robots" / f"{name}.yaml").read_text()
    assert nocdyn.Robot.from_yaml(text, "x.yaml").limb_names == robot.limb_names
    # the planar files still give the planar Robot
    assert isinstance(nocdyn.Robot.load(source_dir / "robots" / "3-rrr.yaml"), nocdyn.Robot)


def _motion(home, n, rng):
    d = home.shape[0]
    t = np.linspace(0.0, 0.5, n)[:, None]
    amp = np.where(np.arange(d) < 3, 0.02, 0.03) * (1.0 + rng.random(d))
    w = 2.0 * np.pi * (1.0 + rng.random(d))
    P = home + amp * np.sin(w * t)
    return P, amp * w * np.cos(w * t), -amp * w * w * np.sin(w * t)


@pytest.mark.parametrize("name", ["stewart", "hexa-6rus", "delta"])
def test_a_batch_equals_one_sample_at_a_time(source_dir, name):
    robot = _load(source_dir, name)
    P, dP, ddP = _motion(robot.home, 40, np.random.default_rng(3))
    # a brisk motion: the Stewart table's legs pass their 0.5 m/s, which is not the point here
    batch = robot.inverse_dynamics(P, dP, ddP, check_limits=False)
    assert all(x.shape == (40, robot.actuators) for x in batch)
    for k in (0, 17, 39):
        one = robot.inverse_dynamics(P[k], dP[k], ddP[k], check_limits=False)
        for a, b in zip(one, batch):
            np.testing.assert_allclose(a, b[k], rtol=1e-12, atol=1e-12)
    assert np.all(np.isfinite(batch.tau))



@pytest.mark.parametrize("threads", [2, 0])
def test_a_threaded_batch_gives_the_arrays_of_one_thread_and_the_same_first_failure(source_dir, threads):
    robot = _load(source_dir, "hexa-6rus")  # cranks and rods of fixed lengths: a reach
    P, dP, ddP = _motion(robot.home, 203, np.random.default_rng(5))
    one = robot.inverse_dynamics(P, dP, ddP, check_limits=False, threads=1)
    many = robot.inverse_dynamics(P, dP, ddP, check_limits=False, threads=threads)
    assert np.all(np.isfinite(one.tau)) and np.abs(one.tau).max() > 1.0
    for a, b in zip(one, many):
        np.testing.assert_array_equal(a, b)
    # two samples 10 m out of reach, one in each half of threads=2's split: the first is raised
    P[[100, 180], 0] += 10.0
    with pytest.raises(nocdyn.Error, match=r"^sample 101: pose out of reach"):
        robot.inverse_dynamics(P, dP, ddP, check_limits=False, threads=threads)
    loose = robot.inverse_dynamics(P, dP, ddP, check=False, check_limits=False, threads=threads)
    assert np.isnan(loose.tau[[100, 180]]).all()
    rows = np.ones(203, bool)
    rows[[100, 180]] = False
    np.testing.assert_array_equal(loose.u[rows], one.u[rows])
    with pytest.raises(TypeError):
        robot.inverse_dynamics(P, dP, ddP, threads=True)
    with pytest.raises(nocdyn.Error, match=r"threads: -1 is not in"):
        robot.inverse_dynamics(P, dP, ddP, threads=-1)

def test_the_legs_of_a_hexapod_with_massless_legs_hold_its_table_by_virtual_work(source_dir):
    # legs of no mass: at rest, tau . du/dz = m g (the table rises by dz), and the same for a
    # roll: tau . du/droll = the weight's moment about the x axis through the pose point
    text = (source_dir / "robots" / "stewart.yaml").read_text()
    text = re.sub(r"\{mass: (25|8)\.0, com", "{mass: 0.0, com", text)
    robot = nocdyn.Robot.from_yaml(text, "massless-legs.yaml")
    p = robot.home + np.array([0.01, -0.02, 0.03, 0.02, -0.01, 0.05])
    zero = np.zeros(6)
    tau = robot.inverse_dynamics(p, zero, zero).tau
    h = 1e-6

    def du(i):
        e = np.zeros(6)
        e[i] = h
        return (robot.inverse_dynamics(p + e, zero, zero).u - robot.inverse_dynamics(p - e, zero, zero).u) / (2 * h)

    m, g = 300.0, 9.81
    np.testing.assert_allclose(tau @ du(2), m * g, rtol=1e-7)
    np.testing.assert_allclose(tau @ du(0), 0.0, atol=1e-6 * m * g)
    # the c.o.m. (0, 0, 0.05) in the platform frame: its height changes with roll and pitch
    def com_z(q):
        c, s = np.cos, np.sin
        roll, pitch, yaw = q[3:]
        R = (np.array([[c(yaw), -s(yaw), 0], [s(yaw), c(yaw), 0], [0, 0, 1]])
             @ np.array([[c(pitch), 0, s(pitch)], [0, 1, 0], [-s(pitch), 0, c(pitch)]])
             @ np.array([[1, 0, 0], [0, c(roll), -s(roll)], [0, s(roll), c(roll)]]))
        return q[2] + (R @ np.array([0.0, 0.0, 0.05]))[2]
    for i in (3, 4, 5):
        e = np.zeros(6)
        e[i] = h
        dz = (com_z(p + e) - com_z(p - e)) / (2 * h)
        np.testing.assert_allclose(tau @ du(i), m * g * dz, atol=1e-6 * m * g * 0.05)


def test_the_delta_at_home_shares_its_weight_equally(source_dir):
    robot = _load(source_dir, "delta")
    out = robot.inverse_dynamics(robot.home, np.zeros(3), np.zeros(3))
    np.testing.assert_allclose(out.tau, out.tau[0], rtol=1e-12)
    assert out.tau[0] != 0.0
    # the arms' crank angles in closed form: zero at home to round-off
    np.testing.assert_allclose(out.u, np.zeros(3), rtol=0, atol=1e-15)


def test_wrong_shapes_and_unreachable_samples_are_refused_with_their_number(source_dir):
    robot = _load(source_dir, "delta")
    P = np.tile(robot.home, (4, 1))
    Z = np.zeros_like(P)
    with pytest.raises(nocdyn.Error, match=r"p: expected shape \(N, 3\)"):
        robot.inverse_dynamics(np.zeros((4, 6)), Z, Z)
    with pytest.raises(nocdyn.Error, match=r"dp: expected shape \(4, 3\)"):
        robot.inverse_dynamics(P, Z[:3], Z)
    P[2, 2] -= 0.6  # 1.4 m below the base: beyond the arms
    with pytest.raises(nocdyn.Error, match=r"^sample 3: pose out of reach: limb 1 \(arm1\) cannot close"):
        robot.inverse_dynamics(P, Z, Z)
    out = robot.inverse_dynamics(P, Z, Z, check=False)
    assert np.isnan(out.tau[2]).all() and np.isfinite(out.tau[[0, 1, 3]]).all()
    with pytest.raises(TypeError):
        robot.inverse_dynamics(P.astype(np.float32), Z, Z)


# --- nocdyn.inverse_dynamics of a spatial robot along a trajectory file -----------------------

def _pick(t):
    """trajectories/delta-pick.yaml and its exact derivatives: x = 0.1 sin(2 pi t),
    z = -0.8 + 0.025 sin(4 pi t + pi/2)."""
    w, v = 2.0 * np.pi, 4.0 * np.pi
    zero = np.zeros_like(t)
    p = np.column_stack([0.1 * np.sin(w * t), zero, -0.8 + 0.025 * np.sin(v * t + np.pi / 2)])
    dp = np.column_stack([0.1 * w * np.cos(w * t), zero, 0.025 * v * np.cos(v * t + np.pi / 2)])
    ddp = np.column_stack([-0.1 * w * w * np.sin(w * t), zero, -0.025 * v * v * np.sin(v * t + np.pi / 2)])
    return p, dp, ddp


def test_the_trajectory_job_of_a_spatial_robot_equals_its_inverse_dynamics(source_dir):
    robot = _load(source_dir, "delta")
    trajectory = source_dir / "trajectories" / "delta-pick.yaml"
    table = nocdyn.inverse_dynamics(trajectory, robot=robot, duration=0.3, rate=100, progress=False)
    assert table.columns == ["t", "x", "y", "z", "u1", "u2", "u3", "du1", "du2", "du3", "ddu1", "ddu2", "ddu3",
                             "tau1", "tau2", "tau3", "kinetic"]
    t = table["t"]
    assert len(t) == 30 and np.array_equal(t, np.arange(30) / 100.0)
    p, dp, ddp = _pick(t)
    np.testing.assert_allclose(np.column_stack([table["x"], table["y"], table["z"]]), p, rtol=0, atol=1e-15)
    expected = robot.inverse_dynamics(p, dp, ddp)
    for name in ("u", "du", "ddu", "tau"):
        got = np.column_stack([table[f"{name}{a}"] for a in (1, 2, 3)])
        np.testing.assert_allclose(got, getattr(expected, name), rtol=1e-12, atol=1e-12, err_msg=name)
    # the file's path does the same as the loaded robot
    by_path = nocdyn.inverse_dynamics(trajectory, robot=source_dir / "robots" / "delta.yaml", duration=0.3, rate=100,
                                      progress=False)
    assert by_path.columns == table.columns and np.array_equal(by_path.data, table.data)


def test_a_hexapod_takes_a_csv_of_samples_and_its_table_has_six_pose_columns(source_dir, tmp_path):
    robot = _load(source_dir, "stewart")
    t = np.linspace(0.0, 0.2, 41)
    z = robot.home[2] + 0.003 * np.sin(2 * np.pi * 2 * t)
    roll = 0.01 * np.sin(2 * np.pi * 3 * t)
    lines = ["t,x,y,z,roll,pitch,yaw"] + [f"{a!r},0,0,{b!r},{c!r},0,0" for a, b, c in zip(t, z, roll)]
    samples = tmp_path / "samples.csv"
    samples.write_text("\n".join(lines) + "\n")
    table = nocdyn.inverse_dynamics(samples, robot=robot, rate=100, progress=False)
    assert table.columns[:7] == ["t", "x", "y", "z", "roll", "pitch", "yaw"] and table.columns[-1] == "kinetic"
    assert len(table) == 20 and np.isfinite(table.data).all()
    # every output time is a sample's (0.01 s apart, samples 0.005 s apart): the spline goes through it
    np.testing.assert_allclose(table["z"], z[::2][:20], rtol=0, atol=1e-15)
    np.testing.assert_allclose(table["roll"], roll[::2][:20], rtol=0, atol=1e-15)
    # a few mm and 0.6 degree at 2-3 Hz: the legs' forces stay within 20 % of their static ones
    # at home (inertia, and the cylinders' friction of 50 N and damping)
    zero = np.zeros(6)
    at_rest = robot.inverse_dynamics(robot.home, zero, zero).tau
    np.testing.assert_allclose(table.data[:, -7:-1].mean(axis=0), at_rest, rtol=0.2)


def test_bad_spatial_trajectories_are_refused_naming_file_and_field(source_dir, tmp_path):
    robot = _load(source_dir, "delta")
    theta = tmp_path / "theta.yaml"
    theta.write_text("x: {offset: 0}\ny: {offset: 0}\nz: {offset: -0.8}\ntheta: {offset: 0.1}\n")
    with pytest.raises(nocdyn.Error, match=re.escape(f"{theta}:4: theta: a planar robot's coordinate")):
        nocdyn.inverse_dynamics(theta, robot=robot, progress=False)
    roll = tmp_path / "roll.yaml"
    roll.write_text("x: {offset: 0}\ny: {offset: 0}\nz: {offset: -0.8}\nroll: {offset: 0}\n")
    with pytest.raises(nocdyn.Error, match=re.escape(f"{roll}:4: roll: a translation robot")):
        nocdyn.inverse_dynamics(roll, robot=source_dir / "robots" / "delta.yaml", progress=False)
    with pytest.raises(nocdyn.Error, match="trajectory 'paper1'.*planar"):
        nocdyn.inverse_dynamics("paper1", robot=robot, progress=False)
    with pytest.raises(ValueError, match="trajectory: a trajectory built in code is planar"):
        nocdyn.inverse_dynamics(nocdyn.Trajectory.paper(1), robot=robot, progress=False)
    with pytest.raises(ValueError, match="reactions"):
        nocdyn.inverse_dynamics(source_dir / "trajectories" / "delta-pick.yaml", robot=robot, reactions=True,
                                progress=False)
    far = tmp_path / "far.yaml"
    far.write_text("duration: 0.25\nx: {offset: 0}\ny: {offset: 0}\n"
                   "z: {offset: -0.8, harmonics: [{amplitude: 0.6, frequency: 1}]}\n")
    with pytest.raises(nocdyn.Error, match=r"^t = 0\.\d+ s: pose out of reach: limb \d \(arm\d\) cannot close"):
        nocdyn.inverse_dynamics(far, robot=robot, allow_limits=True, progress=False)
    with pytest.raises(nocdyn.Error, match=r"^t = 0\.\d+ s: joint range exceeded: limb \d \(arm\d\), joint 1: q = "):
        nocdyn.inverse_dynamics(far, robot=robot, progress=False)


@pytest.mark.parametrize("name", ["stewart", "hexa-6rus", "delta"])
def test_forward_kinematics_gives_back_the_pose_of_u_among_its_modes(source_dir, name):
    robot = _load(source_dir, name)
    d = robot.task_dimension
    p = robot.home + np.array([0.01, -0.005, 0.008, 0.02, -0.03, 0.04])[:d]
    u = robot.inverse_dynamics(p, np.zeros(d), np.zeros(d)).u
    modes = robot.forward_kinematics(u)
    assert modes and all(m["u_error"] <= 1e-10 for m in modes)
    # the working mode (first: nearest home) is p, in the coordinates' order
    assert modes[0]["working"] and modes[0]["pose"].shape == (d,)
    np.testing.assert_allclose(modes[0]["pose"], p, atol=1e-10)
    assert sum(m["working"] for m in modes) == 1
    # every mode gives u back through the inverse kinematics of its own branches (checked in
    # C++); the ones on the home branches give it back from home too
    for m in modes:
        if m["home_branches"]:
            np.testing.assert_allclose(robot.inverse_dynamics(m["pose"], np.zeros(d), np.zeros(d)).u, u, atol=1e-10)
    if name == "delta":
        assert [m["method"] for m in modes] == ["three spheres"] * 2
        assert modes[1]["pose"][2] > modes[0]["pose"][2]  # the other mode above the elbows


def test_the_tracker_follows_sampled_actuator_values(source_dir):
    robot = _load(source_dir, "stewart")
    t = np.arange(0.0, 0.2, 1e-3)[:, None]  # 1 kHz
    P = robot.home + np.array([0.02, 0.01, -0.02, 0.03, 0.02, -0.05]) * np.sin(2 * np.pi * 3 * t)
    U = robot.inverse_dynamics(P, np.zeros_like(P), np.zeros_like(P)).u
    np.testing.assert_allclose(robot.track(U), P, atol=1e-11)
    np.testing.assert_allclose(robot.track(U[5], p0=P[4]), P[5], atol=1e-11)
    U[7, 2] = 5.0  # one leg 5 m longer at sample 8
    with pytest.raises(nocdyn.Error, match=r"^sample 8: "):
        robot.track(U)


def test_forward_kinematics_refuses_bad_values(source_dir):
    robot = _load(source_dir, "delta")
    with pytest.raises(nocdyn.Error, match=r"u: expected shape \(3,\)"):
        robot.forward_kinematics([0.1, 0.2])
    with pytest.raises(nocdyn.Error, match=r"u\[1\]: not a finite number"):
        robot.forward_kinematics([0.1, np.nan, 0.2])
    stewart = _load(source_dir, "stewart")
    assert stewart.forward_kinematics([3.0, 3.0, 3.0, 3.0, 3.0, -1.0]) == []  # out of reach


def _phc_folders():
    return {p.name for p in pathlib.Path(tempfile.gettempdir()).glob("nocdyn-phc-*")}


def test_the_assembly_modes_at_the_home_leg_lengths_hold_the_home_pose_and_give_back_u(source_dir):
    if shutil.which("phc") is None:
        skip_or_fail_in_ci("phc is not installed (Debian package phcpack)")
    robot = _load(source_dir, "stewart")
    u = robot.inverse_dynamics(robot.home, np.zeros(6), np.zeros(6)).u
    before = _phc_folders()
    poses, u_error, info = robot.assembly_modes(u, seed=20261129, details=True)
    assert poses.shape == (8, 6) and u_error.shape == (8,)
    assert info["paths"] == 128 and info["solutions"] == 28 and info["real_solutions"] == 8
    np.testing.assert_allclose(poses[0], robot.home, atol=1e-9)  # nearest to home first
    assert np.all(u_error <= 1e-9)
    # the table translated to z -> -z (base and platform points each in one plane)
    mirrored = robot.home * np.array([1, 1, -1, 1, 1, 1])
    assert np.min(np.max(np.abs(poses - mirrored), axis=1)) < 1e-9
    # a pose near home: the inverse dynamics there gives back u
    near = robot.home + np.array([0.01, -0.02, 0.03, 0.02, -0.01, 0.05])
    u_near = robot.inverse_dynamics(near, np.zeros(6), np.zeros(6)).u
    modes = robot.assembly_modes(u_near)
    np.testing.assert_allclose(modes[0], near, atol=1e-9)
    np.testing.assert_allclose(robot.inverse_dynamics(modes[0], np.zeros(6), np.zeros(6)).u, u_near, atol=1e-9)
    assert _phc_folders() <= before, "a temporary folder was left behind"


def test_assembly_modes_refuse_other_robots_and_bad_u(source_dir):
    with pytest.raises(nocdyn.Error, match="is not a 6-UPS robot"):
        _load(source_dir, "hexa-6rus").assembly_modes(np.zeros(6))
    stewart = _load(source_dir, "stewart")
    with pytest.raises(nocdyn.Error, match=r"u: expected shape \(6,\)"):
        stewart.assembly_modes(np.zeros(5))
    with pytest.raises(nocdyn.Error, match="phcpack"):
        stewart.assembly_modes(np.zeros(6), executable="/nonexistent/phc")


@pytest.mark.parametrize("name, pose", [("stewart", [0.02, -0.01, 1.08, 0.05, -0.03, 0.1]), ("delta", [0.05, -0.03, -0.9])])
def test_the_pose_report_is_the_command_lines_and_its_platform_balances(source_dir, cli, name, pose):
    import json
    path = source_dir / "robots" / f"{name}.yaml"
    report = nocdyn.pose(*pose, robot=str(path))
    assert isinstance(report, nocdyn.SpatialPoseReport)
    same = nocdyn.Robot.load(path).pose(pose)
    np.testing.assert_array_equal(report.tau, same.tau)
    code, out, err = cli("pose", *pose, "--robot", path, "--json")
    assert code == 0, err
    document = json.loads(out)
    np.testing.assert_allclose(report.tau, document["tau"], rtol=1e-15)
    np.testing.assert_allclose(report.u, [a["u"] for a in document["actuators"]], rtol=1e-15, atol=1e-18)
    assert [(r["limb"], r["joint"], r["type"]) for r in report.reactions] == \
        [(r["limb"], r["joint"], r["type"]) for r in document["reactions"]]
    for mine, theirs in zip(report.reactions, document["reactions"]):
        np.testing.assert_allclose(mine["force"], theirs["force"], rtol=1e-15, atol=1e-12)
    # every joint's reaction is reported; the platform balances under the limbs' wrenches
    joints = {"stewart": ["U", "P", "S"], "delta": ["R", "U", "U"]}[name]
    assert [r["type"] for r in report.reactions] == joints * len(report.limbs)
    # the whole robot's weight: the table or the Delta's plate, and each limb's bodies
    weight = {"stewart": 300.0 + 6 * (25.0 + 8.0), "delta": 0.6 + 3 * (0.6 + 0.25)}[name] * 9.81
    assert report.balance_residual < 1e-9 * weight
    # an S passes no moment; at rest the base joints together carry the whole robot's weight
    assert all(np.max(np.abs(r["moment"])) < 1e-9 for r in report.reactions if r["type"] == "S")
    lifted = sum(np.array(r["force"]) for r in report.reactions if r["joint"] == 1)
    np.testing.assert_allclose(lifted, [0.0, 0.0, weight], rtol=1e-12, atol=1e-9 * weight)


def test_the_pose_of_a_spatial_robot_needs_its_coordinates(source_dir):
    path = str(source_dir / "robots" / "stewart.yaml")
    with pytest.raises(nocdyn.Error, match="takes 6 pose coordinates"):
        nocdyn.pose(0.0, 0.0, 1.06, robot=path)
    with pytest.raises(ValueError, match="ROLL PITCH YAW are for a spatial robot"):
        nocdyn.pose(0.0, 0.0, 0.0, 0.1, 0.2, 0.3)


def test_the_batch_checks_the_joints_limits_as_the_trajectory_job_does(source_dir):
    # the Stewart table's cylinders: +-0.15 m, 0.5 m/s and 10 kN; its U and S joints take no limits
    robot = _load(source_dir, "stewart")
    home, zero = robot.home, np.zeros(6)
    P = np.tile(home, (3, 1))
    P[2, 2] += 0.2  # 20 cm up: every leg beyond its +0.15 m stroke
    with pytest.raises(nocdyn.Error, match=r"^sample 3: joint range exceeded: limb 1 \(leg1\), joint 2: q = 0\.1"):
        robot.inverse_dynamics(P, np.zeros_like(P), np.zeros_like(P))
    out = robot.inverse_dynamics(P, np.zeros_like(P), np.zeros_like(P), check_limits=False)
    assert np.all(out.u[2] > 0.15) and np.all(np.isfinite(out.tau))
    fast = np.zeros(6)
    fast[2] = 0.6  # 0.6 m/s up: each leg faster than its 0.5 m/s
    with pytest.raises(nocdyn.Error, match=r"^sample 1: joint velocity exceeded: limb 1 \(leg1\), joint 2: q' = 0\.5"):
        robot.inverse_dynamics(home, fast, zero)
    hard = np.zeros(6)
    hard[2] = 200.0  # 20 g up under 300 kg: every cylinder beyond 10 kN
    with pytest.raises(nocdyn.Error, match=r"effort exceeded: actuator 1, limb 1 \(leg1\), joint 2: tau = 1\d{4}"):
        robot.inverse_dynamics(home, zero, hard)
    assert robot.inverse_dynamics(home, zero, hard, check_limits=False).tau.min() > 1e4
