"""Platform trajectories: harmonic (the paper's eqs. 33-34, a YAML file, harmonics given in code)
or sampled (CSV), evaluated at arrays of times in the pose order [x, y, theta]."""

from __future__ import annotations

import numpy as np

from . import _nocdyn
from ._guards import _floats, _input, _require_finite, _vocabulary
from ._nocdyn import Error

__all__ = ["Trajectory"]


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
