"""Every `nocdyn` command as a Python function.

Each function stands on the command's typed C++ layer (app/), as the command line does: an
option ``--foo-bar`` of ``nocdyn <command>`` is the keyword argument ``foo_bar`` of
``nocdyn.<command>()``, with the same default (read from the command's options struct, one
definition) and the same unit (SI: m, rad, s, kg, N). The answer comes back as NumPy arrays
(nocdyn.results), the command line's numbers bit for bit. Nothing is written to disk unless an
argument names a file or folder (``output``, ``figure``, ``out_dir``, ``log``, ...). The pose is
x, y, theta everywhere (docs/vocabulary.md).

``robot`` is a robot file's path, a nocdyn.Robot, or None for the paper's prototype; ``set`` a
dict of the file's parameters overridden for this call only; ``trajectory`` is 'paper1',
'paper2' or a trajectory file's path (YAML or CSV samples).

Long commands report their progress: ``progress=None`` shows a tqdm bar when Python runs in a
terminal or a notebook and nothing otherwise, ``progress=False`` never, and a callable is
called as ``progress(done, total)`` from the calling thread (it may call nocdyn). The GIL is
released while a command runs, so two threads run two commands at once; Ctrl-C (or a
KeyboardInterrupt raised by the callback) stops it. Warnings are issued as Python warnings.

Bad arguments raise ValueError naming the argument (nocdyn.Error, a ValueError, for what the
command itself refuses: a pose out of reach, a bad file, ...).
"""

from __future__ import annotations

import inspect
import json as _json
import os
import pathlib
import sys
import warnings

from . import _nocdyn
from .results import (Animation, AssemblyModes, Envelope, Excitation, Identification, PoseReport, Report, ShakeResult,
                      Table, Workspace)

__all__ = ["pose", "inverse_dynamics", "forward_kinematics", "simulate", "control", "envelope", "workspace",
           "convert", "animate", "shake", "regressor", "identify", "excite", "loads", "reproduce", "validate",
           "design", "frequency_response", "COMMANDS"]


# --- running a command ---------------------------------------------------------------------

def _interactive():
    """A terminal or a notebook is watching (then a progress bar helps)."""
    if "ipykernel" in sys.modules:
        return True
    stream = sys.stderr
    return bool(stream is not None and hasattr(stream, "isatty") and stream.isatty())


class _TqdmProgress:
    """A tqdm bar over the motion's seconds, opened on the first report."""

    def __init__(self, description):
        self.description = description
        self.bar = None

    def __call__(self, done, total):
        if self.bar is None:
            try:
                from tqdm.auto import tqdm
            except ImportError:  # tqdm is optional (Debian: python3-tqdm)
                self.bar = False
                return
            self.bar = tqdm(total=total, desc=self.description, unit="s", leave=False,
                            bar_format="{l_bar}{bar}| {n:.3g}/{total:.3g} s [{elapsed}<{remaining}]")
        if self.bar:
            self.bar.update(done - self.bar.n)

    def close(self):
        if self.bar:
            self.bar.close()


def _progress_callback(progress, description):
    if progress is False:
        return None
    if progress is None:
        return _TqdmProgress(description) if _interactive() else None
    if not callable(progress):
        raise ValueError("progress: expected None (a bar when interactive), False or a callable(done, total)")
    return progress


def _forces_table(forces, name="forces"):
    """Columns given as a dict, a Table or a DataFrame (the forces, a log) as a Table."""
    if isinstance(forces, Table):
        return forces
    if hasattr(forces, "columns") and hasattr(forces, "to_numpy"):  # a pandas DataFrame
        return Table([str(c) for c in forces.columns], forces.to_numpy(dtype=float))
    if isinstance(forces, dict):
        import numpy as np
        try:
            return Table(list(forces), np.column_stack([np.asarray(v, dtype=float).reshape(-1)
                                                        for v in forces.values()]))
        except (TypeError, ValueError) as error:
            raise ValueError(f"{name}: {error}") from None
    raise ValueError(f"{name}: expected a CSV path, a dict of columns (t, ...), a Table or a DataFrame")


# --- the application layer: options structs in, typed results out ----------------------------
# A command bound this way builds its options struct (nocdyn._nocdyn.<Name>Options, whose
# defaults are the command line's: one definition in C++), runs the command with the GIL
# released and an observer of its own (progress, Ctrl-C, warnings), and converts the typed
# result: no argv, no captured streams, no temporary files, nothing shared between two calls.

def _argument(value, name, default):
    """A Python argument as the struct's field takes it; ValueError naming the argument."""
    if isinstance(value, bool) and not isinstance(default, bool):
        raise ValueError(f"{name}: expected a number, got {value!r}")
    if isinstance(default, bool) and not isinstance(value, bool):
        import numpy as np
        if not isinstance(value, np.bool_):
            raise ValueError(f"{name}: expected True or False, got {value!r}")
        return bool(value)
    if isinstance(value, os.PathLike):
        value = os.fspath(value)
    if isinstance(value, str) and "\0" in value:
        raise ValueError(f"{name}: contains a NUL character")
    try:
        import numpy as np
        if isinstance(value, np.generic):
            return value.item()
    except ImportError:  # pragma: no cover
        pass
    return value


def _numbers(value, name, count=None, what="numbers"):
    """A sequence of numbers (list, tuple, 1-D array) as floats; ValueError naming the argument
    and what it takes for a string, a scalar, a nested array, a wrong length or a non-number."""
    import numpy as np
    want = f"{count} {what}" if count is not None else what
    if isinstance(value, (str, bytes)) or not hasattr(value, "__len__") or \
            (isinstance(value, np.ndarray) and value.ndim != 1):
        shape = f" of shape {value.shape}" if isinstance(value, np.ndarray) else ""
        raise ValueError(f"{name}: expected a sequence of {want}, got {type(value).__name__}{shape} {value!r}"[:200])
    items = list(value)
    if count is not None and len(items) != count:
        raise ValueError(f"{name}: expected {want}, got {len(items)} values")
    out = []
    for i, v in enumerate(items):
        v = _argument(v, f"{name}[{i}]", 0.0)
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise ValueError(f"{name}[{i}]: expected a number, got {v!r}"[:200])
        try:
            out.append(float(v))
        except OverflowError:
            raise ValueError(f"{name}[{i}]: {v!r} is too large for a float") from None
    return out


