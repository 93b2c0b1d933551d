"""Value grids and sampling distributions written as short strings (CLI and scenario sweeps).

* ``"start:stop:n"`` -> n values evenly spaced from start to stop (both included),
  ``"start:stop:n:log"`` -> geometrically spaced (start, stop > 0); ``"a,b,c"`` -> the list;
  ``"a"`` -> one value (:func:`parse_grid`).
* ``"normal:mean,sd"``, ``"lognormal:median,beta"`` (beta the standard deviation of ln x),
  ``"uniform:lo,hi"``, ``"loguniform:lo,hi"``, ``"triangular:lo,mode,hi"``
  (:func:`parse_distribution` -> :class:`Distribution`, sampled by :meth:`Distribution.sample`
  with a numpy ``Generator``).

Every malformed string raises :class:`~blastscale._validate.BlastscaleInputError` with one line
naming the field, the text and what is valid.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validate import BlastscaleInputError

#: Most values of one grid axis (a larger one would not fit in memory before any other check).
MAX_GRID = 10_000_000

__all__ = [
    "MAX_GRID",
    "parse_grid",
    "parse_number",
    "parse_assignment",
    "Distribution",
    "parse_distribution",
    "DISTRIBUTIONS",
]


def parse_number(text: str, name: str, what: str = "value") -> float:
    """``text`` as a finite float (one-line error naming ``name`` and ``what`` otherwise)."""
    try:
        x = float(text)
    except ValueError:
        raise BlastscaleInputError(f"{name} = {text!r}: {what} is not a number") from None
    if not math.isfinite(x):
        raise BlastscaleInputError(f"{name} = {text!r}: {what} must be finite")
    return x


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def parse_grid(text: str, name: str = "grid", numeric: bool = True) -> np.ndarray:
    """Values of a grid string (module docstring) as a float array.

    Parameters
    ----------
    text : str
        ``"start:stop:n[:log]"``, ``"a,b,c"`` or ``"a"`` (in the field's own unit).
    name : str
        Field name for the error messages.
    numeric : bool
        With False, a list ``"a,b,c"`` whose items are not all numbers is returned as strings
        (e.g. ``pulse=friedlander,triangular``; the scenario then validates them).

    Raises
    ------
    BlastscaleInputError
        Not numbers, n not a whole number >= 1, an empty range (stop <= start with n > 1), a
        log range not > 0, a list with repeated values.
    """
    t = str(text).strip()
    if not t:
        raise BlastscaleInputError(f"{name} = {text!r} is empty: give start:stop:n[:log] or a,b,c")
    if ":" in t:
        parts = t.split(":")
        if len(parts) not in (3, 4) or (len(parts) == 4 and parts[3] not in ("log", "lin")):
            raise BlastscaleInputError(f"{name} = {text!r} is not a grid: valid forms are start:stop:n[:log] or a,b,c")
        a, b = parse_number(parts[0], name, "start"), parse_number(parts[1], name, "stop")
        try:
            n = int(parts[2])
        except ValueError:
            raise BlastscaleInputError(f"{name} = {text!r}: n = {parts[2]!r} is not a whole number >= 1") from None
        if not 1 <= n <= MAX_GRID:
            raise BlastscaleInputError(
                f"{name} = {text!r}: n = {n} is out of range: valid range is [1, {MAX_GRID:.0e}]"
            )
        if n > 1 and not b > a:
            raise BlastscaleInputError(f"{name} = {text!r} is an empty range: stop ({b:g}) must exceed start ({a:g})")
        log = len(parts) == 4 and parts[3] == "log"
        if log and not a > 0:
            raise BlastscaleInputError(f"{name} = {text!r}: a log grid needs start > 0, got {a:g}")
        if n == 1:
            return np.array([a])
        return np.geomspace(a, b, n) if log else np.linspace(a, b, n)
    items = [x.strip() for x in t.split(",") if x.strip()]
    if not numeric and items and not all(_is_number(x) for x in items):
        if len(set(items)) != len(items):
            raise BlastscaleInputError(f"{name} = {text!r} repeats a value: each grid value must be distinct")
        return np.array(items)
    vals = np.array([parse_number(x, name, "value") for x in items] or [], dtype=float)
    if vals.size == 0:
        raise BlastscaleInputError(f"{name} = {text!r} is empty: give start:stop:n[:log] or a,b,c")
    if np.unique(vals).size != vals.size:
        raise BlastscaleInputError(f"{name} = {text!r} repeats a value: each grid value must be distinct")
    return vals


def parse_assignment(text: str, option: str) -> tuple[str, str]:
    """Split ``"FIELD=SPEC"`` into ``(FIELD, SPEC)`` (one-line error naming ``option`` otherwise)."""
    field, sep, spec = str(text).partition("=")
    if not sep or not field.strip() or not spec.strip():
        raise BlastscaleInputError(f"{option} = {text!r} is not FIELD=SPEC (e.g. charge_kg=10:100:5)")
    return field.strip(), spec.strip()


#: Distribution name -> its parameter names (the samplers: Distribution.sample)
DISTRIBUTIONS = {
    "normal": ("mean", "sd"),
    "lognormal": ("median", "beta"),
    "uniform": ("lo", "hi"),
    "loguniform": ("lo", "hi"),
    "triangular": ("lo", "mode", "hi"),
}


@dataclass(frozen=True)
class Distribution:
    """A named one-dimensional distribution with its parameters (in the field's unit).

    ``normal(mean, sd)``, ``lognormal(median, beta)`` (ln x ~ N(ln median, beta^2)),
    ``uniform(lo, hi)``, ``loguniform(lo, hi)``, ``triangular(lo, mode, hi)``.
    """

    kind: str
    params: tuple[float, ...]

    def sample(self, rng: np.random.Generator, n: int) -> np.ndarray:
        """n draws with ``rng`` (a numpy ``Generator``); one normal / uniform per draw, so a
        seed reproduces the same values whatever else is sampled after."""
        k, p = self.kind, self.params
        if k == "normal":
            return p[0] + p[1] * rng.standard_normal(n)
        if k == "lognormal":
            return p[0] * np.exp(p[1] * rng.standard_normal(n))
        u = rng.random(n)
        if k == "uniform":
            return p[0] + (p[1] - p[0]) * u
        if k == "loguniform":
            return p[0] * (p[1] / p[0]) ** u
        lo, mode, hi = p  # triangular, by inversion of its CDF
        c = (mode - lo) / (hi - lo)
        return np.where(
            u < c, lo + np.sqrt(u * (hi - lo) * (mode - lo)), hi - np.sqrt((1 - u) * (hi - lo) * (hi - mode))
        )


def parse_distribution(text: str, name: str = "distribution") -> Distribution:
    """A :class:`Distribution` from ``"kind:p1,p2[,p3]"`` (module docstring).

    Raises
    ------
    BlastscaleInputError
        Unknown kind, wrong number of parameters, sd/beta < 0, lo >= hi, a log distribution
        with lo <= 0, a lognormal median <= 0, a triangular mode outside [lo, hi].
    """
    kind, sep, rest = str(text).partition(":")
    kind = kind.strip()
    if not sep or kind not in DISTRIBUTIONS:
        raise BlastscaleInputError(
            f"{name} = {text!r} is not a distribution: valid forms are "
            + ", ".join(f"{k}:{','.join(v)}" for k, v in DISTRIBUTIONS.items())
        )
    names = DISTRIBUTIONS[kind]
    vals = [x for x in rest.split(",") if x.strip()]
    if len(vals) != len(names):
        raise BlastscaleInputError(f"{name} = {text!r}: {kind} takes {len(names)} parameters ({', '.join(names)})")
    p = tuple(parse_number(x, name, pn) for x, pn in zip(vals, names))
    if kind in ("normal", "lognormal") and p[1] < 0:
        raise BlastscaleInputError(f"{name} = {text!r}: {names[1]} = {p[1]:g} is out of range: must be >= 0")
    if kind == "lognormal" and p[0] <= 0:
        raise BlastscaleInputError(f"{name} = {text!r}: median = {p[0]:g} is out of range: must be > 0")
    if kind in ("uniform", "loguniform", "triangular") and not p[-1] > p[0]:
        raise BlastscaleInputError(f"{name} = {text!r} is an empty range: hi ({p[-1]:g}) must exceed lo ({p[0]:g})")
    if kind == "loguniform" and p[0] <= 0:
        raise BlastscaleInputError(f"{name} = {text!r}: lo = {p[0]:g} is out of range: a log distribution needs lo > 0")
    if kind == "triangular" and not p[0] <= p[1] <= p[2]:
        raise BlastscaleInputError(
            f"{name} = {text!r}: mode = {p[1]:g} is out of range: must lie in [{p[0]:g}, {p[2]:g}]"
        )
    return Distribution(kind, p)
