"""The answers of nocdyn's command functions: NumPy arrays in one small type per kind of answer.

Table: samples or grid points in named columns (the command line's CSV columns), e.g. the
inverse dynamics of a trajectory, a simulated or closed-loop motion, the operating envelope.
Every result has ``to_pandas()`` (pandas is optional: imported only there) giving the very
columns the command line writes, and ``text``: what the command printed (its summary).
"""

from __future__ import annotations

import json
import math
import pathlib

import numpy as np

__all__ = ["Table", "PoseReport", "AssemblyModes", "Workspace", "Envelope", "Identification", "Excitation",
           "ShakeResult", "Animation", "Report"]


def _pandas():
    try:
        import pandas
    except ImportError as error:  # pandas is optional
        raise ImportError("to_pandas() needs pandas (Debian: apt install python3-pandas)") from error
    return pandas


def read_csv(path):
    """The command line's CSV (one header line, numbers in shortest round-trip form) as
    (columns, (N, len(columns)) float64 array, labels): the numbers read back bit for bit. A
    column holding categories as words (envelope's axis and limit, the workspace's cell) is NaN
    in the array and its words are labels[column], an array of str."""
    with open(path, encoding="utf-8") as file:
        header = file.readline().strip()
        columns = header.split(",") if header else []
        rows = [line.rstrip("\r\n").split(",") for line in file if line.strip()]
    if not rows:
        return columns, np.empty((0, len(columns))), {}
    words = set()
    for row in rows:
        for k, v in enumerate(row):
            if k not in words:
                try:
                    float(v)
                except ValueError:
                    words.add(k)
    data = np.array([[math.nan if k in words else float(v) for k, v in enumerate(row)] for row in rows],
                    dtype=np.float64)
    labels = {columns[k]: np.array([row[k] for row in rows], dtype=str) for k in sorted(words)}
    return columns, data.reshape(len(rows), len(columns)), labels


class Table:
    """Samples in named columns, as the command line's CSV.

    ``table["tau1"]`` is one column (a NumPy array); ``table.columns`` their names in the CSV's
    order; ``table.data`` all of them as an (N, len(columns)) array; ``len(table)`` the number of
    rows; ``table.to_pandas()`` a pandas DataFrame with the same columns. ``text`` is what the
    command printed (summary lines, warnings are issued as Python warnings). A column of
    categories (``axis``, ``limit``, ``cell``) holds words, as in the CSV: ``table["axis"]`` is
    an array of str, and the same column of ``data`` is NaN. A column of numbers (``limb``,
    ``joint``, ``actuator``, numbered from 1) is an array of int, in ``data`` as floats."""

    def __init__(self, columns, data, text="", name="table", labels=None, integers=()):
        self.columns = list(columns)
        self.data = np.asarray(data, dtype=np.float64).reshape(-1, len(self.columns))
        self.text = text
        self.name = name
        self.labels = dict(labels or {})
        self.integers = tuple(c for c in integers if c in self.columns)

    @classmethod
    def from_csv(cls, path, text="", name="table"):
        columns, data, labels = read_csv(path)
        return cls(columns, data, text, name, labels)

    def __getitem__(self, column):
        if column in self.labels:
            return self.labels[column]
        try:
            values = self.data[:, self.columns.index(column)]
        except ValueError:
            raise KeyError(f"{column!r}: no such column (columns: {', '.join(self.columns)})") from None
        return values.astype(np.int64) if column in self.integers else values

    def __contains__(self, column):
        return column in self.columns

    def __len__(self):
        return self.data.shape[0]

    def group(self, prefix):
        """The columns prefix1, prefix2, ... (e.g. 'tau') side by side: an (N, k) array."""
        names = [c for c in self.columns if c.startswith(prefix) and c[len(prefix):].isdigit()]
        names.sort(key=lambda c: int(c[len(prefix):]))
        return np.stack([self[c] for c in names], axis=1) if names else np.empty((len(self), 0))

    def to_pandas(self):
        """A pandas DataFrame with the command line's CSV columns."""
        frame = _pandas().DataFrame(self.data.copy(), columns=self.columns)
        for column, words in self.labels.items():
            frame[column] = words
        for column in self.integers:
            frame[column] = self[column]
        return frame

    def __repr__(self):
        return f"<nocdyn.Table {self.name}: {len(self)} rows x {len(self.columns)} columns {self.columns[:8]}...>"