def _integer_range(options_type, name):
    """The integers the struct's field `name` holds: (lowest, highest), probed."""
    probe = options_type()
    lowest = 0
    for low in (-(2 ** 63), -(2 ** 31)):
        try:
            setattr(probe, name, low)
            lowest = low
            break
        except TypeError:
            continue
    highest = 2 ** 31 - 1
    for high in (2 ** 64 - 1, 2 ** 63 - 1, 2 ** 32 - 1):
        try:
            setattr(probe, name, high)
            highest = high
            break
        except TypeError:
            continue
    return lowest, highest


def _robot_source(robot, set_, name="robot"):
    """The RobotSource of a robot file's path, a nocdyn.Robot or None (the paper's prototype)."""
    from . import Robot
    source = _nocdyn.RobotSource()
    if isinstance(robot, Robot):
        source.use_yaml(robot.to_yaml(), "<nocdyn.Robot>")
    elif robot is not None:
        if not isinstance(robot, (str, os.PathLike)):
            raise ValueError(f"{name}: expected a robot file's path, a nocdyn.Robot or None")
        path = os.fspath(robot)
        if "\0" in path:
            raise ValueError(f"{name}: contains a NUL character")
        source.path = path
    if set_:
        items = set_.items() if isinstance(set_, dict) else [str(v).split("=", 1) for v in set_]
        overrides = {}
        for key, number in items:
            number = _argument(number, "set", 0.0)
            try:
                overrides[str(key).strip()] = float(number)
            except (TypeError, ValueError):
                raise ValueError(f"set: {key}: expected a number, got {number!r}") from None
        source.set = overrides
    return source


# Old keyword spellings, accepted until the next release with a DeprecationWarning: one name per
# concept across the commands (the command line's old spellings are the same, dashed).
_OLD_SPELLINGS = {
    "FrequencyResponseOptions": {"f_min": "min_frequency", "f_max": "max_frequency", "payload": "payload_mass"},
    "ShakeOptions": {"encoder_noise": "noise_u", "jobs": "threads"},
    "ExciteOptions": {"frequency": "base_frequency", "random": "random_shapes"},
}


def _current_spellings(options_type, arguments):
    """`arguments` with each old keyword spelling replaced by its name, warned of; both refused."""
    old = _OLD_SPELLINGS.get(options_type.__name__, {})
    if not old.keys() & arguments.keys():
        return arguments
    import warnings
    renamed = {}
    for name, value in arguments.items():
        if name in old:
            if old[name] in arguments:
                raise TypeError(f"{name} is the old spelling of {old[name]}: give {old[name]} only")
            warnings.warn(f"{name} is deprecated and will be removed in the next release: use {old[name]}",
                          DeprecationWarning, stacklevel=4)
            name = old[name]
        renamed[name] = value
    return renamed


def _bound_options(options_type, arguments):
    """The options struct of a call: every field the call's arguments name, checked by type."""
    options = options_type()
    arguments = _current_spellings(options_type, arguments)
    for name, value in arguments.items():
        if name not in options_type._fields:
            import difflib
            near = difflib.get_close_matches(name, options_type._fields, n=1)
            raise TypeError(f"unexpected keyword argument {name!r}" + (f"; did you mean {near[0]!r}?" if near else ""))
        default = getattr(options, name)
        value = _argument(value, name, default)
        try:
            setattr(options, name, value)
        except TypeError:
            if isinstance(default, int) and not isinstance(default, bool) and isinstance(value, int):
                lowest, highest = _integer_range(options_type, name)
                want = "a non-negative integer" if lowest == 0 and value < 0 else \
                    f"an integer in [{lowest}, {highest}]"
                raise ValueError(f"{name}: {value} is out of range: expected {want}") from None
            want = {"float": "a number", "int": "an integer", "str": "a string", "list": "a list"}
            raise ValueError(f"{name}: expected {want.get(type(default).__name__, type(default).__name__)}, "
                             f"got {type(value).__name__} {value!r}"[:200]) from None
    return options


def _run(run, options, progress, description):
    callback = _progress_callback(progress, description)
    try:
        return run(options, callback)
    finally:
        if isinstance(callback, _TqdmProgress):
            callback.close()


def _signature(options_type, positional, before=(), after=()):
    """The function's signature from the struct: its fields with the struct's defaults."""
    defaults = options_type()
    fields = options_type._fields
    P = inspect.Parameter
    parameters = [P(name, P.POSITIONAL_OR_KEYWORD) for name in positional]
    parameters += [P(name, P.KEYWORD_ONLY, default=default) for name, default in before]
    parameters += [P(name, P.KEYWORD_ONLY, default=getattr(defaults, name)) for name in fields
                   if name not in positional]
    parameters += [P(name, P.KEYWORD_ONLY, default=default) for name, default in after]
    return inspect.Signature(parameters)


def _path(value, name):
    """A file the caller asks for (None: none) as the C++ side takes it."""
    if value is None:
        return None
    if not isinstance(value, (str, os.PathLike)):
        raise ValueError(f"{name}: expected a path, got {type(value).__name__}")
    text = os.fspath(value)
    if not text or "\0" in text:
        raise ValueError(f"{name}: expected a file name, got {text!r}")
    return text


def _table(answer, name, kind=None, text="", integers=()):
    """A Table (or `kind`) from the bound (columns, data, labels) of a typed result."""
    import numpy as np
    columns, data, labels = answer
    labels = {column: np.array(words, dtype=str) for column, words in labels.items()}
    return (kind or Table)(columns, data, text, name, labels, integers)


# limbs, joints and actuators are numbered from 1 (0: none)
_NUMBERS = ("limb", "joint", "actuator")


def _path_argument(value, name):
    """A file name the caller gave ('' for none); ValueError naming the argument."""
    if value is None:
        return ""
    if not isinstance(value, (str, os.PathLike)):
        raise ValueError(f"{name}: expected a path, got {type(value).__name__}")
    text = os.fspath(value)
    if not text or "\0" in text:
        raise ValueError(f"{name}: expected a non-empty path without NUL characters")
    return text


def _refuse_overwrites(command, inputs=(), outputs=(), stems=(), folders=()):
    """Raises ValueError, as the command line refuses it, when an output of the call would replace
    one of its inputs or another of its outputs: inputs, outputs and folders as (argument, value)
    pairs, stems as (argument, value, suffixes) (a figure's STEM.png and STEM.svg); values that are
    no path (None, a Table, a nocdyn.Robot) are skipped."""
    paths = []

    def add(role, name, value, suffixes=("",)):
        if isinstance(value, (str, os.PathLike)) and os.fspath(value):
            paths.extend((role, name, os.fspath(value) + suffix) for suffix in suffixes)

    for name, value in inputs:
        for one in (value if isinstance(value, (list, tuple)) else [value]):
            add("input", name, one)
    for name, value in outputs:
        add("output", name, value)
    for name, value, suffixes in stems:
        add("output", name, value, suffixes)
    for name, value in folders:
        add("folder", name, value)
    _nocdyn._refuse_output_over_input(command, paths)


