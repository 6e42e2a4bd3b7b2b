"""Design sweeps and optimisation over families of robots, on one machine or a Dask cluster.

A family is a parametric robot file (``parameters:`` with named values, numbers written as
expressions of them) with some parameters varied over ranges. Each design is the robot file
that one parameter set means (``nocdyn convert --set``), and its metrics are the numbers the
single-robot commands give (see ``nocdyn design --help``): ``workspace_area``,
``condition_median``, ``condition_worst``, ``first_frequency_min`` (the lowest first natural
frequency over the workspace [Hz]; a family without compliance is infeasible), ``envelope_x@50`` (any axis x, y, theta and
frequency), ``moving_mass``, and along a trajectory ``peak_force``, ``rms_force``, ``stroke``,
``peak_reaction``. A design that does not assemble, is singular or meets a limit is a row with
``feasible`` False and its ``reason``.

Sweeps: ``grid`` and ``random`` (as the command line), ``sobol`` and ``lhs``
(``scipy.stats.qmc``, scrambled and seeded). Optimisation: Optuna (TPE for one objective,
NSGA-II for several), seeded, with constraints. Scale-out: ``sweep(..., client=...)`` sends
chunks of designs to a ``dask.distributed`` cluster (a ``LocalCluster`` of one worker process
per core by default); every chunk is evaluated by the compiled library with the GIL released.

    from nocdyn import designs
    family = designs.Family("examples/design_3rrr/family.yaml", vary={"r_b": (0.15, 0.25)})
    if __name__ == "__main__":  # the sweep's worker processes import this script again
        table = designs.sweep(family, ["workspace_area", "envelope_x@50"], samples=64, method="sobol")
        table.to_csv("designs.csv")
"""

from __future__ import annotations

import math
import os
import pathlib
import warnings

import numpy as np

from . import _nocdyn
from ._nocdyn import Error

__all__ = ["Family", "Designs", "sample", "evaluate", "sweep", "optimize", "pareto_front"]

_MAX_DESIGNS = 1_000_000
_METHODS = ("grid", "random", "sobol", "lhs")


class Family:
    """A parametric robot file with the parameters a sweep varies.

    path: the robot file (or text= its YAML, with source= its name in messages); vary: {name:
    (lower, upper)} in the order of the table's columns; fixed: {name: value} set for every
    design (as ``--set``). Raises nocdyn.Error for a parameter the file does not declare."""

    def __init__(self, path=None, vary=None, fixed=None, *, text=None, source=None):
        if (path is None) == (text is None):
            raise Error("Family: give a robot file path or text=, not both")
        if text is None:
            text = pathlib.Path(path).read_text(encoding="utf-8")
            source = str(path) if source is None else source
        self.text = text
        self.source = source or "<string>"
        self.fixed = [(str(k), _finite(f"fixed[{k!r}]", v)) for k, v in (fixed or {}).items()]
        self.vary = []
        for k, pair in (vary or {}).items():
            if isinstance(pair, (str, bytes)) or not hasattr(pair, "__len__") or len(pair) != 2:
                raise ValueError(f"vary[{k!r}]: expected (LOWER, UPPER), got {pair!r}"[:200])
            self.vary.append((str(k), _finite(f"vary[{k!r}] lower", pair[0]), _finite(f"vary[{k!r}] upper", pair[1])))
        if not self.vary:
            raise Error("Family: vary at least one parameter")
        for name, lo, hi in self.vary:
            if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi):
                raise Error(f"vary: {name}: expected finite (lower, upper) with lower <= upper")
            if not math.isfinite(hi - lo):
                raise Error(f"vary: {name}: the width {hi} - ({lo}) of the range overflows a double")
        declared = dict(self.parameters())
        for name, _, _ in self.vary:
            if name not in declared:
                raise Error(f"{self.source}: varied parameter '{name}' is not declared "
                            f"(parameters: {', '.join(declared) or 'none'})")

    @property
    def names(self):
        """The varied parameters' names."""
        return [name for name, _, _ in self.vary]

    def parameters(self, point=None):
        """[(name, value)] of every parameter the file declares, at `point` (values of the
        varied parameters) when given."""
        return _nocdyn._robot_file_parameters(self.text, self.source, self._overrides(point))

    def convert(self, point):
        """The plain robot file (general form, YAML text) of one design, as `nocdyn convert
        --set` writes it."""
        return _nocdyn._convert(self.text, self.source, self._overrides(point))

    def robot(self, point):
        """The nocdyn.Robot of one design."""
        from . import Robot
        return Robot.from_yaml(self.convert(point), self.source)

    def _overrides(self, point):
        out = list(self.fixed)
        if point is not None:
            point = [float(v) for v in point]
            if len(point) != len(self.vary):
                raise Error(f"point: expected {len(self.vary)} values ({', '.join(self.names)})")
            out += list(zip(self.names, point))
        return out

    def _key(self):
        return (self.text, self.source, self.fixed, self.names)


