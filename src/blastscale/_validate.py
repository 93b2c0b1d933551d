"""Input validation shared by every subpackage.

Every error names the parameter, the offending value and the valid range, in one line,
so that the CLI can print it as is (exit code 2, no traceback).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "BlastscaleInputError",
    "OutOfRangeError",
    "check_positive",
    "check_positive_scalar",
    "check_range",
    "check_finite",
    "check_choice",
]


class BlastscaleInputError(ValueError):
    """Bad user input: the message names the parameter, its value and the valid range."""


class OutOfRangeError(BlastscaleInputError):
    """An empirical fit was asked for outside the range where it was fitted."""


def _fmt(bad: np.ndarray, whole: np.ndarray, unit: str = "") -> str:
    """The offending value with its unit: the value itself for a scalar input, else the first bad element."""
    first = float(np.asarray(bad).ravel()[0])
    u = f" {unit}" if unit else ""
    if np.ndim(whole) == 0:
        return f"{first:.6g}{u}"
    return f"{first:.6g}{u} (first offending element of an array)"


def check_finite(name: str, value, unit: str = "") -> np.ndarray:
    """Return ``value`` as a float array; raise if any element is NaN or infinite."""
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise BlastscaleInputError(f"{name} must be a number, got {value!r}") from exc
    if not np.all(np.isfinite(arr)):
        bad = arr[~np.isfinite(arr)]
        raise BlastscaleInputError(f"{name} = {_fmt(bad, arr, unit)} is not a finite number")
    return arr


def check_positive(name: str, value, unit: str = "") -> np.ndarray:
    """Return ``value`` as a float array; raise unless every element is finite and > 0."""
    arr = check_finite(name, value, unit)
    if np.any(arr <= 0.0):
        bad = arr[arr <= 0.0]
        u = f" {unit}" if unit else ""
        raise BlastscaleInputError(f"{name} = {_fmt(bad, arr, unit)} is out of range: must be > 0{u}")
    return arr


def check_range(
    name: str,
    value,
    lo: float = -math.inf,
    hi: float = math.inf,
    unit: str = "",
    *,
    lo_open: bool = False,
    hi_open: bool = False,
    error: type[BlastscaleInputError] = BlastscaleInputError,
) -> np.ndarray:
    """Return ``value`` as a float array; raise unless every element lies in the range.

    The range is ``[lo, hi]``, with either end open when ``lo_open`` / ``hi_open``.
    """
    arr = check_finite(name, value, unit)
    below = arr <= lo if lo_open else arr < lo
    above = arr >= hi if hi_open else arr > hi
    bad_mask = below | above
    if np.any(bad_mask):
        u = f" {unit}" if unit else ""
        lb = "(" if lo_open else "["
        rb = ")" if hi_open else "]"
        raise error(
            f"{name} = {_fmt(arr[bad_mask], arr, unit)} is out of range: valid range is {lb}{lo:g}, {hi:g}{rb}{u}"
        )
    return arr


def check_positive_scalar(name: str, value, unit: str = "") -> float:
    """Return ``value`` as a float; raise unless it is a single finite number > 0 (not an array)."""
    arr = check_positive(name, value, unit)
    if arr.ndim != 0:
        raise BlastscaleInputError(f"{name} has shape {arr.shape}: must be a single number (not an array)")
    return float(arr)


def check_choice(name: str, value, choices, hint: str = ""):
    """Return ``value``; raise unless it is one of ``choices`` (a sequence of names, or a mapping's keys).

    The one message of an unknown name: the parameter, the value, then every valid value in the
    order of ``choices``, and ``hint`` (e.g. where else a value may come from) in parentheses.

    Examples
    --------
    >>> check_choice("incidence model", "ufc", ("ufc", "closed-form"))
    'ufc'
    >>> check_choice("incidence model", "UFC", ("ufc", "closed-form"))
    Traceback (most recent call last):
    ...
    blastscale._validate.BlastscaleInputError: incidence model = 'UFC' is not known: valid values are ufc, closed-form
    """
    if value not in choices:
        extra = f" ({hint})" if hint else ""
        raise BlastscaleInputError(f"{name} = {value!r} is not known: valid values are {', '.join(choices)}{extra}")
    return value
