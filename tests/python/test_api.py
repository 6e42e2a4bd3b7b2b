"""Robots, trajectories, direct kinematics, forward dynamics and the envelope from Python, and
errors with the CLI's messages."""

import csv
import os
import pydoc
import subprocess
import sys
import warnings

import numpy as np
import pytest

import nocdyn


def cli_error(stderr):
    """The message of `nocdyn: error: MESSAGE`."""
    line = stderr.strip().splitlines()[-1]
    assert line.startswith("nocdyn: error: "), stderr
    return line[len("nocdyn: error: "):]


def test_robots_load_from_files_text_and_the_examples(source_dir):
    for name in nocdyn.Robot.examples():
        from_file = nocdyn.Robot.load(source_dir / "robots" / f"{name}.yaml")
        text = (source_dir / "robots" / f"{name}.yaml").read_text()
        from_text = nocdyn.Robot.from_yaml(text)
        example = nocdyn.Robot.example(name)
        for robot in (from_file, from_text, example):
            assert (robot.name, robot.limbs, robot.actuators) == (example.name, example.limbs, example.actuators)
        round_trip = nocdyn.Robot.from_yaml(example.to_yaml())
        assert round_trip.actuator_info() == example.actuator_info()
    paper = nocdyn.Robot.paper()
    assert (paper.limbs, paper.actuators, paper.bodies) == (3, 3, 7)
    assert [limb["type"] for limb in paper.limb_info()] == ["PRR"] * 3
    info = paper.actuator_info()
    assert [a["type"] for a in info] == ["P"] * 3 and info[0]["effort"] == 262.0
    assert info[0]["upper"] == pytest.approx(0.0249 / 2, rel=1e-15)
    assert "3 limbs, 3 actuators" in repr(paper)


@pytest.mark.parametrize("contents", [
    "name: bad\nlimbs: []\n",
    "name: bad\ngeometry: {base_side: -1}\n",
])
def test_robot_file_errors_are_nocdyn_errors_with_the_cli_message(tmp_path, cli, contents):
    path = tmp_path / "robot.yaml"
    path.write_text(contents)
    code, _, err = cli("inverse-dynamics", "--robot", path, "--trajectory", "paper1", "--duration", 0.001)
    assert code != 0
    with pytest.raises(nocdyn.Error) as error:
        nocdyn.Robot.load(path)
    assert str(error.value) == cli_error(err)
    assert isinstance(error.value, ValueError)


def test_a_missing_robot_file_is_a_nocdyn_error_naming_it(tmp_path):
    # (the CLI refuses it before reading, with its option parser's message)
    with pytest.raises(nocdyn.Error, match=r"^cannot open robot file '.*nothere.yaml': No such file"):
        nocdyn.Robot.load(tmp_path / "nothere.yaml")
    with pytest.raises(nocdyn.Error, match=r"robot file"):
        nocdyn.Robot.load(tmp_path)


def test_trajectory_errors_have_the_cli_message(tmp_path, cli, paper_robot):
    bad = tmp_path / "bad.yaml"
    bad.write_text("x: {offset: 0.001, harmonics: [{amplitude: 0.002}]}\n")
    code, _, err = cli("inverse-dynamics", "--trajectory", bad)
    assert code != 0
    with pytest.raises(nocdyn.Error) as error:
        nocdyn.Trajectory.load(bad)
    assert str(error.value) == cli_error(err)
    # out of reach along the trajectory: the same "t = ... s: reason"
    far = tmp_path / "far.yaml"
    far.write_text("x: {harmonics: [{amplitude: 0.05, frequency: 10}]}\n")
    code, _, err = cli("inverse-dynamics", "--trajectory", far, "--duration", 0.05)
    assert code != 0
    with pytest.raises(nocdyn.Error) as error:
        nocdyn.inverse_dynamics(nocdyn.Trajectory.load(far), robot=paper_robot, rate=10000, duration=0.05)
    assert str(error.value) == cli_error(err)