class Designs:
    """A table of evaluated designs: points (N, d) of the varied parameters (names), values
    (N, m) of the metrics (NaN where infeasible), feasible (N,) bool, reason (list of str)."""

    def __init__(self, names, metrics, points, values, feasible, reason):
        self.names = list(names)
        self.metrics = list(metrics)
        self.points = np.asarray(points, dtype=float).reshape(-1, len(self.names))
        self.values = np.asarray(values, dtype=float).reshape(-1, len(self.metrics))
        self.feasible = np.asarray(feasible, dtype=bool).reshape(-1)
        self.reason = list(reason)

    def __len__(self):
        return self.points.shape[0]

    def rows(self):
        """One dict per design: design (its number, from 1, as designs.csv; row design - 1), each
        parameter, each metric, feasible, reason."""
        out = []
        for i in range(len(self)):
            row = {"design": i + 1}
            row.update(zip(self.names, map(float, self.points[i])))
            row.update(zip(self.metrics, map(float, self.values[i])))
            row["feasible"] = bool(self.feasible[i])
            row["reason"] = self.reason[i]
            out.append(row)
        return out

    def column(self, name):
        """A parameter's or metric's column as an array."""
        if name in self.names:
            return self.points[:, self.names.index(name)]
        return self.values[:, self.metrics.index(name)]

    def to_csv(self, path):
        """Writes the table in the layout of `nocdyn design`'s designs.csv (numbers in their
        shortest round-trip form, empty for NaN), through a temporary file renamed into place."""
        def number(v):
            return "" if math.isnan(v) else repr(float(v))

        def field(text):
            if any(c in text for c in ',"\r\n'):
                return '"' + text.replace('"', '""').replace("\r", " ").replace("\n", " ") + '"'
            return text
        lines = [",".join(_nocdyn._column_names("design", parameters=self.names, metrics=self.metrics))]
        for i in range(len(self)):
            lines.append(",".join([str(i + 1), *(number(v) for v in self.points[i]),
                                   *(number(v) for v in self.values[i]),
                                   "true" if self.feasible[i] else "false", field(self.reason[i])]))
        path = pathlib.Path(path)
        tmp = path.with_name(f".{path.name}.tmp{os.getpid()}")
        tmp.write_text("\n".join(lines) + "\n", encoding="utf-8")
        os.replace(tmp, path)

    def __repr__(self):
        return f"<nocdyn.designs.Designs {len(self)} designs, {int(self.feasible.sum())} feasible>"


def sample(family, samples, method="sobol", seed=0):
    """Points of a sweep, shape (N, d): 'sobol' (scrambled, N rounded up to a power of 2) and
    'lhs' from scipy.stats.qmc, 'random' uniform, 'grid' round(N^(1/d)) values per parameter
    (ends included, the last varying fastest); all seeded."""
    if method not in _METHODS:
        raise Error(f"method: {method!r} is not one of {', '.join(_METHODS)}")
    samples = int(samples)
    if not 1 <= samples <= _MAX_DESIGNS:
        raise Error(f"samples: {samples} is not in [1, {_MAX_DESIGNS}]")
    d = len(family.vary)
    lo = np.array([v[1] for v in family.vary])
    hi = np.array([v[2] for v in family.vary])
    if method == "grid":
        n = max(2, round(samples ** (1.0 / d)))
        if n ** d > _MAX_DESIGNS:
            raise Error(f"samples: a grid of {n} values per parameter holds more than {_MAX_DESIGNS} designs")
        axes = [np.linspace(a, b, n) for a, b in zip(lo, hi)]
        return np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, d)
    if method == "random":
        unit = np.random.default_rng(seed).random((samples, d))
    else:
        from scipy.stats import qmc
        if method == "sobol":
            engine = qmc.Sobol(d, scramble=True, seed=seed)
            unit = engine.random_base2(max(0, math.ceil(math.log2(samples))))
        else:
            unit = qmc.LatinHypercube(d, seed=seed).random(samples)
    return qmc_scale(unit, lo, hi)


