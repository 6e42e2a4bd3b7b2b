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
subclass of ValueError, with the message the command line prints. Arrays of the wrong dtype
raise TypeError.
"""

from __future__ import annotations

import operator
from collections import namedtuple

import numpy as np

from . import _nocdyn
from ._nocdyn import Error
from .commands import (COMMANDS, animate, control, convert, design, envelope, excite, forward_kinematics, identify,
                       inverse_dynamics, loads, pose, regressor, reproduce, shake, simulate, validate, workspace)
from .commands import frequency_response
from .results import (Animation, AssemblyModes, Envelope, Excitation, Identification, PoseReport, Report, ShakeResult,
                      Table, Workspace)

__all__ = ["Error", "Robot", "Trajectory", "InverseDynamics", "InverseDynamicsMatrices", "ActuatorDerivatives", "PayloadEstimate",
           "load_prior",
           # every command of the command line (nocdyn.commands), and their results (nocdyn.results)
           "pose", "inverse_dynamics", "forward_kinematics", "simulate", "control", "envelope", "workspace", "convert",
           "animate", "shake", "regressor", "identify", "excite", "loads", "validate", "reproduce", "design", "COMMANDS",
           "frequency_response",
           "Table", "PoseReport", "AssemblyModes", "Workspace", "Envelope", "Identification", "Excitation",
           "ShakeResult", "Animation", "Report"]
__version__ = _nocdyn.__version__  # the CMake project version, as `nocdyn --version`

Error.__module__ = "nocdyn"
Error.__doc__ = """An error nocdyn reports: one line naming the problem (file, line, field, limb,
sample time as they apply), the same text as the command line's. A subclass of ValueError."""

InverseDynamics = namedtuple("InverseDynamics", ["u", "du", "ddu", "tau"])
InverseDynamics.__doc__ = """Inverse dynamics of one sample (arrays of shape (n,)) or a batch ((N, n)).

u: actuator variables [m or rad]; du: their rates [m/s or rad/s]; ddu: accelerations
[m/s^2 or rad/s^2]; tau: actuator forces [N or N m] (eq. 20; minimum-norm when redundant)."""

ActuatorDerivatives = namedtuple("ActuatorDerivatives",
                                 ["u", "du", "ddu", "u_p", "du_p", "du_dp", "ddu_p", "ddu_dp", "ddu_ddp"])
ActuatorDerivatives.__doc__ = """The actuator variables of one sample and their exact derivatives.

u, du, ddu: as InverseDynamics, shape (n,). u_p = d u/d p, du_p = d du/d p, du_dp = d du/d dp,
ddu_p = d ddu/d p, ddu_dp = d ddu/d dp, ddu_ddp = d ddu/d ddp: shape (n, 3), row a actuator
a + 1, columns the pose order [x, y, theta]. du_dp = ddu_ddp = u_p (du and ddu are linear in
dp and ddp with the actuation map A S(c) as coefficients)."""

def _derivative_inputs(p, dp, ddp):
    """(False, (p, dp, ddp)) of one sample, shape (3,) each, or (True, (p, dp, ddp)) of a batch,
    shape (N, 3) each, read in place whatever their memory order (NaN allowed: a failed sample)."""
    p_arr = _floats(p, "p")
    if p_arr.ndim == 1:
        return False, (p_arr, _floats(dp, "dp"), _floats(ddp, "ddp"))
    if p_arr.ndim != 2:
        raise Error(f"p: expected shape (3,) or (N, 3), got {p_arr.shape}")
    n = p_arr.shape[0]
    return True, (_input(p_arr, "p", (None, 3), finite=False), _input(dp, "dp", (n, 3), finite=False),
                  _input(ddp, "ddp", (n, 3), finite=False))


def _derivative_batch(answer, check):
    """The arrays of a compiled derivative batch's answer (arrays..., failed, first, message);
    with check, nocdyn.Error "sample K: <reason>" at its first failed sample."""
    *arrays, failed, first, message = answer
    if failed and check:
        raise Error(f"sample {first}: {message} ({failed} of {len(arrays[0])} samples failed)")
    return tuple(arrays)


class EnvelopePoints(list):
    """Robot.envelope's points (a list of dicts) with the band's third bound:
    ``first_natural_frequency`` [Hz], the lumped model's first natural frequency at home, and
    ``band_end`` {"x": f, "y": f, "theta": f} [Hz], per axis the lowest frequency where the damped
    lumped model's dynamic amplification leaves [1/A, A] (points at and above it have the limit
    'resonance'; inf when it never does); both None with ``resonance_reason`` saying why it is
    unknown (no compliance declared, a rigid limb, a free platform)."""

    def __init__(self, points, first_natural_frequency, resonance_reason="", band_end=None):
        super().__init__(points)
        self.first_natural_frequency = first_natural_frequency
        self.resonance_reason = resonance_reason
        self.band_end = band_end


