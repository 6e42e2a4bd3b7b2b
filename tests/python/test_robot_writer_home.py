"""Robot.to_yaml writes the home pose in the order the reader takes it, [x, y, theta]: a robot
with a home away from the origin reads back with the same home and the same forces."""

import numpy as np

import nocdyn


def test_home_pose_round_trips_through_the_writer(source_dir):
    text = (source_dir / "robots" / "3-rrr.yaml").read_text()
    text = text.replace("max_condition: 1.0e4", "home: [0.001, 0.002, 0.0]\nmax_condition: 1.0e4")
    robot = nocdyn.Robot.from_yaml(text)
    np.testing.assert_array_equal(robot.home, [0.001, 0.002, 0.0])
    back = nocdyn.Robot.from_yaml(robot.to_yaml())
    np.testing.assert_array_equal(back.home, robot.home)
    p = np.array([0.002, 0.001, 0.05])
    a = robot.inverse_dynamics(p, np.array([0.01, 0.0, 0.1]), np.array([0.0, 0.2, 0.0]))
    b = back.inverse_dynamics(p, np.array([0.01, 0.0, 0.1]), np.array([0.0, 0.2, 0.0]))
    np.testing.assert_array_equal(a.tau, b.tau)
