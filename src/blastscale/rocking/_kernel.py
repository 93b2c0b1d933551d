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

Pulse codes: 0 no pressure (impulsive loads enter as an initial velocity), 1 Friedlander
``par = (f0, tau_o, d)``, 2 triangular ``par = (f0, tau_d, 0)``, 3 tabulated (``tab_t``
[dimensionless time], ``tab_f`` [load ratio], linear in between).

Not a public module: use :class:`blastscale.rocking.RockingSolver`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

# summary vector layout (float64), shared with solver.py
S_STATUS = 0  # 0 ok, 1 step limit reached, 2 step size underflow
S_OVERTURNED = 1
S_OVERTURN_TAU = 2  # nan when none
S_FIRST_IMPACT_TAU = 3  # nan when none
S_MAX_ABS_THETA = 4
S_N_IMPACTS = 5
S_END_TAU = 6  # end of the simulated motion (t_end, lying-down time, or stop)
S_NSTEPS = 7
S_W_AT_ALPHA = 8  # |w| when |theta| crossed alpha (overturn), nan otherwise
S_N_PEAKS = 9
S_FINAL_THETA = 10
S_FINAL_W = 11
S_NREJECT = 12
S_FIRST_PEAK = 13  # |theta| at the first peak (nan if none)
N_SUMMARY = 14

# Dormand-Prince 5(4) tableau
_C2, _C3, _C4, _C5 = 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0
_A21 = 1.0 / 5.0
_A31, _A32 = 3.0 / 40.0, 9.0 / 40.0
_A41, _A42, _A43 = 44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0
_A51, _A52, _A53, _A54 = 19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0
_A61, _A62, _A63, _A64, _A65 = 9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0
_B1, _B3, _B4, _B5, _B6 = 35.0 / 384.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0
_E1, _E3, _E4, _E5, _E6, _E7 = (
    -71.0 / 57600.0,
    71.0 / 16695.0,
    -71.0 / 1920.0,
    17253.0 / 339200.0,
    -22.0 / 525.0,
    1.0 / 40.0,
)
# Shampine's dense output (scipy RK45.P), rows = stages 1..7 (stage 2 is zero)
_P = np.array(
    [
        [1.0, -8048581381.0 / 2820520608.0, 8663915743.0 / 2820520608.0, -12715105075.0 / 11282082432.0],
        [0.0, 0.0, 0.0, 0.0],
        [0.0, 131558114200.0 / 32700410799.0, -68118460800.0 / 10900136933.0, 87487479700.0 / 32700410799.0],
        [0.0, -1754552775.0 / 470086768.0, 14199869525.0 / 1410260304.0, -10690763975.0 / 1880347072.0],
        [0.0, 127303824393.0 / 49829197408.0, -318862633887.0 / 49829197408.0, 701980252875.0 / 199316789632.0],
        [0.0, -282668133.0 / 205662961.0, 2019193451.0 / 616988883.0, -1453857185.0 / 822651844.0],
        [0.0, 40617522.0 / 29380423.0, -110615467.0 / 29380423.0, 69997945.0 / 29380423.0],
    ]
)

HALF_PI = 0.5 * math.pi


@njit(cache=True)
def _load(tau, kind, par, tab_t, tab_f):
    """Load-to-weight ratio f(tau) [-]."""
    if kind == 1:
        x = tau / par[1]
        if x < 0.0 or x > 1.0:
            return 0.0
        return par[0] * (1.0 - x) * math.exp(-par[2] * x)
    if kind == 2:
        x = tau / par[1]
        if x < 0.0 or x > 1.0:
            return 0.0
        return par[0] * (1.0 - x)
    if kind == 3:
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
def _pulse_end(kind, par, tab_t):
    if kind == 1 or kind == 2:
        return par[1]
    if kind == 3:
        return tab_t[tab_t.size - 1]
    return 0.0


@njit(cache=True)
def _next_breakpoint(tau, kind, par, tab_t):
    """First breakpoint strictly after tau (inf when none)."""
    if kind == 1 or kind == 2:
        if tau < par[1]:
            return par[1]
        return np.inf
    if kind == 3:
        j = np.searchsorted(tab_t, tau, side="right")
        if j < tab_t.size:
            return tab_t[j]
        return np.inf
    return np.inf


