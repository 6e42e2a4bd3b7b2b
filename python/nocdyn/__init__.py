"""nocdyn: kinematics and dynamics of planar parallel robots by the natural orthogonal complement.

The Python face of the nocdyn C++ library (the general model of any planar parallel robot
described by a per-limb robot file). Everything is in SI units: metres, radians, seconds,
kilograms, newtons (newton metres for revolute actuators).

The vocabulary, the same as the command line's CSV tables: a platform pose is p = [x, y, theta]
(m, m, rad), its rate dp and acceleration ddp in the same order, and so is every row or column
that runs over the pose coordinates (derivatives, linearised states); SI units; limbs, joints
and actuators are numbered from 1 where a person reads the number (as the command line
names them), array axes from 0; the core keeps its internal twist order [theta, x, y] inside.
Arrays of samples have one row per sample: poses are (N, 3) float64 arrays, actuator
quantities (N, n) with n = robot.actuators.

Quick start::

    import nocdyn
    robot = nocdyn.Robot.load("robots/paper-3prr.yaml")    # or nocdyn.Robot.example("3-rrr")
    traj = nocdyn.Trajectory.paper(1)                        # eq. 33 of the paper
    t = np.arange(2000) / 10000.0
    P, dP, ddP = traj.evaluate(t)                            # (N, 3) each: [x, y, theta]
    u, du, ddu, tau = robot.inverse_dynamics(P, dP, ddP)     # (N, n) each, GIL released

Every command of the `nocdyn` command line is a function here, running the command's own code
with the same options (``--foo-bar`` is ``foo_bar=``), defaults, checks and numbers::

    nocdyn.pose(0.01, 0.001, -0.002)                      # nocdyn pose 0.01 0.001 -0.002
    table = nocdyn.inverse_dynamics("paper1")             # a Table: table["tau1"], to_pandas()
    nocdyn.control("paper1", plant="nocdyn", payload_mass=0.5)
    nocdyn.shake("data/elcentro_1940_ns.AT2", window=5)    # nocdyn shake --record ... --window 5

pose, inverse_dynamics, forward_kinematics, simulate, control, envelope, workspace, convert,
animate, shake, regressor, identify, excite, loads, validate and reproduce (nocdyn.COMMANDS maps
each command to its function; nocdyn.commands has the details, nocdyn.results the answers).

Errors (a pose out of reach, a singular posture, a bad robot file, ...) raise nocdyn.Error, a
subclass of ValueError, with the message the command line prints (a batch's sample K numbered
from 1). Arrays of the wrong dtype raise TypeError.

The package by concept: nocdyn.robot (Robot), nocdyn.dynamics (its algorithms on sample arrays),
nocdyn.trajectory (Trajectory), nocdyn.identification (PayloadEstimate, load_prior),
nocdyn.commands (every command's job), nocdyn.results (their answers), nocdyn.designs (sweeps,
optimisation, Dask), nocdyn.drawing (SVG). This file only re-exports them.
"""

from __future__ import annotations

from . import _nocdyn
from ._nocdyn import Error
from .commands import (COMMANDS, animate, control, convert, design, envelope, excite, forward_kinematics,
                       frequency_response, identify, inverse_dynamics, loads, pose, regressor, reproduce, shake,
                       simulate, validate, workspace)
from .dynamics import ActuatorDerivatives, InverseDynamics, InverseDynamicsMatrices, LinearModel
from .identification import PayloadEstimate, load_prior
from .results import (Animation, AssemblyModes, Envelope, Excitation, Identification, PoseReport, Report, ShakeResult,
                      SpatialPoseReport, Table, Workspace)
from .robot import Robot
from .spatial import SpatialRobot
from .trajectory import Trajectory

__all__ = ["Error", "Robot", "SpatialRobot", "Trajectory", "InverseDynamics", "InverseDynamicsMatrices", "ActuatorDerivatives",
           "LinearModel", "PayloadEstimate", "load_prior",
           # every command of the command line (nocdyn.commands), and their results (nocdyn.results)
           "pose", "inverse_dynamics", "forward_kinematics", "simulate", "control", "envelope", "workspace", "convert",
           "animate", "shake", "regressor", "identify", "excite", "loads", "validate", "reproduce", "design", "COMMANDS",
           "frequency_response",
           "Table", "PoseReport", "SpatialPoseReport", "AssemblyModes", "Workspace", "Envelope", "Identification", "Excitation",
           "ShakeResult", "Animation", "Report"]
__version__ = _nocdyn.__version__  # the CMake project version, as `nocdyn --version`

Error.__module__ = "nocdyn"
Error.__doc__ = """An error nocdyn reports: one line naming the problem (file, line, field, limb,
sample time as they apply), the same text as the command line's. A subclass of ValueError."""

# the public classes under the package's name (help(), repr, the API pages), wherever defined
for _public in (Robot, Trajectory, PayloadEstimate, LinearModel, InverseDynamics, InverseDynamicsMatrices,
                ActuatorDerivatives):
    _public.__module__ = "nocdyn"
del _public

from . import designs  # noqa: E402,F401  (nocdyn.designs: sweeps, optimisation, Dask)
