"""forward_kinematics, simulate, control and frequency_response on the application layer: each
honours set=, names the argument a bad value breaks, and runs in two threads at once (the GIL is
released: two simulations take well under twice as long as one)."""

import math
import os
import threading
import time
import warnings

import numpy as np
import pytest

import nocdyn


def family(source_dir):
    return str(source_dir / "examples" / "design_3rrr" / "family.yaml")


def in_two_threads(call):
    """call() in two threads at once: both results, and the wall time."""
    results = [None, None]
    errors = []

    def work(k):
        try:
            results[k] = call()
        except Exception as error:  # reported below, not lost in the thread
            errors.append(error)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(2)]
    start = time.perf_counter()
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    return results, time.perf_counter() - start


# --- forward_kinematics ---------------------------------------------------------------------------

def test_forward_kinematics_poses_are_x_y_theta_and_give_back_u(source_dir):
    robot = str(source_dir / "robots" / "3-rrr.yaml")
    report = nocdyn.pose(0.002, -0.001, 0.03, robot=robot)
    modes = nocdyn.forward_kinematics(report.u, robot=robot)
    assert modes.poses.shape[1] == 3
    assert np.min(np.abs(modes.poses - [0.002, -0.001, 0.03]).max(axis=1)) < 1e-9
    for pose in modes.poses:  # every mode listed closes the loops with the same u
        np.testing.assert_allclose(nocdyn.pose(*pose, robot=robot).u, report.u, atol=1e-9)


def test_forward_kinematics_bad_values_name_u():
    with pytest.raises(ValueError, match="^u: "):
        nocdyn.forward_kinematics([0.0, math.nan, 0.0])
    with pytest.raises(ValueError, match="^u: .*has 3 actuators: give 3 values"):
        nocdyn.forward_kinematics([0.0, 0.0])
    with pytest.raises(ValueError, match="^all_branches: "):
        nocdyn.forward_kinematics([0.0, 0.0, 0.0], all_branches="yes")


def test_forward_kinematics_warns_of_a_value_beyond_its_range():
    with pytest.warns(RuntimeWarning, match="u2 is outside its joint's range"):
        modes = nocdyn.forward_kinematics([0.0, 0.013, 0.0])
    assert not modes.within_limits


def test_forward_kinematics_in_two_threads():
    (a, b), _ = in_two_threads(lambda: nocdyn.forward_kinematics([0.0, 0.0, 0.0], all_branches=True))
    np.testing.assert_array_equal(a.poses, b.poses)
    assert len(a) == 2


# --- simulate -----------------------------------------------------------------------------------

def test_simulate_honours_set(source_dir):
    robot = family(source_dir)
    forces = nocdyn.inverse_dynamics("paper1", robot=robot, duration=0.01, rate=2000.0, progress=False)
    plain = nocdyn.simulate(forces, robot=robot, rate=2000.0, progress=False)
    longer = nocdyn.simulate(forces, robot=robot, rate=2000.0, set={"l1": 0.12}, progress=False)
    # the same forces on heavier, longer links: another motion
    assert np.max(np.abs(plain["x"] - longer["x"])) > 1e-9
    np.testing.assert_allclose(plain["x"], forces["x"][: len(plain)], atol=1e-9)


def test_simulate_bad_values_name_the_argument():
    forces = {"t": [0.0, 0.01], "tau1": [0.0, 0.0], "tau2": [0.0, 0.0], "tau3": [0.0, 0.0]}
    with pytest.raises(ValueError, match="^rate: "):
        nocdyn.simulate(forces, rate=-1.0, progress=False)
    with pytest.raises(ValueError, match="^interpolation: expected hold, linear or cubic, got 'cubical'"):
        nocdyn.simulate(forces, interpolation="cubical", progress=False)
    with pytest.raises(ValueError, match="^atol: "):
        nocdyn.simulate(forces, atol=1.0, progress=False)
    with pytest.raises(ValueError, match="^forces: "):
        nocdyn.simulate(42, progress=False)
    with pytest.raises(ValueError, match="^forces: "):
        nocdyn.simulate({"t": [0.0, 0.01], "tau1": [0.0]}, progress=False)