class _Record:
    """A JSON answer with attribute access; arrays as NumPy arrays."""

    def __init__(self, fields, text=""):
        self._fields = dict(fields)
        self.text = text

    def __getattr__(self, name):
        try:
            return self.__dict__["_fields"][name]
        except KeyError:
            raise AttributeError(name) from None

    def as_dict(self):
        return dict(self._fields)


class PoseReport(_Record):
    """Everything the model knows at one pose (``nocdyn pose``): pose [x, y, theta]; q (limbs, 3)
    joint variables [rad or m]; cond_J (limbs,) the limb Jacobians' condition numbers; u (n,)
    actuator variables and range_used (n,) the fraction of their range; A (n, 3) the actuation map
    du = A dp/dt (columns x, y, theta); cond_A; I the inertia (eq. 23) in ``coordinates``
    ('actuators', or 'platform': rows and columns x, y, theta); within_limits; at rest under
    gravity, tau (n,) the actuator forces and reactions (limbs, 3, 3) every joint's reaction
    [fx, fy, m] (as Robot.reactions); for a robot whose file declares compliance, stiffness (3, 3),
    natural_frequencies (3,) [Hz] (lumped model), mode_shapes (3, 3) (columns; rows x, y, theta),
    first_frequency [Hz] and first_frequency_model ('lumped', or 'elastodynamic' where the lumped
    model does not hold: more than 5 % from it) and, with elastic links, elastodynamic_frequencies.
    Limbs, joints and actuators are numbered from 1."""

    def __init__(self, fields, text=""):
        fields = dict(fields)
        self.actuator_table = fields.pop("actuators")
        super().__init__(fields, text)

    def to_pandas(self):
        """Per actuator: actuator, limb, joint, u, range_used."""
        return _pandas().DataFrame(self.actuator_table)

    def __repr__(self):
        return f"<nocdyn.PoseReport {self.robot!r} at {self.pose.tolist()}: cond_A {self.cond_A:.4g}>"


class SpatialPoseReport(_Record):
    """Everything the model knows at one pose of a spatial robot (``nocdyn pose X Y Z [ROLL PITCH
    YAW]``): pose (d,) in the order of ``coordinates``; limbs, a list of dicts (limb, name, type,
    q every freedom's variable base to platform [rad or m], joints the listed joint of each
    freedom, cond_J); u (n,) the actuator variables and range_used (n,); A (n, d) the actuation
    map du = A [v; w] (v the platform point's velocity, w the angular velocity); cond_A,
    max_condition; within_limits and limits (the first range passed); at rest under gravity, tau
    (n,) the actuator forces and reactions, a list of dicts (limb, joint, type R/P/U/S, point,
    force [N], moment [N m] about point: the inboard body on the outboard one, base frame, its
    efforts taken out), with balance_residual, how well the platform balances. Limbs, joints and
    actuators are numbered from 1."""

    def __init__(self, fields, text=""):
        fields = dict(fields)
        self.actuator_table = fields.pop("actuators")
        fields["pose"] = np.asarray(fields["pose"], dtype=np.float64)
        fields["u"] = np.array([a["u"] for a in self.actuator_table], dtype=np.float64)
        fields["range_used"] = np.array([a["range_used"] for a in self.actuator_table], dtype=np.float64)
        super().__init__(fields, text)

    def to_pandas(self):
        """Per actuator: actuator, limb, joint, u, range_used."""
        return _pandas().DataFrame(self.actuator_table)

    def __repr__(self):
        return f"<nocdyn.SpatialPoseReport {self.robot!r} at {self.pose.tolist()}: cond_A {self.cond_A:.4g}>"