_FIGURE = (".png", ".svg")


def _write_table(path, columns, data):
    """The table as the command line's CSV, written safely (a unique temporary file renamed)."""
    _nocdyn._write_table(os.fspath(path), list(columns), data)


# --- the commands, in the order of `nocdyn --help` --------------------------------------------
# Each function binds its arguments to the command's options struct (_bound_options); only the
# robot, the files it reads back and the positional arguments are handled one by one.

def pose(x, y, theta=None, *angles, robot=None, set=None):
    """Everything the model knows at one platform pose (``nocdyn pose X Y THETA``): every limb's
    joint variables and the condition number of its Jacobian, the actuator variables and the
    share of their range they use, the actuation map du = A dp/dt and its condition number, the
    inertia I (eq. 23), and at rest under gravity the actuator forces tau and every joint's reaction.

    x, y [m], theta [rad]: the pose of the platform's operation point C, in the order of every
    table (x, y, theta). Returns a PoseReport; its pose, A's columns and, for compliant robots,
    the stiffness and mode shapes are in the order x, y, theta. A two-DOF robot (motion:
    translation) takes x, y of its tool point and no theta (None: not given, which a turning
    platform refuses, as ``nocdyn pose X Y`` does); its vectors and matrices are over x, y.
    A spatial robot (a nocdyn.SpatialRobot or a spatial file's path) takes x, y, z and, for
    motion full, roll, pitch, yaw, and returns a SpatialPoseReport (SpatialRobot.pose)."""
    from .spatial import SpatialRobot
    spatial = robot if isinstance(robot, SpatialRobot) else None
    if spatial is None and robot is not None and isinstance(robot, (str, os.PathLike)):
        path = os.fspath(robot)
        if "\0" not in path and os.path.isfile(path) and _nocdyn.is_spatial_file(path):
            if set:
                raise ValueError("set: not taken by a spatial robot's pose")
            spatial = SpatialRobot.load(path)
    if spatial is not None:
        return spatial.pose([x, y] + ([] if theta is None else [theta]) + list(angles))
    if angles:
        raise ValueError("pose: ROLL PITCH YAW are for a spatial robot")
    given = {"x": x, "y": y, "theta": float("nan") if theta is None else theta}
    options = _bound_options(_nocdyn.PoseOptions, given)
    options.robot = _robot_source(robot, set)
    return PoseReport(_nocdyn._run_pose(options, None))


_parameters = list(_signature(_nocdyn.PoseOptions, ("x", "y", "theta"),
                              after=(("robot", None), ("set", None))).parameters.values())
_parameters[2] = _parameters[2].replace(default=None)  # theta: none for a two-DOF robot
# a spatial robot's roll, pitch, yaw after x, y, z (z in theta's place)
_parameters.insert(3, inspect.Parameter("angles", inspect.Parameter.VAR_POSITIONAL))
pose.__signature__ = inspect.Signature(_parameters)


def inverse_dynamics(trajectory, *, robot=None, set=None, output=None, progress=None, **options):
    """Actuator variables, rates, accelerations and forces along a trajectory
    (``nocdyn inverse-dynamics``), sampled at ``rate`` [Hz] over ``duration`` [s] (default: the
    file's duration, else 0.2 s). trajectory: 'paper1', 'paper2', a trajectory file's path or a
    nocdyn.Trajectory. allow_limits: warn instead of failing at a joint's limits; reactions: the
    joint reactions as more columns. Returns a Table with the CSV's columns (t, x, y, theta, ...,
    u1..un, du1..dun, ddu1..ddun, tau1..taun); output: also write it as CSV. A two-DOF robot
    (motion: translation) takes a trajectory keyed x, y, and its table has no theta column.
    A spatial robot (a nocdyn.SpatialRobot or a spatial robot file's path) takes a trajectory
    file keyed x, y, z, roll, pitch, yaw (motion translation: x, y, z) or a CSV of samples of
    them; its table's columns are t, x, y, z[, roll, pitch, yaw], u1..un, du1..dun, ddu1..ddun,
    tau1..taun, kinetic."""
    from .spatial import SpatialRobot
    from .trajectory import Trajectory
    given = trajectory if isinstance(trajectory, Trajectory) else None
    bound = _bound_options(_nocdyn.InverseDynamicsOptions,
                           options if given is not None else {"trajectory": trajectory, **options})
    if given is not None:
        bound.use_trajectory(given._core)
    spatial = isinstance(robot, SpatialRobot)
    if spatial and set:
        raise ValueError("set: overrides a robot file's parameters; give the file's path instead of a SpatialRobot")
    bound.robot = _robot_source(None if spatial else robot, set)
    _refuse_overwrites("inverse-dynamics", [("robot", robot), ("trajectory", trajectory)], [("output", output)])
    run = robot._core._run_inverse_dynamics if spatial else _nocdyn._run_inverse_dynamics
    columns, data = _run(run, bound, progress, "inverse dynamics")
    table = Table(columns, data, "", "inverse-dynamics")
    if output is not None:
        _write_table(output, columns, data)
    return table


inverse_dynamics.__signature__ = _signature(_nocdyn.InverseDynamicsOptions, ("trajectory",),
                                            before=(("robot", None), ("set", None)),
                                            after=(("output", None), ("progress", None)))


def forward_kinematics(u, *, robot=None, set=None, **options):
    """Every platform pose the robot assembles in with actuator values u [m or rad]
    (``nocdyn forward-kinematics U...``): the working modes (every limb on its home branch), or
    with all_branches every assembly mode. Returns AssemblyModes (poses (k, 3) [x, y, theta], ...)."""
    values = [u] if not hasattr(u, "__len__") else list(u)
    values = [_argument(v, "u", 0.0) for v in values]
    if any(isinstance(v, bool) or not isinstance(v, (int, float)) for v in values):
        raise ValueError(f"u: expected numbers, got {u!r}")
    bound = _bound_options(_nocdyn.ForwardKinematicsOptions, {"u": [float(v) for v in values], **options})
    bound.robot = _robot_source(robot, set)
    return AssemblyModes(_nocdyn._run_forward_kinematics(bound, None))


forward_kinematics.__signature__ = _signature(_nocdyn.ForwardKinematicsOptions, ("u",),
                                              after=(("robot", None), ("set", None)))