class LinearModel(tuple):
    """A linearised model (Robot.linearize): the tuple (A, B), or (A, B, C, D) when an output was
    asked for, with the attributes A, B, C, D, ``inputs`` (per column of B: "tau" an actuator
    force, "uc" a drive's commanded position) and ``model`` ("rigid" or "lumped")."""

    def __new__(cls, items, A, B, C, D, inputs, model):
        self = super().__new__(cls, items)
        self.A, self.B, self.C, self.D = A, B, C, D
        self.inputs = tuple(inputs)
        self.model = model
        return self


InverseDynamicsMatrices = namedtuple("InverseDynamicsMatrices", ["u", "du", "ddu", "tau", "I", "C", "T"])
InverseDynamicsMatrices.__doc__ = """Inverse dynamics of one sample with the NOC matrices (eq. 23).

u, du, ddu, tau: as InverseDynamics, shape (n,). I: (3, 3) generalized inertia in the
independent coordinates (the actuator variables for 3 actuators, the platform pose when
redundant) [kg, kg m, kg m^2]; C: (3, 3) Coriolis matrix with dI/dt = C + C^T; T: (bodies, 3, 3)
twist-shaping matrices T_i (t_i = T_i v, eq. 22), bodies numbered as the paper does (first
bodies of limbs 1..m, second bodies, then the platform)."""


_PRIOR_KEYS = ("mass", "com_x", "com_y", "inertia")

VOCABULARY = ("Vocabulary: a pose is [x, y, theta] (m, m, rad), its rates in the same order, as in the command "
              "line's CSV tables; SI units; limbs, joints and actuators numbered from 1; array axes from 0; the "
              "core's internal twist order [theta, x, y] stays inside the core.")


def _vocabulary(function):
    """Appends the one sentence of the vocabulary to a docstring that takes or returns a pose."""
    function.__doc__ = (function.__doc__ or "").rstrip() + "\n\n        " + VOCABULARY + "\n        "
    return function

# --- the one guard of every entry: numbers as the command line checks them, arrays of any
# memory order read correctly (copied when the compiled part cannot view them), outputs that
# overlap nothing, threads within reason, results checked finite.

_MAX_THREADS = 1024  # the compiled batch caps this further at the hardware and the work
# trajectory_dynamics holds every sample: t, kinetic, p, dp, ddp and u, du, ddu, tau, that is
# (11 + 4 n) float64 values (184 bytes with 3 actuators); a call asking more is refused
_MAX_HELD_BYTES = 8e8