def test_simulate_partial_returns_the_motion_before_the_stop(tmp_path):
    # forces far beyond what holds the robot: it leaves its reach within the second
    n = 200
    t = np.arange(n) * 0.005
    forces = {"t": t, "tau1": np.full(n, 500.0), "tau2": np.full(n, -500.0), "tau3": np.full(n, 500.0)}
    with pytest.raises(nocdyn.Error, match=r"^t = "):
        nocdyn.simulate(forces, rate=1000.0, progress=False)
    with pytest.warns(RuntimeWarning, match=r"^t = "):
        partial = nocdyn.simulate(forces, rate=1000.0, partial=True, progress=False)
    assert 0 < len(partial) < n and np.all(np.isfinite(partial.data))


def simulation_forces():
    return nocdyn.inverse_dynamics("paper1", duration=3.0, rate=2000.0, progress=False)


def cores_given():
    """How many cores the machine gives this process now (1 to 2): the C++ batch's speed-up on
    two threads against one (its threads never touch the GIL), a control for the test below."""
    if (os.cpu_count() or 1) < 2:
        return 1.0
    robot = nocdyn.Robot.example("paper-3prr")
    p = np.tile(robot.home, (400_000, 1))
    rest = np.zeros_like(p)
    times = []
    for threads in (1, 2, 1, 2):
        start = time.perf_counter()
        robot.inverse_dynamics(p, rest, rest, threads=threads)
        times.append(time.perf_counter() - start)
    return min(times[0], times[2]) / max(times[1], times[3])


def test_two_simulations_in_two_threads_take_well_under_twice_one():
    forces = simulation_forces()
    run = lambda: nocdyn.simulate(forces, rate=2000.0, rtol=1e-12, progress=False)  # noqa: E731
    one = run()
    # held GIL: twice one's time at least; released: one's time on two free cores. The best of up
    # to five tries, against a generous bound. A try around which the machine did not give this
    # process two cores (other tests run beside this one under ctest -j) cannot show two threads
    # at once and is not counted: the control is the C++ batch's speed-up on two threads, which
    # no GIL limits. test_python_runs_while_a_simulation_runs shows the release at any load.
    ratios, busy = [], []
    for _ in range(5):
        before = cores_given()
        start = time.perf_counter()
        run()
        single = time.perf_counter() - start
        (a, b), both = in_two_threads(run)
        np.testing.assert_array_equal(a.data, one.data)
        np.testing.assert_array_equal(b.data, one.data)
        given = min(before, cores_given())
        if given < 1.7:
            busy.append(round(given, 2))
            continue
        ratios.append(both / single)
        if ratios[-1] < 1.6:
            break
    if not ratios:
        pytest.skip(f"the machine is busy: it gave this process {busy} cores")
    assert min(ratios) < 1.6, (ratios, busy)


def test_python_runs_while_a_simulation_runs():
    # the GIL released for the whole integration: this thread counts on while the other
    # simulates (held, it would wait for the call to return); independent of the machine's load
    forces = simulation_forces()
    done = threading.Event()
    counted = []

    def simulate():
        try:
            nocdyn.simulate(forces, rate=2000.0, rtol=1e-12, progress=False)
        finally:
            done.set()

    worker = threading.Thread(target=simulate)
    worker.start()
    count = 0
    while not done.is_set():
        count += 1
    worker.join()
    counted.append(count)
    assert counted[0] > 1000, counted


# --- control ------------------------------------------------------------------------------------