@njit(cache=True)
def _lift_time(tau, thr, kind, par, tab_t, tab_f):
    """First time >= tau at which f > thr (the block at rest lifts off); inf if never."""
    if kind == 1 or kind == 2:  # monotone decreasing pulses
        if tau <= par[1] and _load(tau, kind, par, tab_t, tab_f) > thr:
            return tau
        return np.inf
    if kind == 3:
        if _load(tau, kind, par, tab_t, tab_f) > thr:
            return tau
        n = tab_t.size
        j = np.searchsorted(tab_t, tau, side="right") - 1
        if j < 0:
            j = 0
        while j < n - 1:
            t0 = max(tau, tab_t[j])
            f0 = _load(t0, kind, par, tab_t, tab_f)
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


@njit(cache=True)
def _rhs(tau, th, w, s, alpha, kind, par, tab_t, tab_f):
    a = alpha * s - th
    return w, -math.sin(a) + _load(tau, kind, par, tab_t, tab_f) * math.cos(a)


@njit(cache=True)
def _step(tau, th, w, f1a, f1b, h, s, alpha, kind, par, tab_t, tab_f, K):
    """One Dormand-Prince step from (th, w) with first stage (f1a, f1b) already known.

    Fills K (7 x 2) with the stages and returns (th_new, w_new, err_th, err_w), the error
    estimates being the raw (unscaled) local error components.
    """
    K[0, 0] = f1a
    K[0, 1] = f1b
    a, b = _rhs(tau + _C2 * h, th + h * _A21 * K[0, 0], w + h * _A21 * K[0, 1], s, alpha, kind, par, tab_t, tab_f)
    K[1, 0] = a
    K[1, 1] = b
    a, b = _rhs(
        tau + _C3 * h,
        th + h * (_A31 * K[0, 0] + _A32 * K[1, 0]),
        w + h * (_A31 * K[0, 1] + _A32 * K[1, 1]),
        s, alpha, kind, par, tab_t, tab_f,
    )
    K[2, 0] = a
    K[2, 1] = b
    a, b = _rhs(
        tau + _C4 * h,
        th + h * (_A41 * K[0, 0] + _A42 * K[1, 0] + _A43 * K[2, 0]),
        w + h * (_A41 * K[0, 1] + _A42 * K[1, 1] + _A43 * K[2, 1]),
        s, alpha, kind, par, tab_t, tab_f,
    )
    K[3, 0] = a
    K[3, 1] = b
    a, b = _rhs(
        tau + _C5 * h,
        th + h * (_A51 * K[0, 0] + _A52 * K[1, 0] + _A53 * K[2, 0] + _A54 * K[3, 0]),
        w + h * (_A51 * K[0, 1] + _A52 * K[1, 1] + _A53 * K[2, 1] + _A54 * K[3, 1]),
        s, alpha, kind, par, tab_t, tab_f,
    )
    K[4, 0] = a
    K[4, 1] = b
    a, b = _rhs(
        tau + h,
        th + h * (_A61 * K[0, 0] + _A62 * K[1, 0] + _A63 * K[2, 0] + _A64 * K[3, 0] + _A65 * K[4, 0]),
        w + h * (_A61 * K[0, 1] + _A62 * K[1, 1] + _A63 * K[2, 1] + _A64 * K[3, 1] + _A65 * K[4, 1]),
        s, alpha, kind, par, tab_t, tab_f,
    )
    K[5, 0] = a
    K[5, 1] = b
    thn = th + h * (_B1 * K[0, 0] + _B3 * K[2, 0] + _B4 * K[3, 0] + _B5 * K[4, 0] + _B6 * K[5, 0])
    wn = w + h * (_B1 * K[0, 1] + _B3 * K[2, 1] + _B4 * K[3, 1] + _B5 * K[4, 1] + _B6 * K[5, 1])
    a, b = _rhs(tau + h, thn, wn, s, alpha, kind, par, tab_t, tab_f)
    K[6, 0] = a
    K[6, 1] = b
    e0 = h * (_E1 * K[0, 0] + _E3 * K[2, 0] + _E4 * K[3, 0] + _E5 * K[4, 0] + _E6 * K[5, 0] + _E7 * K[6, 0])
    e1 = h * (_E1 * K[0, 1] + _E3 * K[2, 1] + _E4 * K[3, 1] + _E5 * K[4, 1] + _E6 * K[5, 1] + _E7 * K[6, 1])
    return thn, wn, e0, e1


