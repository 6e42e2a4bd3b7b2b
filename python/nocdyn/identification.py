"""A payload identified from a log (``nocdyn identify``) as numbers, and the prior files that bound
it: the typed result of the identification job, read without PyYAML."""

from __future__ import annotations

from . import _nocdyn
from ._guards import _floats, _input

__all__ = ["PayloadEstimate", "load_prior"]

#: The payload parameters a prior bounds, in the order of the compiled part's bounds.
PRIOR_KEYS = ("mass", "com_x", "com_y", "inertia")


def load_prior(path):
    """Reads a prior file (the YAML of `nocdyn identify --prior`): a dict of the bounds it gives,
    e.g. {"mass": (0.4, 0.6), "inertia": (0.0, None)} (None for an open side), ready for
    nocdyn.identify(prior=...). Errors name the file, line and field."""
    return _nocdyn._load_prior(str(path))


class PayloadEstimate:
    """A payload identified by nocdyn.identify (its ``payload_estimate``) as numbers.

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
    effective_samples, t (M,), measured and predicted (M, n) forces). A two-DOF robot's payload
    is a point mass at the tool point: mass only, com [0, 0] and inertia 0 (with standard
    deviations 0) are not identified, and covariance is (1 + f, 1 + f) of [mass, friction...].
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


def log_columns(robot, t, u, tau, du=None, ddu=None):
    """The log of arrays t (N,), u, tau, du, ddu (N, n) as the columns nocdyn.identify reads (t,
    u1..un, tau1..taun, du1..dun, ddu1..ddun), every value finite (an error names the array and
    the element)."""
    t = _input(_floats(t, "t").reshape(-1), "t", (None,))
    n, m = t.shape[0], robot.actuators
    columns = {"t": t}
    for name, values in (("u", u), ("tau", tau), ("du", du), ("ddu", ddu)):
        if values is not None:
            values = _input(values, name, (n, m))
            columns.update({f"{name}{a + 1}": values[:, a] for a in range(m)})
    return columns