def test_control_honours_set_and_writes_what_is_asked(source_dir, tmp_path):
    robot = family(source_dir)
    plain = nocdyn.control("paper1", robot=robot, plant="nocdyn", duration=0.005, rate=2000.0)
    longer = nocdyn.control("paper1", robot=robot, plant="nocdyn", duration=0.005, rate=2000.0, set={"l1": 0.12})
    assert np.max(np.abs(plain["tau1"] - longer["tau1"])) > 1e-6
    log = tmp_path / "log.csv"
    logged = nocdyn.control("paper1", robot=robot, plant="nocdyn", duration=0.005, rate=2000.0, log=log,
                            output=tmp_path / "run.csv")
    np.testing.assert_array_equal(logged.data, plain.data)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["log.csv", "run.csv"]
    assert log.read_text().startswith("t,u1,")


def test_control_bad_values_name_the_argument():
    with pytest.raises(ValueError, match="^plant: "):
        nocdyn.control("paper1", plant="adams")
    with pytest.raises(ValueError, match="^noise_du: "):
        nocdyn.control("paper1", plant="nocdyn", noise_du=1e-3)
    with pytest.raises(ValueError, match="^natural_frequency: "):
        nocdyn.control("paper1", plant="nocdyn", natural_frequency=0.0)
    with pytest.raises(ValueError, match="^payload_com: "):
        nocdyn.control("paper1", plant="nocdyn", payload_com=[0.01])


def test_control_in_two_threads():
    call = lambda: nocdyn.control("paper1", plant="nocdyn", duration=0.01, rate=2000.0)  # noqa: E731
    (a, b), _ = in_two_threads(call)
    np.testing.assert_array_equal(a.data, b.data)
    assert a.text == b.text and "RMS error" in a.text


# --- frequency_response -------------------------------------------------------------------------

def test_frequency_response_honours_set_and_its_axes_are_x_y_theta(source_dir, tmp_path):
    robot = family(source_dir)
    plain = nocdyn.frequency_response(robot=robot, points=3)
    longer = nocdyn.frequency_response(robot=robot, points=3, set={"l1": 0.12})
    assert np.max(np.abs(plain.data - longer.data)) > 1e-6
    assert plain.columns[1:7] == ["ddx_tau1_db", "ddx_tau1_deg", "ddx_tau2_db", "ddx_tau2_deg", "ddx_tau3_db",
                                  "ddx_tau3_deg"]
    loop = nocdyn.frequency_response(closed_loop=True, points=3, max_frequency=100.0, summary=tmp_path / "s.txt")
    assert [c for c in loop.columns if c.endswith("_loop_db")] == ["x_loop_db", "y_loop_db", "theta_loop_db"]
    assert (tmp_path / "s.txt").read_text() == loop.text


def test_frequency_response_pose_is_x_y_theta(paper_robot):
    # the operating pose [x, y, theta]: the summary says so, and moving along x changes the plant
    home = nocdyn.frequency_response(points=3)
    moved = nocdyn.frequency_response(points=3, pose=[0.002, 0.0, 0.0])
    assert "[x, y, theta] = [0.002, 0, 0]" in moved.text
    assert np.max(np.abs(home.data - moved.data)) > 1e-9


def test_frequency_response_bad_values_name_the_argument():
    with pytest.raises(ValueError, match="^points: "):
        nocdyn.frequency_response(points=1)
    with pytest.raises(ValueError, match="^max_frequency: "):
        nocdyn.frequency_response(min_frequency=10.0, max_frequency=5.0)
    with pytest.raises(ValueError, match="^pose: "):
        nocdyn.frequency_response(pose=[0.0, 0.0])
    with pytest.raises(ValueError, match="^output_kind: "):
        nocdyn.frequency_response(output_kind="velocity")
    with pytest.raises(ValueError, match="^rate: "):
        nocdyn.frequency_response(closed_loop=True, rate=[0.0, 0.0, 0.0])


def test_frequency_response_in_two_threads():
    (a, b), _ = in_two_threads(lambda: nocdyn.frequency_response(points=50))
    np.testing.assert_array_equal(a.data, b.data)
    assert a.text == b.text