def qmc_scale(unit, lo, hi):
    """Points in [0, 1)^d scaled to the box [lo, hi]."""
    return lo + unit * (hi - lo)


def _finite(name, value, lower=None, upper=None, positive=False):
    """float(value), or ValueError naming the argument: NaN, inf, out of [lower, upper] or (with
    positive) not above zero are refused."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name}: expected a number, got {value!r}") from None
    if not math.isfinite(x):
        raise ValueError(f"{name}: expected a finite number, got {value!r}")
    if positive and not x > 0.0:
        raise ValueError(f"{name}: expected a number above 0, got {value!r}")
    if (lower is not None and x < lower) or (upper is not None and x > upper):
        raise ValueError(f"{name}: expected a number in [{lower}, {upper}], got {value!r}")
    return x


# the defaults and ranges of `nocdyn design` (app::DesignOptions, app/design.hpp, app/options.hpp):
# one definition, in C++
_DEFAULTS = _nocdyn.DesignOptions()
_RANGES = _nocdyn._ranges()


def _options(theta=None, resolution=_DEFAULTS.resolution, trajectory=None, duration=None, rate=_DEFAULTS.rate):
    if theta is not None:
        theta = _finite("theta", theta, *_RANGES["design_theta"][:2])
    low, high = (int(v) for v in _RANGES["design_resolution"][:2])
    if isinstance(resolution, bool) or int(resolution) != resolution or not low <= int(resolution) <= high:
        raise ValueError(f"resolution: expected a whole number of grid points from {low} to {high}, got {resolution!r}")
    rate = _finite("rate", rate, *_RANGES["rate"][:2])
    if duration is not None:
        duration = _finite("duration", duration, *_RANGES["duration"][:2])
    traj = None
    if trajectory is not None:
        from . import Trajectory
        if isinstance(trajectory, (str, os.PathLike)):
            trajectory = Trajectory.load(trajectory)
        traj = trajectory._core
        if duration is None:
            duration = trajectory.duration if trajectory.duration is not None else 0.2
    return dict(theta=theta, resolution=int(resolution), trajectory=traj,
                duration=0.2 if duration is None else float(duration), rate=rate)


def _metric_names(metrics):
    """The metrics' names as the library spells them; ValueError for none (a table needs one)."""
    if isinstance(metrics, str):
        metrics = [metrics]
    metrics = list(metrics)
    if not metrics:
        raise ValueError("metrics: name at least one metric (e.g. 'workspace_area')")
    return [name for name, _, _ in _nocdyn._design_metric_names(metrics)]


def _require_main_guard():
    """Raises RuntimeError when a LocalCluster would start from a script's top level without the
    ``if __name__ == "__main__":`` guard: its worker processes import the script again (the
    'spawn' start method), and each would start the sweep, and a cluster, once more."""
    import multiprocessing
    import sys
    fix = ('designs.sweep starts worker processes, which import the main script again: put the call under '
           '`if __name__ == "__main__":` (or give client=)')
    main = sys.modules.get("__main__")
    if getattr(main, "__name__", "") == "__mp_main__" or multiprocessing.parent_process() is not None:
        raise RuntimeError(fix + "; this is a worker process running the script's top level")
    path = getattr(main, "__file__", None)
    if not path or not os.path.isfile(path):
        return  # an interactive session or notebook: nothing is imported again
    frame, line = sys._getframe(1), None
    while frame is not None:
        if frame.f_globals is getattr(main, "__dict__", None) and frame.f_code.co_name == "<module>":
            line = frame.f_lineno
        frame = frame.f_back
    if line is None:
        return  # not called from the script's top level (a function run elsewhere)
    import ast
    try:
        tree = ast.parse(pathlib.Path(path).read_text(encoding="utf-8"))
    except (OSError, SyntaxError, UnicodeDecodeError):
        return
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and _is_main_test(node.test):
            end = getattr(node, "end_lineno", None) or node.lineno
            if node.lineno <= line <= end:
                return
    raise RuntimeError(fix + f" ({path}, line {line})")


