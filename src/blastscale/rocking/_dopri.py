"""Compiled (numba) Dormand-Prince 5(4) step, dense output, root finding and step-size control.

The system is the dimensionless planar rocking equation (paper Eq. eom divided by ``m g r``,
see :mod:`blastscale.rocking.kernel`), state ``(theta [rad], w = dtheta/dtau [-])`` at the
dimensionless time ``tau = p t`` [-]:

.. math:: \\frac{d^2\\theta}{d\\tau^2} = -\\sin(\\alpha s - \\theta) + f(\\tau)\\cos(\\alpha s - \\theta),

with ``s = +-1`` the rocking mode and ``f`` the load-to-weight ratio (:mod:`._load`).

* Dormand-Prince 5(4) (Dormand & Prince 1980, J. Comput. Appl. Math. 6(1), 19-26) with the
  FSAL property; the raw local error estimate ``y5 - y4``;
* Shampine's quartic dense output (Shampine 1986, Math. Comp. 46, 135-150; the coefficients of
  scipy's ``RK45.P``);
* error control on the RMS norm ``|err_i| / (atol + rtol max(|y_i|, |y_new_i|))`` with the
  factors ``0.9 err^(-1/5)`` clipped to [0.2, 10] (Hairer, Norsett & Wanner 1993, II.4);
* the starting step of Hairer, Norsett & Wanner (1993) II.4 (scipy's ``select_initial_step``);
* event roots on the dense output by the Illinois variant of regula falsi (Dowell & Jarratt
  1971, BIT 11, 168-174).

Not a public module: use :class:`blastscale.rocking.RockingSolver`.
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import njit
from ._load import load_ratio

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


@njit(cache=True, inline="always")
def rhs(tau, th, w, s, alpha, kind, par, tab_t, tab_f):
    """Right-hand side ``(dtheta/dtau, dw/dtau)`` [-] of the rocking equation (module docstring)
    in the mode ``s`` (+-1) of a body of slenderness ``alpha`` [rad] under the encoded pulse."""
    a = alpha * s - th
    return w, -math.sin(a) + load_ratio(tau, kind, par, tab_t, tab_f) * math.cos(a)


@njit(cache=True)
def dopri_step(tau, th, w, f1a, f1b, h, s, alpha, kind, par, tab_t, tab_f, K):
    """One Dormand-Prince step of size ``h`` [-] from (th [rad], w [-]) with the first stage
    (f1a, f1b) already known (FSAL).

    Fills K (7 x 2) with the stages and returns (th_new, w_new, err_th, err_w), the error
    estimates being the raw (unscaled) local error components.
    """
    K[0, 0] = f1a
    K[0, 1] = f1b
    a, b = rhs(tau + _C2 * h, th + h * _A21 * K[0, 0], w + h * _A21 * K[0, 1], s, alpha, kind, par, tab_t, tab_f)
    K[1, 0] = a
    K[1, 1] = b
    a, b = rhs(
        tau + _C3 * h,
        th + h * (_A31 * K[0, 0] + _A32 * K[1, 0]),
        w + h * (_A31 * K[0, 1] + _A32 * K[1, 1]),
        s,
        alpha,
        kind,
        par,
        tab_t,
        tab_f,
    )
    K[2, 0] = a
    K[2, 1] = b
    a, b = rhs(
        tau + _C4 * h,
        th + h * (_A41 * K[0, 0] + _A42 * K[1, 0] + _A43 * K[2, 0]),
        w + h * (_A41 * K[0, 1] + _A42 * K[1, 1] + _A43 * K[2, 1]),
        s,
        alpha,
        kind,
        par,
        tab_t,
        tab_f,
    )
    K[3, 0] = a
    K[3, 1] = b
    a, b = rhs(
        tau + _C5 * h,
        th + h * (_A51 * K[0, 0] + _A52 * K[1, 0] + _A53 * K[2, 0] + _A54 * K[3, 0]),
        w + h * (_A51 * K[0, 1] + _A52 * K[1, 1] + _A53 * K[2, 1] + _A54 * K[3, 1]),
        s,
        alpha,
        kind,
        par,
        tab_t,
        tab_f,
    )
    K[4, 0] = a
    K[4, 1] = b
    a, b = rhs(
        tau + h,
        th + h * (_A61 * K[0, 0] + _A62 * K[1, 0] + _A63 * K[2, 0] + _A64 * K[3, 0] + _A65 * K[4, 0]),
        w + h * (_A61 * K[0, 1] + _A62 * K[1, 1] + _A63 * K[2, 1] + _A64 * K[3, 1] + _A65 * K[4, 1]),
        s,
        alpha,
        kind,
        par,
        tab_t,
        tab_f,
    )
    K[5, 0] = a
    K[5, 1] = b
    thn = th + h * (_B1 * K[0, 0] + _B3 * K[2, 0] + _B4 * K[3, 0] + _B5 * K[4, 0] + _B6 * K[5, 0])
    wn = w + h * (_B1 * K[0, 1] + _B3 * K[2, 1] + _B4 * K[3, 1] + _B5 * K[4, 1] + _B6 * K[5, 1])
    a, b = rhs(tau + h, thn, wn, s, alpha, kind, par, tab_t, tab_f)
    K[6, 0] = a
    K[6, 1] = b
    e0 = h * (_E1 * K[0, 0] + _E3 * K[2, 0] + _E4 * K[3, 0] + _E5 * K[4, 0] + _E6 * K[5, 0] + _E7 * K[6, 0])
    e1 = h * (_E1 * K[0, 1] + _E3 * K[2, 1] + _E4 * K[3, 1] + _E5 * K[4, 1] + _E6 * K[5, 1] + _E7 * K[6, 1])
    return thn, wn, e0, e1


@njit(cache=True)
def dense_coeffs(K, h, Q):
    """Q (2 x 4): y(tau_old + x h) = y_old + h * sum_j Q[c, j] x^(j+1) (Shampine's quartic)."""
    for c in range(2):
        for j in range(4):
            acc = 0.0
            for i in range(7):
                acc += K[i, c] * _P[i, j]
            Q[c, j] = acc


@njit(cache=True)
def dense(y0, h, Q, c, x):
    """Component ``c`` (0 theta [rad], 1 w [-]) of the dense output at the fraction ``x`` of the step."""
    return y0 + h * x * (Q[c, 0] + x * (Q[c, 1] + x * (Q[c, 2] + x * Q[c, 3])))


@njit(cache=True)
def dense_root(th0, w0, h, Q, comp, offset, sign, xa, xb):
    """Root in x of sign*(y_comp(x) - offset) on [xa, xb] (values of opposite sign at ends),
    by the Illinois variant of regula falsi, to |dx| ~ 1e-15."""
    y0 = th0 if comp == 0 else w0
    fa = sign * (dense(y0, h, Q, comp, xa) - offset)
    fb = sign * (dense(y0, h, Q, comp, xb) - offset)
    if fa == 0.0:
        return xa
    if fb == 0.0:
        return xb
    side = 0
    for _ in range(200):
        xm = (xa * fb - xb * fa) / (fb - fa)
        if not (xm > xa and xm < xb):
            xm = 0.5 * (xa + xb)
        fm = sign * (dense(y0, h, Q, comp, xm) - offset)
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
def error_norm(e0, e1, th, w, thn, wn, rtol, atol):
    """RMS norm [-] of the local error (e0, e1) scaled by ``atol + rtol max(|y|, |y_new|)``."""
    s0 = atol + rtol * max(abs(th), abs(thn))
    s1 = atol + rtol * max(abs(w), abs(wn))
    return math.sqrt(0.5 * ((e0 / s0) ** 2 + (e1 / s1) ** 2))


@njit(cache=True)
def initial_step(tau, th, w, s, alpha, kind, par, tab_t, tab_f, rtol, atol):
    """Hairer, Norsett & Wanner (1993) II.4 starting step [-], as in scipy's select_initial_step."""
    f0a, f0b = rhs(tau, th, w, s, alpha, kind, par, tab_t, tab_f)
    sc0 = atol + abs(th) * rtol
    sc1 = atol + abs(w) * rtol
    d0 = math.sqrt(0.5 * ((th / sc0) ** 2 + (w / sc1) ** 2))
    d1 = math.sqrt(0.5 * ((f0a / sc0) ** 2 + (f0b / sc1) ** 2))
    if d0 < 1e-5 or d1 < 1e-5:
        h0 = 1e-6
    else:
        h0 = 0.01 * d0 / d1
    f1a, f1b = rhs(tau + h0, th + h0 * f0a, w + h0 * f0b, s, alpha, kind, par, tab_t, tab_f)
    d2 = math.sqrt(0.5 * (((f1a - f0a) / sc0) ** 2 + ((f1b - f0b) / sc1) ** 2)) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** 0.2
    return min(100.0 * h0, h1)


@njit(cache=True)
def restart_step(tau, th, w, s, alpha, kind, par, tab_t, tab_f, rtol, atol, tbp, tau_pend):
    """Step size [-] to restart with at ``tau`` (start, lift-off, impact, pulse breakpoint).

    :func:`initial_step`, at most 1/100 of the way to the next breakpoint ``tbp`` [-] while the
    pulse (ending at ``tau_pend`` [-]) acts, and at least 1e-9 of it."""
    h = initial_step(tau, th, w, s, alpha, kind, par, tab_t, tab_f, rtol, atol)
    if tau < tau_pend:
        h = min(h, 0.01 * (tbp - tau))
    # Hairer's estimate collapses for a state near zero under a large load (theta0 ~ 1e-15):
    # floor it; the error control shrinks it again where that is really needed
    return max(h, 1e-9 * (tbp - tau))


@njit(cache=True)
def rejected_step(h, err):
    """Step size [-] to retry with after a step of size ``h`` [-] failed with the error norm ``err`` (> 1 or NaN)."""
    if err != err:  # nan: shrink hard
        return h * 0.1
    return h * max(0.2, 0.9 * err**-0.2)


@njit(cache=True)
def next_step(h, err):
    """Step size [-] after an accepted step of size ``h`` [-] with the error norm ``err`` (<= 1)."""
    if err == 0.0:
        fac = 10.0
    else:
        fac = min(10.0, 0.9 * err**-0.2)
    return h * fac
