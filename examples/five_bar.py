# %% [markdown]
# # A five-bar, from its file to its forces and its workspace
#
# A desk-top five-bar (robots/five-bar.yaml: two direct-drive motors 0.2 m apart, arms and
# forearms meeting at the tool point, a 0.3 kg tool): a two-DOF robot (`motion: translation`)
# whose pose is the tool point's [x, y]. Drawn, its workspace, one tool point both ways (its
# motors' angles, then the tool points of those angles against the circles' intersection in
# closed form), and the motors' torques along a circle drawn at 2 Hz, checked by the power
# balance and played back through the forward dynamics. Each step checks its result and the
# script fails (exit status 1) when one is off.

# %%
import os
import pathlib
import sys

import numpy as np

import nocdyn

root = pathlib.Path(os.environ.get("NOCDYN_SOURCE_DIR", pathlib.Path.cwd()))
path = root / "robots" / "five-bar.yaml"
out = pathlib.Path(os.environ.get("NOCDYN_EXAMPLE_OUT", "."))
robot = nocdyn.Robot.load(path)
print(robot, " pose coordinates:", robot.task_dimension, " home [x, y]:", robot.home)
(out / "five-bar.svg").write_text(robot.svg())
robot  # drawn in Jupyter: the motors (green), the arms, the forearms, the tool point C

# %% [markdown]
# ## Its workspace
# The tool points within both motors' ranges, away from both kinds of singularity (an arm and
# its forearm aligned; the two forearms aligned), on a 101 x 101 grid.

# %%
ws = nocdyn.workspace(robot=robot, resolution=101, figure=out / "five-bar-workspace")
print(ws.text)
print(f"feasible area: {ws.area * 1e4:.1f} cm^2")
if not 0.1 < ws.area < 0.3:
    sys.exit(f"the five-bar's workspace is {ws.area:.3g} m^2, not the 0.1-0.3 m^2 of its 0.45 m reach")

# %% [markdown]
# ## One tool point, both ways
# The inverse kinematics of the tool point gives the motors' angles u; the direct kinematics of
# u gives both tool points the two forearms can meet at, which are the intersections of two
# circles of the forearm's length about the elbows.

# %%
tool = np.array([0.04, 0.28])
report = nocdyn.pose(*tool, robot=robot)  # a two-DOF robot takes x, y and no theta
print("u [rad]:", report.u, " cond(A):", round(report.cond_A, 3))
modes = nocdyn.forward_kinematics(report.u, robot=robot, all_branches=True)
print("tool points of u [m]:", modes.poses.tolist())

motors, elbows_home = np.array([[-0.1, 0.0], [0.1, 0.0]]), np.array([[-0.2, 0.2], [0.2, 0.2]])
arm, forearm = np.linalg.norm(elbows_home[0] - motors[0]), 0.25
elbows = []
for m, e, angle in zip(motors, elbows_home, report.u):
    c, s = np.cos(angle), np.sin(angle)
    elbows.append(m + np.array([[c, -s], [s, c]]) @ (e - m))
d = np.linalg.norm(elbows[1] - elbows[0])
along = d / 2  # equal forearms: the chord's midpoint
unit = (elbows[1] - elbows[0]) / d
h = np.sqrt(forearm**2 - along**2)
normal = np.array([-unit[1], unit[0]])
closed_form = [elbows[0] + along * unit + h * normal, elbows[0] + along * unit - h * normal]
error = max(min(np.abs(modes.poses - p).max(axis=1)) for p in closed_form)
print(f"largest distance to the circles' intersections: {error:.2g} m")
if not error <= 1e-12:
    sys.exit(f"the direct kinematics misses the closed form by {error:.3g} m")
if not np.min(np.abs(modes.poses - tool).max(axis=1)) <= 1e-12:
    sys.exit("the tool point solved for is not among the direct kinematics' solutions")

# %% [markdown]
# ## Torques along a circle
# A circle of 3 cm radius about (0, 0.30) m drawn twice a second: the motors' torques tau by
# the NOC in one batch call (arrays of shape (N, 2), columns x, y), their peak against the
# motors' effort, and the power balance: the motors' power tau . du equals the rate of the
# kinetic energy (the five-bar lies in a horizontal plane: no gravity work).

# %%
rate, f, r = 4000.0, 2.0, 0.03
t = np.arange(0.0, 0.5, 1.0 / rate)
w = 2 * np.pi * f
P = np.column_stack([r * np.cos(w * t), 0.30 + r * np.sin(w * t)])
dP = np.column_stack([-r * w * np.sin(w * t), r * w * np.cos(w * t)])
ddP = np.column_stack([-r * w * w * np.cos(w * t), -r * w * w * np.sin(w * t)])
u, du, ddu, tau = robot.inverse_dynamics(P, dP, ddP)
peak = np.abs(tau).max(axis=0)
effort = np.array([a["effort"] for a in robot.actuator_info()])
print("peak |tau| [N m]:", peak.round(4), " effort:", effort)

power = np.sum(tau * du, axis=1)  # [W]


def circle(time):
    """The tool point and its velocity on the circle at `time`."""
    return (np.array([r * np.cos(w * time), 0.30 + r * np.sin(w * time)]),
            np.array([-r * w * np.sin(w * time), r * w * np.cos(w * time)]))


def kinetic(time):
    """T = 1/2 dp . I dp, with I the generalised inertia over x, y at the pose (nocdyn pose)."""
    p, dp = circle(time)
    return 0.5 * dp @ nocdyn.pose(*p, robot=robot).I @ dp


h, k = 1e-5, np.arange(0, len(t), 100)  # dT/dt by central differences every 25 ms
dT = np.array([(kinetic(t[i] + h) - kinetic(t[i] - h)) / (2 * h) for i in k])
balance = np.abs(dT - power[k]).max() / np.abs(power).max()
print(f"power balance |dT/dt - tau . du| / max|tau . du|: {balance:.2g} ({len(k)} samples)")

# %% [markdown]
# The check: every torque within its motor's effort, the power balance within the finite
# difference's error, and the torques played back through the forward dynamics (`nocdyn
# simulate`, from the first sample's state) draw the same circle.

# %%
forces = {"t": t, "tau1": tau[:, 0], "tau2": tau[:, 1], "u1": u[:, 0], "u2": u[:, 1],
          "du1": du[:, 0], "du2": du[:, 1]}
replayed = nocdyn.simulate(forces, robot=robot, rate=rate, duration=0.25)
n = len(replayed)
drift = max(np.abs(replayed["x"] - P[:n, 0]).max(), np.abs(replayed["y"] - P[:n, 1]).max())
print(f"forward dynamics of the torques over {replayed['t'][-1]:.3g} s: largest tool point error {drift:.2g} m")
if not np.all(peak <= effort):
    sys.exit(f"a torque exceeds its motor's effort: {peak} > {effort}")
if not balance <= 1e-6:
    sys.exit(f"the power balance is off by {balance:.3g}")
if not drift <= 1e-6:
    sys.exit(f"the torques do not draw the circle: tool point error {drift:.3g} m")
print("checked: the workspace, both tool points, the efforts, the power balance and the motion")
