"""Pressure-time pulses of the positive phase of a blast wave, with t = 0 at shock arrival.

All pulses are small immutable objects with SI attributes and vectorised methods:

* ``pressure(t)`` [Pa] for t [s] (zero before 0 and after the pulse ends),
* ``cumulative_impulse(t)`` [Pa*s], the exact running integral of the pressure,
* ``peak`` [Pa], ``duration`` [s] (time at which the pressure returns to zero),
  ``impulse`` [Pa*s] (total area), and ``kind`` (a short string).

References
----------
.. [1] Friedlander, F. G. (1946). The diffraction of sound pulses I. Proc. R. Soc. A 186.
.. [2] Masi, Stefanou & Maffi-Berthier, *Scaling laws ...*, Eqs. (1)-(3) (modified Friedlander,
       its impulse, and the first-order triangular approximation).
.. [3] UFC 3-340-02 (2008), Structures to resist the effects of accidental explosions, Sec. 2-15
       (equivalent triangular pulse of equal impulse).
"""

from __future__ import annotations

import abc
import math
import warnings
from dataclasses import dataclass

import numpy as np

from .._validate import BlastscaleInputError, check_finite, check_positive

__all__ = [
    "Pulse",
    "Friedlander",
    "Triangular",
    "Impulsive",
    "Tabulated",
    "friedlander_decay",
    "friedlander_impulse_ratio",
    "friedlander_cumulative",
    "friedlander_decay_newton",
    "NegativeDecayWarning",
    "MAX_IMPULSE_RATIO",
]


class NegativeDecayWarning(UserWarning):
    """The impulse exceeds P*t_o/2: the Friedlander fit needs a negative decay coefficient."""


def friedlander_impulse_ratio(d):
    """Dimensionless impulse ``k(d) = i / (P_ro t_o)`` of a modified Friedlander pulse.

    .. math:: k(d) = \\frac{e^{-d} + d - 1}{d^2}, \\qquad k(0) = 1/2,

    paper Eq. (2). ``k`` decreases monotonically over the real line (k -> 1/d for large d).
    Evaluated with a Taylor series near d = 0 to avoid cancellation.
    """
    d = np.asarray(d, dtype=float)
    small = np.abs(d) < 1e-3
    ds = np.where(small, 1.0, d)
    exact = (np.expm1(-ds) + ds) / ds**2
    series = 0.5 - d / 6.0 + d**2 / 24.0 - d**3 / 120.0
    out = np.where(small, series, exact)
    return out if out.ndim else float(out)


#: k(-1) = e - 2: above this impulse ratio even a negative decay cannot give a pulse that
#: decreases monotonically from its peak, and no modified Friedlander pulse fits.
MAX_IMPULSE_RATIO = math.e - 2.0


