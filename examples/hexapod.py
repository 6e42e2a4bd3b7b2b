# %% [markdown]
# # A hexapod, from its file to its leg forces
#
# A 6-UPS Gough-Stewart shake table (robots/stewart.yaml: six electric cylinders of +-0.15 m
# stroke, 0.5 m/s and 10 kN between a U at the base and an S under a 300 kg table): its pose
# [x, y, z, roll, pitch, yaw] (m, rad; R = Rz(yaw) Ry(pitch) Rx(roll)), the legs' lengths of a
# pose against the closed form, every assembly mode of those lengths, the cylinders' forces
# along a sway against their limits, and two checks of those forces: the power balance and the
# legs as two-force members. Each step checks its result and the script fails (exit status 1)
# when one is off.

# %%
import os
import pathlib
import re
import shutil
import sys

import numpy as np

import nocdyn

root = pathlib.Path(os.environ.get("NOCDYN_SOURCE_DIR", pathlib.Path.cwd()))
path = root / "robots" / "stewart.yaml"
sway = root / "trajectories" / "stewart-sway.yaml"
out = pathlib.Path(os.environ.get("NOCDYN_EXAMPLE_OUT", "."))
robot = nocdyn.Robot.load(path)
print(robot.name, "pose coordinates:", robot.coordinates, " home:", robot.home.round(6).tolist())


def rotation(roll, pitch, yaw):
    """R = Rz(yaw) Ry(pitch) Rx(roll), the robot files' convention."""
    c, s = np.cos, np.sin
    return (np.array([[c(yaw), -s(yaw), 0], [s(yaw), c(yaw), 0], [0, 0, 1]])
            @ np.array([[c(pitch), 0, s(pitch)], [0, 1, 0], [-s(pitch), 0, c(pitch)]])
            @ np.array([[1, 0, 0], [0, c(roll), -s(roll)], [0, s(roll), c(roll)]]))


# %% [markdown]
# ## One pose: the legs' lengths in closed form
# `nocdyn pose X Y Z ROLL PITCH YAW --robot robots/stewart.yaml` prints what `robot.pose(p)`
# returns: every limb's joint variables, the cylinders' strokes u (0 at home), the actuation map,
# and at rest under gravity the cylinders' forces and every joint's reaction. A leg's length is
# the distance from its base U to its S, which the table carries: s_i = p + R b_i with b_i the S
# at home less the home position. The strokes are those lengths less the 1.2 m at home.

# %%
home = robot.pose(robot.home)
p = robot.home + np.array([0.02, -0.01, 0.03, 0.05, -0.03, 0.1])
report = robot.pose(p)
print(f"at p = {p.round(4).tolist()}: strokes u [mm] = {(report.u * 1e3).round(3).tolist()}, "
      f"cond(A) = {report.cond_A:.3g}")
base = np.array([r["point"] for r in home.reactions if r["type"] == "U"])
carried = np.array([r["point"] for r in home.reactions if r["type"] == "S"]) - robot.home[:3]
spheres = p[:3] + carried @ rotation(*p[3:]).T
lengths = np.linalg.norm(spheres - base, axis=1)
error = np.max(np.abs(lengths - 1.2 - report.u))
print(f"largest difference from the closed form |p + R b_i - a_i| - 1.2 m: {error:.2g} m")
if not error <= 1e-12:
    sys.exit(f"the strokes miss the closed form by {error:.3g} m")
if not report.within_limits or np.max(report.range_used) >= 1.0:
    sys.exit(f"the pose should be within the strokes: {report.limits}")

# %% [markdown]
# ## The same lengths, every way the table can sit on them
# The direct kinematics: `robot.forward_kinematics(u)` (`nocdyn forward-kinematics U1 ... U6`)
# runs Newton from deterministic seeds; `robot.assembly_modes(u)` solves the 40th-degree
# polynomial system by homotopy continuation (PHCpack's `phc`) and lists every real assembly
# mode. The pose above is among both, and every mode found gives back the six lengths by the
# closed form above.

# %%
modes = robot.forward_kinematics(report.u)
nearest = min(np.max(np.abs(m["pose"] - p)) for m in modes)
print(f"Newton from many starts: {len(modes)} modes; the pose to {nearest:.2g}")
if not nearest <= 1e-9:
    sys.exit(f"the pose is not among the direct kinematics' modes ({nearest:.3g})")