class AssemblyModes(_Record):
    """The assembly modes of actuator values u (``nocdyn forward-kinematics``): poses (k, 3)
    [x, y, theta] sorted by theta ((k, 2) [x, y] for a two-DOF robot), their branches (k, limbs), working (k,) booleans, and the
    JSON's other fields (degenerate, within_limits, solutions_all_branches, ...)."""

    def __init__(self, document, text=""):
        solutions = document.get("solutions", [])
        fields = dict(document)
        fields["solutions"] = solutions
        axes = ("x", "y", "theta") if not solutions or "theta" in solutions[0]["pose"] else ("x", "y")
        fields["poses"] = np.array([[s["pose"][k] for k in axes] for s in solutions],
                                   dtype=np.float64).reshape(-1, len(axes))
        if solutions and "branch" in solutions[0]:
            fields["branches"] = np.array([s["branch"] for s in solutions], dtype=np.int64)
        fields["working"] = np.array([bool(s.get("working", True)) for s in solutions])
        super().__init__(fields, text)

    def __len__(self):
        return len(self.solutions)

    def to_pandas(self):
        """One row per assembly mode: the fields of each solution, then its pose x, y, theta (the
        order of every table nocdyn writes)."""
        rows = []
        for s in self.solutions:
            row = {k: v for k, v in s.items() if k != "pose"}
            row.update({k: s["pose"][k] for k in ("x", "y", "theta")})
            rows.append(row)
        return _pandas().DataFrame(rows)

    def __repr__(self):
        return f"<nocdyn.AssemblyModes: {len(self)} poses>"


class Workspace(Table):
    """The workspace grid (``nocdyn workspace``): columns x, y [m] and cell (feasible,
    unreachable: out of reach, range: a joint out of its range, singular); ``cells`` as an (n, n)
    array of codes (0 feasible, 1 unreachable, 2 range, 3 singular) indexed [ix, iy]; ``text``
    the summary line with the area."""

    CELLS = ("feasible", "unreachable", "range", "singular")
    # with first_frequency=True: f_1 [Hz] per grid point, (n, n) indexed [ix, iy], NaN where not
    # feasible; its lowest [Hz] and where (x, y, theta); the highest; the feasible points as a Table
    first_frequency = None
    first_frequency_min = None
    first_frequency_at = None
    first_frequency_max = None
    frequency_table = None

    @property
    def cells(self):
        n = int(round(np.sqrt(len(self))))
        codes = np.array([self.CELLS.index(w) for w in self["cell"]], dtype=np.int64)
        return codes.reshape(n, n)

    @property
    def area(self):
        """Feasible area [m^2] from the grid (cells times the cell area)."""
        x = np.unique(self["x"])
        y = np.unique(self["y"])
        step = (x[1] - x[0]) * (y[1] - y[0]) if len(x) > 1 and len(y) > 1 else 0.0
        return float(np.count_nonzero(self["cell"] == "feasible") * step)


class Envelope(Table):
    """The operating envelope (``nocdyn envelope``): one row per axis (x, y, theta) and frequency,
    the CSV's columns. ``first_natural_frequency``: the band's third bound [Hz], the first
    natural frequency of the lumped model at home, when the robot file declares compliance
    (rows at or above it have the limit 'resonance'), else None; ``band_end`` {"x": f, "y": f,
    "theta": f} [Hz], per axis the lowest frequency where the damped lumped model's dynamic
    amplification leaves [1/A, A] (inf when it never does; None when unknown, and
    ``resonance_reason`` says why); ``text`` the summary line that names it or says why it is
    unknown."""

    def __init__(self, columns, data, text="", name="envelope", labels=None, integers=(),
                 first_natural_frequency=None, band_end=None, resonance_reason=""):
        super().__init__(columns, data, text, name, labels, integers)
        self.first_natural_frequency = first_natural_frequency
        self.band_end = band_end
        self.resonance_reason = resonance_reason


