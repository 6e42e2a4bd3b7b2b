"""The robot: the general NOC model of a planar parallel robot built from a robot file, and its
algorithms bound one to one (inverse dynamics on sample arrays and its derivatives, reactions,
regressor and linearisation in nocdyn.dynamics; direct kinematics, the state from actuator
values, stiffness and natural frequencies here). Jobs (a trajectory, a simulation, an envelope,
an identification) are nocdyn.<command>(..., robot=robot) (nocdyn.commands)."""

from __future__ import annotations

import os
import warnings

from . import _nocdyn
from . import commands as _commands
from . import spatial as _spatial
from ._guards import _input, _integer, _number, _vocabulary
from ._nocdyn import Error
from .dynamics import RobotDynamics
from .identification import PayloadEstimate, log_columns

__all__ = ["Robot"]


def _deprecated(old, new):
    warnings.warn(f"{old} is deprecated and will be removed in the next release: use {new}", DeprecationWarning,
                  stacklevel=3)


def _ignored(method, options, names):
    """Old keyword arguments without a counterpart in the job: removed from options, said once."""
    for name in names:
        if options.pop(name, None) is not None:
            warnings.warn(f"{method}: {name} is no longer an option and is ignored", UserWarning, stacklevel=4)


def _old_simulate(actuators, t, forces, force_times=None, **options):
    """Robot.simulate's old arguments (output times t, forces (M, n) at force_times, default t)
    as the job's forces table and options."""
    import numpy as np

    t = np.asarray(t, dtype=float).reshape(-1)
    times = t if force_times is None else np.asarray(force_times, dtype=float).reshape(-1)
    forces = np.asarray(forces, dtype=float).reshape(times.shape[0], -1)
    if forces.shape[1] != actuators:
        raise ValueError(f"forces: expected {actuators} columns (one per actuator), got {forces.shape[1]}")
    if t.shape[0] < 2 or not np.all(np.diff(t) > 0):
        raise ValueError("t: expected increasing output times [s], at least two")
    for name in ("p0", "dp0", "u0", "du0"):
        if name in options and name != "dp0" or name == "dp0" and any(options.get(name, (0.0,))):
            raise ValueError(f"Robot.simulate: {name} is no longer an option: give the initial state as "
                             "u1..un, du1..dun in the forces' first row (nocdyn.simulate)")
        options.pop(name, None)
    options.setdefault("duration", float(t[-1] - t[0]))
    options.setdefault("rate", float((t.shape[0] - 1) / (t[-1] - t[0])))
    columns = {"t": times, **{f"tau{i + 1}": forces[:, i] for i in range(actuators)}}
    return columns, options


