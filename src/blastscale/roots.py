"""The one bracketed root finder: roots of many increasing functions of one variable, solved together.

Every search of the package that brackets a root goes through here: the inversion of the blast fits
(:mod:`blastscale.blast.inverse`: charge, stand-off or scaled distance for a given peak or impulse), the
general scaling law (:func:`blastscale.similitude.laws.solve_scaled_distance_factors`, paper Eq. 8), the
critical loads (:mod:`blastscale.rocking.critical`) and the pressure-impulse diagram
(:mod:`blastscale.rocking.pressure_impulse`). Two searches keep their own bisection, each for a stated reason:
the compiled rocking kernels' suction root (``rocking._load._suction_root``: an ``@njit`` function cannot call
this numpy code) and the Friedlander decay (:func:`blastscale.blast.friedlander.friedlander_decay`: moved onto
this finder it changed decays near d = 0 by up to 1e-9 relative and tipped the series-vs-DOP853 check of the
tabulated pulse phase (tests/unit/rocking/test_free_rocking.py) past its 1e-11 bound, and its one-decay call
took 1.44x as long; measured in issue #34, kept as it was).

Method
------
n functions ``f_k(u)``, increasing in ``u`` (callers work in ``u = ln x`` for a positive x: a charge, a
stand-off, a scaled distance, an impulse, a scaled-distance factor), are solved at once:

* :func:`bracketed_root` refines given brackets ``[lo, hi]`` with ``f(lo) <= 0 <= f(hi)`` by the Illinois
  variant of regula falsi (Dowell & Jarratt 1971), with a bisection safeguard every third step that does
  not halve the bracket, and Brent's minimum step (0.4 ``xtol`` from either end; Brent 1973, ch. 4). It
  stops where ``|hi - lo| <= xtol`` or where the bracket is four spacings of double precision wide; with
  ``xtol = 0`` ("to double precision") also where f is exactly 0 at an end (a root found exactly; with
  ``xtol > 0`` the bracket is closed to ``xtol`` around it all the same).
* :func:`scalar_root` is :func:`bracketed_root` for one scalar function (any monotone sign change).
* :func:`vector_root` first finds the brackets from a starting point (geometric steps away from it,
  capped at the search bounds), then refines them as :func:`bracketed_root`.

Tolerances: absolute on u, so relative on x = e^u (``xtol`` = 1e-9: x to 1e-9 relative).

References
----------
.. [1] Dowell, M. & Jarratt, P. (1971). A modified regula falsi method for computing the root of an
   equation. BIT 11, 168-174. doi:10.1007/BF01934364
.. [2] Brent, R. P. (1973). *Algorithms for Minimization without Derivatives*, ch. 4. Prentice-Hall.
"""

from __future__ import annotations

import numpy as np

__all__ = ["bracketed_root", "vector_root", "root_of_bracket", "scalar_root"]


def bracketed_root(evaluate, lo, hi, flo, fhi, xtol: float = 0.0, max_iter: int = 200):
    """Refine the brackets of n increasing functions, evaluated together (Illinois regula falsi).

    Parameters
    ----------
    evaluate : callable
        ``evaluate(idx, u) -> f`` for the cases ``idx`` (int array) at the points ``u`` (same size).
    lo, hi : ndarray (n,)
        Bracket ends with ``flo <= 0`` at ``lo`` and ``fhi >= 0`` at ``hi`` (``lo`` may be above ``hi``:
        the function then decreases from ``lo`` to ``hi``; the sign convention is what matters).
    flo, fhi : ndarray (n,)
        The function at ``lo`` and ``hi``.
    xtol : float
        Absolute tolerance on u [units of u], >= 0; 0 refines to the resolution of double precision (and
        stops at an exact zero of f).
    max_iter : int
        Most refinement steps.

    Returns
    -------
    (lo, hi, flo, fhi, evaluations) : tuple of ndarray
        The final brackets (the inputs are not modified), the function at their ends and the number of
        evaluations per case. :func:`root_of_bracket` turns them into one point per case.
    """
    lo, hi = np.array(lo, dtype=float), np.array(hi, dtype=float)
    flo, fhi = np.array(flo, dtype=float), np.array(fhi, dtype=float)
    n = lo.size
    nev = np.zeros(n, dtype=np.int64)
    side = np.zeros(n, dtype=np.int64)  # Illinois: which end was kept last (-1 lo, +1 hi)
    width0 = np.abs(hi - lo)

    def open_(idx):
        w = np.abs(hi[idx] - lo[idx])
        live = (w > xtol) & (w > 4.0 * np.spacing(np.maximum(np.abs(lo[idx]), np.abs(hi[idx]))))
        return live & (flo[idx] != 0.0) & (fhi[idx] != 0.0) if xtol == 0.0 else live

    act = open_(np.arange(n))
    it = 0
    while np.any(act) and it < max_iter:
        it += 1
        idx = np.flatnonzero(act)
        l, h, fl, fh = lo[idx], hi[idx], flo[idx], fhi[idx]
        with np.errstate(invalid="ignore", divide="ignore"):
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
        below = fx <= 0.0
        i_s, i_o = idx[below], idx[~below]
        lo[i_s], flo[i_s] = x[below], fx[below]
        fhi[i_s] = np.where(side[i_s] == -1, 0.5 * fhi[i_s], fhi[i_s])
        side[i_s] = -1
        hi[i_o], fhi[i_o] = x[~below], fx[~below]
        flo[i_o] = np.where(side[i_o] == 1, 0.5 * flo[i_o], flo[i_o])
        side[i_o] = 1
        act[idx] = open_(idx)
    return lo, hi, flo, fhi, nev