def _is_main_test(test):
    """Whether an if's test is __name__ == "__main__" (either way round)."""
    import ast
    if not (isinstance(test, ast.Compare) and len(test.ops) == 1 and isinstance(test.ops[0], ast.Eq)):
        return False
    sides = [test.left, test.comparators[0]]
    names = [s for s in sides if isinstance(s, ast.Name) and s.id == "__name__"]
    values = [s for s in sides if isinstance(s, ast.Constant) and s.value == "__main__"]
    return len(names) == 1 and len(values) == 1


def _evaluate_chunk(family_key, points, metrics, options, threads=1):
    """Evaluates a chunk of designs (a Dask task: plain arguments, picklable)."""
    text, source, fixed, names = family_key
    values, feasible, reason = _nocdyn._evaluate_designs(text, source, fixed, names, np.asarray(points, dtype=float),
                                                         list(metrics), options["theta"], options["resolution"],
                                                         options["trajectory"], options["duration"],
                                                         options["rate"], int(threads))
    return values, feasible, reason


def evaluate(family, points, metrics, *, threads=None, **options):
    """Evaluates designs (points (N, d)) on this machine's threads (default: every core),
    returning a Designs table. options: theta (workspace orientation [rad], default each
    design's home), resolution (workspace grid, 201), trajectory (nocdyn.Trajectory or a file
    name), duration [s], rate [Hz] for the force metrics."""
    metrics = _metric_names(metrics)
    points = np.asarray(points, dtype=float)
    if points.size == 0:
        raise ValueError("points: no design to evaluate (an empty array)")
    d = len(family.vary)
    if points.ndim > 2 or points.size % d != 0 or (points.ndim == 2 and points.shape[1] != d):
        raise ValueError(f"points: expected shape (N, {d}) (one value per varied parameter: "
                         f"{', '.join(family.names)}), got {points.shape}")
    points = points.reshape(-1, d)
    threads = (os.cpu_count() or 1) if threads is None else int(threads)
    values, feasible, reason = _evaluate_chunk(family._key(), points, metrics, _options(**options), threads)
    return Designs(family.names, metrics, points, values, feasible, reason)


def sweep(family, metrics, samples=64, method="sobol", seed=0, *, client=None, chunk=8, workers=None, **options):
    """A sweep of `samples` designs (see sample()) evaluated on a Dask cluster: chunks of
    `chunk` designs are submitted to `client` (a dask.distributed.Client, e.g.
    Client("tcp://scheduler:8786")); with client=None a LocalCluster of `workers` worker
    processes (default: every core), one thread each, is started and closed. The result is
    one Designs table in the sweep's order, equal row for row to evaluate() on the same points."""
    if client is None:
        _require_main_guard()
    from dask.distributed import Client, LocalCluster, as_completed
    metrics = _metric_names(metrics)
    points = sample(family, samples, method, seed)
    chunk = max(1, int(chunk))
    opts = _options(**options)
    own = None
    if client is None:
        n = workers or os.cpu_count() or 1
        cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None)
        own = (cluster, Client(cluster))
        client = own[1]
    try:
        key = family._key()
        futures = {}
        for start in range(0, len(points), chunk):
            future = client.submit(_evaluate_chunk, key, points[start:start + chunk], metrics, opts, 1, pure=False)
            futures[future] = start
        values = np.full((len(points), len(metrics)), np.nan)
        feasible = np.zeros(len(points), dtype=bool)
        reason = [""] * len(points)
        for future in as_completed(futures):
            start = futures[future]
            v, f, r = future.result()
            values[start:start + len(f)] = v
            feasible[start:start + len(f)] = f
            reason[start:start + len(f)] = r
    finally:
        if own is not None:
            own[1].close()
            own[0].close()
    return Designs(family.names, metrics, points, values, feasible, reason)