def test_paper_trajectories_equal_their_files_and_have_exact_derivatives(source_dir):
    t = np.linspace(0.0, 0.2, 101)
    for k in (1, 2):
        built_in = nocdyn.Trajectory.paper(k).evaluate(t)
        from_file = nocdyn.Trajectory.load(source_dir / "trajectories" / f"paper{k}.yaml").evaluate(t)
        for a, b in zip(built_in, from_file):
            np.testing.assert_allclose(a, b, rtol=0, atol=1e-15)
    traj = nocdyn.Trajectory.harmonic(x=[(0.002, 10.0, 0.5)], theta=[(0.05, 5.0)], offset=(0.001, 0.0, 0.0))
    h = 1e-6
    p, dp, ddp = traj.evaluate(t)
    p_plus, _, _ = traj.evaluate(t + h)
    p_minus, _, _ = traj.evaluate(t - h)
    np.testing.assert_allclose((p_plus - p_minus) / (2 * h), dp, rtol=0, atol=1e-7)
    np.testing.assert_allclose((p_plus - 2 * p + p_minus) / h**2, ddp, rtol=0, atol=2e-3 * np.max(np.abs(ddp)))
    assert traj.harmonics("x") == (0.001, [(0.002, 10.0, 0.5)])
    assert traj.highest_frequency == 10.0
    with pytest.raises(nocdyn.Error, match="^x: a harmonic"):
        nocdyn.Trajectory.harmonic(x=[(0.002, -10.0, 0.0)])
    with pytest.raises(nocdyn.Error, match="not 1 or 2"):
        nocdyn.Trajectory.paper(3)


def test_sampled_trajectories_pass_through_their_samples_and_name_bad_lines(tmp_path):
    # positions of trajectory 1 at 2 kHz: the spline passes through every sample
    t = np.arange(0, 401) / 2000.0
    p, _, _ = nocdyn.Trajectory.paper(1).evaluate(t)
    path = tmp_path / "samples.CSV"
    rows = ["t,x,y,theta"] + [f"{a!r},{b!r},{c!r},{d!r}" for a, (b, c, d) in zip(t, p)]
    path.write_text("\n".join(rows) + "\n")
    sampled = nocdyn.Trajectory.load(path)
    q, _, _ = sampled.evaluate(t)
    np.testing.assert_allclose(q, p, rtol=0, atol=1e-15)
    same = nocdyn.Trajectory.from_csv(path.read_text())
    np.testing.assert_array_equal(same.evaluate(t)[0], q)
    # and between the samples it follows the harmonic to the spline's error, O(h^4)
    mid = t[:-1] + 0.25e-3
    np.testing.assert_allclose(sampled.evaluate(mid)[0], nocdyn.Trajectory.paper(1).evaluate(mid)[0], rtol=0,
                               atol=1e-9)
    with pytest.raises(nocdyn.Error, match=r"bad\.csv:3: .*t"):
        nocdyn.Trajectory.from_csv("t,x\n0.1,0\n0.05,0\n", "bad.csv")


@pytest.mark.parametrize("name", ["paper-3prr", "3-rrr", "4-rrr"])
def test_forward_kinematics_finds_the_pose_that_gave_u_in_the_working_mode(name):
    robot = nocdyn.Robot.example(name)
    p = robot.home + np.array([0.002, -0.001, 0.02])  # [x, y, theta]
    u = robot.inverse_dynamics(p, np.zeros(3), np.zeros(3)).u
    modes = robot.forward_kinematics(u)
    assert len(modes) >= 1
    # the pose itself, on every limb's home branch (other poses may share those branches)
    match = [m for m in modes if np.max(np.abs(m["pose"] - p)) <= 1e-9]
    assert len(match) == 1 and match[0]["working"]
    for m in modes:  # every mode gives u back
        assert m["u_error"] <= 1e-9
        back = nocdyn.Robot.example(name)
        assert len(m["branch"]) == back.limbs
    with pytest.raises(nocdyn.Error, match="^u: expected"):
        robot.forward_kinematics(u[:-1])


def forces_table(t, tau, first_row):
    """The forces' columns t, tau1..taun with the initial state's columns (read in the first row)."""
    columns = {"t": t, **{f"tau{a + 1}": tau[:, a] for a in range(tau.shape[1])}}
    columns.update({name: np.full(len(t), value) for name, value in first_row.items()})
    return columns