def friedlander_decay(peak, duration, impulse, *, allow_negative: bool = True):
    """Decay coefficient d of the modified Friedlander pulse with the given impulse.

    Solves paper Eq. (2), :math:`i = P_{ro} t_o (e^{-d} + d - 1)/d^2`, for d. The left side
    is strictly decreasing in d, so the root is unique; it is found by vectorised bisection
    on the bracket ``-1 < d < 1/k`` in ``asinh(d)``, followed by Newton polishing (relative
    accuracy ~1e-14 over k in (0, e - 2), i.e. d from -1 to beyond 1e12).

    Parameters
    ----------
    peak : array_like
        Peak reflected overpressure P_ro [Pa], > 0.
    duration : array_like
        Positive-phase duration t_o [s], > 0.
    impulse : array_like
        Positive-phase impulse i_ro [Pa*s], > 0.
    allow_negative : bool
        What to do when ``k = i/(P t_o) >= 1/2`` (impulse at least that of the triangle of the
        same peak and duration), where no *positive* decay exists. If True (default) the
        negative root in (-1, 0] is returned, which still gives a pulse decreasing
        monotonically from its peak, and a :class:`NegativeDecayWarning` is issued; if False
        an error is raised.

    Returns
    -------
    d : float or ndarray
        Decay coefficient [-].

    Raises
    ------
    BlastscaleInputError
        If ``k >= e - 2`` (no monotone Friedlander pulse carries that impulse), or if
        ``k >= 1/2`` and ``allow_negative`` is False.
    """
    P = check_positive("peak pressure", peak, "Pa")
    t = check_positive("positive duration", duration, "s")
    i = check_positive("impulse", impulse, "Pa*s")
    k = np.broadcast_to(i / (P * t), np.broadcast_shapes(P.shape, t.shape, i.shape)).astype(float)
    if np.any(k >= MAX_IMPULSE_RATIO):
        kb = float(k[k >= MAX_IMPULSE_RATIO].ravel()[0])
        raise BlastscaleInputError(
            f"impulse ratio i/(P*t_o) = {kb:.6g} is out of range for a modified Friedlander pulse: "
            f"valid range is (0, {MAX_IMPULSE_RATIO:.6g}) (use a triangular or tabulated pulse)"
        )
    if np.any(k >= 0.5):
        kb = float(k[k >= 0.5].ravel()[0])
        msg = (
            f"impulse ratio i/(P*t_o) = {kb:.6g} >= 0.5: no positive Friedlander decay exists "
            "(the impulse exceeds that of the triangle with the same peak and duration)"
        )
        if not allow_negative:
            raise BlastscaleInputError(msg + "; valid range for a positive decay is (0, 0.5)")
        warnings.warn(msg + "; using the negative decay in (-1, 0]", NegativeDecayWarning, stacklevel=2)
    # bisection in u = asinh(d): k(sinh u) is decreasing in u. Bracket: k(-1) = e - 2 > k, and
    # k(d) < 1/d for every d > 0 (as e^{-d} < 1), so the root lies below d = 1/k.
    lo = np.full(k.shape, math.asinh(-1.0))
    hi = np.arcsinh(1.0 / k)
    one = k.size == 1 and float(hi.ravel()[0]) < 700.0  # one decay (math.sinh overflows beyond ~710)
    if one:  # the same bisection, bit for bit, with fewer array calls
        lo, hi = (np.full(k.shape, x) for x in _bisect_one(k, float(lo.ravel()[0]), float(hi.ravel()[0])))
    for _ in range(0 if one else 90):
        mid = 0.5 * (lo + hi)
        f = friedlander_impulse_ratio(np.sinh(mid)) - k
        lo = np.where(f > 0.0, mid, lo)
        hi = np.where(f > 0.0, hi, mid)
    d = np.sinh(0.5 * (lo + hi))
    for _ in range(3):  # Newton polish
        kd = friedlander_impulse_ratio(d)
        dsafe = np.where(np.abs(d) < 1e-6, 1e-6, d)
        dk = _impulse_ratio_slope(dsafe, friedlander_impulse_ratio(dsafe))
        step = np.where(np.abs(d) < 1e-6, 0.0, (kd - k) / dk)
        d = d - step
    return d if d.ndim else float(d)


def _bisect_one(k, lo: float, hi: float) -> tuple:
    """The 90 bisection steps of :func:`friedlander_decay` for one ratio ``k`` (an array of size 1),
    with the same result bit for bit, faster: a step whose side is certain is decided by a plain
    float evaluation of k(d) (math module), the others by the array expression itself.

    The float and array evaluations of k differ by < 1e-12 relative (both accurate to a few
    ulps, the series below |d| = 1e-3 included), so where they differ from the target by more
    than 1e-9 relative their signs agree. Once ``mid`` equals an end of the bracket the
    remaining steps cannot move it (the function is deterministic and ``lo`` / ``hi`` keep the
    sign they were set with), so the loop stops there.
    """
    kf = float(k.ravel()[0])
    for _ in range(90):
        mid = 0.5 * (lo + hi)
        if mid == lo or mid == hi:
            break
        d = math.sinh(mid)
        kd = 0.5 - d / 6.0 + d**2 / 24.0 - d**3 / 120.0 if abs(d) < 1e-3 else (math.expm1(-d) + d) / d**2
        if abs(kd - kf) <= 1e-9 * kf:  # close to the root: the array expression decides
            kd = friedlander_impulse_ratio(np.sinh(np.full(k.shape, mid))) - k
            up = float(np.ravel(kd)[0]) > 0.0
        else:
            up = kd > kf
        lo, hi = (mid, hi) if up else (lo, mid)
    return lo, hi


