"""nocdyn: kinematics and dynamics of planar parallel robots by the natural orthogonal complement.

The Python face of the nocdyn C++ library (the general model of any planar parallel robot
described by a per-limb robot file). Everything is in SI units: metres, radians, seconds,
kilograms, newtons (newton metres for revolute actuators).

A platform pose is p = [theta, x, y] (rad, m, m), its rate dp and acceleration ddp in the same
order. Arrays of samples have one row per sample: poses are (N, 3) float64 arrays, actuator
quantities (N, n) with n = robot.actuators.

Quick start::

    import nocdyn
    robot = nocdyn.Robot.load("robots/paper-3prr.yaml")    # or nocdyn.Robot.example("3-rrr")
    traj = nocdyn.Trajectory.paper(1)                        # eq. 33 of the paper
    t = np.arange(2000) / 10000.0
    P, dP, ddP = traj.evaluate(t)                            # (N, 3) each
    u, du, ddu, tau = robot.inverse_dynamics(P, dP, ddP)     # (N, n) each, GIL released

Errors (a pose out of reach, a singular posture, a bad robot file, ...) raise nocdyn.Error, a
subclass of ValueError, with the message the command line prints. Arrays of the wrong dtype
raise TypeError.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from . import _nocdyn
from ._nocdyn import Error

__all__ = ["Error", "Robot", "Trajectory", "InverseDynamics", "InverseDynamicsMatrices", "PayloadEstimate",
           "load_prior"]
__version__ = "0.1.0"

Error.__module__ = "nocdyn"
Error.__doc__ = """An error nocdyn reports: one line naming the problem (file, line, field, limb,
sample time as they apply), the same text as the command line's. A subclass of ValueError."""

InverseDynamics = namedtuple("InverseDynamics", ["u", "du", "ddu", "tau"])
InverseDynamics.__doc__ = """Inverse dynamics of one sample (arrays of shape (n,)) or a batch ((N, n)).

u: actuator variables [m or rad]; du: their rates [m/s or rad/s]; ddu: accelerations
[m/s^2 or rad/s^2]; tau: actuator forces [N or N m] (eq. 20; minimum-norm when redundant)."""

InverseDynamicsMatrices = namedtuple("InverseDynamicsMatrices", ["u", "du", "ddu", "tau", "I", "C", "T"])
InverseDynamicsMatrices.__doc__ = """Inverse dynamics of one sample with the NOC matrices (eq. 23).

u, du, ddu, tau: as InverseDynamics, shape (n,). I: (3, 3) generalized inertia in the
independent coordinates (the actuator variables for 3 actuators, the platform pose when
redundant) [kg, kg m, kg m^2]; C: (3, 3) Coriolis matrix with dI/dt = C + C^T; T: (bodies, 3, 3)
twist-shaping matrices T_i (t_i = T_i v, eq. 22), bodies numbered as the paper does (first
bodies of limbs 1..m, second bodies, then the platform)."""


_PRIOR_KEYS = ("mass", "com_x", "com_y", "inertia")


def load_prior(path):
    """Reads a prior file (the YAML of `nocdyn identify --prior`): a dict of the bounds it gives,
    e.g. {"mass": (0.4, 0.6), "inertia": (0.0, None)} (None for an open side), ready for
    Robot.identify_payload(prior=...). Errors name the file, line and field."""
    return _nocdyn.Robot._load_prior(str(path))


class PayloadEstimate:
    """A payload identified by Robot.identify_payload.

    mass [kg], com (2,) [m] (platform frame), inertia [kg m^2] (about the payload's own c.o.m.),
    each with its standard deviation from the residuals (mass_sd, com_sd, inertia_sd);
    active_bounds: the bounds the estimate lies on (list of dicts: parameter, side 'lower' or
    'upper', bound, unbounded: the unbounded fit's value); inertia_constrained: the unbounded
    inertia was negative (set to 0); friction: the actuated joints' damping and friction when
    asked (list of dicts: name, value, stddev, unit); fit: dict of the fit on the held-out
    samples (fit_samples, holdout_samples, rms_fit, rms_holdout, rms_measured (n,) [N or N m],
    condition, t (M,), measured and predicted (M, n) forces).
    """

    __slots__ = ("mass", "com", "inertia", "mass_sd", "com_sd", "inertia_sd", "active_bounds",
                 "inertia_constrained", "friction", "fit")

    def __init__(self, values):
        for key in self.__slots__:
            setattr(self, key, values[key])

    def as_dict(self):
        """The estimate as a plain dict (numpy arrays kept)."""
        return {key: getattr(self, key) for key in self.__slots__}

    def __repr__(self):
        return (f"<nocdyn.PayloadEstimate mass={self.mass:.6g} kg (sd {self.mass_sd:.2g}), "
                f"com=[{self.com[0]:.6g}, {self.com[1]:.6g}] m, inertia={self.inertia:.6g} kg m^2 "
                f"(sd {self.inertia_sd:.2g})>")