def pose_columns(table):
    return np.column_stack([table["x"], table["y"], table["theta"]])


def test_simulating_the_inverse_dynamics_forces_follows_the_trajectory(paper_robot):
    """Open loop over 20 ms: the forces of trajectory 1 (sampled at 20 kHz, cubic) drive the
    forward dynamics (nocdyn.simulate with robot=) from the trajectory's own initial state along
    the trajectory."""
    traj = nocdyn.Trajectory.paper(1)
    t = np.arange(401) / 20000.0
    P, dP, ddP = traj.evaluate(t)
    tau = paper_robot.inverse_dynamics(P, dP, ddP).tau
    start = dict(zip(("x", "y", "theta", "dx", "dy", "dtheta"), (*P[0], *dP[0])))
    sim = nocdyn.simulate(forces_table(t, tau, start), robot=paper_robot, rate=20000.0, interpolation="cubic",
                          progress=False)
    assert len(sim) == 401
    np.testing.assert_allclose(sim["t"], t, rtol=0, atol=1e-15)
    np.testing.assert_allclose(pose_columns(sim), P, rtol=0, atol=1e-6)
    sim_tau = np.column_stack([sim[f"tau{a + 1}"] for a in range(3)])
    np.testing.assert_allclose(sim_tau, tau, rtol=0, atol=1e-9 * np.max(np.abs(tau)))
    # the deprecated wrapper: the same numbers, and a DeprecationWarning
    with pytest.warns(DeprecationWarning, match="nocdyn.simulate"):
        wrapped = paper_robot.simulate(forces_table(t, tau, start), rate=20000.0)
    np.testing.assert_array_equal(wrapped.data, sim.data)
    # the old form (output times, a force array, max_step) read as the job's table: the same
    # numbers as the job from home at rest with the same largest step
    from_home = nocdyn.simulate({"t": t, **{f"tau{a + 1}": tau[:, a] for a in range(3)}}, robot=paper_robot,
                                rate=20000.0, max_step=1e-3, progress=False)
    with pytest.warns(DeprecationWarning):
        old = paper_robot.simulate(t, tau, max_step=1e-3)
    np.testing.assert_array_equal(old.data, from_home.data)
    with pytest.warns(DeprecationWarning), pytest.raises(ValueError, match="max_step"):
        paper_robot.simulate(t, tau, max_step=1e-9)
    with pytest.warns(DeprecationWarning), pytest.raises(ValueError, match="p0 is no longer an option"):
        paper_robot.simulate(t, tau, p0=P[0])
    with pytest.raises(ValueError, match="interpolation"):
        nocdyn.simulate(forces_table(t, tau, start), robot=paper_robot, interpolation="spline")


