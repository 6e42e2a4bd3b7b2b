# %% [markdown]
# # Your own robot: from its file to its forces
#
# A 3-RRR robot described by a file (robots/3-rrr.yaml, the general per-limb form): drawn, its
# workspace, one pose, the assembly modes of its actuator values, and the actuator forces along
# a harmonic trajectory about its home. Run it as a script or open it as a notebook (jupytext).

# %%
import os
import pathlib

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
theta, x, y = robot.home + np.array([0.02, 0.002, -0.001])
report = nocdyn.pose(theta, x, y, robot=robot)
print("u [rad]:", report.u, " cond(A):", round(report.cond_A, 3))
modes = nocdyn.forward_kinematics(report.u, robot=robot, all_branches=True)
print(f"{len(modes)} assembly modes; working modes: {int(modes.working.sum())}")

# %%
home = robot.home
trajectory = out / "own.yaml"
trajectory.write_text(f"""name: small circle about home
duration: 0.2
x:     {{offset: {home[1]!r}, harmonics: [{{amplitude: 0.002, frequency: 5, phase: 0}}]}}
y:     {{offset: {home[2]!r}, harmonics: [{{amplitude: 0.002, frequency: 5, phase: 1.5707963267948966}}]}}
theta: {{offset: {home[0]!r}, harmonics: [{{amplitude: 0.01, frequency: 5, phase: 0}}]}}
""")
forces = nocdyn.inverse_dynamics(str(trajectory), robot=robot, rate=2000.0)
print("peak |tau| [N m]:", np.abs(forces.group("tau")).max(axis=0))