def simulate(forces, *, robot=None, set=None, output=None, progress=None, **options):
    """Forward dynamics (``nocdyn simulate``): the motion under actuator forces.

    forces: a CSV path, or columns t, tau1..taun [s, N or N m] (a dict, Table or DataFrame; with
    u1..un and du1..dun in the first row for the initial state, as the command reads them),
    interpolated ('cubic', 'linear' or 'hold') and held beyond the last time. rate: output samples
    per second; duration: seconds (default: the span of the forces). atol, rtol: the integrator's
    tolerances; assembly_mode: which working mode of the first u (1-based; 0: nearest home);
    partial: return the motion up to a failure (and warn of it) instead of raising; reactions: every
    joint's reaction at each sample (limb{i}_j{k}_fx, _fy, _m) as more columns. Returns a Table
    with the CSV's columns; output: also write it as CSV."""
    if isinstance(forces, (str, os.PathLike)):
        bound = _bound_options(_nocdyn.SimulateOptions, {"forces": forces, **options})
    else:
        bound = _bound_options(_nocdyn.SimulateOptions, options)
        table = _forces_table(forces)
        bound.use_forces(table.columns, table.data)
    bound.robot = _robot_source(robot, set)
    _refuse_overwrites("simulate", [("robot", robot), ("forces", forces)], [("output", output)])
    columns, data, text, stopped = _run(_nocdyn._run_simulate, bound, progress, "simulate")
    if stopped:
        warnings.warn(stopped, RuntimeWarning, stacklevel=2)
    if output is not None:
        _write_table(output, columns, data)
    return Table(columns, data, "" if stopped else text, "simulate")


simulate.__signature__ = _signature(_nocdyn.SimulateOptions, ("forces",), before=(("robot", None), ("set", None)),
                                    after=(("output", None), ("progress", None)))


def control(trajectory, *, robot=None, set=None, plant=None, log=None, output=None, figure=None, progress=None,
            **options):
    """Closed-loop tracking of a platform trajectory (``nocdyn control``) by computed torque or PD
    on a plant: 'simbody' (the independent model, when built in; the default then), 'nocdyn' or
    'nocdyn-rk4'. The payload_* arguments put a payload on the plant only (model mismatch); the
    noise_* arguments are sensor noise; log: also write the sensors' log for identify. Returns a
    Table with the CSV's columns (t, x_d, y_d, theta_d, ..., e_x, e_y, e_theta, u1..un, ..., tau1..taun);
    its text holds the RMS and peak errors. output, figure: also write the CSV and the
    tracking-error figure (STEM.png and STEM.svg). A two-DOF robot (motion: translation) takes a
    trajectory keyed x, y and runs on 'nocdyn' by default (plant 'simbody' is refused); its Table
    has no theta columns."""
    if options.get("payload_com") is None:
        options.pop("payload_com", None)
    else:
        options["payload_com"] = _numbers(options["payload_com"], "payload_com", 2, "numbers [x, y]")
    bound = _bound_options(_nocdyn.ControlOptions, {"trajectory": trajectory, **options})
    if plant is not None:  # None: the build's default (Simbody's when built in; nocdyn's for a two-DOF robot)
        bound.plant = _argument(plant, "plant", "")
    bound.plant_given = plant is not None
    bound.robot = _robot_source(robot, set)
    files = [_path_argument(log, "log"), _path_argument(figure, "figure")]
    _refuse_overwrites("control", [("robot", robot), ("trajectory", trajectory)], [("output", output), ("log", log)],
                       [("figure", figure, _FIGURE)])
    columns, data, text = _run(lambda o, p: _nocdyn._run_control(o, *files, p), bound, progress, "control")
    if output is not None:
        _write_table(output, columns, data)
    return Table(columns, data, text.rstrip("\n"), "control")


control.__signature__ = _signature(_nocdyn.ControlOptions, ("trajectory",), before=(("robot", None), ("set", None)),
                                   after=(("log", None), ("output", None), ("figure", None), ("progress", None)))
control.__signature__ = control.__signature__.replace(parameters=[
    p.replace(default=None) if p.name == "plant" else p for p in control.__signature__.parameters.values()])


def envelope(*, robot=None, set=None, output=None, figure=None, progress=None, **options):
    """The operating envelope (``nocdyn envelope``): per axis (x, y, theta; x, y of a two-DOF
    robot; x, y, z, roll, pitch, yaw of a spatial robot file, x, y, z for motion translation) and
    ``points`` log-spaced frequencies in [min_frequency, max_frequency] Hz, the
    largest amplitude within every limit and which limit binds. Returns an Envelope (a Table with the CSV's columns: axis
    and limit as words; frequency, amplitude, ...; limb, joint, actuator numbered from 1, 0 when
    none) whose ``first_natural_frequency`` [Hz] is the band's third bound when the robot file
    declares compliance (None otherwise; ``text`` says which), ``band_end`` {"x": f, "y": f,
    "theta": f} [Hz] the lowest frequency per axis where the dynamic amplification leaves
    [1/amplification, amplification] (None when unknown; ``resonance_reason`` says why). output: also write the CSV;
    figure: the figure's stem (STEM.png, STEM.svg). A spatial robot
    has no resonance bound (amplification other than 1.1 is refused)."""
    bound = _bound_options(_nocdyn.EnvelopeOptions, options)
    bound.robot = _robot_source(robot, set)
    _refuse_overwrites("envelope", [("robot", robot)], [("output", output)], [("figure", figure, _FIGURE)])
    answer, summary, first, band_end, reason = _run(
        lambda o, p: _nocdyn._run_envelope(o, p, _path(output, "output"), _path(figure, "figure")), bound, progress,
        "envelope")
    table = _table(answer, "envelope", Envelope, summary, integers=_NUMBERS)
    table.first_natural_frequency, table.band_end, table.resonance_reason = first, band_end, reason
    return table


envelope.__signature__ = _signature(_nocdyn.EnvelopeOptions, (), before=(("robot", None), ("set", None)),
                                    after=(("output", None), ("figure", None), ("progress", None)))


