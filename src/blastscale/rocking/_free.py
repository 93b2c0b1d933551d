"""Compiled (numba) free rocking after the pulse: event-driven, in closed form between impacts.

Once the pulse (negative phase included) is over, the dimensionless rocking equation of
:mod:`blastscale.rocking.kernel` is autonomous and conservative between impacts. In the mode
``s`` (+-1) write ``q = s theta`` [rad] (>= 0 while rocking on that pivot), ``v = s w`` [-] and
``phi = alpha - q``: ``q'' = -sin(phi)`` and the energy (units of ``m g r``)

.. math:: \\tfrac12 v^2 + \\cos\\phi = \\cos\\phi_m,\\qquad
          \\sin^2\\tfrac{\\phi_m}{2} = \\sin^2\\tfrac{\\phi}{2} - \\tfrac{v^2}{4} \\;(= k'^2)

gives the peak ``q_max = alpha - phi_m`` and the speed at the impact (``phi = alpha``)
``|v| = 2 sqrt(sin^2(alpha/2) - k'^2)`` exactly (Housner 1963, Bull. Seismol. Soc. Am. 53(2):
``cos(alpha - theta_max) = cos(alpha) + theta_dot^2 / (2 p^2)`` after an impact). The motion is the
libration of a pendulum ``psi = pi - phi`` of modulus ``k = cos(phi_m / 2)``:
``sin(phi / 2) = dn(u, k)``, ``v = 2 k cn(u, k)``, ``u - u_0 = tau - tau_0``, the peak at ``u = K(k)``
(Byrd & Friedman 1971, Handbook of Elliptic Integrals, 2nd ed., formulas 121.00 and 122.00 with
``sin(psi/2) = k sn u``). The time from a state to the peak is therefore ``K - F(varphi, k)`` with
``sin varphi = cos(phi / 2) / k``, ``cos^2 varphi = v^2 / (4 k^2)`` (no cancellation), and the half
cycle from the peak to the impact is ``K - F(varphi_alpha, k)``; ``K`` and ``F`` come from Carlson's
symmetric integral ``R_F`` (Carlson 1995, Numer. Algorithms 10, 13-26; DLMF 19.25.5, 19.36.1):
``F(varphi, k) = sin(varphi) R_F(cos^2 varphi, 1 - k^2 sin^2 varphi, 1)``, ``K = R_F(0, k'^2, 1)``.
No ODE step is taken between the events; each half cycle starts from the exact state after the
impact (``theta = 0``, Housner's restitution on ``w``).

Samples between the events (and the state at the end time) come from Taylor series of the same
equation, ``phi'' = sin(phi)``, about the last exact state (the start of the half cycle, its peak):
the coefficients of ``sin`` and ``cos`` by the usual recurrences (``S' = C phi'``, ``C' = -S phi'``;
Moore 1966, Interval Analysis, ch. 11), up to the order where two consecutive terms fall below 1e-17
over :data:`H_MAX`; every sample within that reach is read off one expansion (Horner), and the anchor
hops by :data:`H_MAX` beyond it (the series converges within ``K(k') >= pi/2`` of the real axis, the
poles of ``dn``).

Not a public module: use :class:`blastscale.rocking.RockingSolver`.
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import njit
from ._events import record_impact, record_peak
from .layout import S_OVERTURN_TAU, S_W_AT_ALPHA

#: Reach of one Taylor expansion [-] (a tenth of the smallest radius of convergence, pi/2: terms
#: shrink about 10x per order); the samples within it are read off one expansion.
H_MAX = 0.15
#: Highest Taylor order; the sums stop earlier, once two consecutive terms are below 1e-17.
N_MAX = 48

# reciprocals of the recurrences (a division costs ~10 multiplications): 1/k and 1/((k + 1)(k + 2))
_INV = np.array([0.0] + [1.0 / k for k in range(1, N_MAX)])
_INV2 = np.array([1.0 / ((k + 1) * (k + 2)) for k in range(N_MAX)])
_INV_H = 1.0 / H_MAX

_RF_ERRTOL = 0.0025  # Carlson's duplication stops here: relative error < ERRTOL^6 / 4 ~ 6e-17


@njit(cache=True)
def carlson_rf(x, y, z):
    """Carlson's symmetric elliptic integral of the first kind ``R_F(x, y, z)`` [-] for x, y, z >= 0,
    at most one of them 0 (Carlson 1995, Numer. Algorithms 10, 13-26: duplication, then the
    fifth-order series; relative error below 1e-16)."""
    for _ in range(60):
        sx = math.sqrt(x)
        sy = math.sqrt(y)
        sz = math.sqrt(z)
        lam = sx * (sy + sz) + sy * sz
        x = 0.25 * (x + lam)
        y = 0.25 * (y + lam)
        z = 0.25 * (z + lam)
        ave = (x + y + z) / 3.0
        dx = (ave - x) / ave
        dy = (ave - y) / ave
        dz = (ave - z) / ave
        if max(abs(dx), abs(dy), abs(dz)) <= _RF_ERRTOL:
            break
    e2 = dx * dy - dz * dz
    e3 = dx * dy * dz
    return (1.0 + (e2 / 24.0 - 0.1 - 3.0 * e3 / 44.0) * e2 + e3 / 14.0) / math.sqrt(ave)


@njit(cache=True)
def taylor_coeffs(alpha, q, v, h, sf, F, nf, A, S, C):
    """Scaled Taylor coefficients ``A[j] = phi^(j)(0) h^j / j!`` of the rocking from the state
    ``(q [rad], v [-])`` over ``h`` [-], ``phi = alpha - q``, ``phi'' = sin(phi) - sf f cos(phi)``
    (module docstring; ``sf`` the mode s, ``f`` the load ratio with scaled coefficients ``F[:nf]``,
    ``nf = 0`` for the free motion); ``S``, ``C`` those of ``sin(phi)``, ``cos(phi)``. Work arrays of
    :data:`N_MAX` entries. Returns the order n: the sums stop once two consecutive terms are below
    1e-17 (:data:`N_MAX` - 1: not converged)."""
    A[0] = alpha - q
    A[1] = -v * h
    S[0] = math.sin(A[0])
    C[0] = math.cos(A[0])
    hh = h * h
    k = 0
    while k < N_MAX - 2:
        load = 0.0
        for j in range(min(k + 1, nf)):  # the coefficient k of f cos(phi)
            load += F[j] * C[k - j]
        A[k + 2] = hh * (S[k] - sf * load) * _INV2[k]
        if abs(A[k + 2]) < 1e-17 and abs(A[k + 1]) < 1e-17:
            return k + 2
        n = k + 1  # coefficients of sin(phi) and cos(phi) of order n from those of phi up to n
        sa = 0.0
        ca = 0.0
        for j in range(1, n + 1):
            sa += j * A[j] * C[n - j]
            ca += j * A[j] * S[n - j]
        S[n] = sa * _INV[n]
        C[n] = -ca * _INV[n]
        k += 1
    return N_MAX - 1


@njit(cache=True, inline="always")
def taylor_eval(alpha, A, n, x, inv_h):
    """State ``(q [rad], v [-])`` at the fraction ``x`` (in [0, 1]) of the step ``h = 1 / inv_h`` [-]
    from the expansion ``A[:n + 1]`` of :func:`taylor_coeffs` (Horner)."""
    ph = A[n]
    dph = n * A[n]
    for j in range(n - 1, 0, -1):
        ph = ph * x + A[j]
        dph = dph * x + j * A[j]
    ph = ph * x + A[0]
    return alpha - ph, -dph * inv_h


@njit(cache=True, inline="always")
def march(alpha, ta, qa, va, n, t, A, S, C):
    """The free-rocking state at ``t`` [-] (``t >= ta``) from the expansion ``A[:n + 1]`` about the
    state ``(qa [rad], va [-])`` at ``ta`` [-] (``n < 0``: none yet), hopping the anchor by
    :data:`H_MAX` where ``t`` lies beyond its reach.

    Returns ``(q, v, ta, qa, va, n)``: the state and the anchor and expansion to use next."""
    if n < 0:
        n = taylor_coeffs(alpha, qa, va, H_MAX, 0.0, A, 0, A, S, C)
    while t - ta > H_MAX:
        qa, va = taylor_eval(alpha, A, n, 1.0, _INV_H)
        ta += H_MAX
        n = taylor_coeffs(alpha, qa, va, H_MAX, 0.0, A, 0, A, S, C)
    q, v = taylor_eval(alpha, A, n, (t - ta) * _INV_H, _INV_H)
    return q, v, ta, qa, va, n


@njit(cache=True)
def fill_samples(alpha, tau, q, v, s, t_stop, tau_eval, ie, th_eval, w_eval, A, S, C):
    """Samples ``tau_eval[ie:]`` up to ``t_stop`` [-] of the free motion from ``(q, v)`` at ``tau`` [-]
    in the mode ``s``, with no event between; returns ``(ie, q, v)``, the state at ``t_stop``."""
    ta, qa, vb, nx = tau, q, v, -1
    while ie < tau_eval.size and tau_eval[ie] <= t_stop:
        qs, vs, ta, qa, vb, nx = march(alpha, ta, qa, vb, nx, tau_eval[ie], A, S, C)
        th_eval[ie] = s * qs
        w_eval[ie] = s * vs
        ie += 1
    qs, vs, ta, qa, vb, nx = march(alpha, ta, qa, vb, nx, t_stop, A, S, C)
    return ie, qs, vs


@njit(cache=True)
def free_rocking(
    tau,
    th,
    w,
    s,
    alpha,
    e,
    w_rest,
    tau_end,
    max_impacts,
    stop_at_overturn,
    tau_eval,
    ie,
    th_eval,
    w_eval,
    imp,
    nimp,
    pk,
    npk,
    summ,
    max_abs,
    A,
    S,
    C,
):
    """Follow the free rocking from ``(tau, th [rad], w [-])`` in the mode ``s`` event by event
    (module docstring) until the end time ``tau_end`` [-], rest (rebound below ``w_rest`` [-]),
    ``max_impacts`` impacts, the tipping point with ``stop_at_overturn`` (moving outward with an
    energy above the top, ``k'^2 < 0``: the time to ``q = alpha`` is
    ``X R_F(c (1 - X^2), c + X^2, c)``, ``X = sin(phi / 2)``, ``c = -k'^2``, and ``|v| = 2 sqrt(c)``
    there), or a state it does not cover (other energies at or above the top, a body beyond the
    top): handed back to the Dormand-Prince steps.

    Fills the samples ``tau_eval[ie:]`` that fall before the stop, the impacts and peaks (and the
    summary's first peak and first impact time) like the stepping kernel.

    Returns
    -------
    tuple
        ``(tau, th, w, s, resting, early, handed_back, tipped, ie, imp, nimp, pk, npk, max_abs, n_events)``.
    """
    m = tau_eval.size
    ca = math.sin(0.5 * alpha)
    ca2 = ca * ca
    cosa2 = math.cos(0.5 * alpha)
    n_events = 0
    while True:
        q = s * th
        v = s * w
        phi = alpha - q
        sp = math.sin(0.5 * phi)
        mp = sp * sp - 0.25 * v * v  # k'^2 = sin^2(phi_m / 2)
        if not (mp > 0.0 and phi > 0.0):
            if not (stop_at_overturn and phi > 0.0 and v > 0.0 and mp < 0.0):
                return tau, th, w, s, False, False, True, False, ie, imp, nimp, pk, npk, max_abs, n_events
            t_tip = tau + sp * carlson_rf(-mp * (1.0 - sp * sp), sp * sp - mp, -mp)
            if t_tip > tau_end:  # still on its way to the top at the end time
                ie, qs, vs = fill_samples(alpha, tau, q, v, s, tau_end, tau_eval, ie, th_eval, w_eval, A, S, C)
                return (
                    tau_end,
                    s * qs,
                    s * vs,
                    s,
                    False,
                    False,
                    False,
                    False,
                    ie,
                    imp,
                    nimp,
                    pk,
                    npk,
                    max(max_abs, abs(qs)),
                    n_events,
                )
            ie, qs, vs = fill_samples(alpha, tau, q, v, s, t_tip, tau_eval, ie, th_eval, w_eval, A, S, C)
            summ[S_OVERTURN_TAU] = t_tip
            summ[S_W_AT_ALPHA] = 2.0 * math.sqrt(-mp)
            return (
                t_tip,
                s * alpha,
                s * 2.0 * math.sqrt(-mp),
                s,
                False,
                True,
                False,
                True,
                ie,
                imp,
                nimp,
                pk,
                npk,
                max(max_abs, alpha),
                n_events + 1,
            )
        k2 = 1.0 - mp
        kk = math.sqrt(k2)
        kc = carlson_rf(0.0, mp, 1.0)
        va2 = ca2 - mp  # (v / 2)^2 at the impact
        if va2 < 0.0:
            va2 = 0.0
        u_a = cosa2 / kk * carlson_rf(va2 / k2, ca2, 1.0)
        if q == 0.0 and v > 0.0:  # just after an impact (or lift-off): the exact symmetric half cycle
            u_s = u_a
            v_imp = v
        else:
            u_s = math.cos(0.5 * phi) / kk * carlson_rf(0.25 * v * v / k2, sp * sp, 1.0)
            if v < 0.0:
                u_s = 2.0 * kc - u_s
            v_imp = 2.0 * math.sqrt(va2)
        t_pk = tau + (kc - u_s)
        t_imp = max(tau + (2.0 * kc - u_a - u_s), tau)
        q_m = alpha - 2.0 * math.asin(math.sqrt(mp))
        peak_ahead = v > 0.0
        t_stop = min(t_imp, tau_end)
        # samples in this half cycle, marched from the last exact state (the start, then the peak)
        ta, qa, vb, nx = tau, q, v, -1
        at_peak = False
        while ie < m and tau_eval[ie] <= t_stop:
            tt = tau_eval[ie]
            if peak_ahead and not at_peak and tt >= t_pk:
                ta, qa, vb, nx = t_pk, q_m, 0.0, -1
                at_peak = True
            qs, vs, ta, qa, vb, nx = march(alpha, ta, qa, vb, nx, tt, A, S, C)
            th_eval[ie] = s * qs
            w_eval[ie] = s * vs
            ie += 1
        if peak_ahead and t_pk <= tau_end:
            pk, npk, max_abs = record_peak(pk, npk, summ, t_pk, s * q_m, max_abs)
        if t_imp > tau_end:  # the end time falls inside this half cycle
            if peak_ahead and not at_peak and tau_end >= t_pk:
                ta, qa, vb, nx = t_pk, q_m, 0.0, -1
            qs, vs, ta, qa, vb, nx = march(alpha, ta, qa, vb, nx, tau_end, A, S, C)
            if abs(qs) > max_abs:
                max_abs = abs(qs)
            return tau_end, s * qs, s * vs, s, False, False, False, False, ie, imp, nimp, pk, npk, max_abs, n_events
        # the impact: Housner's restitution on the exact impact velocity
        w_before = -s * v_imp
        w_after = e * w_before
        imp, nimp = record_impact(imp, nimp, summ, t_imp, w_before, w_after)
        n_events += 1
        tau = t_imp
        th = 0.0
        if abs(w_after) <= w_rest or e == 0.0:
            return tau, 0.0, 0.0, 0.0, True, False, False, False, ie, imp, nimp, pk, npk, max_abs, n_events
        w = w_after
        s = -s
        if max_impacts >= 0 and nimp >= max_impacts:
            return tau, th, w, s, False, True, False, False, ie, imp, nimp, pk, npk, max_abs, n_events