class Identification:
    """An identification (``nocdyn identify``), its numbers typed (no YAML parsed back):

    ``payload`` {mass [kg], com [x, y] [m], inertia [kg m^2]} when a payload was identified (else
    None), ``payload_estimate`` the same with its standard deviations, covariance, active bounds,
    friction and fit (a nocdyn.PayloadEstimate); ``base`` with base: {base_parameters: [{name,
    value, stddev, robot_file, unit}], covariance, fit}; ``text`` the report the command prints
    (YAML), ``robot_yaml`` the file the command writes (the robot with the payload merged, or the
    calibration with base). ``report`` is ``text`` read as a dict, only when PyYAML is installed
    (Debian's python3-yaml; else None): every number is in ``payload_estimate`` and ``base``
    without it."""

    def __init__(self, text, robot_yaml, payload=None, base=None, log=""):
        from .identification import PayloadEstimate
        self.text = text
        self.log = log
        self.robot_yaml = robot_yaml
        self.payload_estimate = None if payload is None else PayloadEstimate(payload)
        self.payload = None if payload is None else {
            "mass": float(payload["mass"]), "com": [float(v) for v in payload["com"]],
            "inertia": float(payload["inertia"])}
        self.base = base

    @property
    def report(self):
        """The printed report read as a dict (needs PyYAML; None without it)."""
        try:
            import yaml
            report = yaml.safe_load(self.text)
        except Exception:  # PyYAML missing, or a report that is not a YAML mapping
            return None
        return report if isinstance(report, dict) else None

    def to_pandas(self):
        """The estimates: parameter, value, standard deviation (payload and friction, or the base
        parameters)."""
        rows = []
        e = self.payload_estimate
        if e is not None:
            rows += [{"parameter": "mass", "value": e.mass, "stddev": e.mass_sd},
                     {"parameter": "com_x", "value": e.com[0], "stddev": e.com_sd[0]},
                     {"parameter": "com_y", "value": e.com[1], "stddev": e.com_sd[1]},
                     {"parameter": "inertia", "value": e.inertia, "stddev": e.inertia_sd}]
            rows += [{"parameter": f["name"], "value": f["value"], "stddev": f["stddev"]} for f in e.friction]
        if self.base is not None:
            rows += [{"parameter": b["name"], "value": b["value"], "stddev": b["stddev"]}
                     for b in self.base["base_parameters"]]
        return _pandas().DataFrame(rows)

    def __repr__(self):
        return f"<nocdyn.Identification payload={self.payload}>"


class Excitation(_Record):
    """A designed excitation (``nocdyn excite``): ``yaml`` the trajectory file's text,
    ``trajectory`` it as a nocdyn.Trajectory, ``path`` where it was written, ``text`` the
    printed comparison with the paper's trajectories."""

    def to_pandas(self):
        """The trajectory's harmonics per axis: axis, frequency, amplitude, phase."""
        rows = []
        for axis in ("theta", "x", "y"):
            for f, a, phase in self.trajectory.harmonics(axis):
                rows.append({"axis": axis, "frequency": f, "amplitude": a, "phase": phase})
        return _pandas().DataFrame(rows)


class ShakeResult(Table):
    """An earthquake replay (``nocdyn shake``): the samples of DIR/shake.csv as a Table, plus
    ``metrics`` (DIR/shake.json: time_scale, amplitude_scale, RMS and peak errors, spectra),
    ``folder`` the output folder (None when it was temporary)."""

    def __init__(self, columns, data, metrics, folder, text=""):
        super().__init__(columns, data, text, "shake")
        self.metrics = metrics
        self.folder = folder


class Animation:
    """The robot in motion as one self-contained HTML page (``nocdyn animate``); shows inline in
    Jupyter (``_repr_html_``); ``save(path)`` writes it, ``html`` is its text."""

    def __init__(self, html, path=None, text=""):
        self.html = html
        self.path = path
        self.text = text

    def save(self, path):
        pathlib.Path(path).write_text(self.html, encoding="utf-8")
        return path

    def _repr_html_(self):
        # in an iframe: the page's script and styles stay apart from the notebook's
        escaped = self.html.replace("&", "&amp;").replace('"', "&quot;")
        return f'<iframe srcdoc="{escaped}" style="width:100%;height:620px;border:0"></iframe>'

    def __repr__(self):
        return f"<nocdyn.Animation: {len(self.html)} characters of HTML>"


class Report:
    """A folder of results (``nocdyn reproduce``): ``folder``, ``summary`` (summary.md's text,
    shown as Markdown in Jupyter), ``files`` (the paths written) and ``table(name)`` to read
    one of its CSV files."""

    def __init__(self, folder, text=""):
        self.folder = pathlib.Path(folder)
        summary = self.folder / "summary.md"
        self.summary = summary.read_text(encoding="utf-8") if summary.exists() else ""
        self.text = text

    @property
    def files(self):
        return sorted(p for p in self.folder.rglob("*") if p.is_file())

    def table(self, name):
        return Table.from_csv(self.folder / name, name=name)

    def to_pandas(self):
        """The files written: path, size in bytes."""
        return _pandas().DataFrame([{"path": str(p), "bytes": p.stat().st_size} for p in self.files])

    def _repr_markdown_(self):
        return self.summary

    def __repr__(self):
        return f"<nocdyn.Report {str(self.folder)!r}: {len(self.files)} files>"


def load_json(path):
    with open(path, encoding="utf-8") as file:
        return json.load(file)
