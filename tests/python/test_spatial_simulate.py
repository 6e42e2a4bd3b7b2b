"""nocdyn.simulate on a spatial robot (the same job as the command line's `simulate`): the
forces of the inverse dynamics, played back from the first row's state, give the motion back."""

import numpy as np
import pytest

import nocdyn


@pytest.mark.parametrize("name", ["stewart", "delta"])
def test_the_forces_of_a_motion_played_back_give_the_motion(source_dir, tmp_path, name):
    robot = nocdyn.Robot.load(source_dir / "robots" / f"{name}.yaml")
    d, n = robot.task_dimension, robot.actuators
    t = np.arange(0.0, 0.0505, 1e-3)[:, None]
    w = 4.0 * np.pi
    amp = np.full(d, 0.01)
    P, dP, ddP = robot.home + amp * np.sin(w * t), amp * w * np.cos(w * t), -amp * w * w * np.sin(w * t)
    _, du, _, tau = robot.inverse_dynamics(P, dP, ddP)
    names = robot.coordinates
    columns = ["t", *names, *[f"du{a + 1}" for a in range(n)], *[f"tau{a + 1}" for a in range(n)]]
    path = tmp_path / "forces.csv"
    rows = np.hstack([t, P, du, tau])
    np.savetxt(path, rows, delimiter=",", header=",".join(columns), comments="", fmt="%.17g")
    motion = nocdyn.simulate(robot=str(source_dir / "robots" / f"{name}.yaml"), forces=str(path), rate=1000)
    assert motion.columns == ["t", *names, *[f"{p}{a + 1}" for p in ("u", "du", "tau") for a in range(n)], "kinetic"]
    simulated = np.asarray(motion.data)
    assert simulated.shape == (51, len(motion.columns))
    # the first row's du give the pose rates; friction's Coulomb jumps keep it near, not on
    assert np.allclose(simulated[:, 1 : 1 + d], P, atol=3e-5)
    assert np.max(np.abs(simulated[:, 1 : 1 + d] - P)) > 0.0


def test_a_planar_column_in_a_spatial_robots_forces_is_refused(source_dir, tmp_path):
    path = tmp_path / "forces.csv"
    path.write_text("t,x,y,theta,tau1,tau2,tau3,tau4,tau5,tau6\n0,0,0,0,1,1,1,1,1,1\n0.1,0,0,0,1,1,1,1,1,1\n")
    with pytest.raises(nocdyn.Error, match=r"forces\.csv:2: column 'theta'"):
        nocdyn.simulate(robot=str(source_dir / "robots" / "stewart.yaml"), forces=str(path))