@njit(cache=True)
def _dense_coeffs(K, h, Q):
    """Q (2 x 4): y(tau_old + x h) = y_old + h * sum_j Q[c, j] x^(j+1)."""
    for c in range(2):
        for j in range(4):
            acc = 0.0
            for i in range(7):
                acc += K[i, c] * _P[i, j]
            Q[c, j] = acc


@njit(cache=True)
def _dense(y0, h, Q, c, x):
    return y0 + h * x * (Q[c, 0] + x * (Q[c, 1] + x * (Q[c, 2] + x * Q[c, 3])))


@njit(cache=True)
def _root(th0, w0, h, Q, comp, offset, sign, xa, xb):
    """Root in x of sign*(y_comp(x) - offset) on [xa, xb] (values of opposite sign at ends),
    by the Illinois variant of regula falsi, to |dx| ~ 1e-15."""
    y0 = th0 if comp == 0 else w0
    fa = sign * (_dense(y0, h, Q, comp, xa) - offset)
    fb = sign * (_dense(y0, h, Q, comp, xb) - offset)
    if fa == 0.0:
        return xa
    if fb == 0.0:
        return xb
    side = 0
    for _ in range(200):
        xm = (xa * fb - xb * fa) / (fb - fa)
        if not (xm > xa and xm < xb):
            xm = 0.5 * (xa + xb)
        fm = sign * (_dense(y0, h, Q, comp, xm) - offset)
        if fm == 0.0:
            return xm
        if (fm > 0.0) == (fa > 0.0):
            xa = xm
            fa = fm
            if side == -1:
                fb *= 0.5
            side = -1
        else:
            xb = xm
            fb = fm
            if side == 1:
                fa *= 0.5
            side = 1
        if xb - xa <= 4e-16 * max(1.0, abs(xb)):
            break
    return 0.5 * (xa + xb)


@njit(cache=True)
def _grow(buf, n):
    if n < buf.shape[0]:
        return buf
    nb = np.empty((2 * buf.shape[0] + 16, buf.shape[1]))
    for i in range(buf.shape[0]):  # plain loops: a slice assignment here cost ~3 s of compile time
        for j in range(buf.shape[1]):
            nb[i, j] = buf[i, j]
    return nb


@njit(cache=True)
def _wnorm(e0, e1, th, w, thn, wn, rtol, atol):
    s0 = atol + rtol * max(abs(th), abs(thn))
    s1 = atol + rtol * max(abs(w), abs(wn))
    return math.sqrt(0.5 * ((e0 / s0) ** 2 + (e1 / s1) ** 2))


@njit(cache=True)
def _initial_step(tau, th, w, s, alpha, kind, par, tab_t, tab_f, rtol, atol):
    """Hairer, Norsett & Wanner (1993) II.4 starting step, as in scipy's select_initial_step."""
    f0a, f0b = _rhs(tau, th, w, s, alpha, kind, par, tab_t, tab_f)
    sc0 = atol + abs(th) * rtol
    sc1 = atol + abs(w) * rtol
    d0 = math.sqrt(0.5 * ((th / sc0) ** 2 + (w / sc1) ** 2))
    d1 = math.sqrt(0.5 * ((f0a / sc0) ** 2 + (f0b / sc1) ** 2))
    if d0 < 1e-5 or d1 < 1e-5:
        h0 = 1e-6
    else:
        h0 = 0.01 * d0 / d1
    f1a, f1b = _rhs(tau + h0, th + h0 * f0a, w + h0 * f0b, s, alpha, kind, par, tab_t, tab_f)
    d2 = math.sqrt(0.5 * (((f1a - f0a) / sc0) ** 2 + ((f1b - f0b) / sc1) ** 2)) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** 0.2
    return min(100.0 * h0, h1)