if shutil.which("phc"):
    homotopy = robot.assembly_modes(report.u, seed=1)
    found = min(np.max(np.abs(q - p)) for q in homotopy)
    gives_back = max(np.max(np.abs(np.linalg.norm(q[:3] + carried @ rotation(*q[3:]).T - base, axis=1) - lengths))
                     for q in homotopy)
    print(f"homotopy continuation: {len(homotopy)} real assembly modes; the pose to {found:.2g}, "
          f"lengths given back to {gives_back:.2g} m")
    if not (found <= 1e-8 and gives_back <= 1e-8 and len(homotopy) >= len(modes)):
        sys.exit("the homotopy's modes do not hold the pose or do not give back the lengths")
else:
    print("(PHCpack's phc is not installed: the homotopy step is skipped)")

# %% [markdown]
# ## The cylinders' forces along a sway
# trajectories/stewart-sway.yaml moves every coordinate at once (a few millimetres and about a
# degree, 1 to 3 Hz). `nocdyn.inverse_dynamics` (`nocdyn inverse-dynamics --robot
# robots/stewart.yaml --trajectory trajectories/stewart-sway.yaml`) gives the strokes u, their
# rates du and the forces tau along it, gravity and the cylinders' friction included; each peak is
# checked against the cylinder's stroke, rate and force in the file's `limits`.

# %%
table = nocdyn.inverse_dynamics(str(sway), robot=str(path), rate=2000.0)
columns = table.columns
data = np.asarray(table.data)
u = data[:, [columns.index(f"u{i}") for i in range(1, 7)]]
du = data[:, [columns.index(f"du{i}") for i in range(1, 7)]]
tau = data[:, [columns.index(f"tau{i}") for i in range(1, 7)]]
peaks = np.abs(u).max(), np.abs(du).max(), np.abs(tau).max()
print(f"peaks: stroke {peaks[0] * 1e3:.2f} mm of 150, rate {peaks[1]:.3f} m/s of 0.5, "
      f"force {peaks[2]:.0f} N of 10 000 (at rest: {np.abs(home.tau).max():.0f} N)")
if not (peaks[0] < 0.15 and peaks[1] < 0.5 and peaks[2] < 1e4):
    sys.exit(f"the sway exceeds a cylinder's limits: {peaks}")

# %% [markdown]
# ## Two checks of the forces
# With the legs' masses and the cylinders' friction taken out of the file, each leg is a
# two-force member (a U and an S, nothing between them with mass), so
# - the cylinders' power sum tau_i du_i equals the rate of the table's kinetic energy (the
#   `kinetic` column) plus that of its potential energy m g z_c, z_c the height of its c.o.m.
#   (0, 0, 0.05) m in the table's frame;
# - at rest, the S joints pass each leg's force along the leg to the table: tau_i n_i, n_i the
#   leg's direction, is the reaction of `robot.pose(p)` at each S.

# %%
text = path.read_text()
text = re.sub(r"\{mass: (25|8)\.0, com", "{mass: 0.0, com", text)
text = re.sub(r"damping: 200\.0, friction: 50\.0", "damping: 0.0, friction: 0.0", text)
light = out / "stewart-massless-legs.yaml"
light.write_text(text)
table = nocdyn.inverse_dynamics(str(sway), robot=str(light), rate=10000.0)
data = np.asarray(table.data)
t = data[:, 0]
P = data[:, [table.columns.index(c) for c in robot.coordinates]]
power = np.sum(data[:, [table.columns.index(f"tau{i}") for i in range(1, 7)]]
               * data[:, [table.columns.index(f"du{i}") for i in range(1, 7)]], axis=1)
z_c = np.array([q[2] + (rotation(*q[3:]) @ np.array([0.0, 0.0, 0.05]))[2] for q in P])
energy = data[:, table.columns.index("kinetic")] + 300.0 * 9.81 * z_c
rate_of_energy = np.gradient(energy, t)
inner = slice(2, -2)  # central differences: second order inside
balance = np.max(np.abs(power[inner] - rate_of_energy[inner])) / np.max(np.abs(power))
print(f"power balance: largest difference {balance:.2g} of the peak power {np.max(np.abs(power)):.0f} W")
if not balance <= 1e-5:
    sys.exit(f"the power balance is off by {balance:.3g} of the peak power")

still = nocdyn.Robot.load(light).pose(p)
legs = np.array([r["point"] for r in still.reactions if r["type"] == "S"]) - base
legs /= np.linalg.norm(legs, axis=1)[:, None]
on_table = np.array([r["force"] for r in still.reactions if r["type"] == "S"])
two_force = np.max(np.abs(on_table - still.tau[:, None] * legs))
print(f"S joints' forces against tau_i n_i: {two_force:.2g} N (forces up to {np.abs(still.tau).max():.0f} N)")
if not two_force <= 1e-9 * np.abs(still.tau).max():
    sys.exit(f"the S joints do not pass the legs' forces along the legs ({two_force:.3g} N)")
print("every check passed")
