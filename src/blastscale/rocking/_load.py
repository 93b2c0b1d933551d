"""Compiled (numba) load of an encoded pulse: the load-to-weight ratio ``f(tau)`` of the kernel.

``f`` is the right-hand side's load term of the dimensionless rocking equation
(:mod:`blastscale.rocking._kernel`): ``f = S P(t) l / (m g r cos(alpha))`` [-] (``S P / (m g)``
for a rectangular block), at the dimensionless time ``tau = p t`` [-] (p the frequency
parameter [rad/s]). :func:`blastscale.rocking.encoding.encode_pulse` turns a
:class:`~blastscale.blast.pulses.Pulse` into the code and parameters read here.

Pulse codes (the single table; :data:`blastscale.rocking.encoding.PULSE_CODES` names them):

* :data:`NO_PULSE` 0: no pressure (an impulsive load enters as an initial velocity);
* :data:`FRIEDLANDER` 1: ``par = (f0, tau_o, d)``, ``f = f0 (1 - x) exp(-d x)``, ``x = tau / tau_o``
  (paper Eq. 1);
* :data:`TRIANGULAR` 2: ``par = (f0, tau_d, 0)``, ``f = f0 (1 - x)``, ``x = tau / tau_d``
  (paper Eq. 3);
* :data:`TABULATED` 3: the table ``tab_t`` [-] (dimensionless times, increasing), ``tab_f``
  [-] (load ratios), linear in between, zero outside.

Not a public module: use :class:`blastscale.rocking.RockingSolver`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

NO_PULSE = 0
FRIEDLANDER = 1
TRIANGULAR = 2
TABULATED = 3


@njit(cache=True)
def load_ratio(tau, kind, par, tab_t, tab_f):
    """Load-to-weight ratio f(tau) [-] of an encoded pulse (module docstring, paper Eqs. 1, 3).

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
    """Dimensionless end time of the pulse [-] (0 without pressure)."""
    if kind == FRIEDLANDER or kind == TRIANGULAR:
        return par[1]
    if kind == TABULATED:
        return tab_t[tab_t.size - 1]
    return 0.0


@njit(cache=True)
def next_breakpoint(tau, kind, par, tab_t):
    """First breakpoint of the load strictly after ``tau`` [-] (pulse end, table point); inf when none.

    The integrator never steps across one: the load is not smooth there."""
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
def lift_time(tau, thr, kind, par, tab_t, tab_f):
    """First time >= ``tau`` [-] at which ``f > thr`` (a body at rest lifts off); inf if never.

    ``thr = tan(alpha)`` [-] is the uplift ratio (``P S h = m g b`` for a rectangular block,
    paper Eq. eom at theta = 0)."""
    if kind == FRIEDLANDER or kind == TRIANGULAR:  # monotone decreasing pulses
        if tau <= par[1] and load_ratio(tau, kind, par, tab_t, tab_f) > thr:
            return tau
        return np.inf
    if kind == TABULATED:
        if load_ratio(tau, kind, par, tab_t, tab_f) > thr:
            return tau
        n = tab_t.size
        j = np.searchsorted(tab_t, tau, side="right") - 1
        if j < 0:
            j = 0
        while j < n - 1:
            t0 = max(tau, tab_t[j])
            f0 = load_ratio(t0, kind, par, tab_t, tab_f)
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
