"""Spatial parallel robots (robot files with ``space: spatial``): the Delta (pose [x, y, z]) and
the Gough-Stewart hexapods (pose [x, y, z, roll, pitch, yaw], R = Rz(yaw) Ry(pitch) Rx(roll)),
and their inverse dynamics by the natural orthogonal complement in six dimensions.

``nocdyn.Robot.load(path)`` returns a SpatialRobot for a spatial file; it has the inverse
dynamics on sample arrays, and ``nocdyn.inverse_dynamics(trajectory, robot=...)`` takes it (or
the file's path) with a spatial trajectory file (the other Robot methods and the other commands
are planar for now)."""

from __future__ import annotations

import numpy as np

from . import _nocdyn
from ._guards import _MAX_THREADS, _floats, _input, _integer
from .dynamics import InverseDynamics

__all__ = ["SpatialRobot"]


class SpatialRobot:
    """A spatial parallel robot built from a robot file (``space: spatial``,
    ``motion: full | translation``).

    Vocabulary: a pose is [x, y, z, roll, pitch, yaw] (m and rad; R = Rz(yaw) Ry(pitch)
    Rx(roll)) for motion full, [x, y, z] for motion translation (the platform keeps the base
    frame's orientation); dp and ddp are the time derivatives of these numbers (Euler-angle
    rates, not the angular velocity). Actuators are numbered in file order.
    """

    __slots__ = ("_core",)

    def __init__(self, core):
        """Internal: use nocdyn.Robot.load(path) or SpatialRobot.load(path)."""
        if not isinstance(core, _nocdyn.SpatialRobot):
            raise TypeError("use nocdyn.Robot.load(path) or nocdyn.SpatialRobot.load(path)")
        self._core = core

    @classmethod
    def load(cls, path):
        """Reads and checks a spatial robot file; raises nocdyn.Error naming the file, line,
        limb, joint or body and field."""
        return cls(_nocdyn.SpatialRobot.load(str(path)))

    @classmethod
    def from_yaml(cls, text, source="<string>"):
        """Parses spatial robot YAML text; `source` names it in error messages."""
        return cls(_nocdyn.SpatialRobot.from_yaml(text, source))

    @property
    def name(self):
        """The robot's name (from its file)."""
        return self._core.name

    @property
    def actuators(self):
        """Number n of actuated joints (the columns of u, du, ddu, tau)."""
        return self._core.actuator_count

    @property
    def limbs(self):
        """Number of limbs."""
        return self._core.limb_count

    @property
    def limb_names(self):
        """The limbs' names, in file order."""
        return list(self._core.limb_names)

    @property
    def task_dimension(self):
        """6 (motion full) or 3 (motion translation): the columns of a pose array."""
        return self._core.task_dimension

    @property
    def coordinates(self):
        """The pose coordinates' names: ['x', 'y', 'z'] and, for motion full, 'roll', 'pitch', 'yaw'."""
        return list(self._core.coordinates)

    @property
    def home(self):
        """The platform pose at home, shape (task_dimension,)."""
        return np.array(self._core.home)

    def inverse_dynamics(self, p, dp, ddp, *, threads=1, check=True, check_limits=True):
        """Actuator variables, rates, accelerations and forces for platform motions.

        p, dp, ddp of shape (N, d) or (d,) with d = task_dimension (columns in the order of
        ``coordinates``; float64) give InverseDynamics(u, du, ddu, tau), each of shape (N, n)
        (or (n,) for one sample): u the joint variables of the actuated joints (m or rad, 0 at
        home), tau the actuator forces (N or N m) along them, gravity and joint friction
        included; the minimum-norm forces when there are more actuators than pose coordinates.
        A sample out of reach or singular raises nocdyn.Error "sample K: <reason>" (K from 1);
        check=False returns it as a NaN row instead. With check_limits=True (the default) the
        first sample where an R or P joint leaves its range or exceeds its velocity, or an actuator
        its effort (the file's ``limits``; U and S joints take none), raises nocdyn.Error with the
        command line's reason ("sample K: joint range exceeded: limb 1 (arm1), joint 1: q = ...");
        check_limits=False checks none. The GIL is released during the computation. threads
        (0..1024) > 1 splits the samples over that many C++ threads, at most one per hardware
        thread and 8 samples (0: one per hardware thread); the sample K raised is that of
        threads=1, and so are the results (to Newton's tolerance for a limb with no closed form,
        which each thread's first sample solves from home).
        """
        threads = min(_integer(threads, "threads", 0, 2**63), _MAX_THREADS)
        d = self.task_dimension
        p_arr = _floats(p, "p")
        single = p_arr.ndim == 1
        shape = (d,) if single else (None, d)
        p_arr = _input(p_arr, "p", shape, finite=False)
        n = p_arr.shape[0] if not single else None
        dp_arr = _input(dp, "dp", (d,) if single else (n, d), finite=False)
        ddp_arr = _input(ddp, "ddp", (d,) if single else (n, d), finite=False)
        rows = [np.ascontiguousarray(a.reshape(-1, d)) for a in (p_arr, dp_arr, ddp_arr)]
        u, du, ddu, tau = self._core._inverse_dynamics(*rows, bool(check), bool(check_limits), threads)
        if single:
            return InverseDynamics(u[0], du[0], ddu[0], tau[0])
        return InverseDynamics(u, du, ddu, tau)

    def pose(self, p):
        """Everything the model knows at pose p (d numbers in the order of ``coordinates``), as
        ``nocdyn pose`` prints it: a SpatialPoseReport (every limb's joint variables and
        condition number, the actuators and the share of their range used, the actuation map,
        and at rest under gravity the actuator forces and every joint's reaction). A pose out of
        reach or singular raises nocdyn.Error; a joint beyond its range is reported
        (within_limits False, limits) and warned of."""
        from .results import SpatialPoseReport
        values = _floats(p, "pose")
        if values.ndim != 1:
            raise ValueError(f"pose: expected one pose of {self.task_dimension} numbers, got shape {values.shape}")
        return SpatialPoseReport(self._core._pose([float(v) for v in values]))  # the count checked there

    def forward_kinematics(self, u):
        """Every platform pose found with actuator values u (n values, m or rad, in file order).

        Returns a list of dicts, nearest home first: pose (np.ndarray in the order of
        ``coordinates``: [x, y, z] or [x, y, z, roll, pitch, yaw]; roll, yaw in (-pi, pi],
        pitch in [-pi/2, pi/2]), working (True for the working mode: its limbs on their home
        branches, the nearest such mode to home), home_branches (inverse kinematics from home
        gives back u), u_error (the largest abs(u(p) - u)) and condition (the largest of the limbs' and the
        actuation map's condition numbers), and method ("three spheres": a Delta of three
        R-U-U limbs, both modes in closed form; "many starts": the modes continuation from
        deterministic seeds finds, perhaps not every one). Empty when no pose closes the loops.
        """
        values = _input(u, "u", (self.actuators,))
        result = self._core._forward_kinematics([float(v) for v in values])
        modes = []
        for mode in result["modes"]:
            mode = dict(mode)
            mode["pose"] = np.array(mode["pose"], dtype=np.float64)
            mode["method"] = result["method"]
            modes.append(mode)
        return modes

    def track(self, u, p0=None):
        """The platform poses of actuator samples u (N, n) (or one sample (n,)), each by Newton on
        u(p) - u from the previous pose (the first from p0, default home): the tracker a
        controller or a simulation runs, converging to 1e-13 in u and keeping the assembly mode
        of p0. Returns poses (N, d) (or (d,)) in the order of ``coordinates``; a sample where
        Newton does not converge, out of reach or singular raises nocdyn.Error "sample K: ..."."""
        d = self.task_dimension
        u_arr = _floats(u, "u")
        single = u_arr.ndim == 1
        u_arr = _input(u_arr, "u", (self.actuators,) if single else (None, self.actuators))
        start = self.home if p0 is None else _input(p0, "p0", (d,))
        poses = self._core._track(np.ascontiguousarray(u_arr.reshape(-1, self.actuators)),
                                  [float(v) for v in start])
        return poses[0] if single else poses

    def assembly_modes(self, u, *, timeout=120.0, seed=0, executable="", details=False):
        """Every real assembly mode of a 6-UPS hexapod (each limb a U at the base, the actuated
        P, an S at the platform) at the actuator values u: the poses at which the legs have the
        lengths that u gives, by polynomial homotopy continuation (PHCpack's ``phc -b``, Debian
        package phcpack, run as a separate program).

        u of shape (6,) (m, actuator order) gives an array of shape (m, 6) of poses
        [x, y, z, roll, pitch, yaw], nearest to home first, each checked by the inverse
        kinematics (its u back to 1e-9 m). ``timeout`` [s] stops phc; ``seed`` fixes phc's
        random numbers (0: from the clock); ``executable`` is phc's path (empty: ``phc`` on
        PATH). details=True returns (poses, u_error, info) with info the counts (paths,
        finite complex solutions, real ones, rejected ones) and phc's wall and CPU seconds.
        Raises nocdyn.Error for another kind of robot, a missing phc (naming phcpack), a phc
        that fails or runs too long. The GIL is released while phc runs.
        """
        u_arr = _input(u, "u", (self.actuators,))
        poses, errors, info = self._core._assembly_modes(np.ascontiguousarray(u_arr), float(timeout), int(seed),
                                                         str(executable))
        if details:
            return poses, errors, info
        return poses

    def __repr__(self):
        return (f"SpatialRobot('{self.name}': {self.limbs} limbs, {self.actuators} actuators, "
                f"pose {', '.join(self.coordinates)})")


def _load_any(path, planar):
    """Robot.load's dispatch: a spatial file gives a SpatialRobot, any other the planar Robot."""
    if _nocdyn.is_spatial_file(str(path)):
        return SpatialRobot.load(path)
    return planar()


def _from_yaml_any(text, source, planar):
    if _nocdyn.is_spatial_text(text, source):
        return SpatialRobot.from_yaml(text, source)
    return planar()

