"""The one guard of every entry of nocdyn's Robot and Trajectory: numbers as the command line
checks them, arrays of any memory order read correctly (copied when the compiled part cannot view
them), outputs that overlap nothing, threads within reason, results checked finite; and the one
sentence of the vocabulary the docstrings append."""

from __future__ import annotations

import operator

import numpy as np

from ._nocdyn import Error

VOCABULARY = ("Vocabulary: a pose is [x, y, theta] (m, m, rad), its rates in the same order, as in the command "
              "line's CSV tables; SI units; limbs, joints and actuators numbered from 1; array axes from 0; the "
              "core's internal twist order [theta, x, y] stays inside the core.")


def _vocabulary(function):
    """Appends the one sentence of the vocabulary to a docstring that takes or returns a pose."""
    function.__doc__ = (function.__doc__ or "").rstrip() + "\n\n        " + VOCABULARY + "\n        "
    return function


_MAX_THREADS = 1024  # the compiled batch caps this further at the hardware and the work


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
    """Raises nocdyn.Error naming the first sample (row K - 1 is sample K) where one of the result arrays is not
    finite: finite input that overflows (huge rates or accelerations)."""
    for a in arrays:
        a = np.asarray(a)
        if a.size and not _all_finite(a):
            rows = np.argwhere(~np.isfinite(a))
            where = f"sample {int(rows[0][0]) + 1}: " if a.ndim > 1 else ""  # numbered from 1
            raise Error(f"{where}{what} is not finite (the input is too large)")

