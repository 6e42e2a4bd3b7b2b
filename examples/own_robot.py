# %% [markdown]
# # Your own robot: from its file to its forces
#
# A 3-RRR robot described by a file (robots/3-rrr.yaml, the general per-limb form): drawn, its
# workspace, one pose, the assembly modes of its actuator values, and the actuator forces along
# a harmonic trajectory about its home. Run it as a script or open it as a notebook (jupytext).
# Each step checks its result against the truth it started from (the pose it solved for, the
# actuators' limits, the motion it asked for) and the script fails (exit status 1) when one is off.

# %%
import os
import pathlib
import sys

import numpy as np

import nocdyn

root = pathlib.Path(os.environ.get("NOCDYN_SOURCE_DIR", pathlib.Path.cwd()))
path = root / "robots" / "3-rrr.yaml"
out = pathlib.Path(os.environ.get("NOCDYN_EXAMPLE_OUT", "."))
robot = nocdyn.Robot.load(path)
(out / "3-rrr.svg").write_text(robot.svg())
robot  # drawn in Jupyter: base, limbs, platform, the actuated joints in green

# %%
ws = nocdyn.workspace(robot=robot, resolution=61)
print(ws.text)
print(f"feasible area from the grid: {ws.area * 1e4:.2f} cm^2")

# %%
x, y, theta = robot.home + np.array([0.002, -0.001, 0.02])  # Robot's poses: [x, y, theta]
report = nocdyn.pose(x, y, theta, robot=robot)
print("u [rad]:", report.u, " cond(A):", round(report.cond_A, 3))
modes = nocdyn.forward_kinematics(report.u, robot=robot, all_branches=True)
print(f"{len(modes)} assembly modes; working modes: {int(modes.working.sum())}")
# the check: the direct kinematics of u gives back the pose u was computed from
distance = np.min(np.abs(modes.poses - report.pose).max(axis=1))  # both x, y, theta
print(f"nearest assembly mode to the pose solved for: {distance:.2g} (m, rad)")
if not distance <= 1e-9:
    sys.exit(f"the direct kinematics misses the pose by {distance:.3g}")

# %%
home = robot.home
trajectory = out / "own.yaml"
trajectory.write_text(f"""name: small circle about home
duration: 0.2
x:     {{offset: {home[0]!r}, harmonics: [{{amplitude: 0.002, frequency: 5, phase: 0}}]}}
y:     {{offset: {home[1]!r}, harmonics: [{{amplitude: 0.002, frequency: 5, phase: 1.5707963267948966}}]}}
theta: {{offset: {home[2]!r}, harmonics: [{{amplitude: 0.01, frequency: 5, phase: 0}}]}}
""")
forces = nocdyn.inverse_dynamics(str(trajectory), robot=robot, rate=2000.0)
peak = np.abs(forces.group("tau")).max(axis=0)
effort = np.array([a["effort"] for a in robot.actuator_info()])
print("peak |tau| [N m]:", peak, " effort limits:", effort)

# %% [markdown]
# The check: every force within its actuator's effort, and the forces played back through the
# forward dynamics (`nocdyn simulate`, from the first sample's state) move the platform along the
# trajectory they were computed for.

# %%
replayed = nocdyn.simulate(forces, robot=robot, rate=2000.0, duration=0.1)
n = len(replayed)
error = max(np.abs(replayed[axis] - forces[axis][:n]).max() for axis in ("x", "y", "theta"))
print(f"forward dynamics of the forces over {replayed['t'][-1]:.3g} s: largest pose error {error:.2g} (m, rad)")
if not np.all(peak <= effort):
    sys.exit(f"a force exceeds its actuator's effort: {peak} > {effort}")
if not error <= 1e-6:
    sys.exit(f"the forces do not reproduce the motion: pose error {error:.3g}")
print("checked: the pose, the efforts and the motion")