def frequency_response(*, robot=None, set=None, output=None, summary=None, figure=None, **options):
    """The rigid robot linearised at an operating point and its frequency response
    (``nocdyn frequency-response``): pose [x, y, theta] (default home) and rate [dx, dy, dtheta]
    (default at rest; [x, y] and [dx, dy] of a two-DOF robot, whose channels are x, y), held by
    the inverse dynamics' forces; from each actuator force to each
    platform acceleration (output_kind "acceleration") or actuator variable ("actuators") over
    ``points`` log-spaced frequencies in [min_frequency, max_frequency] Hz. Returns a Table (f, then
    <output>_tau<a>_db and _deg per channel, axes x, y, theta); ``text`` holds the summary with
    each channel's -3 dB bandwidth. output, summary, figure: also write the CSV, the summary and
    the Bode figure (STEM.png and STEM.svg).

    compliance "auto" (default): when the robot file declares compliance (joint or drive
    stiffness, elastic links) the plant is the lumped compliant model, from each drive's
    commanded position (columns <output>_uc<a>; a drive of stiffness 0 keeps its force,
    _tau<a>), with the lumped natural frequencies in ``text``; "rigid" forces the rigid model,
    "lumped" requires the compliant one.

    payload_mass [kg]: a point mass at C that the plant carries.

    closed_loop=True: the shake-table loop linearised at rest (``--closed-loop``), from the
    reference to the achieved platform acceleration per axis, with the plant's ``payload_mass`` [kg]
    at C unknown to the controller, ``controller_rate`` [Hz] and the pose feedback's
    ``natural_frequency`` [Hz] (both only with closed_loop; an unstable loop is refused); the
    Table has <axis>_db, _deg, _loop_db, _loop_deg per axis and ``text`` each axis's -3 dB
    bandwidth, crossover and phase margin, and its usable band (``band <axis> <end Hz> <peak dB>
    <at Hz>`` lines: |H| within [1/A, A] up to the end, A = ``amplification``, 1.1 by default). On a
    robot file that declares compliance the loop's plant is the lumped compliant model
    (``compliance`` "auto" or "lumped"; "rigid" forces the rigid plant)."""
    options = {k: v for k, v in options.items() if not (k in ("pose", "rate") and v is None)}
    for name, what in (("pose", "numbers [x, y, theta] ([x, y] of a two-DOF robot)"),
                       ("rate", "numbers [dx, dy, dtheta] ([dx, dy] of a two-DOF robot)")):
        if name in options:
            options[name] = _numbers(options[name], name, None, what)
            if len(options[name]) not in (2, 3):
                raise ValueError(f"{name}: expected 3 {what}, got {len(options[name])} values")
    bound = _bound_options(_nocdyn.FrequencyResponseOptions, options)
    bound.robot = _robot_source(robot, set)
    files = [_path_argument(summary, "summary"), _path_argument(figure, "figure")]
    _refuse_overwrites("frequency-response", [("robot", robot)], [("output", output), ("summary", summary)],
                       [("figure", figure, _FIGURE)])
    columns, data, text = _nocdyn._run_frequency_response(bound, *files)
    if output is not None:
        _write_table(output, columns, data)
    return Table(columns, data, text, "frequency-response")


frequency_response.__signature__ = _signature(_nocdyn.FrequencyResponseOptions, (),
                                              before=(("robot", None), ("set", None)),
                                              after=(("output", None), ("summary", None), ("figure", None)))


def workspace(*, robot=None, set=None, output=None, figure=None, frequency_map=None, progress=None, **options):
    """The workspace at one platform orientation theta [rad] (default: the robot's home)
    (``nocdyn workspace``): a resolution x resolution grid of C's positions, each feasible (0),
    out of reach (1), with a joint out of range (2) or singular (3). Returns a Workspace (x, y,
    cell; ``cells`` as a grid, ``area``; ``text`` the summary line). output: also write the CSV;
    figure: the figure's stem (STEM.png, STEM.svg). first_frequency=True (robot files that declare
    compliance): also ``first_frequency``, the lowest natural frequency [Hz] per grid point as an
    (n, n) array indexed [ix, iy] (NaN where not feasible), ``first_frequency_min`` and
    ``first_frequency_at`` (x, y, theta); frequency_map: its stem (STEM.csv, STEM.png, STEM.svg),
    which implies first_frequency."""
    bound = _bound_options(_nocdyn.WorkspaceOptions, options)
    bound.robot = _robot_source(robot, set)
    _refuse_overwrites("workspace", [("robot", robot)], [("output", output)],
                       [("figure", figure, _FIGURE), ("frequency_map", frequency_map, (".csv",) + _FIGURE)])
    answer, summary, frequency = _run(
        lambda o, p: _nocdyn._run_workspace(o, p, _path(output, "output"), _path(figure, "figure"),
                                            _path(frequency_map, "frequency_map")),
        bound, progress, "workspace")
    result = _table(answer, "workspace", Workspace, summary)
    if frequency is not None:
        result.first_frequency = frequency["first"]
        result.first_frequency_min = frequency["lowest"]
        result.first_frequency_at = frequency["lowest_at"]
        result.first_frequency_max = frequency["highest"]
        result.frequency_table = _table(frequency["table"], "first_frequency")
    return result


workspace.__signature__ = _signature(_nocdyn.WorkspaceOptions, (), before=(("robot", None), ("set", None)),
                                     after=(("output", None), ("figure", None), ("frequency_map", None),
                                            ("progress", None)))


def convert(robot, *, set=None, output=None):
    """A robot file in the general per-limb form (``nocdyn convert``): returns its YAML text
    (numbers in shortest round-trip form); also written to ``output`` when given."""
    if robot is None:
        raise ValueError("robot: a robot file's path or a nocdyn.Robot is required")
    bound = _nocdyn.ConvertOptions()
    bound.robot = _robot_source(robot, set)
    _refuse_overwrites("convert", [("robot", robot)], [("output", output)])
    return _run(lambda o, p: _nocdyn._run_convert(o, p, _path(output, "output")), bound, False, "convert")


