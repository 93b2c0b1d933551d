"""Compiled (numba) events of the rocking kernel and the recording into its output buffers.

Everything is in the dimensionless time ``tau = p t`` [-] with the state ``(theta [rad],
w = dtheta/dtau [-])`` and the rocking mode ``s`` (+1 pivot on the rear edge, -1 on the front
edge, 0 at rest) of :mod:`blastscale.rocking.kernel`. The events of one accepted step are
located on its dense output (:func:`._dopri.dense`) as fractions ``x`` of the step:

* peak (a local maximum of |theta|): ``s w`` goes from > 0 to <= 0;
* impact: ``s theta`` goes below 0; the angular velocity is then multiplied by the restitution
  ``e`` and the pivot changes (Housner 1963, Bull. Seismol. Soc. Am. 53(2), Eq. 8; paper Sec.
  "Equations of motion"), or the body comes to rest below the rest velocity;
* tipping point: ``|theta|`` crosses ``alpha`` outward (the centre of mass over the pivot);
* lying on the side after overturning: ``|theta| = pi/2``.

Not a public module: use :class:`blastscale.rocking.RockingSolver`.
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import njit
from ._dopri import dense, dense_root, dopri_step
from .layout import (
    S_END_TAU,
    S_FINAL_THETA,
    S_FINAL_W,
    S_FIRST_IMPACT_TAU,
    S_FIRST_PEAK,
    S_MAX_ABS_THETA,
    S_N_IMPACTS,
    S_N_PEAKS,
    S_NREJECT,
    S_NSTEPS,
    S_OVERTURNED,
    S_STATUS,
)

# event codes of a step (the earliest one ends it)
EV_NONE = 0
EV_IMPACT = 1
EV_LYING = 2
EV_TIPPED = 3  # tipping point, with stop_at_overturn

HALF_PI = 0.5 * math.pi


# ----------------------------------------------------------------------------- state
@njit(cache=True)
def initial_mode(th, w, w_rest):
    """Starting ``(w, s)``: an upright body slower than the rest velocity ``w_rest`` [-] is at
    rest (w = 0, as after an impact); the mode ``s`` from the sign of theta, else of w (0 at rest)."""
    if th == 0.0 and abs(w) <= w_rest:
        w = 0.0
    if th > 0.0:
        s = 1.0
    elif th < 0.0:
        s = -1.0
    elif w > 0.0:
        s = 1.0
    elif w < 0.0:
        s = -1.0
    else:
        s = 0.0
    return w, s


@njit(cache=True)
def starts_overturned(th, w, s, alpha, tau_pend, tau_pull):
    """Whether an initial state beyond ``alpha`` [rad], moving outward, is already past the tipping
    point (toward the blast, s < 0, only without a pulse, ``tau_pend`` [-] <= 0: a pulse may still
    push it back over the top; away from it, s > 0, only without a negative phase to come,
    ``tau_pull`` [-] <= 0: suction may still pull it back)."""
    return abs(th) >= alpha and s * w >= 0.0 and s != 0.0 and ((s > 0.0 and tau_pull <= 0.0) or tau_pend <= 0.0)


# ----------------------------------------------------------------------------- events of a step
@njit(cache=True)
def locate_events(tau, th, w, thn, wn, s, alpha, tau_pend, tau_pull, overturned, h, Q):
    """Events of one accepted step from ``(tau, th, w)`` to ``(thn, wn)`` of size ``h`` [-]
    (dense coefficients Q), as fractions of the step.

    Returns ``(x_pk, x_ev, ev, xo)``: the peak of |theta| (2.0 when none); the earliest event
    ending the step and its code (``EV_IMPACT`` or ``EV_LYING``; 2.0 and ``EV_NONE`` when none);
    the tipping point (inf when none, or when already ``overturned``). The root finders are
    called only where a sign change brackets an event (most steps have none).
    """
    x_pk = 2.0
    if s * w > 0.0 and s * wn <= 0.0:  # peak: s w goes from > 0 to <= 0
        x_pk = dense_root(th, w, h, Q, 1, 0.0, s, 0.0, 1.0)
    x_ev = 2.0
    ev = EV_NONE
    if s * thn < 0.0:  # impact: s theta goes below 0
        x_ev = impact_fraction(th, w, s, x_pk, h, Q)
        ev = EV_IMPACT
    if s * thn >= HALF_PI:  # lying on the side (after overturning): |theta| = pi/2
        xl = dense_root(th, w, h, Q, 0, s * HALF_PI, s, 0.0, 1.0)
        if xl < x_ev:
            x_ev = xl
            ev = EV_LYING
    xo = np.inf
    # tipping point: |theta| crosses alpha outward. Toward the blast (s < 0) only in a step that
    # starts once the pulse is over (steps never cross the pulse end): while the load acts it
    # pushes the body back and a crossing of -alpha decides nothing; away from it (s > 0) likewise
    # while a negative phase (ending at tau_pull, 0 without one) may still pull it back.
    if not overturned and s * thn >= alpha and ((s > 0.0 and tau >= tau_pull) or tau >= tau_pend):
        xo = tipping_fraction(th, w, s, alpha, h, Q)
    return x_pk, x_ev, ev, xo


@njit(cache=True)
def impact_fraction(th, w, s, x_pk, h, Q):
    """Fraction of a step in which ``s theta`` goes below 0 at which the impact occurs.

    ``x_pk`` (the peak of |theta| in the step, 2.0 when none) starts the search past the peak
    when the whole excursion lies inside the step."""
    xa = 0.0
    if s * th <= 0.0:  # the whole excursion lies inside this step: start past the peak
        xa = x_pk if x_pk <= 1.0 else 0.5
        if s * dense(th, h, Q, 0, xa) <= 0.0:
            xa = 0.0
    if s * dense(th, h, Q, 0, xa) > 0.0:
        return dense_root(th, w, h, Q, 0, 0.0, s, xa, 1.0)
    return 1.0  # cannot bracket (tiny excursion below round-off): impact at the step end


@njit(cache=True)
def tipping_fraction(th, w, s, alpha, h, Q):
    """Fraction of a step in which ``s theta`` reaches ``alpha`` [rad] at which the body passes
    its tipping point for good; inf when it does not.

    A body already past the top at the start of the step and moving back inward (the
    stabilising load has just ended) overturns unless its kinetic energy lifts it back over the
    top: ``w^2 / 2 > 1 - cos(s theta - alpha)`` (energy in units of ``m g r``)."""
    if s * th < alpha:
        xo = dense_root(th, w, h, Q, 0, s * alpha, s, 0.0, 1.0)
    else:
        xo = 0.0
    if s * th >= alpha and s * w < 0.0:
        if 0.5 * w * w > 1.0 - math.cos(s * th - alpha):
            return np.inf
    return xo


@njit(cache=True)
def impact(tau, th, w, f1a, f1b, x_ev, h, taun, wn, s, e, w_rest, alpha, kind, par, tab_t, tab_f, K):
    """The impact located at the fraction ``x_ev`` of the step of size ``h`` [-] from
    ``(tau, th, w)``: ``(tau_impact, w_before, w_after, w, s, resting)`` [-].

    The impact is reached by one exact Runge-Kutta step (overwrites K; at the step end, ``x_ev =
    1``, it is the step's own end ``(taun, wn)``). Housner's restitution (1963, Eq. 8) then
    multiplies the angular velocity by ``e`` [-], ``w_after = e w_before``, and the pivot
    changes (``s -> -s``); the body is at rest (w = 0, s = 0) where ``|w_after| <= w_rest`` [-]
    or ``e = 0``."""
    if x_ev < 1.0:
        te = tau + x_ev * h
        _thi, w_before, _e0, _e1 = dopri_step(tau, th, w, f1a, f1b, te - tau, s, alpha, kind, par, tab_t, tab_f, K)
    else:
        te = taun
        w_before = wn
    w_after = e * w_before
    if abs(w_after) <= w_rest or e == 0.0:
        return te, w_before, w_after, 0.0, 0.0, True
    return te, w_before, w_after, w_after, -s, False


# ----------------------------------------------------------------------------- recording
@njit(cache=True)
def grow(buf, n):
    """``buf`` (rows, cols) with room for row ``n``: itself, or a copy about twice as long."""
    if n < buf.shape[0]:
        return buf
    nb = np.empty((2 * buf.shape[0] + 16, buf.shape[1]))
    for i in range(buf.shape[0]):  # plain loops: a slice assignment here cost ~3 s of compile time
        for j in range(buf.shape[1]):
            nb[i, j] = buf[i, j]
    return nb


@njit(cache=True)
def record_row(hist, nh, tau, th, w):
    """Append the row (tau [-], theta [rad], w [-]) to the history ``hist`` (or any 3-column
    record: the impacts); returns ``(hist, nh + 1)``."""
    hist = grow(hist, nh)
    hist[nh, 0] = tau
    hist[nh, 1] = th
    hist[nh, 2] = w
    return hist, nh + 1


@njit(cache=True)
def record_peak(pk, npk, summ, tpk, thpk, max_abs):
    """Append the peak (tau [-], theta [rad]), the first one's |theta| into the summary; returns
    ``(pk, npk + 1, max |theta| so far)``."""
    pk = grow(pk, npk)
    pk[npk, 0] = tpk
    pk[npk, 1] = thpk
    npk += 1
    if npk == 1:
        summ[S_FIRST_PEAK] = abs(thpk)
    if abs(thpk) > max_abs:
        max_abs = abs(thpk)
    return pk, npk, max_abs


@njit(cache=True)
def record_impact(imp, nimp, summ, te, w_before, w_after):
    """Append the impact (tau [-], w before, w after [-]), the first one's time into the summary;
    returns ``(imp, nimp + 1)``."""
    if nimp == 0:
        summ[S_FIRST_IMPACT_TAU] = te
    return record_row(imp, nimp, te, w_before, w_after)


@njit(cache=True)
def sample_rest(tau_eval, ie, tnext, th_eval, w_eval):
    """Samples up to ``tnext`` [-] of a body at rest (0, 0); returns the next sample index."""
    m = tau_eval.size
    while ie < m and tau_eval[ie] <= tnext:
        th_eval[ie] = 0.0
        w_eval[ie] = 0.0
        ie += 1
    return ie


@njit(cache=True)
def sample_step(tau_eval, ie, tau, th, w, h, Q, tcut, last, th_eval, w_eval):
    """Samples inside the step from ``(tau, th, w)`` of size ``h`` [-] up to ``tcut`` [-] (all the
    rest with ``last``: round-off beyond the end time), from the dense output; returns the next
    sample index."""
    m = tau_eval.size
    while ie < m and (tau_eval[ie] <= tcut or last):
        x = (tau_eval[ie] - tau) / h
        if x < 0.0:
            x = 0.0
        if x > 1.0:
            x = 1.0
        th_eval[ie] = dense(th, h, Q, 0, x)
        w_eval[ie] = dense(w, h, Q, 1, x)
        ie += 1
    return ie


@njit(cache=True)
def sample_after_end(ie, th, w, held, stopped, th_eval, w_eval):
    """Samples after the end of the motion: ``(th, 0)`` where ``held`` (at rest or lying on the
    side), NaN where ``stopped`` (an early stop or a solver failure), else the final state."""
    m = th_eval.size
    while ie < m:
        if held:
            th_eval[ie] = th
            w_eval[ie] = 0.0
        elif stopped:
            th_eval[ie] = np.nan
            w_eval[ie] = np.nan
        else:  # round-off beyond the end time
            th_eval[ie] = th
            w_eval[ie] = w
        ie += 1


@njit(cache=True)
def write_summary(summ, status, overturned, max_abs, nimp, tau, nsteps, npk, th, w, nrej):
    """Fill the scalar results of ``summ`` (layout ``S_*``; the event times are written as they occur)."""
    summ[S_STATUS] = status
    summ[S_OVERTURNED] = 1.0 if overturned else 0.0
    summ[S_MAX_ABS_THETA] = max_abs
    summ[S_N_IMPACTS] = nimp
    summ[S_END_TAU] = tau
    summ[S_NSTEPS] = nsteps
    summ[S_N_PEAKS] = npk
    summ[S_FINAL_THETA] = th
    summ[S_FINAL_W] = w
    summ[S_NREJECT] = nrej