def pareto_front(table, senses=None):
    """Indices of the feasible designs no other feasible design dominates; senses: {metric:
    'maximize' | 'minimize'} for metrics of the table (default: workspace, first frequency and
    envelope maximised, the rest minimised); ValueError for any other key or value. The library's
    front (nocdyn::paretoFront), the one `nocdyn design` writes to pareto.csv: O(n log n) for one
    or two metrics (a sort and one pass), O(n |front|) for more."""
    larger = {name: better for name, _, better in _nocdyn._design_metric_names(table.metrics)}
    senses = dict(senses or {})
    for metric, sense in senses.items():
        if metric not in larger:
            raise ValueError(f"senses: {metric!r} is not a metric of the table ({', '.join(table.metrics)})")
        if sense not in ("maximize", "minimize"):
            raise ValueError(f"senses: {metric}: expected 'maximize' or 'minimize', got {sense!r}")
    larger_is_better = [senses.get(m, "maximize" if larger[m] else "minimize") == "maximize" for m in table.metrics]
    front = _nocdyn._pareto_front(table.values, table.feasible, larger_is_better)
    return [int(i) for i in front]


def optimize(family, objectives, n_trials=100, seed=0, *, constraints=None, sampler=None, storage=None,
             study_name=None, **options):
    """Optimises the family's varied parameters with Optuna: objectives {metric: 'maximize' |
    'minimize'}; TPE for one objective, NSGA-II for several (or sampler='tpe' / 'nsga2'),
    seeded. constraints {metric: (lower, upper)} (None for an open side) are Optuna
    constraints (a violating design is not on the front); an infeasible design counts as the
    worst value. storage (an Optuna RDB URL) shares one study between processes on several
    machines, as Optuna's distributed optimisation does. Returns (study, Designs of every trial
    in order)."""
    import optuna
    optuna.logging.set_verbosity(optuna.logging.WARNING)
    warnings.filterwarnings("ignore", category=optuna.exceptions.ExperimentalWarning)
    metrics = list(objectives)
    directions = [objectives[m] for m in metrics]
    cons = dict(constraints or {})
    all_metrics = metrics + [m for m in cons if m not in metrics]
    opts = _options(**options)
    key = family._key()
    if sampler is None:
        sampler = "tpe" if len(metrics) == 1 else "nsga2"
    constraints_func = None
    if cons:
        def constraints_func(trial):
            return trial.user_attrs["constraints"]
    if sampler == "tpe":
        chosen = optuna.samplers.TPESampler(seed=seed, constraints_func=constraints_func)
    elif sampler == "nsga2":
        chosen = optuna.samplers.NSGAIISampler(seed=seed, constraints_func=constraints_func)
    else:
        raise Error(f"sampler: {sampler!r} is not 'tpe' or 'nsga2'")
    study = optuna.create_study(directions=directions, sampler=chosen, storage=storage, study_name=study_name,
                                load_if_exists=storage is not None)
    rows = []

    def objective(trial):
        point = [trial.suggest_float(name, lo, hi) for name, lo, hi in family.vary]
        values, feasible, reason = _evaluate_chunk(key, np.array([point]), all_metrics, opts, 1)
        v = values[0]
        rows.append((point, v, bool(feasible[0]), reason[0]))
        violation = []
        for m, (lo, hi) in cons.items():
            x = v[all_metrics.index(m)]
            if not feasible[0]:
                violation.append(1.0)
            else:
                violation.append(max((lo - x) if lo is not None else -math.inf,
                                     (x - hi) if hi is not None else -math.inf))
        trial.set_user_attr("constraints", violation)
        out = []
        for m, d in zip(metrics, directions):
            x = v[all_metrics.index(m)]
            out.append(x if feasible[0] else (-1e300 if d == "maximize" else 1e300))
        return out if len(out) > 1 else out[0]

    study.optimize(objective, n_trials=int(n_trials))
    table = Designs(family.names, all_metrics, [r[0] for r in rows], [r[1] for r in rows], [r[2] for r in rows],
                    [r[3] for r in rows])
    return study, table