def animate(trajectory=None, *, robot=None, set=None, output=None, png=None, svg=None, **options):
    """The robot in motion as one self-contained HTML page (``nocdyn animate``), from a
    trajectory (inverse dynamics at ``rate`` over ``duration``) or a motion CSV written by
    simulate, control or inverse-dynamics (``motion``, a path or a Table). Returns an Animation,
    shown inline in Jupyter; output: also write the page. frame (with png or svg): also draw
    the robot at that time. A spatial robot (a spatial robot file's path) is drawn in 3-D along
    a trajectory file keyed x, y, z (, roll, pitch, yaw); motion, frame, png and svg are planar
    only."""
    from .spatial import SpatialRobot
    if isinstance(robot, SpatialRobot):
        raise ValueError("robot: animate takes a spatial robot file's path, not a SpatialRobot")
    motion = options.pop("motion", None)
    arguments = {name: value for name, value in options.items() if value is not None or name == "frame"}
    if trajectory is not None:
        arguments["trajectory"] = trajectory
    if isinstance(motion, Table):
        bound = _bound_options(_nocdyn.AnimateOptions, arguments)
        bound.use_motion_table(list(motion.columns), motion.data, motion.name or "motion")
    else:
        if motion is not None:
            arguments["motion"] = motion
        bound = _bound_options(_nocdyn.AnimateOptions, arguments)
    bound.robot = _robot_source(robot, set)
    _refuse_overwrites("animate", [("robot", robot), ("trajectory", trajectory), ("motion", motion)],
                       [("output", output), ("png", png), ("svg", svg)])
    path, png_path, svg_path = (_path_argument(output, "output"), _path_argument(png, "png"),
                                _path_argument(svg, "svg"))
    if bound.frame is not None and not (png_path or svg_path):
        raise ValueError("frame: needs png or svg")
    if bound.frame is None and (png_path or svg_path):
        raise ValueError(f"{'png' if png_path else 'svg'}: needs frame (the time to draw)")
    html = _run(lambda o, callback: _nocdyn._run_animate(o, callback, png_path, svg_path), bound, False, "animate")
    if path:
        _nocdyn._write_text(path, html)
    return Animation(html, None if output is None else pathlib.Path(output))


def _animate_signature():
    signature = _signature(_nocdyn.AnimateOptions, ("trajectory",), before=(("robot", None), ("set", None)),
                           after=(("output", None), ("png", None), ("svg", None)))
    parameters = list(signature.parameters.values())
    parameters[0] = parameters[0].replace(default=None)
    return signature.replace(parameters=parameters)


animate.__signature__ = _animate_signature()


def shake(record=None, *, robot=None, set=None, out_dir=None, progress=None, records=None, **options):
    """Play a ground-motion record (PEER AT2, values in g) on a robot (``nocdyn shake``):
    high-passed, integrated, scaled by similitude to fit every actuator, and played on the plant
    with an unknown payload, as a shake table plays it: controller "table" (model feed-forward,
    low-gain feedback from a Kalman estimate fusing the encoders and the platform accelerometers;
    optionally the payload identified first and drive-signal iterations, corrected through
    the identity or the inverse linearised loop: drive_model, drive_specimen), or "pose" (computed
    torque on noisy pose feedback). natural_frequency: None for the controller's own default. window: play only the
    record's first seconds (0: all); axis: "x" (the default) or "y", the axis the record drives
    (a two-DOF robot's table: its tool point in x, y, no theta or alpha columns). Returns a
    ShakeResult: the samples (t, x, y, theta, ax, ay,
    alpha, ..._achieved, u1..un, tau1..taun) and ``metrics`` (shake.json: scales, and per axis
    the errors in percent, ``rms_error_percent``, ``peak_error_percent``, ..., and the spectra).
    out_dir: also write the files and figures there. Ctrl-C (or a KeyboardInterrupt raised by
    ``progress``) stops the replay and writes nothing. record: an AT2 file, or the list of one
    record's component files (two horizontals and at most one vertical, each header's azimuth or
    UP): its horizontals drive x and y, rotated onto the table (``nocdyn shake`` says how; x_azimuth
    turns the table's x). records: the same list of component files, by another name. On a
    six-DOF table (a spatial robot such as robots/stewart.yaml) the three components drive x, y
    and z in computed torque with the rotations held at zero; the samples are t, x_d, y_d, z_d,
    ax, ay, az, ..._achieved, x .. yaw, u1..u6, tau1..tau6, the metrics keyed ax, ay, az, and
    per_axis_scale scales each axis to its own limit; identify_payload identifies the specimen's
    mass, c.o.m. and inertia tensor first (``metrics["payload_estimate"]``: each value with its
    standard deviation, the true values under ``"true"``) and the controller's model carries it;
    iterations iterate the drive on x, y, z (the identity drive model, a pass's error its worst
    axis's; metrics pass_rms_error_percent, pass_rms_error_percent_axes, pass_kept,
    iteration_stop)."""
    if records is not None:
        if record is not None:
            raise ValueError("record, records: give one of them (records is the list of a record's component files)")
        record = records
    if record is None:
        raise ValueError("record: expected an AT2 file's path or a list of its component files (or records=[...])")
    # a folder (or several records) is a suite, whose results are one folder per record and no
    # samples to return: refused before anything runs, rather than after. The component files of
    # one record (two horizontals and a vertical sharing a name) are one record.
    files = list(record) if isinstance(record, (list, tuple)) else [record]
    if not files or any(not isinstance(f, (str, os.PathLike)) for f in files):
        raise ValueError(f"record: expected an AT2 file's path or a list of its component files, got {record!r}")
    files = [_argument(f, "record", "") for f in files]
    several = len(files) > 1 and len(_nocdyn._record_groups(files)) > 1
    if several or os.path.isdir(files[0]):
        raise ValueError(f"record: {record!r} is a suite of records, and nocdyn.shake plays one record and "
                         "returns its samples: call it once per record, or run the suite with "
                         "`nocdyn shake --record FOLDER --out-dir DIR` (summary.md and one folder per record)")
    arguments = {"record": files, **options}
    if arguments.get("natural_frequency", None) is None:
        arguments.pop("natural_frequency", None)
    bound = _bound_options(_nocdyn.ShakeOptions, arguments)
    bound.robot = _robot_source(robot, set)
    _refuse_overwrites("shake", [("robot", robot), ("record", files), ("record_y", options.get("record_y")),
                                 ("record_theta", options.get("record_theta"))], folders=[("out_dir", out_dir)])
    if out_dir is not None:
        bound.out_dir = _argument(out_dir, "out_dir", "")
    columns, data, metrics, text = _run(_nocdyn._run_shake, bound, progress, "shake")
    return ShakeResult(columns, data, _json.loads(metrics), None if out_dir is None else pathlib.Path(out_dir),
                       text.rstrip("\n"))


shake.__signature__ = _signature(_nocdyn.ShakeOptions, ("record",), before=(("robot", None), ("set", None)),
                                 after=(("out_dir", None), ("progress", None), ("records", None)))


def regressor(*, robot=None, set=None, output=None, **options):
    """The robot's standard inertial and friction parameters and its base parameters (the
    combinations the actuator forces identify) (``nocdyn regressor``). Returns the report's text;
    output: also write it there."""
    bound = _bound_options(_nocdyn.RegressorOptions, options)
    bound.robot = _robot_source(robot, set)
    _refuse_overwrites("regressor", [("robot", robot)], [("output", output)])
    return _run(lambda o, p: _nocdyn._run_regressor(o, p, _path(output, "output")), bound, False, "regressor")["text"]