def test_simulating_from_actuator_values_starts_where_the_pose_does(paper_robot):
    """u0, du0 of the trajectory's first sample give back its pose and rate (the library call the
    command line's simulate uses), and the motion equals the one started from p0, dp0."""
    traj = nocdyn.Trajectory.paper(1)
    t = np.arange(201) / 20000.0
    P, dP, ddP = traj.evaluate(t)
    result = paper_robot.inverse_dynamics(P, dP, ddP)
    start = paper_robot.state_from_actuators(result.u[0], result.du[0])
    np.testing.assert_allclose(start["p"], P[0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(start["dp"], dP[0], rtol=0, atol=1e-10)
    assert start["mode"] >= 1 and start["working"] >= start["mode"] and start["modes"] >= start["working"]
    from_u = nocdyn.simulate(forces_table(t, result.tau, {**{f"u{a + 1}": result.u[0, a] for a in range(3)},
                                                          **{f"du{a + 1}": result.du[0, a] for a in range(3)}}),
                             robot=paper_robot, rate=20000.0, progress=False)
    from_p = nocdyn.simulate(forces_table(t, result.tau, dict(zip(("x", "y", "theta", "dx", "dy", "dtheta"),
                                                                   (*P[0], *dP[0])))),
                             robot=paper_robot, rate=20000.0, progress=False)
    np.testing.assert_allclose(pose_columns(from_u), pose_columns(from_p), rtol=0, atol=1e-10)
    with pytest.raises(nocdyn.Error, match="fewer than the one asked for"):
        paper_robot.state_from_actuators(result.u[0], assembly_mode=12)


def test_simulation_out_of_reach_stops_with_the_time():
    t = np.linspace(0.0, 0.5, 11)
    with pytest.raises(nocdyn.Error, match=r"t = [0-9.e-]+ s: "):
        nocdyn.simulate(forces_table(t, np.full((11, 3), 262.0), {}), rate=100.0, progress=False)


def test_envelope_equals_the_cli_envelope(tmp_path, cli, paper_robot):
    out = tmp_path / "env.csv"
    code, _, err = cli("envelope", "--min-frequency", 5, "--max-frequency", 50, "--points", 2, "--output", out,
                       "--figure", "")
    assert code == 0, err
    with open(out, newline="") as f:
        rows = list(csv.DictReader(f))
    table = nocdyn.envelope(robot=paper_robot, min_frequency=5, max_frequency=50, points=2, progress=False)
    assert len(table) == len(rows) == 6
    for k, theirs in enumerate(rows):
        assert table["axis"][k] == theirs["axis"]
        assert table["frequency"][k] == float(theirs["frequency"])
        assert table["amplitude"][k] == float(theirs["amplitude"])
        # numbered from 1 as the CSV, 0 where not applicable
        for key in ("limb", "joint", "actuator"):
            assert table[key][k] == int(float(theirs[key])), key
    with pytest.warns(DeprecationWarning, match="nocdyn.envelope"):
        wrapped = paper_robot.envelope(min_frequency=5, max_frequency=50, points=2)
    np.testing.assert_array_equal(wrapped["amplitude"], table["amplitude"])
    # the old arguments: frequencies is points, samples_per_period the job's; axes said to be ignored
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        old = paper_robot.envelope("x", min_frequency=5, max_frequency=50, frequencies=2, samples_per_period=64)
    assert [w.category for w in said] == [DeprecationWarning, UserWarning], said
    assert "axes is no longer an option" in str(said[1].message)
    coarse = nocdyn.envelope(robot=paper_robot, min_frequency=5, max_frequency=50, points=2, samples_per_period=64,
                             progress=False)
    np.testing.assert_array_equal(old["amplitude"], coarse["amplitude"])
    np.testing.assert_array_equal(old["amplitude"], table["amplitude"])


def test_help_documents_units_and_shapes():
    text = pydoc.render_doc(nocdyn.Robot, renderer=pydoc.plaintext)
    for phrase in ("(N, 3)", "(N, n)", "GIL", "nocdyn.Error", "[m or rad]", "TypeError"):
        assert phrase in text, phrase
    assert "SI units" in nocdyn.__doc__
    assert nocdyn.Trajectory.evaluate.__doc__ and nocdyn.Robot.simulate.__doc__


def test_quickstart_example_writes_its_png(tmp_path, source_dir):
    out = tmp_path / "quickstart.png"
    done = subprocess.run([sys.executable, str(source_dir / "examples" / "quickstart.py"), "--out", str(out)],
                          capture_output=True, text=True, timeout=120, env=dict(os.environ, MPLBACKEND="Agg"))
    assert done.returncode == 0, done.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and out.stat().st_size > 10_000
    assert "peak |tau| per actuator [N]" in done.stdout


@pytest.mark.parametrize(
    "name, first_actuator",
    [("delta", "19: limbs[0] (arm1).joints[0]"), ("stewart", "19: limbs[0] (leg1).joints[1]"),
     ("hexa-6rus", "17: limbs[0] (leg1).joints[0]")],
)
def test_a_spatial_robot_file_is_read_checked_and_loads_as_a_spatial_robot(source_dir, name, first_actuator):
    path = str(source_dir / "robots" / f"{name}.yaml")
    assert isinstance(nocdyn.Robot.load(path), nocdyn.SpatialRobot)
    # an error in the file comes first, with its line and joint
    text = (source_dir / "robots" / f"{name}.yaml").read_text().replace("actuated: true", "actuated: maybe", 1)
    with pytest.raises(nocdyn.Error) as error:
        nocdyn.Robot.from_yaml(text, f"{name}.yaml")
    assert str(error.value) == f"{name}.yaml:{first_actuator}.actuated: expected true or false"