def _impulse_ratio_slope(d, k):
    """dk/dd = (1 - e^{-d}) / d^2 - 2 k / d [-] of :func:`friedlander_impulse_ratio` at decays d
    (|d| >= 1e-6; the callers keep d away from 0), given k = k(d); < 0 everywhere."""
    return (-np.expm1(-d)) / d**2 - 2.0 * k / d


def friedlander_cumulative(x, d):
    """Dimensionless running impulse of a modified Friedlander pulse, vectorised over x and d.

    .. math:: J(x, d) = \\int_0^x (1 - s)\\,e^{-d s}\\,ds
              = \\frac{1 - e^{-d x}}{d} - \\frac{1 - e^{-d x}(1 + d x)}{d^2},

    so that the impulse from arrival to t is :math:`P_{ro} t_o J(t/t_o, d)` (paper Eq. 1);
    ``J(1, d)`` is :func:`friedlander_impulse_ratio`. ``x`` [-] is t/t_o clipped to [0, 1] by the
    caller; for |d| < 1e-4 a series in d (error ~1e-12) avoids the cancellation.
    """
    x = np.asarray(x, dtype=float)
    d = np.asarray(d, dtype=float)
    small = np.abs(d) < 1e-4
    ds = np.where(small, 1.0, d)
    e = np.exp(-ds * x)
    exact = (-np.expm1(-ds * x)) / ds - (1.0 - e * (1.0 + ds * x)) / ds**2
    series = (x - 0.5 * x**2) - d * (0.5 * x**2 - x**3 / 3.0) + 0.5 * d**2 * (x**3 / 3.0 - 0.25 * x**4)
    return np.where(small, series, exact)


def friedlander_decay_newton(impulse_ratio, initial, iterations: int = 4):
    """Refine Friedlander decays by Newton's method on arrays, from nearby ``initial`` values.

    Solves :math:`k(d) = i/(P t_o)` (:func:`friedlander_impulse_ratio`) for d, elementwise,
    starting from ``initial`` (e.g. the decays of the previous time step, whose impulse ratios
    differ by round-off to a few 1e-3): each iteration squares the relative error, so 4
    iterations from a guess within 10 % give full precision. No input checks (the caller checked
    the ratios once); use :func:`friedlander_decay` for a cold start.

    Parameters
    ----------
    impulse_ratio : ndarray
        k = i / (P t_o) [-], in (0, e - 2).
    initial : ndarray
        Starting decays d [-] (> -1).
    iterations : int
        Newton iterations.

    Returns
    -------
    ndarray
        Decays d [-].
    """
    k = np.asarray(impulse_ratio, dtype=float)
    d = np.array(initial, dtype=float, copy=True)
    for _ in range(iterations):
        small = np.abs(d) < 1e-6
        ds = np.where(small, 1e-6, d)
        kd = friedlander_impulse_ratio(ds)
        dk = _impulse_ratio_slope(ds, kd)
        d = np.maximum(d - (kd - k) / dk, -1.0 + 1e-9)
    return d


class Pulse(abc.ABC):
    """A positive-phase pressure pulse starting at t = 0 (shock arrival)."""

    kind: str = "pulse"

    @property
    @abc.abstractmethod
    def peak(self) -> float:
        """Peak overpressure [Pa]."""

    @property
    @abc.abstractmethod
    def duration(self) -> float:
        """Time [s] after arrival at which the pressure is back to zero."""

    @property
    @abc.abstractmethod
    def impulse(self) -> float:
        """Total impulse of the pulse [Pa*s]."""

    @abc.abstractmethod
    def pressure(self, t):
        """Overpressure [Pa] at times t [s] after arrival (0 outside the pulse)."""

    @abc.abstractmethod
    def cumulative_impulse(self, t):
        """Running impulse [Pa*s] from arrival to t [s] (equals ``impulse`` after the pulse)."""

    def scaled(self, pressure_factor: float, time_factor: float) -> "Tabulated | Pulse":
        """The same pulse shape with pressure x ``pressure_factor`` and time x ``time_factor``."""
        raise NotImplementedError  # overridden by every concrete pulse