class Robot(RobotDynamics):
    """A planar parallel robot: the general NOC model built from a robot file.

    Create one with Robot.load(path), Robot.from_yaml(text), Robot.example(name) (the robots
    shipped in robots/: paper-3prr, paper-3prr-general, 3-rrr, 3-rpr, 4-rrr) or Robot.paper()
    (the paper's 3-PRR prototype). A Robot is immutable and may be shared between threads.

    Vocabulary: a pose is [x, y, theta] (m, m, rad), its rates in the same order, as in the command
    line's CSV tables; SI units; limbs, joints and actuators numbered from 1; array axes from 0; the
    core's internal twist order [theta, x, y] stays inside the core.
    """

    __slots__ = ("_core",)

    def __init__(self, core):
        """Internal: use Robot.load, Robot.from_yaml, Robot.example or Robot.paper."""
        if not isinstance(core, _nocdyn.Robot):
            raise TypeError("use Robot.load(path), Robot.from_yaml(text), Robot.example(name) or Robot.paper()")
        self._core = core

    # --- construction ---------------------------------------------------------------
    @classmethod
    def load(cls, path):
        """Reads and validates a robot file of either form (general per-limb, or the paper's
        3-PRR short form). Raises nocdyn.Error naming the file, line, limb, joint and field.
        A spatial robot file (``space: spatial``) gives a nocdyn.SpatialRobot (its inverse
        dynamics; nocdyn.spatial)."""
        return _spatial._load_any(path, lambda: cls(_nocdyn.Robot.load(str(path))))

    @classmethod
    def from_yaml(cls, text, source="<string>"):
        """Parses robot YAML text of either form; `source` names it in error messages. Spatial
        text gives a nocdyn.SpatialRobot."""
        return _spatial._from_yaml_any(text, source, lambda: cls(_nocdyn.Robot.from_yaml(text, source)))

    @classmethod
    def example(cls, name):
        """One of the example robots compiled into the library (see Robot.examples())."""
        return cls(_nocdyn.Robot.example(name))

    @staticmethod
    def examples():
        """Names of the example robots: ['paper-3prr', 'paper-3prr-general', '3-rrr', ...]."""
        return list(_nocdyn.Robot.example_names())

    @classmethod
    def paper(cls):
        """The paper's 3-PRR prototype (robots/paper-3prr.yaml)."""
        return cls(_nocdyn.Robot.paper())

    # --- description ------------------------------------------------------------------
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
    def bodies(self):
        """Number of moving bodies, 2 * limbs + 1 (the platform last)."""
        return self._core.bodies

    @property
    def home(self):
        """Platform pose at home [x, y, theta] (m, m, rad), shape (3,); for a two-DOF robot the tool
        point's [x, y] (m), shape (2,)."""
        return self._core.home

    @property
    def task_dimension(self):
        """Number of pose coordinates: 3 ([x, y, theta]) or 2 (motion: translation, [x, y] of the
        tool point: a two-DOF robot such as the five-bar or the biglide)."""
        return self._core.task_dimension

    @property
    def redundant(self):
        """True when the robot has more than three actuators (minimum-norm forces)."""
        return self._core.redundant

    def limb_info(self):
        """Per limb: dict(name, type 'PRR'/'RRR'/..., actuated: 3 booleans, base to platform)."""
        return self._core.limb_info()

    def actuator_info(self):
        """Per actuator, in file order (list index a is actuator a + 1, column a of u and tau):
        dict(limb, limb_name, joint, type 'P' or 'R', lower, upper [m or rad], effort [N or N m],
        velocity [m/s or rad/s]) (inf when absent); limb and joint are numbered from 1 as the
        command line names them (joint 1 at the base)."""
        return self._core.actuator_info()

    def to_yaml(self):
        """The robot in the general file form (numbers read back exactly)."""
        return self._core.to_yaml()

    def __repr__(self):
        return f"<nocdyn.Robot {self.name!r}: {self.limbs} limbs, {self.actuators} actuators>"

    def svg(self, pose=None):
        """The robot drawn as SVG text at pose [x, y, theta] ([x, y] for a two-DOF robot; default
        home): base, limbs, platform, C, actuated joints marked (green). Jupyter shows a Robot this
        way (_repr_svg_)."""
        from .drawing import robot_svg
        return robot_svg(self, pose)

    def _repr_svg_(self):
        return self.svg()

    # --- identification -------------------------------------------------------------
    def parameter_names(self):
        """Names of the P standard parameters, the columns of the regressor: per body (first
        bodies of the limbs, second bodies, the platform) m, mc_x, mc_y, I_O in the body's own
        frame ('platform.m', 'limb1.body2.I_O', ...), then per joint damping and friction
        ('limb1.joint1.damping', ...). See `nocdyn regressor`."""
        return list(self._core._parameter_names())

    def parameter_units(self):
        """Units of the standard parameters ('kg', 'kg m', 'kg m^2', 'N s/m', 'N', ...)."""
        return list(self._core._parameter_units())

    def standard_parameters(self):
        """The standard parameters pi of the robot file, shape (P,): tau = Y pi."""
        return self._core._standard_parameters()

    def with_payload(self, mass, com=(0.0, 0.0), inertia=0.0):
        """This robot with a payload merged into its platform: mass [kg], c.o.m. [x, y] in the
        platform frame [m], moment of inertia about its own c.o.m. [kg m^2]. A two-DOF robot's
        platform is a point mass at the tool point: its payload is a mass there (com [0, 0],
        inertia 0)."""
        com = _input(com, "com", (2,))
        if self._core.task_dimension == 2 and (any(c != 0.0 for c in com) or _number(inertia, "inertia") != 0.0):
            raise Error("with_payload: a two-DOF robot's payload is a point mass at its tool point: "
                        "com must be [0, 0] and inertia 0")
        return Robot(self._core._with_payload(_number(mass, "mass"), [float(v) for v in com],
                                              _number(inertia, "inertia")))


    # --- direct kinematics ----------------------------------------------------------
    @_vocabulary
    def forward_kinematics(self, u, *, tolerance=1e-9):
        """Every platform pose the robot assembles in with actuator values u (n values, m or rad).

        Returns a list (sorted by theta) of dicts: pose [x, y, theta] ([x, y] for a two-DOF
        robot), branch (each limb's
        inverse-kinematics branch, +1/-1, 0 for limbs with one solution), working (True for the
        robot's working mode: every limb on its home branch), u_error (how well the pose gives
        back u) and condition (large next to a singularity). Empty when u does not assemble.
        """
        result = self._core._forward_kinematics(_input(u, "u", (self.actuators,)),
                                                _number(tolerance, "tolerance", 1e-15, 1e-3))
        modes = result["modes"]
        for mode in modes:
            mode["degenerate"] = result["degenerate"]
        return modes

    @_vocabulary
    def state_from_actuators(self, u, du=None, *, assembly_mode=0):
        """The state whose actuator values are u (and rates du; None: at rest), as ``nocdyn simulate``
        starts from a first row of u1..un (du1..dun): among the assembly modes with every limb on its
        home branch, the one nearest home (assembly_mode 0) or the assembly_mode-th as
        forward_kinematics lists the working ones; dp from du by least squares (exact with three
        actuators; with more, du must be the rates of a platform motion).

        Returns a dict: p [x, y, theta] ([x, y] for a two-DOF robot), dp in the same order, mode (1-based), working (how many working modes),
        modes (how many on any branches). Raises nocdyn.Error when no working mode has u."""
        return self._core._state_from_actuators(_input(u, "u", (self.actuators,)),
                                                None if du is None else _input(du, "du", (self.actuators,)),
                                                _integer(assembly_mode, "assembly_mode", 0, 12))

    # --- stiffness and natural frequencies --------------------------------------------
    # the order of the command line's stiffness report (kReportedCoordinates)
    stiffness_coordinates = ("x [m]", "y [m]", "theta [rad]")

    @_vocabulary
    def stiffness(self, p):
        """The 3 x 3 Cartesian stiffness K of the platform at pose p = [x, y, theta] (virtual joint
        method on the compliance of the robot file: joint `stiffness`, body `elastic`; gravity
        preload ignored), as a numpy array in the order Robot.stiffness_coordinates, x, y, theta:
        the pose's order and the command line's stiffness report's (`nocdyn pose`), so that the
        numbers compare one to one with it: dQ = K dp,
        Q = (f_x [N], f_y [N], moment about C [N m]); units N/m, N/rad, N, N m/rad.
        Raises nocdyn.Error when the robot declares no compliance, a limb is rigid, or the pose is
        out of reach. A two-DOF robot (motion: translation): p = [x, y] and K is 2 x 2 over x, y
        (E^T K E; theta moves no body and loads no limb)."""
        return self._core._stiffness(p)["matrix"]

    @_vocabulary
    def natural_frequencies(self, p, *, modes=False, model=None):
        """Natural frequencies [Hz], ascending, at pose p = [x, y, theta].

        model='lumped' (K v = w^2 M v, M the rigid bodies' mass matrix in the pose coordinates):
        3 frequencies; model='elastodynamic' (every body keeps its inertia, every virtual spring
        is a degree of freedom): one per degree of freedom. The default (model=None) returns 3
        frequencies, as model='lumped', and they are the lumped ones wherever that model holds;
        with elastic bodies, where the lumped first frequency is more than 5 % from the
        elastodynamic one (next to a limb singularity the links' inertia, carried rigidly, swamps
        it), they are the 3 lowest elastodynamic frequencies (and their platform shapes) instead,
        with a RuntimeWarning ("the lumped model does not hold at this pose ... the elastodynamic
        frequencies are used here"). model='lumped' returns the lumped values there too, with
        the warning ("... are the ones to use here"). With modes=True returns (frequencies,
        shapes): shapes' columns are the platform's displacement in each mode, rows in the order
        Robot.stiffness_coordinates, x, y, theta, as `nocdyn pose` reports them (lumped shapes
        are mass-normalised).

        Also warns (RuntimeWarning, as `nocdyn pose`) when the stiffness contrast costs the
        lowest frequency digits. A two-DOF robot (motion: translation): p = [x, y], the 2 lumped
        frequencies over x, y (K_t v = w^2 M_t v; elastic bodies are not modelled for it)."""
        if model not in (None, "lumped", "elastodynamic"):
            raise Error("model: expected 'lumped' or 'elastodynamic', got " + repr(model))
        result = self._core._stiffness(p, model == "elastodynamic", True, model == "lumped")
        if model == "elastodynamic":
            frequencies, shapes = result["elastodynamic_frequencies"], result["elastodynamic_platform_shapes"]
        elif model is None and not result["lumped_holds"]:
            # the same count as the lumped answer: the 3 lowest elastodynamic modes
            frequencies = result["elastodynamic_frequencies"][:3]
            shapes = result["elastodynamic_platform_shapes"][:, :3]
        else:
            frequencies, shapes = result["frequencies"], result["mode_shapes"]
        if not modes:
            return frequencies
        return frequencies, shapes

    # --- jobs of their own, kept one release as wrappers over nocdyn's commands ----------
    def trajectory_dynamics(self, trajectory, **options):
        """Deprecated: ``nocdyn.inverse_dynamics(trajectory, robot=robot, rate=..., duration=...,
        allow_limits=...)``, the same numbers as a Table (t, x, y, theta, ..., tau1..taun)."""
        _deprecated("Robot.trajectory_dynamics", "nocdyn.inverse_dynamics(trajectory, robot=robot, ...)")
        return _commands.inverse_dynamics(trajectory, robot=self, progress=False, **options)

    def simulate(self, forces, *args, **options):
        """Deprecated: ``nocdyn.simulate(forces, robot=robot, ...)`` (forces: columns t,
        tau1..taun, and u1..un, du1..dun in the first row for the initial state). The old form
        ``simulate(t, forces[, force_times])`` (arrays) is read as that table, output over the
        span of t at its mean rate; the initial state p0, dp0, u0, du0 is refused (it is the
        table's first row in the job)."""
        _deprecated("Robot.simulate", "nocdyn.simulate(forces, robot=robot, ...)")
        if args or not isinstance(forces, (str, os.PathLike, dict)) and not hasattr(forces, "columns"):
            forces, options = _old_simulate(self.actuators, forces, *args, **options)
        return _commands.simulate(forces, robot=self, progress=False, **options)

    def envelope(self, axes=None, **options):  # noqa: ARG002 (axes: old, ignored)
        """Deprecated: ``nocdyn.envelope(robot=robot, ...)``, an Envelope table whose
        ``first_natural_frequency`` is the band's third bound. The old arguments are read as the
        job's (frequencies is points); axes is ignored with a warning (every axis is returned,
        the column axis says which)."""
        _deprecated("Robot.envelope", "nocdyn.envelope(robot=robot, ...)")
        if "frequencies" in options:
            options["points"] = options.pop("frequencies")
        _ignored("Robot.envelope", {"axes": axes}, ("axes",))
        return _commands.envelope(robot=self, progress=False, **options)

    def identify_payload(self, t, u, tau, du=None, ddu=None, **options) -> PayloadEstimate:
        """Deprecated: ``nocdyn.identify(columns, robot=robot, ...).payload_estimate``, the log's
        arrays as columns t, u1..un, tau1..taun (du1..dun, ddu1..ddun)."""
        _deprecated("Robot.identify_payload", "nocdyn.identify(data, robot=robot, ...).payload_estimate")
        return _commands.identify(log_columns(self, t, u, tau, du, ddu), robot=self, **options).payload_estimate