regressor.__signature__ = _signature(_nocdyn.RegressorOptions, (), before=(("robot", None), ("set", None)),
                                     after=(("output", None),))


def identify(data, *, robot=None, set=None, output=None, figure=None, progress=None, **options):
    """Identify a payload (the default) or the robot's base parameters (base) from a log of
    actuator positions and forces (``nocdyn identify``): a CSV path, or columns (a dict, Table or
    DataFrame) t, u1..un with tau1..taun (forces at each sample) or tau1_held..taun_held (commands
    held until the next sample, as control's ``log`` writes them; taken so without held_forces),
    and du1..dun, ddu1..ddun when known (used as given; else u and tau are low-pass filtered at
    ``cutoff`` and u differentiated). prior: bounds on the payload, a prior file's path or a dict
    {"mass": (lower, upper), "com_x": ..., "com_y": ..., "inertia": ...} (None for an open side;
    see nocdyn.load_prior). Returns an Identification: its numbers typed (``payload``,
    ``payload_estimate`` with the standard deviations, covariance and fit; ``base``), the report
    the command prints (``text``) and ``robot_yaml``, the file the command writes (the robot with
    the payload merged, or with base the calibration). output: also write that file; figure: STEM
    of the held-out forces' figure (STEM.png, STEM.svg). A two-DOF robot's (motion: translation)
    payload is a point mass at the tool point: its mass only (com [0, 0] and inertia 0 are not
    identified; a prior may bound only the mass)."""
    prior = options.pop("prior", None)
    table = None if isinstance(data, (str, os.PathLike)) else _forces_table(data, "data")
    bound = _bound_options(_nocdyn.IdentifyOptions, options if table is not None else {"data": data, **options})
    if table is not None:
        bound.use_data(table.columns, table.data)
    if isinstance(prior, dict):
        bound.use_prior(_prior_bounds(prior))
    elif prior is not None:
        bound.prior = _argument(prior, "prior", "")
    bound.robot = _robot_source(robot, set)
    _refuse_overwrites("identify", [("robot", robot), ("data", data), ("calibration", options.get("calibration")),
                                    ("prior", prior)], [("output", output)], [("figure", figure, _FIGURE)])
    path, stem = _path_argument(output, "output"), _path_argument(figure, "figure")
    text, robot_yaml, payload, base = _run(lambda o, callback: _nocdyn._run_identify(o, callback, stem), bound,
                                           progress, "identify")
    if path:
        _nocdyn._write_text(path, robot_yaml)
    return Identification(text, robot_yaml, payload, base)


def _prior_bounds(prior):
    """The (lower, upper) pairs of mass, com_x, com_y, inertia of a prior given as a dict, infinite
    where open; ValueError naming an unknown key or a bad pair."""
    from ._guards import _number
    from .identification import PRIOR_KEYS
    unknown = sorted(set(prior) - set(PRIOR_KEYS))
    if unknown:
        raise _nocdyn.Error(f"prior: unknown key {unknown[0]!r} (expected one of: {', '.join(PRIOR_KEYS)})")
    bounds = []
    for key in PRIOR_KEYS:
        pair = prior.get(key, (None, None))
        if pair is None or isinstance(pair, (str, bytes)) or not hasattr(pair, "__len__") or len(pair) != 2:
            raise _nocdyn.Error(f"prior: {key}: expected (lower, upper), None for an open side")
        lower = -float("inf") if pair[0] is None else _number(pair[0], f"prior: {key}: lower")
        upper = float("inf") if pair[1] is None else _number(pair[1], f"prior: {key}: upper")
        bounds.append((lower, upper))
    return bounds


identify.__signature__ = _signature(_nocdyn.IdentifyOptions, ("data",), before=(("robot", None), ("set", None)),
                                    after=(("output", None), ("figure", None), ("progress", None)))


def excite(*, robot=None, set=None, output=None, progress=None, **options):
    """Design an excitation trajectory for identify (``nocdyn excite``): Fourier series of
    ``harmonics`` harmonics of ``frequency`` [Hz] per axis, as large as every limit allows (with
    ``margin`` to spare), minimising the condition number of the payload's (or with base, the
    robot's base parameters') regressor. payload_guess: (mass, com_x, com_y, inertia) or None.
    Returns an Excitation (yaml, trajectory, text); output: also write the trajectory file.
    Ctrl-C (or a KeyboardInterrupt raised by ``progress``) stops the design. A two-DOF robot
    (motion: translation) moves on x, y only; its payload is a point mass (guess: (mass, 0, 0, 0))."""
    from . import Trajectory
    guess = options.pop("payload_guess", None)
    bound = _bound_options(_nocdyn.ExciteOptions, options)
    if guess is not None:
        bound.payload_guess = _numbers(guess, "payload_guess", 4, "numbers: mass, com_x, com_y, inertia")
    bound.robot = _robot_source(robot, set)
    _refuse_overwrites("excite", [("robot", robot)], [("output", output)])
    path = _path_argument(output, "output")
    text, yaml_text = _run(_nocdyn._run_excite, bound, progress, "excite")
    if path:
        _nocdyn._write_text(path, yaml_text)
    return Excitation({"yaml": yaml_text, "trajectory": Trajectory.from_yaml(yaml_text, "<excite>" if output is None else os.fspath(output)),
                       "path": None if output is None else pathlib.Path(output)}, text.rstrip("\n"))


excite.__signature__ = _signature(_nocdyn.ExciteOptions, (), before=(("robot", None), ("set", None)),
                                  after=(("output", None), ("progress", None)))


def loads(trajectory=None, *, robot=None, set=None, output=None, figure=None, progress=None, **options):
    """Joint reactions and design loads (``nocdyn loads``) along a trajectory, or over the
    operating envelope's motions (envelope=True). Returns a Table with the CSV's columns (limb and
    joint numbered from 1, peak and RMS forces, ...); ``text`` the command line's report. output:
    also write the CSV; figure: the robot at the worst pose (STEM.png, STEM.svg). A spatial
    robot file (space: spatial) takes a trajectory file keyed x, y, z (roll, pitch, yaw): one row
    per listed joint with its ``type`` (R, P, U or S), no envelope, no figure."""
    bound = _bound_options(_nocdyn.LoadsOptions, {"trajectory": "" if trajectory is None else trajectory, **options})
    bound.robot = _robot_source(robot, set)
    _refuse_overwrites("loads", [("robot", robot), ("trajectory", trajectory)], [("output", output)],
                       [("figure", figure, _FIGURE)])
    answer, text = _run(lambda o, p: _nocdyn._run_loads(o, p, _path(output, "output"), _path(figure, "figure")),
                        bound, progress, "loads")
    return _table(answer, "loads", text=text.rstrip("\n"), integers=_NUMBERS)