def _ret(x, t):
    return x if np.ndim(t) else float(x)


@dataclass(frozen=True)
class Friedlander(Pulse):
    """Modified Friedlander pulse, paper Eq. (1):

    .. math:: P(t) = P_{ro}\\,(1 - t/t_o)\\,e^{-d\\,t/t_o}, \\quad 0 \\le t \\le t_o,

    with impulse :math:`i = P_{ro} t_o (e^{-d} + d - 1)/d^2` (Eq. 2).

    Attributes: ``peak_pressure`` P_ro [Pa], ``positive_duration`` t_o [s], ``decay`` d [-].
    Use :meth:`from_impulse` to fit d to a known impulse.
    """

    peak_pressure: float
    positive_duration: float
    decay: float
    kind = "friedlander"

    def __post_init__(self):
        check_positive("peak pressure", self.peak_pressure, "Pa")
        check_positive("positive duration", self.positive_duration, "s")
        d = float(check_finite("Friedlander decay", self.decay))
        if d <= -1.0:
            raise BlastscaleInputError(
                f"Friedlander decay = {d:.6g} is out of range: valid range is (-1, inf) (monotone pulse)"
            )

    @classmethod
    def from_impulse(cls, peak, duration, impulse, *, allow_negative: bool = True) -> "Friedlander":
        """Friedlander pulse of peak [Pa] and duration [s] whose area equals ``impulse`` [Pa*s]."""
        d = friedlander_decay(peak, duration, impulse, allow_negative=allow_negative)
        return cls(float(peak), float(duration), float(d))

    @property
    def peak(self) -> float:
        return float(self.peak_pressure)

    @property
    def duration(self) -> float:
        return float(self.positive_duration)

    @property
    def impulse(self) -> float:
        return float(self.peak_pressure * self.positive_duration * friedlander_impulse_ratio(self.decay))

    def pressure(self, t):
        x = np.asarray(t, dtype=float) / self.positive_duration
        inside = (x >= 0.0) & (x <= 1.0)
        p = np.where(inside, self.peak_pressure * (1.0 - x) * np.exp(-self.decay * x), 0.0)
        return _ret(p, t)

    def cumulative_impulse(self, t):
        x = np.clip(np.asarray(t, dtype=float) / self.positive_duration, 0.0, 1.0)
        return _ret(self.peak_pressure * self.positive_duration * friedlander_cumulative(x, self.decay), t)

    def scaled(self, pressure_factor: float, time_factor: float) -> "Friedlander":
        return Friedlander(self.peak_pressure * pressure_factor, self.positive_duration * time_factor, self.decay)


@dataclass(frozen=True)
class Triangular(Pulse):
    """First-order (triangular) pulse of equal peak and impulse, paper Eq. (3):

    .. math:: P(t) = P_{ro}\\,(1 - t/\\bar t_o), \\quad 0 \\le t \\le \\bar t_o = 2\\,i_{ro}/P_{ro}.

    The paper prints the cut-off at t_o; the pulse must be cut at t_bar_o so that its area is
    i_ro (with the printed cut, the area would be wrong whenever t_bar_o != t_o).
    Attributes: ``peak_pressure`` [Pa], ``total_impulse`` [Pa*s].
    """

    peak_pressure: float
    total_impulse: float
    kind = "triangular"

    def __post_init__(self):
        check_positive("peak pressure", self.peak_pressure, "Pa")
        check_positive("impulse", self.total_impulse, "Pa*s")

    @property
    def peak(self) -> float:
        return float(self.peak_pressure)

    @property
    def duration(self) -> float:
        return float(2.0 * self.total_impulse / self.peak_pressure)

    @property
    def impulse(self) -> float:
        return float(self.total_impulse)

    def pressure(self, t):
        x = np.asarray(t, dtype=float) / self.duration
        return _ret(np.where((x >= 0.0) & (x <= 1.0), self.peak_pressure * (1.0 - x), 0.0), t)

    def cumulative_impulse(self, t):
        x = np.clip(np.asarray(t, dtype=float) / self.duration, 0.0, 1.0)
        return _ret(self.peak_pressure * self.duration * (x - 0.5 * x**2), t)

    def scaled(self, pressure_factor: float, time_factor: float) -> "Triangular":
        return Triangular(self.peak_pressure * pressure_factor, self.total_impulse * pressure_factor * time_factor)


