"""Vectorised bracketing root finder of the capacity searches (critical loads, P-I diagram).

n increasing functions of ``u`` (``u = ln x``, x a charge, a stand-off or an impulse) are
solved together: a geometric bracket search away from a starting point, then the Illinois
variant of regula falsi (Dowell & Jarratt 1971, BIT 11, 168-174) with a bisection safeguard
and Brent's minimum step (Brent 1973, *Algorithms for Minimization without Derivatives*,
Ch. 4), to an absolute tolerance on u (a relative one on x).
"""

from __future__ import annotations

import numpy as np

__all__ = ["vector_root"]


def vector_root(evaluate, u0, ulo, uhi, xtol: float, max_iter: int = 200):
    """Roots in u of n increasing functions, evaluated together.

    ``evaluate(idx, u) -> mu`` for the cases ``idx`` at ``u``; ``u0``, ``ulo``, ``uhi`` (n,)
    the start and the search bounds. Returns ``(u_survive, u_overturn, evaluations, status)``:
    the final bracket (mu <= 0 at u_survive, > 0 at u_overturn), the number of evaluations per
    case and a status per case (0 found; 1 survives up to ``uhi``; 2 overturns down to ``ulo``).
    """
    n = u0.size
    u0 = np.clip(u0, ulo, uhi)
    f0 = evaluate(np.arange(n), u0)
    nev = np.ones(n, dtype=np.int64)
    status = np.zeros(n, dtype=np.int64)
    # bracket: step away from the start, geometrically growing, capped at the bounds
    a, fa = u0.copy(), f0.copy()  # the last point on the start's side
    b, fb = u0.copy(), f0.copy()
    up = f0 <= 0.0
    # first step: about the distance to the root (mu grows like 2 ln W near it: E ~ i^2), so a
    # good start (the impulsive closed form is exact for an impulsive pulse) gives a tight bracket
    step = np.clip(1.5 * np.abs(f0), 2.0 * xtol, 0.5)
    todo = np.ones(n, dtype=bool)
    while np.any(todo):
        idx = np.flatnonzero(todo)
        bound = np.where(up[idx], uhi[idx], ulo[idx])
        at_bound = np.where(up[idx], a[idx] >= uhi[idx], a[idx] <= ulo[idx])
        if np.any(at_bound):
            status[idx[at_bound]] = np.where(up[idx[at_bound]], 1, 2)
            todo[idx[at_bound]] = False
            idx, bound = idx[~at_bound], bound[~at_bound]
            if idx.size == 0:
                break
        un = np.where(up[idx], np.minimum(a[idx] + step[idx], bound), np.maximum(a[idx] - step[idx], bound))
        fn = evaluate(idx, un)
        nev[idx] += 1
        changed = (fn > 0.0) != (fa[idx] > 0.0)
        b[idx], fb[idx] = un, fn
        keep = idx[~changed]
        a[keep], fa[keep] = un[~changed], fn[~changed]
        step[keep] *= 3.0
        todo[idx[changed]] = False
    ok = status == 0
    # order each bracket as (survive, overturn)
    lo = np.where(fa <= 0.0, a, b)
    flo = np.where(fa <= 0.0, fa, fb)
    hi = np.where(fa <= 0.0, b, a)
    fhi = np.where(fa <= 0.0, fb, fa)
    side = np.zeros(n, dtype=np.int64)  # Illinois: which end was kept last (-1 lo, +1 hi)
    width0 = np.abs(hi - lo)
    act = ok & (np.abs(hi - lo) > xtol)
    it = 0
    while np.any(act) and it < max_iter:
        it += 1
        idx = np.flatnonzero(act)
        l, h, fl, fh = lo[idx], hi[idx], flo[idx], fhi[idx]
        x = (l * fh - h * fl) / (fh - fl)
        # bisection safeguard every third iteration without halving, and for a degenerate secant
        bis = (it % 3 == 0) & (np.abs(h - l) > 0.5 * width0[idx])
        bad = ~np.isfinite(x) | (x <= np.minimum(l, h)) | (x >= np.maximum(l, h)) | bis
        x = np.where(bad, 0.5 * (l + h), x)
        # at least 0.4 xtol from either end (as Brent's method): once one end sits on the root,
        # the next point lands beyond it and closes the bracket instead of creeping along
        a_, b_ = np.minimum(l, h) + 0.4 * xtol, np.maximum(l, h) - 0.4 * xtol
        x = np.where(a_ < b_, np.clip(x, a_, b_), x)
        if it % 3 == 0:
            width0[idx] = np.abs(h - l)
        fx = evaluate(idx, x)
        nev[idx] += 1
        surv = fx <= 0.0
        i_s, i_o = idx[surv], idx[~surv]
        lo[i_s], flo[i_s] = x[surv], fx[surv]
        fhi[i_s] = np.where(side[i_s] == -1, 0.5 * fhi[i_s], fhi[i_s])
        side[i_s] = -1
        hi[i_o], fhi[i_o] = x[~surv], fx[~surv]
        flo[i_o] = np.where(side[i_o] == 1, 0.5 * flo[i_o], flo[i_o])
        side[i_o] = 1
        act[idx] = np.abs(hi[idx] - lo[idx]) > xtol
    return lo, hi, nev, status