def root_of_bracket(lo, hi, flo, fhi):
    """One point per bracket of :func:`bracketed_root`: an end where the function is exactly 0 there,
    else the middle (within half the final bracket of the root)."""
    return np.where(flo == 0.0, lo, np.where(fhi == 0.0, hi, 0.5 * (lo + hi)))


def vector_root(evaluate, u0, ulo, uhi, xtol: float, max_iter: int = 200):
    """Roots in u of n increasing functions, evaluated together, searched from a start.

    Parameters
    ----------
    evaluate : callable
        ``evaluate(idx, u) -> f`` for the cases ``idx`` at ``u``.
    u0, ulo, uhi : ndarray (n,)
        The start and the search bounds (the start is clipped to them).
    xtol : float
        Absolute tolerance on u, > 0.
    max_iter : int
        Most refinement steps (:func:`bracketed_root`).

    Returns
    -------
    (u_below, u_above, evaluations, status) : tuple of ndarray
        The final bracket (f <= 0 at ``u_below``, > 0 at ``u_above``), the number of evaluations per
        case and a status per case (0 found; 1 f <= 0 up to ``uhi``; 2 f > 0 down to ``ulo``).
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
    # first step: about the distance to the root (the rocking margin grows like 2 ln W near it: E ~ i^2),
    # so a good start (the impulsive closed form is exact for an impulsive pulse) gives a tight bracket
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
    # order each bracket as (f <= 0, f > 0)
    lo = np.where(fa <= 0.0, a, b)
    flo = np.where(fa <= 0.0, fa, fb)
    hi = np.where(fa <= 0.0, b, a)
    fhi = np.where(fa <= 0.0, fb, fa)
    idx = np.flatnonzero(ok)
    if idx.size:

        def sub(j, u):
            return evaluate(idx[j], u)

        lo[idx], hi[idx], _, _, more = bracketed_root(sub, lo[idx], hi[idx], flo[idx], fhi[idx], xtol, max_iter)
        nev[idx] += more
    return lo, hi, nev, status


def scalar_root(f, a: float, b: float, xtol: float = 0.0) -> float:
    """The root of one scalar function ``f(u) -> float`` that changes sign between ``a`` and ``b`` (either way:
    the end where f <= 0 is taken as ``lo``), refined by :func:`bracketed_root` to ``xtol`` (0: double
    precision). Raises ValueError when f has the same strict sign at both ends."""
    fa, fb = float(f(a)), float(f(b))
    if fa > 0.0 and fb > 0.0 or fa < 0.0 and fb < 0.0:
        raise ValueError(f"no sign change of f between {a!r} ({fa!r}) and {b!r} ({fb!r})")
    lo, hi, flo, fhi = (a, b, fa, fb) if fa <= 0.0 <= fb else (b, a, fb, fa)

    def evaluate(idx, u):
        return np.array([float(f(float(u[0])))])

    out = bracketed_root(evaluate, np.array([lo]), np.array([hi]), np.array([flo]), np.array([fhi]), xtol)
    return float(root_of_bracket(*out[:4])[0])