loads.__signature__ = _signature(_nocdyn.LoadsOptions, ("trajectory",), before=(("robot", None), ("set", None)),
                                 after=(("output", None), ("figure", None), ("progress", None)))
loads.__signature__ = loads.__signature__.replace(parameters=[
    p.replace(default=None) if p.name == "trajectory" else p for p in loads.__signature__.parameters.values()])


def validate(trajectory, *, robot=None, set=None, output=None, progress=None, **options):
    """Our actuator forces against Simbody's and MuJoCo's (``nocdyn validate``; only when the
    package was built with both engines). Returns a Table with the CSV's columns
    (t, u1..un, tau1..taun, simbody_..., mujoco_..., simbody_dtau1..n, mujoco_dtau1..n); its text
    holds the largest differences. output: also write the CSV. A spatial robot file's path
    (space: spatial) with a spatial trajectory file is compared with Simbody's and MuJoCo's
    spatial models, or the one engine ("simbody" or "mujoco") names: columns t, x, y, z[, roll,
    pitch, yaw], u1..un, tau1..taun, then each engine's <engine>_tau1..n, then its
    <engine>_dtau1..n."""
    from .spatial import SpatialRobot
    if not hasattr(_nocdyn, "_run_validate"):
        raise _nocdyn.Error("validate needs the package built with Simbody and MuJoCo")
    if isinstance(robot, SpatialRobot):
        raise ValueError("robot: validate takes a spatial robot file's path, not a SpatialRobot")
    bound = _bound_options(_nocdyn.ValidateOptions, {"trajectory": trajectory, **options})
    bound.robot = _robot_source(robot, set)
    _refuse_overwrites("validate", [("robot", robot), ("trajectory", trajectory)], [("output", output)])
    columns, data, text = _run(_nocdyn._run_validate, bound, progress, "validate")
    if output is not None:
        _write_table(output, columns, data)
    return Table(columns, data, text.rstrip("\n"), "validate")


if hasattr(_nocdyn, "ValidateOptions"):
    validate.__signature__ = _signature(_nocdyn.ValidateOptions, ("trajectory",), before=(("robot", None), ("set", None)),
                                        after=(("output", None), ("progress", None)))


def reproduce(*, progress=None, **options):
    """The paper's results for its prototype (``nocdyn reproduce``): CSV files, figures and
    summary.md in out_dir. Returns a Report (shown as Markdown in Jupyter). Ctrl-C (or a
    KeyboardInterrupt raised by ``progress``) stops it between sections."""
    bound = _bound_options(_nocdyn.ReproduceOptions, options)
    folder = _run(_nocdyn._run_reproduce, bound, progress, "reproduce")
    return Report(folder)


reproduce.__signature__ = _signature(_nocdyn.ReproduceOptions, (), after=(("progress", None),))


def design(vary, metric, *, robot=None, set=None, out_dir=None, progress=None, **options):
    """Sweep a parametric robot family over its declared parameters (``nocdyn design``): each
    design's metrics (workspace_area, condition_median, condition_worst, envelope_x@F, ...,
    moving_mass, peak_force, rms_force, stroke, peak_reaction), infeasible designs as rows with
    their reason. vary: "NAME=LOWER:UPPER" strings (a dict {NAME: (LOWER, UPPER)}, the form
    nocdyn.designs.Family takes, is refused with the strings it means); metric: metric names.
    Returns a
    nocdyn.designs.Designs (``front``: the indices of the Pareto front). out_dir: also write
    designs.csv, pareto.csv, the journal and the figures there (the sweep resumes from its
    journal); without it nothing is written. Ctrl-C (or an exception from ``progress``) stops the
    sweep once the designs under way finish. For Sobol or Latin-hypercube sweeps, optimisation
    and Dask, see nocdyn.designs."""
    from .designs import Designs
    if isinstance(vary, dict):
        # the form nocdyn.designs.Family takes, {NAME: (LOWER, UPPER)}: refused, but with the
        # strings that say the same, so that a dict is never read as its keys
        pairs = []
        for key, pair in vary.items():
            if isinstance(pair, (str, bytes)) or not hasattr(pair, "__len__") or len(pair) != 2:
                raise ValueError(f"vary: {key!r}: expected (LOWER, UPPER), got {pair!r}"[:200])
            lower, upper = _numbers(pair, f"vary[{key!r}]", 2, "numbers (LOWER, UPPER)")
            pairs.append(f"{key}={lower!r}:{upper!r}")
        raise ValueError(f"vary: a dict is the form nocdyn.designs.Family takes; nocdyn.design takes "
                         f"'NAME=LOWER:UPPER' strings: vary={pairs!r}")
    vary = [vary] if isinstance(vary, str) else list(vary)
    metric = [metric] if isinstance(metric, str) else list(metric)
    bound = _bound_options(_nocdyn.DesignOptions, {"vary": vary, "metric": metric, **options})
    bound.robot = _robot_source(robot, set)
    bound.out_dir = "" if out_dir is None else _path(out_dir, "out_dir")
    _refuse_overwrites("design", [("robot", robot), ("trajectory", options.get("trajectory"))],
                       folders=[("out_dir", out_dir)])
    answer = _run(_nocdyn._run_design, bound, progress, "design")
    designs = Designs(answer["names"], answer["metrics"], answer["points"], answer["values"], answer["feasible"],
                      answer["reason"])
    designs.front = list(answer["front"])
    return designs


design.__signature__ = _signature(_nocdyn.DesignOptions, ("vary", "metric"), before=(("robot", None), ("set", None)),
                                  after=(("out_dir", None), ("progress", None)))


#: The command line's command of each function (the parity test and docs/python-parity.md).
COMMANDS = {"pose": pose, "inverse-dynamics": inverse_dynamics, "forward-kinematics": forward_kinematics,
            "simulate": simulate, "control": control, "envelope": envelope, "workspace": workspace,
            "convert": convert, "animate": animate, "shake": shake, "regressor": regressor, "identify": identify,
            "excite": excite, "loads": loads, "validate": validate, "reproduce": reproduce, "design": design,
            "frequency-response": frequency_response}


def main(argv=None):
    """The `nocdyn` command (pip's console script): the command line in this process."""
    args = list(sys.argv if argv is None else argv)
    args[0] = "nocdyn"
    sys.stdout.flush()
    sys.stderr.flush()
    return _nocdyn._main(args)
