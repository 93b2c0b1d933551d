"""Compiled (numba) load of an encoded pulse: the load-to-weight ratio ``f(tau)`` of the kernel.

``f`` is the right-hand side's load term of the dimensionless rocking equation
(:mod:`blastscale.rocking.kernel`): ``f = S P(t) l / (m g r cos(alpha))`` [-] (``S P / (m g)``
for a rectangular block), at the dimensionless time ``tau = p t`` [-] (p the frequency
parameter [rad/s]). :func:`blastscale.rocking.encoding.encode_pulse` turns a
:class:`~blastscale.blast.pulses.Pulse` into the code and parameters read here.

Pulse codes (the single table, in :mod:`.layout`; :data:`blastscale.rocking.encoding.PULSE_CODES` names them):

* :data:`NO_PULSE` 0: no pressure (an impulsive load enters as an initial velocity);
* :data:`FRIEDLANDER` 1: ``par = (f0, tau_o, d)``, ``f = f0 (1 - x) exp(-d x)``, ``x = tau / tau_o``
  (paper Eq. 1);
* :data:`TRIANGULAR` 2: ``par = (f0, tau_d, 0)``, ``f = f0 (1 - x)``, ``x = tau / tau_d``
  (paper Eq. 3);
* :data:`TABULATED` 3: the table ``tab_t`` [-] (dimensionless times, increasing), ``tab_f``
  [-] (load ratios), linear in between, zero outside.

Every code may carry a negative phase (suction) after it, in ``par[3:6] = (f_-, tau_-s, tau_-)``:
``f = -f_- (27/4) x (1 - x)^2``, ``x = (tau - tau_-s) / tau_-`` in [0, 1] (Granström's cubic,
:mod:`blastscale.blast.negative_phase`); ``tau_- = 0`` means none, and then every function here
returns exactly what it returned before the negative phase existed. ``par`` has :data:`PAR_SIZE`
entries.

Not a public module: use :class:`blastscale.rocking.RockingSolver`.
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import njit
from .layout import FRIEDLANDER, TABULATED, TRIANGULAR


@njit(cache=True, inline="always")
def tail_ratio(tau, par):
    """Load ratio [-] of the negative phase at ``tau`` [-] (0 outside it, and without one)."""
    if par[5] <= 0.0:
        return 0.0
    x = (tau - par[4]) / par[5]
    if x < 0.0 or x > 1.0:
        return 0.0
    return -par[3] * 6.75 * x * (1.0 - x) * (1.0 - x)


@njit(cache=True, inline="always")
def load_ratio(tau, kind, par, tab_t, tab_f):
    """Load-to-weight ratio f(tau) [-] of an encoded pulse, negative phase included."""
    f = base_ratio(tau, kind, par, tab_t, tab_f)
    if par[5] > 0.0:
        f += tail_ratio(tau, par)
    return f


@njit(cache=True, inline="always")
def base_ratio(tau, kind, par, tab_t, tab_f):
    """Load-to-weight ratio f(tau) [-] of an encoded pulse's positive part (module docstring, paper Eqs. 1, 3).

    Parameters
    ----------
    tau : float
        Dimensionless time [-].
    kind : int
        Pulse code.
    par : ndarray, shape (3,)
        Pulse parameters (peak ratio [-], dimensionless duration [-], Friedlander decay [-]).
    tab_t, tab_f : ndarray
        Table of a tabulated pulse: dimensionless times [-] and load ratios [-].

    Returns
    -------
    float
        f(tau) [-]; 0 outside the pulse.
    """
    if kind == FRIEDLANDER:
        x = tau / par[1]
        if x < 0.0 or x > 1.0:
            return 0.0
        return par[0] * (1.0 - x) * math.exp(-par[2] * x)
    if kind == TRIANGULAR:
        x = tau / par[1]
        if x < 0.0 or x > 1.0:
            return 0.0
        return par[0] * (1.0 - x)
    if kind == TABULATED:
        n = tab_t.size
        if tau < tab_t[0] or tau > tab_t[n - 1]:
            return 0.0
        j = np.searchsorted(tab_t, tau, side="right") - 1
        if j >= n - 1:
            return tab_f[n - 1]
        if j < 0:
            j = 0
        return tab_f[j] + (tab_f[j + 1] - tab_f[j]) * (tau - tab_t[j]) / (tab_t[j + 1] - tab_t[j])
    return 0.0


@njit(cache=True)
def pulse_end(kind, par, tab_t):
    """Dimensionless end time of the pulse [-] (0 without pressure), negative phase included."""
    end = base_end(kind, par, tab_t)
    if par[5] > 0.0:
        end = max(end, par[4] + par[5])
    return end


@njit(cache=True)
def pull_end(par):
    """End of the negative phase [-] (0 without one): before it, a body tipped away from the blast
    may still be pulled back (:mod:`._events`)."""
    if par[5] > 0.0:
        return par[4] + par[5]
    return 0.0


@njit(cache=True)
def base_end(kind, par, tab_t):
    """Dimensionless end time of the positive part [-] (0 without pressure)."""
    if kind == FRIEDLANDER or kind == TRIANGULAR:
        return par[1]
    if kind == TABULATED:
        return tab_t[tab_t.size - 1]
    return 0.0


@njit(cache=True)
def next_breakpoint(tau, kind, par, tab_t):
    """First breakpoint of the load strictly after ``tau`` [-] (pulse end, table point); inf when none.

    The integrator never steps across one: the load is not smooth there."""
    bp = base_breakpoint(tau, kind, par, tab_t)
    if par[5] > 0.0:
        if tau < par[4] and par[4] < bp:
            bp = par[4]
        elif tau < par[4] + par[5] and par[4] + par[5] < bp:
            bp = par[4] + par[5]
    return bp


@njit(cache=True)
def base_breakpoint(tau, kind, par, tab_t):
    """First breakpoint of the positive part strictly after ``tau`` [-]; inf when none."""
    if kind == FRIEDLANDER or kind == TRIANGULAR:
        if tau < par[1]:
            return par[1]
        return np.inf
    if kind == TABULATED:
        j = np.searchsorted(tab_t, tau, side="right")
        if j < tab_t.size:
            return tab_t[j]
        return np.inf
    return np.inf


@njit(cache=True)
def _suction_root(lo, hi, c, rising):
    """Bracket ``(lo, hi)`` [-] of the root of ``g(x) = 6.75 x (1 - x)^2 = c`` after 80 bisections of
    ``[lo, hi]``, where ``g`` rises (``rising``: g(lo) <= c < g(hi)) or falls (g(lo) > c >= g(hi))."""
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if (6.75 * mid * (1.0 - mid) * (1.0 - mid) > c) == rising:
            hi = mid
        else:
            lo = mid
    return lo, hi


@njit(cache=True)
def tail_lift_time(tau, thr, par):
    """First time >= ``tau`` [-] at which the negative phase's suction exceeds ``thr`` (``f < -thr``:
    a body at rest lifts off toward the blast); inf if never (and without a negative phase)."""
    if par[5] <= 0.0 or par[3] <= thr:
        return np.inf
    c = thr / par[3]  # the cubic g(x) = 6.75 x (1 - x)^2 rises to 1 at x = 1/3, then falls
    x = (tau - par[4]) / par[5]
    x1 = _suction_root(0.0, 1.0 / 3.0, c, True)[1]  # rising root: g(lo) <= c < g(hi)
    x2 = _suction_root(1.0 / 3.0, 1.0, c, False)[0]  # falling root: g(lo) > c >= g(hi)
    if x >= x2:
        return np.inf
    if x >= x1:
        return tau
    return par[4] + x1 * par[5]


@njit(cache=True)
def lift_time(tau, thr, kind, par, tab_t, tab_f):
    """First time >= ``tau`` [-] at which ``f > thr`` (a body at rest lifts off); inf if never.

    ``thr = tan(alpha)`` [-] is the uplift ratio (``P S h = m g b`` for a rectangular block,
    paper Eq. eom at theta = 0)."""
    if kind == FRIEDLANDER or kind == TRIANGULAR:  # monotone decreasing pulses
        if tau <= par[1] and base_ratio(tau, kind, par, tab_t, tab_f) > thr:
            return tau
        return np.inf
    if kind == TABULATED:
        if base_ratio(tau, kind, par, tab_t, tab_f) > thr:
            return tau
        n = tab_t.size
        j = np.searchsorted(tab_t, tau, side="right") - 1
        if j < 0:
            j = 0
        while j < n - 1:
            t0 = max(tau, tab_t[j])
            f0 = base_ratio(t0, kind, par, tab_t, tab_f)
            f1 = tab_f[j + 1]
            if f1 > thr and f1 > f0:
                if f0 > thr:
                    return t0
                # linear segment: root of f = thr, then nudge to where f > thr
                tr = t0 + (thr - f0) / (f1 - f0) * (tab_t[j + 1] - t0)
                return min(tr * (1.0 + 1e-15) + 1e-300, tab_t[j + 1])
            j += 1
        return np.inf
    return np.inf
