"""The modified Friedlander pulse's decay coefficient: its impulse ratio, the inverse, running impulse.

A modified Friedlander pulse of peak P_ro [Pa], positive duration t_o [s] and decay d [-],

.. math:: P(t) = P_{ro}\\,(1 - t/t_o)\\,e^{-d\\,t/t_o}, \\quad 0 \\le t \\le t_o

(paper Eq. 1, Friedlander 1946), carries the impulse :math:`i = P_{ro}\\,t_o\\,k(d)` with the
dimensionless impulse ratio

.. math:: k(d) = \\frac{e^{-d} + d - 1}{d^2}

(paper Eq. 2). Fitting d to a known (P_ro, t_o, i) is the inversion of k, strictly decreasing
on d > -1. Everything here works on plain float arrays; the pulse object is
:class:`~blastscale.blast.pulses.Friedlander`.

References
----------
.. [1] Friedlander, F. G. (1946). The diffraction of sound pulses I. Proc. R. Soc. A 186.
.. [2] Masi, Stefanou & Maffi-Berthier, *Scaling laws ...*, Eqs. (1)-(2) (modified Friedlander
       pulse and its impulse).
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from .._validate import BlastscaleInputError, check_positive

__all__ = [
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
    Evaluated with a Taylor series for |d| < 1e-3 to avoid cancellation.

    Parameters
    ----------
    d : array_like
        Decay coefficient [-].

    Returns
    -------
    float or ndarray
        Impulse ratio k [-] (a float for a scalar d).
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
    """Slope of :func:`friedlander_impulse_ratio` [-], the derivative of paper Eq. (2):

    .. math:: \\frac{dk}{dd} = \\frac{1 - e^{-d}}{d^2} - \\frac{2\\,k}{d} < 0,

    at decays d [-] (|d| >= 1e-6; the callers keep d away from 0), given k = k(d) [-].
    """
    return (-np.expm1(-d)) / d**2 - 2.0 * k / d


def friedlander_cumulative(x, d):
    """Dimensionless running impulse of a modified Friedlander pulse, vectorised over x and d.

    .. math:: J(x, d) = \\int_0^x (1 - s)\\,e^{-d s}\\,ds
              = \\frac{1 - e^{-d x}}{d} - \\frac{1 - e^{-d x}(1 + d x)}{d^2},

    so that the impulse from arrival to t is :math:`P_{ro} t_o J(t/t_o, d)` (integral of paper
    Eq. 1); ``J(1, d)`` is :func:`friedlander_impulse_ratio`. For |d| < 1e-4 a series in d
    (error ~1e-12) avoids the cancellation.

    Parameters
    ----------
    x : array_like
        Time since arrival over the positive duration, t/t_o [-], clipped to [0, 1] by the caller.
    d : array_like
        Decay coefficient [-], broadcast against ``x``.

    Returns
    -------
    ndarray
        Running impulse ratio J [-].
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
