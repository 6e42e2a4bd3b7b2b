"""`set=` overrides a parametric robot file's parameters for the one call it is given to: it
changes that call's numbers, every command that takes a robot honours it, and it does not reach
the next call."""

import numpy as np

import nocdyn


def family(source_dir):
    return str(source_dir / "examples" / "design_3rrr" / "family.yaml")


def test_set_applies_to_its_call_and_does_not_reach_the_next(source_dir):
    robot = family(source_dir)
    plain = nocdyn.inverse_dynamics("paper1", robot=robot, duration=0.01)
    longer = nocdyn.inverse_dynamics("paper1", robot=robot, duration=0.01, set={"l1": 0.12})
    again = nocdyn.inverse_dynamics("paper1", robot=robot, duration=0.01)
    tau = [c for c in plain.columns if c.startswith("tau")]
    assert tau
    # a longer proximal link changes the forces ...
    assert np.max(np.abs(plain[tau[0]] - longer[tau[0]])) > 1e-6
    # ... and the call after it, without set=, gives the forces of the plain file again
    for column in tau:
        np.testing.assert_array_equal(plain[column], again[column])


def test_pose_forward_kinematics_and_convert_honour_set(source_dir):
    robot = family(source_dir)
    plain = nocdyn.pose(0.0, 0.0, 0.0, robot=robot)
    longer = nocdyn.pose(0.0, 0.0, 0.0, robot=robot, set={"l1": 0.12})
    # heavier, longer proximal links: a different inertia at the same pose
    assert np.max(np.abs(plain.I - longer.I)) > 1e-6 * np.max(np.abs(plain.I))
    assert nocdyn.convert(robot, set={"l1": 0.12}) != nocdyn.convert(robot)
    u = [0.05, -0.02, 0.03]
    poses_plain = nocdyn.forward_kinematics(u, robot=robot).poses
    poses_longer = nocdyn.forward_kinematics(u, robot=robot, set={"l1": 0.12}).poses
    assert len(poses_plain) >= 1 and len(poses_longer) >= 1
    assert np.max(np.abs(poses_plain[0] - poses_longer[0])) > 1e-6
