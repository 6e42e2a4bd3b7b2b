"""forward_kinematics on the application layer: it honours set=, names the argument a bad value
breaks, and runs in two threads at once."""

import math
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