@dataclass(frozen=True)
class Impulsive(Pulse):
    """Impulsive limit: a Dirac pulse of area ``total_impulse`` [Pa*s] at t = 0.

    ``pressure`` is zero everywhere (the load acts as an initial velocity); ``peak`` is inf.
    """

    total_impulse: float
    kind = "impulsive"

    def __post_init__(self):
        check_positive("impulse", self.total_impulse, "Pa*s")

    @property
    def peak(self) -> float:
        return math.inf

    @property
    def duration(self) -> float:
        return 0.0

    @property
    def impulse(self) -> float:
        return float(self.total_impulse)

    def pressure(self, t):
        return _ret(np.zeros_like(np.asarray(t, dtype=float)), t)

    def cumulative_impulse(self, t):
        return _ret(np.where(np.asarray(t, dtype=float) >= 0.0, self.total_impulse, 0.0), t)

    def scaled(self, pressure_factor: float, time_factor: float) -> "Impulsive":
        return Impulsive(self.total_impulse * pressure_factor * time_factor)


class Tabulated(Pulse):
    """Arbitrary pulse from a table of (time [s], overpressure [Pa]), linear in between.

    Times must start at 0 and increase strictly; pressures must be finite and >= 0, and the
    last one 0 (the pulse ends). The impulse is the exact (trapezoidal) area of the
    piecewise-linear curve.
    """

    kind = "tabulated"

    def __init__(self, times, pressures):
        t = check_finite("pulse times", times, "s")
        p = check_finite("pulse pressures", pressures, "Pa")
        if t.ndim != 1 or p.shape != t.shape or t.size < 2:
            raise BlastscaleInputError(
                f"tabulated pulse needs 1-D times and pressures of equal length >= 2, got shapes {t.shape} and {p.shape}"
            )
        if t[0] != 0.0:
            raise BlastscaleInputError(f"pulse times[0] = {t[0]:.6g} s is out of range: the table must start at 0 s")
        dt = np.diff(t)
        if np.any(dt <= 0.0):
            raise BlastscaleInputError("pulse times must increase strictly (a pulse with negative duration)")
        if np.any(p < 0.0):
            raise BlastscaleInputError(
                f"pulse pressure = {float(p[p < 0][0]):.6g} Pa is out of range: must be >= 0 (positive phase only)"
            )
        if p[-1] != 0.0:
            p = np.append(p, 0.0)
            t = np.append(t, t[-1] + 1e-12 * max(t[-1], 1.0))
        self.times = t
        self.pressures = p
        self._cum = np.concatenate([[0.0], np.cumsum(0.5 * (p[1:] + p[:-1]) * np.diff(t))])

    @property
    def peak(self) -> float:
        return float(self.pressures.max())

    @property
    def duration(self) -> float:
        return float(self.times[-1])

    @property
    def impulse(self) -> float:
        return float(self._cum[-1])

    def pressure(self, t):
        tt = np.asarray(t, dtype=float)
        return _ret(np.interp(tt, self.times, self.pressures, left=0.0, right=0.0), t)

    def cumulative_impulse(self, t):
        tt = np.clip(np.asarray(t, dtype=float), 0.0, self.times[-1])
        j = np.clip(np.searchsorted(self.times, tt, side="right") - 1, 0, self.times.size - 2)
        t0 = self.times[j]
        p0 = self.pressures[j]
        slope = (self.pressures[j + 1] - p0) / (self.times[j + 1] - t0)
        dt = tt - t0
        return _ret(self._cum[j] + p0 * dt + 0.5 * slope * dt**2, t)

    def scaled(self, pressure_factor: float, time_factor: float) -> "Tabulated":
        return Tabulated(self.times * time_factor, self.pressures * pressure_factor)

    def __repr__(self) -> str:
        return f"Tabulated(n={self.times.size}, peak={self.peak:.6g} Pa, duration={self.duration:.6g} s)"
