"""Compiled (numba) pulse phase by Taylor series: one expansion over a whole piece of the pulse.

A pulse lasts ``p t_o ~ 1e-3..1e-1`` of dimensionless time, far inside the radius of convergence of
the rocking equation's solution (``>= pi/2``, :mod:`._free`), and its load ratio is entire on a
piece between breakpoints: the Friedlander pulse ``f0 (1 - x) exp(-d x)`` (paper Eq. 1) has the
coefficients ``c (1 - x0) E_k - c r E_(k-1)``, ``E_k = (-d r)^k / k!`` (``x = tau / tau_o``,
``r = h / tau_o``, ``c = f0 exp(-d x0)``); a triangular pulse (Eq. 3) and a table's segment are linear.
So one Taylor expansion of ``phi'' = sin(phi) - s f cos(phi)`` (:func:`._free.taylor_coeffs`) crosses a
piece where the Dormand-Prince steps take ~30 (rtol 1e-10), to the rounding of its sums.

It is taken only where no event can fall inside the piece: the body moving outward (``s w >= 0``),
``0 <= s theta < alpha`` and ``s w > 0`` at 16 points across the piece and at its end (no impact, peak,
tipping or lying down), the series converged, and no negative phase acting on the piece (its cubic is
left to the steps); otherwise the steps do the piece.

Not a public module: use :class:`blastscale.rocking.RockingSolver`.
"""

from __future__ import annotations

import math

from .._jit import njit
from ._free import H_MAX, N_MAX, taylor_coeffs, taylor_eval
from ._load import base_ratio
from .layout import FRIEDLANDER, TABULATED, TRIANGULAR

#: Points across a piece at which the absence of events is checked.
N_CHECK = 16


@njit(cache=True)
def load_series(tau, tbp, kind, par, tab_t, tab_f, F):
    """Scaled Taylor coefficients ``F[k] = f^(k)(tau) h^k / k!`` [-] of the load ratio over the piece
    ``[tau, tbp]``, ``h = tbp - tau`` (no breakpoint inside; module docstring). Returns their number,
    0 for no load, -1 where the series is not offered (a negative phase acting on the piece)."""
    h = tbp - tau
    if par[5] > 0.0 and tau >= par[4] and tau < par[4] + par[5]:
        return -1
    if kind == FRIEDLANDER:
        if tau >= par[1]:
            return 0
        x0 = tau / par[1]
        r = h / par[1]
        c = par[0] * math.exp(-par[2] * x0)
        g = -par[2] * r
        ek = 1.0
        F[0] = c * (1.0 - x0)
        for k in range(1, N_MAX):
            ekm = ek
            ek = ekm * g / k
            F[k] = c * ((1.0 - x0) * ek - r * ekm)
            if k > abs(g) and abs(F[k]) < 1e-20 * abs(F[0]) + 1e-300:
                return k + 1
        return N_MAX
    if kind == TRIANGULAR:
        if tau >= par[1]:
            return 0
        F[0] = par[0] * (1.0 - tau / par[1])
        F[1] = -par[0] * h / par[1]
        return 2
    if kind == TABULATED:
        if tau < tab_t[0] or tbp > tab_t[tab_t.size - 1]:  # before or after the table: no load
            return 0
        f0 = base_ratio(tau, kind, par, tab_t, tab_f)
        F[0] = f0
        F[1] = base_ratio(tbp, kind, par, tab_t, tab_f) - f0
        return 2
    return 0


@njit(cache=True)
def pulse_piece(tau, th, w, s, alpha, kind, par, tab_t, tab_f, tbp, tau_eval, ie, th_eval, w_eval, A, S, C, F):
    """Cross the piece ``[tau, tbp]`` [-] of the pulse in Taylor expansions from ``(th [rad], w [-])`` in
    the mode ``s`` where no event can fall inside (module docstring), filling the samples ``tau_eval[ie:]``
    on the way. The piece is cut into parts no longer than :data:`._free.H_MAX` over which the
    Friedlander decay ``d r`` stays below 2 (its series then converges within :data:`N_MAX` terms).

    Returns
    -------
    tuple
        ``(tau, th, w, ie)``: how far it went (``tbp``, or where the steps must take over) and the state there.
    """
    h_all = tbp - tau
    nsub = max(1, math.ceil(h_all / H_MAX))
    if kind == FRIEDLANDER and tau < par[1]:
        nsub = max(nsub, math.ceil(par[2] * h_all / par[1] / 2.0))
    m = tau_eval.size
    for i in range(nsub):
        tb = tbp if i == nsub - 1 else tau + h_all / (nsub - i)
        q = s * th
        v = s * w
        h = tb - tau
        if not (h > 0.0 and q >= 0.0 and q < alpha and v >= 0.0):
            return tau, th, w, ie
        nf = load_series(tau, tb, kind, par, tab_t, tab_f, F)
        if nf < 0:
            return tau, th, w, ie
        n = taylor_coeffs(alpha, q, v, h, s, F, nf, A, S, C)
        if n >= N_MAX - 1:
            return tau, th, w, ie
        inv_h = 1.0 / h
        for j in range(1, N_CHECK + 1):
            qj, vj = taylor_eval(alpha, A, n, j / N_CHECK, inv_h)
            if not (vj > 0.0 and qj >= 0.0 and qj < alpha):
                return tau, th, w, ie
        while ie < m and tau_eval[ie] <= tb:
            x = (tau_eval[ie] - tau) * inv_h
            qj, vj = taylor_eval(alpha, A, n, min(max(x, 0.0), 1.0), inv_h)
            th_eval[ie] = s * qj
            w_eval[ie] = s * vj
            ie += 1
        qj, vj = taylor_eval(alpha, A, n, 1.0, inv_h)
        tau, th, w = tb, s * qj, s * vj
        h_all = tbp - tau
    return tau, th, w, ie
