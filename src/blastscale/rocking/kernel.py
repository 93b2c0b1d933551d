"""Compiled (numba) integrator of the dimensionless planar rocking equation.

Everything here works on plain floats and arrays in *dimensionless* time ``tau = p t``
(``p = sqrt(m g r / J_o)``, Housner's frequency parameter for a rectangular block), with
state ``(theta, w = dtheta/dtau)``:

.. math:: \\frac{d^2\\theta}{d\\tau^2} = -\\sin(\\alpha s - \\theta) + f(\\tau)\\cos(\\alpha s - \\theta),

where ``s = +1`` / ``-1`` is the rocking mode (pivot on the rear / front edge), held constant
between impacts, and ``f`` is the load-to-weight ratio (``S P l / (m g r cos(alpha))``;
``S P / (m g)`` for a rectangular block). This is paper Eq. (eq:eom) divided by ``m g r``.
Working in dimensionless time makes the solver's step sequence scale-free, so a reduced-scale
model with an impulsive load reproduces its prototype to round-off.

Integrator: Dormand-Prince 5(4) (Dormand & Prince 1980) with Shampine's quartic dense output
(the coefficients of scipy's ``RK45``), standard error control on the RMS norm
``|err_i| / (atol + rtol max(|y_i|, |y_new_i|))``. Steps never cross a pulse breakpoint
(pulse end, table points). Events (impact ``theta = 0``, peak ``w = 0``, tipping
``|theta| = alpha``, lying down ``|theta| = pi/2``) are located by Illinois regula falsi on the
dense output; an impact is then reached by one exact Runge-Kutta step to the located time.

Pulse codes (0 none, 1 Friedlander, 2 triangular, 3 tabulated): :mod:`._load`.

Where no step-by-step history is recorded (``record`` False: batches), a piece of the pulse where no
event can fall is crossed in one Taylor expansion (:mod:`._series`), and once the pulse is over the
free rocking is followed event by event in closed form (:mod:`._free`); what they do not cover goes
to the steps.

Modules: this one holds the driver (:func:`solve_case`, releases the GIL; the loop of a batch over
it, ``solve_into``, is in :mod:`._batch`); :mod:`._load` the pulse load
``f(tau)``; :mod:`._dopri` the Dormand-Prince step, dense output, roots and step-size control;
:mod:`._events` the impact, peak, tipping and lying-down events, the summary layout (``S_*``,
``N_SUMMARY``) and the recording into the output
buffers; :mod:`._batch` splits a batch over threads. ``rhs`` and ``load_ratio`` are inlined into the
step by numba (``inline="always"``: 1.6x faster per step, bitwise the same).
Every ``@njit(cache=True)`` here goes through :mod:`blastscale._jit`: its cache is keyed on this
file and every module it imports (``_load``, ``_dopri``, ``_events``, ``_free``, ``_series``), so an
edited helper is never run from stale machine code.

Not a public module: use :class:`blastscale.rocking.RockingSolver`.
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import njit
from ._dopri import dense, dense_coeffs, dopri_step, error_norm, next_step, rejected_step, restart_step, rhs
from ._events import (
    EV_IMPACT,
    EV_LYING,
    EV_NONE,
    EV_TIPPED,
    HALF_PI,
    impact,
    initial_mode,
    locate_events,
    record_impact,
    record_peak,
    record_row,
    sample_after_end,
    sample_rest,
    sample_step,
    starts_overturned,
    write_summary,
)
from ._free import N_MAX, free_rocking
from ._load import lift_time, next_breakpoint, pull_end, pulse_end, tail_lift_time
from ._series import pulse_piece
from .layout import N_SUMMARY, S_OVERTURN_TAU, S_W_AT_ALPHA

# the summary layout (S_*, N_SUMMARY) lives in ._events, read there by the solver, the first swing and the batch
__all__ = ["solve_case"]


@njit(cache=True, nogil=True)
def solve_case(
    alpha,
    e,
    th0,
    w0,
    tau_end,
    kind,
    par,
    tab_t,
    tab_f,
    tau_eval,
    rtol,
    atol,
    w_rest,
    max_impacts,
    stop_at_overturn,
    max_steps,
    record,
):
    """Integrate one case; see the module docstring for the equation and the conventions.

    Parameters
    ----------
    alpha, e : float
        Slenderness [rad] and restitution on the angular velocity [-].
    th0, w0 : float
        Initial angle [rad] and angular velocity / p [-].
    tau_end : float
        Dimensionless end time [-].
    kind, par, tab_t, tab_f
        Encoded pulse (:mod:`._load`).
    tau_eval : ndarray
        Non-decreasing dimensionless sampling times [-].
    rtol, atol : float
        Tolerances of the error control [-].
    w_rest : float
        Rebound velocity / p [-] below which the body is at rest.
    max_impacts : int
        Stop after this many impacts (-1: never).
    stop_at_overturn, record : bool
        Stop at the tipping point; record the history.
    max_steps : int
        Step budget (status 1 when spent).

    Returns
    -------
    tuple
        ``(summary[N_SUMMARY], th_eval, w_eval, hist[n,3], impacts[k,3], peaks[q,2])``;
        ``hist`` rows are (tau, theta, w) at every accepted step and event (only when
        ``record``), ``impacts`` rows (tau, w_before, w_after), ``peaks`` rows (tau, theta).
    """
    summ = np.full(N_SUMMARY, np.nan)
    m = tau_eval.size
    th_eval = np.empty(m)
    w_eval = np.empty(m)
    ie = 0  # next sample to fill
    hist = np.empty((256 if record else 1, 3))
    nh = 0
    imp = np.empty((16, 3))
    nimp = 0
    pk = np.empty((16, 2))
    npk = 0
    K = np.empty((7, 2))
    Q = np.empty((2, 4))
    thr_lift = math.tan(alpha)
    tau_pend = pulse_end(kind, par, tab_t)
    tau_pull = pull_end(par)  # 0 without a negative phase

    free = not record  # closed-form free rocking (_free) where no step-by-step history is asked for
    TW = np.empty((4, N_MAX + 2))  # work arrays of the Taylor series (_free, _series)
    tbp_steps = -1.0  # the piece of the pulse left to the steps
    tau = 0.0
    th = th0
    w, s = initial_mode(th0, w0, w_rest)
    resting = s == 0.0
    overturned = False
    lying = False
    status = 0
    nsteps = 0
    nrej = 0
    max_abs = abs(th)
    h = 0.0
    need_f1 = True
    f1a = 0.0
    f1b = 0.0
    stop = False
    early = False
    if record:
        hist, nh = record_row(hist, nh, tau, th, w)
    if starts_overturned(th, w, s, alpha, tau_pend, tau_pull):
        overturned = True
        summ[S_OVERTURN_TAU] = 0.0
        summ[S_W_AT_ALPHA] = abs(w)
        if stop_at_overturn:
            stop = True
            early = True

    while tau < tau_end and not stop:
        if resting:  # until the load lifts the body off (tan(alpha) load ratio)
            tl = lift_time(tau, thr_lift, kind, par, tab_t, tab_f)
            s_lift = 1.0
            tn = tail_lift_time(tau, thr_lift, par)  # suction lifting it toward the blast (inf without)
            if tn < tl:
                tl, s_lift = tn, -1.0
            ie = sample_rest(tau_eval, ie, min(tl, tau_end), th_eval, w_eval)
            if tl >= tau_end:
                tau = tau_end
                break
            tau, th, w, s = tl, 0.0, 0.0, s_lift
            resting = False
            need_f1 = True
            h = 0.0
            if record:
                hist, nh = record_row(hist, nh, tau, 0.0, 0.0)
            continue

        if free and tau >= tau_pend and not overturned:  # the pulse is over: event-driven free rocking
            tau, th, w, s, resting, early, back, tipped, ie, imp, nimp, pk, npk, max_abs, nev = free_rocking(
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
                TW[0],
                TW[1],
                TW[2],
            )
            nsteps += nev  # one per half cycle
            free = not back
            stop = early
            overturned = tipped
            need_f1 = True
            h = 0.0
            continue

        tbp = min(next_breakpoint(tau, kind, par, tab_t), tau_end)
        if free and tbp != tbp_steps:  # this piece of the pulse in Taylor expansions (_series), where it may
            tau_n, th, w, ie = pulse_piece(
                tau,
                th,
                w,
                s,
                alpha,
                kind,
                par,
                tab_t,
                tab_f,
                tbp,
                tau_eval,
                ie,
                th_eval,
                w_eval,
                TW[0],
                TW[1],
                TW[2],
                TW[3],
            )
            nsteps += 1
            if tau_n > tau:
                tau, need_f1, h, max_abs = tau_n, True, 0.0, max(max_abs, abs(th))
            if tau == tbp:
                continue
            tbp_steps = tbp  # the steps do the rest of it
        # ---------------------------------------------------------------- one step
        if nsteps >= max_steps:
            status = 1
            break
        if need_f1:
            f1a, f1b = rhs(tau, th, w, s, alpha, kind, par, tab_t, tab_f)
            need_f1 = False
        if h <= 0.0:
            h = restart_step(tau, th, w, s, alpha, kind, par, tab_t, tab_f, rtol, atol, tbp, tau_pend)
        hit_bp = False
        if tau + h >= tbp:
            h = tbp - tau
            hit_bp = True
        if h <= 1e-15 * max(1.0, abs(tau)):
            if hit_bp:  # degenerate sliver before a breakpoint: jump onto it
                tau = tbp
                need_f1 = True
                h = 0.0
                continue
            status = 2
            break
        thn, wn, e0, e1 = dopri_step(tau, th, w, f1a, f1b, h, s, alpha, kind, par, tab_t, tab_f, K)
        err = error_norm(e0, e1, th, w, thn, wn, rtol, atol)
        nsteps += 1
        if not (err <= 1.0):
            nrej += 1
            h = rejected_step(h, err)
            continue
        taun = tbp if hit_bp else tau + h
        hstep = h  # the step actually taken (for the dense output)
        h_next = next_step(h, err)

        # ---------------------------------------------------------------- events
        dense_coeffs(K, hstep, Q)
        x_pk, x_ev, ev, xo = locate_events(tau, th, w, thn, wn, s, alpha, tau_pend, tau_pull, overturned, hstep, Q)
        if xo <= x_ev:  # passed the tipping point before any other event: overturns
            overturned = True
            summ[S_OVERTURN_TAU] = tau + xo * hstep
            summ[S_W_AT_ALPHA] = abs(dense(w, hstep, Q, 1, xo))
            if stop_at_overturn:
                x_ev = xo
                ev = EV_TIPPED
        x_cut = min(x_ev, 1.0)
        if x_pk <= x_cut:
            pk, npk, max_abs = record_peak(pk, npk, summ, tau + x_pk * hstep, dense(th, hstep, Q, 0, x_pk), max_abs)
        tcut = tau + x_cut * hstep if ev != EV_NONE else taun
        last = ev == EV_NONE and taun >= tau_end
        if ie < m and (tau_eval[ie] <= tcut or last):  # (a call only where samples fall in the step)
            ie = sample_step(tau_eval, ie, tau, th, w, hstep, Q, tcut, last, th_eval, w_eval)

        if ev == EV_NONE:
            tau = taun
            th = thn
            w = wn
            f1a = K[6, 0]
            f1b = K[6, 1]
            h = h_next
            if hit_bp:
                need_f1 = True  # the load may jump at a breakpoint
                if tau < tau_pend:
                    h = 0.0  # restart the step size on the next piece of the pulse
            if abs(th) > max_abs:
                max_abs = abs(th)
            if record:
                hist, nh = record_row(hist, nh, tau, th, w)
            continue

        # an event ends the step at x_ev
        if ev == EV_IMPACT:
            te, w_before, w_after, w, s, resting = impact(
                tau, th, w, f1a, f1b, x_ev, hstep, taun, wn, s, e, w_rest, alpha, kind, par, tab_t, tab_f, K
            )
            imp, nimp = record_impact(imp, nimp, summ, te, w_before, w_after)
            if record:
                hist, nh = record_row(hist, nh, te, 0.0, w_before)
                hist, nh = record_row(hist, nh, te, 0.0, w_after)
            # the sample exactly at the impact time (if any) was filled from the dense output
            tau = te
            th = 0.0
            need_f1 = True
            if max_impacts >= 0 and nimp >= max_impacts:
                stop = True
                early = True
            continue
        tau = tau + x_ev * hstep
        if ev == EV_LYING:
            th = s * HALF_PI
            w = 0.0
            lying = True
            max_abs = HALF_PI
            if record:
                hist, nh = record_row(hist, nh, tau, th, 0.0)
            stop = True
            continue
        # EV_TIPPED: overturned and asked to stop there
        th, w = dense(th, hstep, Q, 0, x_ev), dense(w, hstep, Q, 1, x_ev)
        if abs(th) > max_abs:
            max_abs = abs(th)
        stop = True
        early = True

    # samples after the end of the motion: at rest / lying on the side / frozen at a stop
    sample_after_end(ie, th, w, lying or resting, early or status != 0, th_eval, w_eval)
    write_summary(summ, status, overturned, max_abs, nimp, tau, nsteps, npk, th, w, nrej)
    if record and nh > 0 and hist[nh - 1, 0] < tau:
        hist, nh = record_row(hist, nh, tau, th, w)
    return summ, th_eval, w_eval, hist[:nh].copy(), imp[:nimp].copy(), pk[:npk].copy()