@njit(cache=True)
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

    Returns ``(summary[N_SUMMARY], th_eval, w_eval, hist[n,3], impacts[k,3], peaks[q,2])``;
    ``hist`` rows are (tau, theta, w) at every accepted step and event (only when
    ``record``), ``impacts`` rows (tau, w_before, w_after), ``peaks`` rows (tau, theta).
    """
    summ = np.full(N_SUMMARY, np.nan)
    m = tau_eval.size
    th_eval = np.empty(m)
    w_eval = np.empty(m)
    ie = 0  # next sample to fill
    cap = 256 if record else 1
    hist = np.empty((cap, 3))
    nh = 0
    imp = np.empty((16, 3))
    nimp = 0
    pk = np.empty((16, 2))
    npk = 0
    K = np.empty((7, 2))
    Q = np.empty((2, 4))
    thr_lift = math.tan(alpha)
    tau_pend = _pulse_end(kind, par, tab_t)

    tau = 0.0
    th = th0
    w = w0
    if th == 0.0 and abs(w) <= w_rest:
        w = 0.0  # upright and slower than the rest velocity (as after an impact): at rest
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
        hist[0, 0] = tau
        hist[0, 1] = th
        hist[0, 2] = w
        nh = 1
    # an initial state beyond alpha, moving outward, is already past the tipping point (toward
    # the blast, s < 0, only without a pulse: a pulse may still push it back over the top)
    if abs(th) >= alpha and s * w >= 0.0 and not resting and (s > 0.0 or tau_pend <= 0.0):
        overturned = True
        summ[S_OVERTURN_TAU] = 0.0
        summ[S_W_AT_ALPHA] = abs(w)
        if stop_at_overturn:
            stop = True
            early = True

    while tau < tau_end and not stop:
        if resting:
            tl = _lift_time(tau, thr_lift, kind, par, tab_t, tab_f)
            tnext = min(tl, tau_end)
            while ie < m and tau_eval[ie] <= tnext:
                th_eval[ie] = 0.0
                w_eval[ie] = 0.0
                ie += 1
            if tl >= tau_end:
                tau = tau_end
                break
            tau = tl
            th = 0.0
            w = 0.0
            s = 1.0
            resting = False
            need_f1 = True
            h = 0.0
            if record:
                hist = _grow(hist, nh)
                hist[nh, 0] = tau
                hist[nh, 1] = 0.0
                hist[nh, 2] = 0.0
                nh += 1
            continue

        if nsteps >= max_steps:
            status = 1
            break
        if need_f1:
            f1a, f1b = _rhs(tau, th, w, s, alpha, kind, par, tab_t, tab_f)
            need_f1 = False
        tbp = min(_next_breakpoint(tau, kind, par, tab_t), tau_end)
        if h <= 0.0:
            h = _initial_step(tau, th, w, s, alpha, kind, par, tab_t, tab_f, rtol, atol)
            if tau < tau_pend:
                h = min(h, 0.01 * (tbp - tau))
            # Hairer's estimate collapses for a state near zero under a large load (theta0 ~ 1e-15):
            # floor it; the error control shrinks it again where that is really needed
            h = max(h, 1e-9 * (tbp - tau))
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
        thn, wn, e0, e1 = _step(tau, th, w, f1a, f1b, h, s, alpha, kind, par, tab_t, tab_f, K)
        err = _wnorm(e0, e1, th, w, thn, wn, rtol, atol)
        nsteps += 1
        if not (err <= 1.0):
            nrej += 1
            if err != err:  # nan: shrink hard
                h *= 0.1
            else:
                h *= max(0.2, 0.9 * err**-0.2)
            continue
        taun = tbp if hit_bp else tau + h
        hstep = h  # the step actually taken (for the dense output)
        if err == 0.0:
            fac = 10.0
        else:
            fac = min(10.0, 0.9 * err**-0.2)
        h_next = h * fac

        # ---------------------------------------------------------------- events
        _dense_coeffs(K, hstep, Q)
        x_ev = 2.0  # earliest terminal-ish event (fraction of the step)
        ev = 0  # 1 impact, 2 lying down
        # peak (|theta| maximum): s*w goes from > 0 to <= 0
        x_pk = 2.0
        if s * w > 0.0 and s * wn <= 0.0:
            x_pk = _root(th, w, hstep, Q, 1, 0.0, s, 0.0, 1.0)
        # impact: s*theta goes below 0
        if s * thn < 0.0:
            xa = 0.0
            if s * th <= 0.0:  # the whole excursion lies inside this step: start past the peak
                xa = x_pk if x_pk <= 1.0 else 0.5
                if s * _dense(th, hstep, Q, 0, xa) <= 0.0:
                    xa = 0.0
            if s * _dense(th, hstep, Q, 0, xa) > 0.0:
                x_ev = _root(th, w, hstep, Q, 0, 0.0, s, xa, 1.0)
            else:  # cannot bracket (tiny excursion below round-off): impact at the step end
                x_ev = 1.0
            ev = 1
        # lying down on the side (after overturning): |theta| = pi/2
        if s * thn >= HALF_PI:
            xl = _root(th, w, hstep, Q, 0, s * HALF_PI, s, 0.0, 1.0)
            if xl < x_ev:
                x_ev = xl
                ev = 2
        # tipping point: |theta| crosses alpha outward. Toward the blast (s < 0) only in a step
        # that starts once the pulse is over (steps never cross the pulse end): while the load
        # acts it pushes the body back and a crossing of -alpha decides nothing.
        if not overturned and s * thn >= alpha and (s > 0.0 or tau >= tau_pend):
            if s * th < alpha:
                xo = _root(th, w, hstep, Q, 0, s * alpha, s, 0.0, 1.0)
            else:
                xo = 0.0
            tipped = True
            if s * th >= alpha and s * w < 0.0:
                # past the tipping point when the (stabilising) load ended, moving back inward:
                # it overturns unless its kinetic energy lifts it back over the top
                if 0.5 * w * w > 1.0 - math.cos(s * th - alpha):
                    tipped = False
            if xo <= x_ev and tipped:
                overturned = True
                summ[S_OVERTURN_TAU] = tau + xo * hstep
                summ[S_W_AT_ALPHA] = abs(_dense(w, hstep, Q, 1, xo))
                if stop_at_overturn:
                    x_ev = xo
                    ev = 3
        x_cut = min(x_ev, 1.0)
        if x_pk <= x_cut:
            tpk = tau + x_pk * hstep
            thpk = _dense(th, hstep, Q, 0, x_pk)
            pk = _grow(pk, npk)
            pk[npk, 0] = tpk
            pk[npk, 1] = thpk
            npk += 1
            if npk == 1:
                summ[S_FIRST_PEAK] = abs(thpk)
            if abs(thpk) > max_abs:
                max_abs = abs(thpk)
        tcut = tau + x_cut * hstep if ev != 0 else taun
        # samples inside the step
        last = ev == 0 and taun >= tau_end
        while ie < m and (tau_eval[ie] <= tcut or last):
            x = (tau_eval[ie] - tau) / hstep
            if x < 0.0:
                x = 0.0
            if x > 1.0:
                x = 1.0
            th_eval[ie] = _dense(th, hstep, Q, 0, x)
            w_eval[ie] = _dense(w, hstep, Q, 1, x)
            ie += 1

        if ev == 0:
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
                hist = _grow(hist, nh)
                hist[nh, 0] = tau
                hist[nh, 1] = th
                hist[nh, 2] = w
                nh += 1
            continue

        # an event ends the step at x_ev
        te = tau + x_ev * hstep
        if ev == 1:
            if x_ev < 1.0:
                he = te - tau
                thi, wi, _e0, _e1 = _step(tau, th, w, f1a, f1b, he, s, alpha, kind, par, tab_t, tab_f, K)
                w_before = wi
            else:
                w_before = wn
                te = taun
            w_after = e * w_before
            if nimp == 0:
                summ[S_FIRST_IMPACT_TAU] = te
            imp = _grow(imp, nimp)
            imp[nimp, 0] = te
            imp[nimp, 1] = w_before
            imp[nimp, 2] = w_after
            nimp += 1
            if record:
                hist = _grow(hist, nh + 1)
                hist[nh, 0] = te
                hist[nh, 1] = 0.0
                hist[nh, 2] = w_before
                hist[nh + 1, 0] = te
                hist[nh + 1, 1] = 0.0
                hist[nh + 1, 2] = w_after
                nh += 2
            # the sample exactly at the impact time (if any) was filled from the dense output
            tau = te
            th = 0.0
            need_f1 = True
            if abs(w_after) <= w_rest or e == 0.0:
                w = 0.0
                s = 0.0
                resting = True
            else:
                w = w_after
                s = -s
            if max_impacts >= 0 and nimp >= max_impacts:
                stop = True
                early = True
            continue
        if ev == 2:
            tau = te
            th = s * HALF_PI
            w = 0.0
            lying = True
            max_abs = HALF_PI
            if record:
                hist = _grow(hist, nh)
                hist[nh, 0] = tau
                hist[nh, 1] = th
                hist[nh, 2] = 0.0
                nh += 1
            stop = True
            continue
        # ev == 3: overturned and asked to stop there
        tau = te
        th = _dense(th, hstep, Q, 0, x_ev)
        w = _dense(w, hstep, Q, 1, x_ev)
        if abs(th) > max_abs:
            max_abs = abs(th)
        stop = True
        early = True

    # samples after the end of the motion: at rest / lying on the side / frozen at a stop
    while ie < m:
        if lying or resting:
            th_eval[ie] = th
            w_eval[ie] = 0.0
        elif early or status != 0:
            th_eval[ie] = np.nan
            w_eval[ie] = np.nan
        else:  # round-off beyond the end time
            th_eval[ie] = th
            w_eval[ie] = w
        ie += 1

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
    if record and nh > 0 and hist[nh - 1, 0] < tau:
        hist = _grow(hist, nh)
        hist[nh, 0] = tau
        hist[nh, 1] = th
        hist[nh, 2] = w
        nh += 1
    return summ, th_eval, w_eval, hist[:nh].copy(), imp[:nimp].copy(), pk[:npk].copy()


@njit(cache=True)
def solve_batch(
    alpha,
    e,
    th0,
    w0,
    tau_end,
    kind,
    par,
    tab_t,
    tab_f,
    tab_off,
    tau_eval,
    rtol,
    atol,
    w_rest,
    max_impacts,
    stop_at_overturn,
    max_steps,
    record,
):
    """Loop :func:`solve_case` over n cases (arrays of length n; ``par`` (n, 3);
    tabulated pulses concatenated in ``tab_t``/``tab_f`` with case i at
    ``tab_off[i]:tab_off[i+1]``; ``tau_eval`` (n, m)). Returns summaries (n, N_SUMMARY),
    theta (n, m) and w (n, m)."""
    n = alpha.size
    m = tau_eval.shape[1]
    summ = np.empty((n, N_SUMMARY))
    th_out = np.empty((n, m))
    w_out = np.empty((n, m))
    for i in range(n):
        tt = tab_t[tab_off[i] : tab_off[i + 1]].copy()
        tf = tab_f[tab_off[i] : tab_off[i + 1]].copy()
        te = tau_eval[i].copy()
        pr = par[i].copy()
        r = solve_case(
            alpha[i], e[i], th0[i], w0[i], tau_end[i], kind[i], pr, tt, tf, te,
            rtol, atol, w_rest, max_impacts, stop_at_overturn, max_steps, record,
        )
        for k in range(N_SUMMARY):  # plain loops: row slice assignments are slow to compile
            summ[i, k] = r[0][k]
        for k in range(m):
            th_out[i, k] = r[1][k]
            w_out[i, k] = r[2][k]
    return summ, th_out, w_out