def _number(value, name, lower=-np.inf, upper=np.inf):
    """A finite float in [lower, upper] (the command line's range for the option); TypeError
    for what is not a real number, nocdyn.Error for NaN, inf or a value out of range."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise TypeError(f"{name}: expected a number, got {type(value).__name__}")
    try:
        v = float(value)
    except OverflowError:
        raise Error(f"{name}: {value!r} is not a finite number") from None
    if not np.isfinite(v) or not lower <= v <= upper:
        raise Error(f"{name}: {value!r} is not a finite number in [{lower:g}, {upper:g}]")
    return v


def _integer(value, name, lower, upper):
    """An int in [lower, upper]; TypeError for what is not an integer (bool included)."""
    if isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name}: expected an integer, got bool")
    try:
        v = operator.index(value)
    except TypeError:
        raise TypeError(f"{name}: expected an integer, got {type(value).__name__}") from None
    if not lower <= v <= upper:
        raise Error(f"{name}: {v} is not in [{lower}, {upper}]")
    return v


def _floats(x, name):
    """x as a float64 array: a sequence is converted; a byte-swapped float64 array is copied
    to the native order (same values); an ndarray of another dtype raises TypeError (no silent
    cast of the caller's data)."""
    if isinstance(x, np.ndarray):
        if x.dtype.kind == "f" and x.dtype.itemsize == 8 and not x.dtype.isnative:
            return x.astype(np.float64)
        if x.dtype != np.float64:
            raise TypeError(f"{name}: expected an array of float64, got dtype {x.dtype} "
                            "(convert it with numpy.asarray(x, dtype=float))")
        return x
    try:
        a = np.asarray(x, dtype=float)
    except (TypeError, ValueError) as e:
        raise TypeError(f"{name}: expected numbers: {e}") from None
    return a


def _viewable(a):
    """True when the compiled part can read a in place: aligned, native byte order, strides
    whole non-negative elements."""
    item = a.itemsize
    return (a.flags.aligned and a.dtype.isnative and
            all(s >= 0 and s % item == 0 for s in a.strides))


def _input(x, name, shape, finite=True):
    """An input array of float64 of the given shape (None: any length), every value finite
    (unless finite=False: the compiled part then reports the sample), read in place when
    possible, else copied."""
    a = _floats(x, name)
    if a.ndim != len(shape) or any(want is not None and got != want for got, want in zip(a.shape, shape)):
        want = ", ".join("N" if w is None else str(w) for w in shape)
        raise Error(f"{name}: expected shape ({want}{',' if len(shape) == 1 else ''}), got {a.shape}")
    if not _viewable(a):
        a = np.ascontiguousarray(a)
    if finite and a.size and not _all_finite(a):
        bad = np.argwhere(~np.isfinite(a))[0]
        raise Error(f"{name}[{', '.join(str(int(i)) for i in bad)}]: not a finite number")
    return a


def _all_finite(a):
    """Whether every value is finite, without an array-sized temporary (min and max propagate
    NaN and show an infinity)."""
    return bool(np.isfinite(a.min()) and np.isfinite(a.max()))


def _overlaps_itself(a):
    """True when two elements of a 2-D array share memory (a zero stride, or strides that
    interleave rows and columns)."""
    dims = sorted((abs(s), n) for s, n in zip(a.strides, a.shape) if n > 1)
    extent = a.itemsize
    for stride, n in dims:
        if stride < extent:
            return True
        extent = stride * n
    return False


def _shares(a, b):
    try:
        return np.shares_memory(a, b, max_work=1 << 20)
    except np.exceptions.TooHardError if hasattr(np, "exceptions") else np.TooHardError:
        return True


def _outputs(out, names, shape, inputs):
    """The caller's output arrays: float64, writeable, of `shape`, each overlapping neither
    itself, another output nor an input (overlap would give wrong numbers, silently)."""
    out = tuple(out)
    if len(out) != len(names):
        raise Error(f"out: expected a tuple of four arrays ({', '.join(names)})")
    for a, name in zip(out, names):
        if not isinstance(a, np.ndarray):
            raise TypeError(f"{name}: expected a numpy array, got {type(a).__name__}")
        if a.dtype != np.float64:
            raise TypeError(f"{name}: expected an array of float64, got dtype {a.dtype}")
        if a.shape != shape:
            raise Error(f"{name}: expected shape {shape}, got {a.shape}")
        if not a.flags.writeable:
            raise Error(f"{name}: the output array is read-only")
        if not _viewable(a):
            raise Error(f"{name}: strides {a.strides} or alignment not supported (pass a C- or F-ordered array)")
        if _overlaps_itself(a):
            raise Error(f"out: {name}: its elements overlap one another (strides {a.strides})")
    for i, a in enumerate(out):
        for b, other in zip(out[i + 1:], names[i + 1:]):
            if _shares(a, b):
                raise Error(f"out: {names[i]} and {other} overlap in memory")
        for b, other in inputs:
            if _shares(a, b):
                raise Error(f"out: {names[i]} overlaps the input {other} in memory")
    return out


def _require_finite(arrays, what):
    """Raises nocdyn.Error naming the first sample (row) where one of the result arrays is not
    finite: finite input that overflows (huge rates or accelerations)."""
    for a in arrays:
        a = np.asarray(a)
        if a.size and not _all_finite(a):
            rows = np.argwhere(~np.isfinite(a))
            where = f"sample {int(rows[0][0])}: " if a.ndim > 1 else ""
            raise Error(f"{where}{what} is not finite (the input is too large)")


def load_prior(path):
    """Reads a prior file (the YAML of `nocdyn identify --prior`): a dict of the bounds it gives,
    e.g. {"mass": (0.4, 0.6), "inertia": (0.0, None)} (None for an open side), ready for
    Robot.identify_payload(prior=...). Errors name the file, line and field."""
    return _nocdyn.Robot._load_prior(str(path))


class PayloadEstimate:
    """A payload identified by Robot.identify_payload.

    mass [kg], com (2,) [m] (platform frame), inertia [kg m^2] (about the payload's own c.o.m.),
    each with its standard deviation from the residuals, counting their correlation along the
    samples (mass_sd, com_sd, inertia_sd); covariance: (4 + f, 4 + f) of [mass, com_x, com_y,
    inertia, then the friction's parameters];
    active_bounds: the bounds the estimate lies on (list of dicts: parameter, side 'lower' or
    'upper', bound, unbounded: the unbounded fit's value); inertia_constrained: the unbounded
    inertia was negative (set to 0); friction: the actuated joints' damping and friction when
    asked (list of dicts: name, value, stddev, unit); fit: dict of the fit on the held-out
    samples (fit_samples, holdout_samples, rms_fit, rms_holdout, rms_measured (n,) [N or N m],
    condition, correlation_samples (the residuals' integrated autocorrelation time) and
    effective_samples, t (M,), measured and predicted (M, n) forces).
    """

    __slots__ = ("mass", "com", "inertia", "mass_sd", "com_sd", "inertia_sd", "covariance", "active_bounds",
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
        """Platform pose at home [x, y, theta] (m, m, rad), shape (3,)."""
        return self._core.home

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
        """The robot drawn as SVG text at pose [x, y, theta] (default home): base, limbs, platform,
        C, actuated joints marked (green). Jupyter shows a Robot this way (_repr_svg_)."""
        from .drawing import robot_svg
        return robot_svg(self, pose)

    def _repr_svg_(self):
        return self.svg()

    # --- inverse dynamics -------------------------------------------------------------
    @_vocabulary
    def inverse_dynamics(self, p, dp, ddp, *, matrices=False, out=None, threads=1, check=True, check_limits=True):
        """Actuator variables, rates, accelerations and forces for platform motions.

        One sample: p, dp, ddp of shape (3,) ([x, y, theta], its rate and acceleration) give
        InverseDynamics(u, du, ddu, tau), each of shape (n,). With matrices=True (one sample
        only) the full NOC path also returns I, C (3, 3) and T (bodies, 3, 3)
        (InverseDynamicsMatrices; when the robot is redundant their pose rows and columns are
        in the order [x, y, theta], and T_i's rows, body i's twist, are [v_x, v_y, omega]).

        Batch: p, dp, ddp of shape (N, 3), float64, give u, du, ddu, tau of shape (N, n). The
        inputs are read in place, whatever their memory order (C, Fortran, or a strided view:
        no copy; reversed, misaligned or byte-swapped arrays are copied); another dtype raises
        TypeError, a NaN or infinite input nocdyn.Error. The results are written into `out`, a
        tuple of four (N, n) float64 arrays of the same memory order, when given (and
        returned), else into new C-ordered arrays; outputs that overlap one another, themselves
        or an input are refused. The GIL is released during the computation, so other Python
        threads run meanwhile. threads (0..1024) > 1 splits the samples over that many C++
        threads, at most one per hardware thread and sample (0: one per hardware thread).

        A sample out of reach or singular raises nocdyn.Error "sample K: <reason>" (the first
        such sample; its row, like every failed one, is NaN), and so does a result that is not
        finite (rates or accelerations so large that the forces overflow). check=False returns
        instead, leaving NaN rows for the failed samples.

        Limits, as `nocdyn inverse-dynamics` checks them: with check_limits=True (the default) a
        sample where a joint leaves its range or exceeds its velocity limit, or an actuator its
        effort, raises nocdyn.Error with the command line's reason ("sample K: <reason>" for a
        batch: the first such sample; the outputs are filled all the same). They are checked on
        the results u, du, tau when every limited joint is actuated (no second inverse dynamics;
        a batch checks them inside its kernel, on values still in registers, at no measurable
        cost), else by the full path at every sample (a range on a passive joint needs its q,
        which the batch's kernel does not compute); check_limits=False checks none.
        """
        threads = min(_integer(threads, "threads", 0, 2**63), _MAX_THREADS)
        p_arr = _floats(p, "p")
        if p_arr.ndim == 1:
            if out is not None:
                raise Error("out: only for a batch of (N, 3) arrays")
            # the compiled part checks that the results are finite (check): no pass here
            result = self._core._inverse_dynamics_sample(p_arr, dp, ddp, bool(matrices), bool(check_limits),
                                                         bool(check))
            return InverseDynamicsMatrices(*result) if matrices else InverseDynamics(*result)
        if matrices:
            raise Error("matrices: only for one sample (p of shape (3,))")
        if p_arr.ndim != 2:
            raise Error(f"p: expected shape (3,) or (N, 3), got {p_arr.shape}")
        n = p_arr.shape[0]
        p_arr = _input(p_arr, "p", (None, 3), finite=False)
        dp_arr = _input(dp, "dp", (n, 3), finite=False)
        ddp_arr = _input(ddp, "ddp", (n, 3), finite=False)
        shape = (n, self.actuators)
        if out is None:
            out = tuple(np.empty(shape) for _ in range(4))
        else:
            out = _outputs(out, ("u", "du", "ddu", "tau"), shape, ((p_arr, "p"), (dp_arr, "dp"), (ddp_arr, "ddp")))
        failed, first, message, beyond, reason = self._core._inverse_dynamics_batch(
            p_arr, dp_arr, ddp_arr, *out, threads=threads, check_limits=bool(check_limits))
        # the compiled batch counts a sample whose results overflow as failed (its row NaN):
        # no second pass over the outputs here
        if failed and check:
            raise Error(f"sample {first}: {message} ({failed} of {n} samples failed)")
        if beyond >= 0:
            raise Error(f"sample {beyond}: {reason}")
        return InverseDynamics(*out)

    @_vocabulary
    def inverse_dynamics_derivatives(self, p, dp, ddp, *, threads=1, check=True):
        """Exact first derivatives of the actuator forces: (d tau/d p, d tau/d dp, d tau/d ddp).

        One sample, p, dp, ddp of shape (3,), gives three arrays of shape (n, 3); a batch,
        shape (N, 3) each, three of shape (N, n, 3). Row a is actuator a + 1, columns the pose
        order [x, y, theta] of inverse_dynamics; d tau/d ddp is the mass matrix mapped to the
        actuators. Forward-mode automatic differentiation: exact to rounding. Coulomb friction
        is differentiated with its sign held (at a joint rate of exactly 0 its force and
        derivative are 0). Errors and threads as in inverse_dynamics.
        """
        threads = min(_integer(threads, "threads", 0, 2**63), _MAX_THREADS)
        batch, inputs = _derivative_inputs(p, dp, ddp)
        if not batch:
            return self._core._inverse_dynamics_derivatives_sample(*inputs)
        return _derivative_batch(self._core._inverse_dynamics_derivatives_batch(*inputs, threads=threads), check)

    @_vocabulary
    def actuator_derivatives(self, p, dp, ddp, *, threads=1, check=True):
        """Exact first derivatives of the actuator variables u, du, ddu of one sample (p, dp,
        ddp of shape (3,)): an ActuatorDerivatives of u, du, ddu (n,) and d u/d p, d du/d p,
        d du/d dp, d ddu/d p, d ddu/d dp, d ddu/d ddp (n, 3), columns in the pose order
        [x, y, theta]. The actuated joints' rates and accelerations by the same forward-mode
        automatic differentiation as inverse_dynamics_derivatives: exact to rounding. A batch,
        p, dp, ddp of shape (N, 3), gives u, du, ddu of shape (N, n) and the derivatives of
        shape (N, n, 3), each row the sample's own values to the bit. Errors, check and threads
        as in inverse_dynamics (check=False: a failed sample's rows are NaN).
        """
        threads = min(_integer(threads, "threads", 0, 2**63), _MAX_THREADS)
        batch, inputs = _derivative_inputs(p, dp, ddp)
        if not batch:
            return ActuatorDerivatives(*self._core._actuator_derivatives_sample(*inputs))
        return ActuatorDerivatives(*_derivative_batch(
            self._core._actuator_derivatives_batch(*inputs, threads=threads), check))

    @_vocabulary
    def linearize(self, p, dp, tau, *, output=None, compliance="auto"):
        """The robot linearised at the state (p, dp) ([x, y, theta] and its rate) under the
        actuator forces tau (n,): (A, B) with the state x = [p; dp] = [x, y, theta, dx/dt, dy/dt,
        dtheta/dt] and the input u, dx/dt = A x + B u (deviations from the operating point),
        A (6, 6), B (6, n), from the exact derivatives of the forward dynamics. output=
        "acceleration" or "actuators" also returns C and D of that output (y = C x + D u, y = ddp
        in the order [x, y, theta], or the actuator variables A_p p): (A, B, C, D).

        compliance, as ``nocdyn frequency-response --compliance``: "rigid" the rigid model, every
        input an actuator force [N or N m]; "lumped" the compliant lumped model of the joint and
        drive stiffness and elastic links the robot file declares (an error when it declares
        none); "auto" (default) lumped when the file declares compliance, else rigid. The lumped
        model's springs are massless and quasi-static and its bodies rigid, carried by the
        platform's pose: its state is the same x = [p; dp] (6 states; A's lower left block
        gains -M_p^-1 K, K the Cartesian stiffness of Robot.stiffness, so that A's
        eigenfrequencies at rest without gravity are Robot.natural_frequencies), and its input a
        is drive a's commanded position (its spring's rest position) [m or rad] when the drive
        has a stiffness (or none is given and the drive is locked), its force when its
        stiffness is 0.

        The result is a LinearModel: a tuple (A, B) or (A, B, C, D) with the attributes A, B, C,
        D, ``inputs`` (per column of B "tau" for a force, "uc" for a commanded drive position:
        the command line's channel names) and ``model`` ("rigid" or "lumped").
        """
        if not isinstance(compliance, str):
            raise TypeError("compliance: expected 'auto', 'rigid' or 'lumped'")
        A, B, C, D, inputs, model = self._core._linearize(p, dp, tau, output or "acceleration", compliance)
        return LinearModel((A, B) if output is None else (A, B, C, D), A, B, C, D, inputs, model)

    @_vocabulary
    def reactions(self, p, dp, ddp, *, threads=1, check=True, check_limits=True):
        """Every joint's reaction with the inverse dynamics' forces (the minimum-norm ones when
        redundant), as in `nocdyn inverse-dynamics --reactions`: base frame, the wrench of the
        joint's inboard body on its outboard body, the joint's effort and friction taken out
        (R: the force at the axis, m = 0; P: the force normal to the joint and the couple about
        the outboard body's c.o.m.).

        p, dp, ddp of shape (N, 3) ([x, y, theta], its rate and acceleration; float64, read in
        place whatever their memory order) give an array of shape (N, limbs, 3, 3): sample,
        limb, joint (file order: index j is limb j + 1, k joint k + 1), [fx, fy, m] [N, N, N m].
        One sample, shape (3,) each, gives (limbs, 3, 3). The GIL is released during the
        computation; threads as in inverse_dynamics. A sample out of reach or singular raises
        nocdyn.Error "sample K: <reason>" (the first such; failed rows are NaN); check=False
        returns instead. check_limits=True (the default, as `nocdyn inverse-dynamics
        --reactions`) raises nocdyn.Error at the first sample beyond a joint's range or
        velocity limit or an actuator's effort (checked by the full path at every sample);
        check_limits=False checks none.
        """
        threads = min(_integer(threads, "threads", 0, 2**63), _MAX_THREADS)
        p_arr = _floats(p, "p")
        single = p_arr.ndim == 1
        if single:
            p_arr = p_arr.reshape(1, -1)
            dp, ddp = _floats(dp, "dp").reshape(1, -1), _floats(ddp, "ddp").reshape(1, -1)
        if p_arr.ndim != 2:
            raise Error(f"p: expected shape (3,) or (N, 3), got {p_arr.shape}")
        n = p_arr.shape[0]
        if n == 0:
            raise ValueError("p: no samples (shape (0, 3)): give at least one pose")
        p_arr = _input(p_arr, "p", (None, 3), finite=False)
        dp_arr = _input(dp, "dp", (n, 3), finite=False)
        ddp_arr = _input(ddp, "ddp", (n, 3), finite=False)
        out = np.empty((n, self.limbs, 3, 3))
        failed, first, message = self._core._reactions_batch(p_arr, dp_arr, ddp_arr, out.reshape(n, 9 * self.limbs),
                                                             threads=threads)
        if failed and check:
            raise Error(message if single else f"sample {first}: {message} ({failed} of {n} samples failed)")
        if check:
            _require_finite((out.reshape(n, -1),), "the reactions")
        if check_limits:
            beyond, reason = self._core._limits_batch(p_arr, dp_arr, ddp_arr)
            if beyond >= 0:
                raise Error(reason if single else f"sample {beyond}: {reason}")
        return out[0] if single else out

    @_vocabulary
    def trajectory_dynamics(self, trajectory, rate=10000.0, duration=None, *, allow_limits=False, check_limits=True):
        """The command line's `nocdyn inverse-dynamics`: samples t_k = k / rate over `duration`
        [s] (default: the trajectory's, else 0.2 s), with its checks between samples (joint
        ranges, velocities, efforts, reach) and its messages ("t = ... s: <reason>").

        Returns a dict of arrays: t (N,), p, dp, ddp (N, 3) ([x, y, theta], the CSV's column
        order), u, du, ddu, tau (N, n), kinetic (N,) [J], and warnings (the limit violations
        when allow_limits=True or check_limits=False, which record them instead of raising, as
        `--allow-limits` does).

        Memory: every sample is held, (11 + 4 n) float64 values (184 bytes with 3 actuators: 1e6
        samples take 184 MB); a call needing more than 800 MB is refused (the command line's
        inverse-dynamics streams any number to a file). Ctrl-C stops it within a few
        milliseconds (KeyboardInterrupt)."""
        if not isinstance(trajectory, Trajectory):
            raise TypeError("trajectory: expected a nocdyn.Trajectory")
        rate = _number(rate, "rate", 1.0, 1e8)
        if duration is not None:
            duration = _number(duration, "duration", 1e-6, 1e6)
        span = duration if duration is not None else (trajectory.duration or 0.2)
        per_sample = 8 * (11 + 4 * self.actuators)
        if span * rate * per_sample > _MAX_HELD_BYTES:
            raise Error(f"duration * rate = {span * rate:.6g} samples of {per_sample} bytes would hold "
                        f"{span * rate * per_sample / 1e9:.3g} GB in memory, more than the "
                        f"{_MAX_HELD_BYTES / 1e6:.0f} MB allowed: give a shorter duration or a lower rate "
                        "(the command line's inverse-dynamics streams any number to a file)")
        return self._core._sample_trajectory(trajectory._core, rate, duration,
                                             bool(allow_limits) or not bool(check_limits))

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
        com = _input(com, "com", (2,))
        return Robot(self._core._with_payload(_number(mass, "mass"), [float(v) for v in com],
                                              _number(inertia, "inertia")))

    @_vocabulary
    def regressor(self, p, dp, ddp):
        """The inverse-dynamics regressor Y, linear in the standard parameters: tau = Y pi.

        One sample: p, dp, ddp of shape (3,) ([x, y, theta], rate, acceleration) give Y of
        shape (n, P). A batch: (N, 3) float64
        arrays (read in place, any memory order) give the stacked regressor of shape (N * n, P),
        rows k * n .. k * n + n - 1 those of sample k (reshape(N, n, P) separates them). A
        sample out of reach or singular raises nocdyn.Error ("sample K: <reason>")."""
        p_arr = _floats(p, "p")
        if p_arr.ndim == 1:
            Y = self._core._regressor_sample(p_arr, dp, ddp)
        elif p_arr.ndim == 2:
            n = p_arr.shape[0]
            Y = self._core._regressor_batch(_input(p_arr, "p", (None, 3), finite=False),
                                            _input(dp, "dp", (n, 3), finite=False),
                                            _input(ddp, "ddp", (n, 3), finite=False))
        else:
            raise Error(f"p: expected shape (3,) or (N, 3), got {p_arr.shape}")
        if Y.size and not _all_finite(Y):
            row = int(np.argwhere(~np.isfinite(Y))[0][0])
            raise Error(f"sample {row // max(self.actuators, 1)}: the regressor is not finite (the input is too large)")
        return Y

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
        control --log` writes them: its columns tau1_held..taun_held; pass held_forces=True with
        them, or identify the file with nocdyn.identify, which reads the names); the last `holdout` fraction of the samples is held out to
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
            lower = -np.inf if pair[0] is None else _number(pair[0], f"prior: {key}: lower")
            upper = np.inf if pair[1] is None else _number(pair[1], f"prior: {key}: upper")
            bounds.append((lower, upper))

        t = _floats(t, "t").reshape(-1)
        n = t.shape[0]

        def actuator_array(x, name):
            return None if x is None else _input(x, name, (n, self.actuators))

        cutoff = 0.0 if cutoff is None else _number(cutoff, "cutoff", 1e-3, 1e6)
        result = self._core._identify_payload(_input(t, "t", (None,)), actuator_array(u, "u"),
                                              actuator_array(tau, "tau"), actuator_array(du, "du"),
                                              actuator_array(ddu, "ddu"), bool(friction), bool(held_forces), cutoff,
                                              _number(holdout, "holdout", 0.0, 0.9), bounds)
        return PayloadEstimate(result)

    # --- direct kinematics ----------------------------------------------------------
    @_vocabulary
    def forward_kinematics(self, u, *, tolerance=1e-9):
        """Every platform pose the robot assembles in with actuator values u (n values, m or rad).

        Returns a list (sorted by theta) of dicts: pose [x, y, theta], branch (each limb's
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

        Returns a dict: p [x, y, theta], dp (3,) in the same order, mode (1-based), working (how many working modes),
        modes (how many on any branches). Raises nocdyn.Error when no working mode has u."""
        return self._core._state_from_actuators(_input(u, "u", (self.actuators,)),
                                                None if du is None else _input(du, "du", (self.actuators,)),
                                                _integer(assembly_mode, "assembly_mode", 0, 12))

    # --- forward dynamics -----------------------------------------------------------
    @_vocabulary
    def simulate(self, t, forces, force_times=None, *, p0=None, dp0=(0.0, 0.0, 0.0), u0=None, du0=None,
                 assembly_mode=0, interpolation="cubic", rtol=1e-10, atol=1e-12, max_step=1e-2):
        """Forward dynamics: the motion under given actuator forces.

        t: increasing output times [s] (from 0); forces: (M, n) actuator forces [N or N m] at
        force_times (M,) (default: t itself), interpolated ('cubic', the default as on the command
        line: uniformly spaced times; 'linear' or 'hold') by the command line's ForceSignal and
        held beyond their ends; p0, dp0: initial pose [x, y, theta] (default home) and rate, or instead u0 (and
        du0): initial actuator values and rates, the state by state_from_actuators (assembly_mode
        as there). Integrated by Dormand-Prince 5(4) with the given tolerances.

        Returns a dict of arrays at t: t, p, dp (len(t), 3) ([x, y, theta]), u, du, tau (len(t), n). Raises
        nocdyn.Error "t = ... s: <reason>" where the motion leaves the workspace or turns
        singular."""
        t = _input(_floats(t, "t").reshape(-1), "t", (None,))
        force_times = t if force_times is None else _input(_floats(force_times, "force_times").reshape(-1),
                                                           "force_times", (None,))
        forces = _input(forces, "forces", (force_times.shape[0], self.actuators))
        if u0 is not None:
            if p0 is not None:
                raise ValueError("give the initial state as p0 (and dp0) or as u0 (and du0), not both")
            start = self.state_from_actuators(u0, du0, assembly_mode=assembly_mode)
            p0, dp0 = start["p"], start["dp"]
        elif du0 is not None:
            raise ValueError("du0 needs u0 (the initial actuator values)")
        p0 = _input(self.home if p0 is None else p0, "p0", (3,))
        dp0 = _input(dp0, "dp0", (3,))
        if not isinstance(interpolation, str):
            raise TypeError("interpolation: expected 'hold', 'linear' or 'cubic'")
        result = self._core._simulate(p0, dp0, force_times, forces, interpolation, t,
                                      _number(rtol, "rtol", 1e-14, 1e-2), _number(atol, "atol", 1e-15, 1e-2),
                                      _number(max_step, "max_step", 1e-9, 1e3))
        _require_finite([result[k] for k in ("p", "dp", "u", "du", "tau")], "the simulated motion")
        return result

    # --- operating envelope ---------------------------------------------------------
    def envelope(self, axes=("x", "y", "theta"), *, min_frequency=1.0, max_frequency=100.0, points=41,
                 samples_per_period=256, relative_tolerance=1e-6, frequencies=None, amplification=1.1):
        """Largest sinusoid amplitude along each pose axis about home at log-spaced frequencies
        [Hz] (as `nocdyn envelope`), within every joint range, velocity and effort limit and away
        from singularities.

        axes selects the axes returned ('x', 'y', 'theta'); all three are computed, by the same
        call as the command line's, so that the numbers are the same, in the order x, y, theta.

        Returns a list of dicts: axis, frequency [Hz], amplitude [rad or m], limit ('range',
        'velocity', 'effort', 'workspace', 'none', or 'resonance' at and above the axis' band end
        when the robot file declares compliance: where the dynamic amplification leaves
        [1/amplification, amplification], see nocdyn.envelope), limb, joint,
        actuator (numbered from 1 as the command line's CSV, 0 when not applicable),
        kinematic_amplitude, peak_effort_ratio. points: frequencies per axis (as
        `nocdyn envelope --points`; ``frequencies`` is its old name).

        The list is an EnvelopePoints: its ``first_natural_frequency`` is the band's third bound
        [Hz] (the lumped model's first natural frequency at home, as nocdyn.envelope's), None when
        the robot file declares no compliance or it is unknown (``resonance_reason`` says why)."""
        if frequencies is not None:
            points = frequencies
        if isinstance(axes, str):
            axes = (axes,)
        points, first, reason = self._core._envelope(
            list(axes), _number(min_frequency, "min_frequency", 1e-3, 1e4),
            _number(max_frequency, "max_frequency", 1e-3, 1e4), _integer(points, "points", 1, 1000),
            _integer(samples_per_period, "samples_per_period", 8, 65536),
            _number(relative_tolerance, "relative_tolerance", 1e-15, 0.5),
            _number(amplification, "amplification", 1.001, 100.0))
        first, band_end = first if first is not None else (None, None)
        return EnvelopePoints(points, first, reason, band_end)


    # --- stiffness and natural frequencies --------------------------------------------
    # the order of the command line's stiffness report (analysis::kReportedCoordinates)
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
        out of reach."""
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
        lowest frequency digits."""
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
    @_vocabulary
    def harmonic(cls, *, theta=(), x=(), y=(), offset=(0.0, 0.0, 0.0), duration=None, name="harmonic"):
        """A trajectory from harmonics: theta, x, y are sequences of (amplitude, frequency,
        phase) triples [rad or m, Hz, rad]; offset is the pose [x, y, theta] (m, m, rad);
        duration [s] is optional."""
        def terms(axis, values):
            out = []
            for h in values:
                try:
                    h = tuple(float(v) for v in h)
                except (TypeError, ValueError):
                    raise Error(f"{axis}: a harmonic is (amplitude, frequency >= 0, phase), numbers; got {h!r}"[:200]) \
                        from None
                if len(h) == 2:
                    h = h + (0.0,)
                if len(h) != 3 or not all(np.isfinite(h)) or h[1] < 0.0:
                    raise Error(f"{axis}: a harmonic is (amplitude, frequency >= 0, phase), finite; got {h}")
                out.append(h)
            return out
        try:
            off = [float(v) for v in offset]
        except (TypeError, ValueError):
            raise Error(f"offset: expected 3 numbers [x, y, theta], got {offset!r}"[:200]) from None
        if len(off) != 3 or not all(np.isfinite(off)):
            raise Error("offset: expected 3 finite values [x, y, theta]")
        if duration is not None and not (np.isfinite(duration) and duration > 0):
            raise Error("duration: expected a positive number of seconds")
        return cls(_nocdyn.Trajectory(name, off[2], terms("theta", theta), off[0], terms("x", x), off[1],
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

    @_vocabulary
    def evaluate(self, t):
        """p, dp/dt, d2p/dt2 at the times t [s] (any shape-(N,) sequence): three (N, 3) arrays
        with columns [x, y, theta] (exact derivatives), ready for Robot.inverse_dynamics."""
        result = self._core._evaluate(_input(_floats(t, "t").reshape(-1), "t", (None,)))
        _require_finite(result, "the trajectory")
        return result

    def __repr__(self):
        return f"<nocdyn.Trajectory {self.name!r}>"
from . import designs  # noqa: E402,F401  (nocdyn.designs: sweeps, optimisation, Dask)