class Robot:
    """A planar parallel robot: the general NOC model built from a robot file.

    Create one with Robot.load(path), Robot.from_yaml(text), Robot.example(name) (the robots
    shipped in robots/: paper-3prr, paper-3prr-general, 3-rrr, 3-rpr, 4-rrr) or Robot.paper()
    (the paper's 3-PRR prototype). A Robot is immutable and may be shared between threads.
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
        3-PRR short form). Raises nocdyn.Error naming the file, line, limb, joint and field."""
        return cls(_nocdyn.Robot.load(str(path)))

    @classmethod
    def from_yaml(cls, text, source="<string>"):
        """Parses robot YAML text of either form; `source` names it in error messages."""
        return cls(_nocdyn.Robot.from_yaml(text, source))

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
        """Platform pose at home [theta, x, y] (rad, m, m), shape (3,)."""
        return self._core.home

    @property
    def redundant(self):
        """True when the robot has more than three actuators (minimum-norm forces)."""
        return self._core.redundant

    def limb_info(self):
        """Per limb: dict(name, type 'PRR'/'RRR'/..., actuated: 3 booleans, base to platform)."""
        return self._core.limb_info()

    def actuator_info(self):
        """Per actuator, in file order: dict(limb, limb_name, joint, type 'P' or 'R',
        lower, upper [m or rad], effort [N or N m], velocity [m/s or rad/s]) (inf when absent)."""
        return self._core.actuator_info()

    def to_yaml(self):
        """The robot in the general file form (numbers read back exactly)."""
        return self._core.to_yaml()

    def __repr__(self):
        return f"<nocdyn.Robot {self.name!r}: {self.limbs} limbs, {self.actuators} actuators>"

    # --- inverse dynamics -------------------------------------------------------------
    def inverse_dynamics(self, p, dp, ddp, *, matrices=False, out=None, threads=1, check=True):
        """Actuator variables, rates, accelerations and forces for platform motions.

        One sample: p, dp, ddp of shape (3,) ([theta, x, y], its rate and acceleration) give
        InverseDynamics(u, du, ddu, tau), each of shape (n,). With matrices=True (one sample
        only) the full NOC path also returns I, C (3, 3) and T (bodies, 3, 3)
        (InverseDynamicsMatrices).

        Batch: p, dp, ddp of shape (N, 3), float64, give u, du, ddu, tau of shape (N, n). The
        inputs are read in place, whatever their memory order (C, Fortran, or a strided view:
        no copy); another dtype raises TypeError. The results are written into `out`, a tuple
        of four (N, n) float64 arrays of the same memory order, when given (and returned), else
        into new C-ordered arrays. The GIL is released during the computation, so other Python
        threads run meanwhile. threads > 1 splits the samples over that many C++ threads (0:
        one per hardware thread).

        A sample out of reach or singular raises nocdyn.Error "sample K: <reason>" (the first
        such sample; its row, like every failed one, is NaN). check=False returns instead,
        leaving NaN rows for the failed samples.
        """
        p_arr = p if isinstance(p, np.ndarray) else np.asarray(p, dtype=float)
        if p_arr.ndim == 1:
            if out is not None:
                raise Error("out: only for a batch of (N, 3) arrays")
            result = self._core._inverse_dynamics_sample(p_arr, dp, ddp, matrices)
            return InverseDynamicsMatrices(*result) if matrices else InverseDynamics(*result)
        if matrices:
            raise Error("matrices: only for one sample (p of shape (3,))")
        dp_arr = dp if isinstance(dp, np.ndarray) else np.asarray(dp, dtype=float)
        ddp_arr = ddp if isinstance(ddp, np.ndarray) else np.asarray(ddp, dtype=float)
        if p_arr.ndim != 2:
            raise Error(f"p: expected shape (3,) or (N, 3), got {p_arr.shape}")
        n = p_arr.shape[0]
        if out is None:
            out = tuple(np.empty((n, self.actuators)) for _ in range(4))
        else:
            out = tuple(out)
            if len(out) != 4:
                raise Error("out: expected a tuple of four arrays (u, du, ddu, tau)")
        failed, first, message = self._core._inverse_dynamics_batch(p_arr, dp_arr, ddp_arr, *out, threads=threads)
        if failed and check:
            raise Error(f"sample {first}: {message} ({failed} of {n} samples failed)")
        return InverseDynamics(*out)

    def trajectory_dynamics(self, trajectory, rate=10000.0, duration=None, *, allow_limits=False):
        """The command line's `nocdyn inverse-dynamics`: samples t_k = k / rate over `duration`
        [s] (default: the trajectory's, else 0.2 s), with its checks between samples (joint
        ranges, velocities, efforts, reach) and its messages ("t = ... s: <reason>").

        Returns a dict of arrays: t (N,), p, dp, ddp (N, 3), u, du, ddu, tau (N, n), kinetic (N,)
        [J], and warnings (the limit violations when allow_limits=True, which records them
        instead of raising)."""
        if not isinstance(trajectory, Trajectory):
            raise TypeError("trajectory: expected a nocdyn.Trajectory")
        return self._core._sample_trajectory(trajectory._core, float(rate), duration, allow_limits)

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
        platform frame [m], moment of inertia about its own c.o.m. [kg m^2]."""
        com = [float(v) for v in com]
        if len(com) != 2:
            raise Error("com: expected 2 values [x, y]")
        return Robot(self._core._with_payload(float(mass), com, float(inertia)))

    def regressor(self, p, dp, ddp):
        """The inverse-dynamics regressor Y, linear in the standard parameters: tau = Y pi.

        One sample: p, dp, ddp of shape (3,) give Y of shape (n, P). A batch: (N, 3) float64
        arrays (read in place, any memory order) give the stacked regressor of shape (N * n, P),
        rows k * n .. k * n + n - 1 those of sample k (reshape(N, n, P) separates them). A
        sample out of reach or singular raises nocdyn.Error ("sample K: <reason>")."""
        p_arr = p if isinstance(p, np.ndarray) else np.asarray(p, dtype=float)
        if p_arr.ndim == 1:
            return self._core._regressor_sample(p_arr, dp, ddp)
        if p_arr.ndim != 2:
            raise Error(f"p: expected shape (3,) or (N, 3), got {p_arr.shape}")
        dp_arr = dp if isinstance(dp, np.ndarray) else np.asarray(dp, dtype=float)
        ddp_arr = ddp if isinstance(ddp, np.ndarray) else np.asarray(ddp, dtype=float)
        return self._core._regressor_batch(p_arr, dp_arr, ddp_arr)

    def identify_payload(self, t, u, tau, du=None, ddu=None, *, friction=False, held_forces=False, cutoff=None,
                         holdout=0.2, prior=None):
        """A payload fixed to the platform from a log, as `nocdyn identify --payload` does it.

        t (N,) [s], increasing; u and tau (N, n): actuator positions [m or rad] and forces
        [N or N m]; du, ddu (N, n): their rates and accelerations when known (used as given, so
        that exact data identify exactly), else u and tau are low-pass filtered at `cutoff` [Hz]
        (default: a tenth of the sampling rate, at most 50 Hz) at zero phase and u is
        differentiated (uniform sampling needed). The robot's own parameters are this robot's.
        friction=True identifies the actuated joints' damping and Coulomb friction alongside;
        held_forces=True takes the forces as commands held until the next sample (as `nocdyn
        control --log` writes them); the last `holdout` fraction of the samples is held out to
        check the fit. prior: bounds on the payload, a dict {"mass": (lower, upper), "com_x":
        ..., "com_y": ..., "inertia": ...} (None for an open side; see load_prior) or the path
        of a prior file: the estimate is then the weighted least-squares solution within them.

        Returns a PayloadEstimate. Raises nocdyn.Error as the command line does (too few
        samples, time not increasing, a parameter the motion leaves unidentifiable, ...)."""
        if isinstance(prior, (str, bytes)) or hasattr(prior, "__fspath__"):
            prior = load_prior(prior)
        bounds = []
        prior = dict(prior or {})
        unknown = sorted(set(prior) - set(_PRIOR_KEYS))
        if unknown:
            raise Error(f"prior: unknown key {unknown[0]!r} (expected one of: {', '.join(_PRIOR_KEYS)})")
        for key in _PRIOR_KEYS:
            pair = prior.get(key, (None, None))
            if pair is None or len(pair) != 2:
                raise Error(f"prior: {key}: expected (lower, upper), None for an open side")
            lower = -np.inf if pair[0] is None else float(pair[0])
            upper = np.inf if pair[1] is None else float(pair[1])
            bounds.append((lower, upper))

        def actuator_array(x):
            return None if x is None else np.asarray(x, dtype=float)

        result = self._core._identify_payload(np.asarray(t, dtype=float).reshape(-1), actuator_array(u),
                                              actuator_array(tau), actuator_array(du), actuator_array(ddu),
                                              bool(friction), bool(held_forces),
                                              0.0 if cutoff is None else float(cutoff), float(holdout), bounds)
        return PayloadEstimate(result)

    # --- direct kinematics ----------------------------------------------------------
    def forward_kinematics(self, u, *, tolerance=1e-9):
        """Every platform pose the robot assembles in with actuator values u (n values, m or rad).

        Returns a list (sorted by theta) of dicts: pose [theta, x, y], branch (each limb's
        inverse-kinematics branch, +1/-1, 0 for limbs with one solution), working (True for the
        robot's working mode: every limb on its home branch), u_error (how well the pose gives
        back u) and condition (large next to a singularity). Empty when u does not assemble.
        """
        result = self._core._forward_kinematics(u, tolerance)
        modes = result["modes"]
        for mode in modes:
            mode["degenerate"] = result["degenerate"]
        return modes

    # --- forward dynamics -----------------------------------------------------------
    def simulate(self, t, forces, force_times=None, *, p0=None, dp0=(0.0, 0.0, 0.0), interpolation="linear",
                 rtol=1e-10, atol=1e-12, max_step=1e-2):
        """Forward dynamics: the motion under given actuator forces.

        t: increasing output times [s] (from 0); forces: (M, n) actuator forces [N or N m] at
        force_times (M,) (default: t itself), interpolated ('hold', 'linear' or 'cubic') and
        held beyond their ends; p0, dp0: initial pose (default home) and rate. Integrated by
        Dormand-Prince 5(4) with the given tolerances.

        Returns a dict of arrays at t: t, p, dp (len(t), 3), u, du, tau (len(t), n). Raises
        nocdyn.Error "t = ... s: <reason>" where the motion leaves the workspace or turns
        singular."""
        t = np.asarray(t, dtype=float)
        if force_times is None:
            force_times = t
        if p0 is None:
            p0 = self.home
        return self._core._simulate(p0, dp0, np.asarray(force_times, dtype=float), np.asarray(forces, dtype=float),
                                    interpolation, t, rtol, atol, max_step)

    # --- operating envelope ---------------------------------------------------------
    def envelope(self, axes=("theta", "x", "y"), *, min_frequency=1.0, max_frequency=100.0, frequencies=41,
                 samples_per_period=256, relative_tolerance=1e-6):
        """Largest sinusoid amplitude along each pose axis about home at log-spaced frequencies
        [Hz] (as `nocdyn envelope`), within every joint range, velocity and effort limit and away
        from singularities.

        axes selects the axes returned ('theta', 'x', 'y'); all three are computed, by the same
        call as the command line's, so that the numbers are the same.

        Returns a list of dicts: axis, frequency [Hz], amplitude [rad or m], limit ('range',
        'velocity', 'effort', 'workspace', 'none'), limb, joint, actuator (0-based, -1 when not
        applicable), kinematic_amplitude, peak_effort_ratio."""
        if isinstance(axes, str):
            axes = (axes,)
        return self._core._envelope(list(axes), min_frequency, max_frequency, frequencies, samples_per_period,
                                    relative_tolerance)


class Trajectory:
    """A harmonic platform trajectory: per axis q(t) = offset + sum_k a_k sin(2 pi f_k t + phase_k).

    Create one with Trajectory.paper(1) or Trajectory.paper(2) (eqs. 33 and 34 of the paper),
    Trajectory.load(path) / Trajectory.from_yaml(text) (the trajectory file format), or
    Trajectory.harmonic(x=..., y=..., theta=...).
    """

    __slots__ = ("_core",)

    def __init__(self, core):
        """Internal: use Trajectory.paper, Trajectory.load, Trajectory.from_yaml or Trajectory.harmonic."""
        if not isinstance(core, _nocdyn.Trajectory):
            raise TypeError("use Trajectory.paper(k), Trajectory.load(path), Trajectory.from_yaml(text) "
                            "or Trajectory.harmonic(...)")
        self._core = core

    @classmethod
    def paper(cls, number):
        """Trajectory 1 (eq. 33) or 2 (eq. 34) of the paper, in SI units."""
        if number == 1:
            return cls(_nocdyn.Trajectory.paper1())
        if number == 2:
            return cls(_nocdyn.Trajectory.paper2())
        raise Error(f"paper trajectory: {number!r} is not 1 or 2")

    @classmethod
    def load(cls, path):
        """Reads a trajectory file: harmonics (YAML), or samples when the name ends in .csv
        (a column t [s] and any of x, y, theta (positions, C2 spline) or ax, ay, alpha
        (accelerations, integrated from rest)). Errors name the file, line and field or column."""
        return cls(_nocdyn.Trajectory.load(str(path)))

    @classmethod
    def from_csv(cls, text, source="<string>"):
        """A sampled trajectory from CSV text (the format of Trajectory.load's .csv files);
        `source` names it in error messages."""
        return cls(_nocdyn.Trajectory.from_csv(text, source))

    @classmethod
    def from_yaml(cls, text, source="<string>"):
        """Parses trajectory YAML text; `source` names it in error messages."""
        return cls(_nocdyn.Trajectory.from_yaml(text, source))

    @classmethod
    def harmonic(cls, *, theta=(), x=(), y=(), offset=(0.0, 0.0, 0.0), duration=None, name="harmonic"):
        """A trajectory from harmonics: theta, x, y are sequences of (amplitude, frequency,
        phase) triples [rad or m, Hz, rad]; offset is [theta, x, y] (rad, m, m); duration [s]
        is optional."""
        def terms(axis, values):
            out = []
            for h in values:
                h = tuple(float(v) for v in h)
                if len(h) == 2:
                    h = h + (0.0,)
                if len(h) != 3 or not all(np.isfinite(h)) or h[1] < 0.0:
                    raise Error(f"{axis}: a harmonic is (amplitude, frequency >= 0, phase), finite; got {h}")
                out.append(h)
            return out
        off = [float(v) for v in offset]
        if len(off) != 3 or not all(np.isfinite(off)):
            raise Error("offset: expected 3 finite values [theta, x, y]")
        if duration is not None and not (np.isfinite(duration) and duration > 0):
            raise Error("duration: expected a positive number of seconds")
        return cls(_nocdyn.Trajectory(name, off[0], terms("theta", theta), off[1], terms("x", x), off[2],
                                      terms("y", y), duration))

    @property
    def name(self):
        return self._core.name

    @property
    def duration(self):
        """Duration [s] when the description gives one, else None."""
        return self._core.duration

    @property
    def highest_frequency(self):
        """Highest harmonic frequency of any axis [Hz]."""
        return self._core.highest_frequency

    def harmonics(self, axis):
        """(offset, [(amplitude, frequency, phase), ...]) of axis 'theta', 'x' or 'y'."""
        if axis not in ("theta", "x", "y"):
            raise Error(f"axis: {axis!r} is not one of theta, x, y")
        offset, terms = self._core._axis(axis)
        return offset, [tuple(h) for h in terms]

    def evaluate(self, t):
        """p, dp/dt, d2p/dt2 at the times t [s] (any shape-(N,) sequence): three (N, 3) arrays
        with columns [theta, x, y] (exact derivatives)."""
        return self._core._evaluate(np.asarray(t, dtype=float).reshape(-1))

    def __repr__(self):
        return f"<nocdyn.Trajectory {self.name!r}>"
