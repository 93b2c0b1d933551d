"""Overturning capacity: critical charge, critical stand-off, capacity curves and the P-I diagram.

First-swing energy criterion
----------------------------
Everything rests on one statement about the planar rocking equation (paper Eq. eom, divided
by ``m g r``, in the dimensionless time ``tau = p t``; see :mod:`blastscale.rocking.system`):
once the pulse is over the motion is free and conservative between impacts, with the energy

.. math:: E = \\tfrac12 \\dot\\theta^2 + \\cos(\\alpha - s\\theta) - \\cos\\alpha
          \\qquad (\\dot\\theta \\text{ in units of } p),

whose barrier (the centre of mass over the pivot, ``s theta = alpha``) is
``B = 1 - cos(alpha)`` in both rocking directions. Every impact multiplies the angular velocity
by the restitution e, hence the energy by e^2 <= 1 (Housner 1963). So, with ``(theta, theta_dot)``
the state when the pulse ends, the outcome of the whole motion is decided on the first free
swing:

* moving outward (``s theta_dot >= 0``) below the top: it overturns iff ``E > B``; otherwise
  it comes back, impacts, and every later swing has less energy than ``E <= B``;
* moving inward below the top: it impacts first; it overturns (in the other direction) iff
  ``e^2 E > B``;
* beyond the top (possible only toward the blast: the pulse pushes back, and a crossing of
  ``-alpha`` decides nothing while it acts, docs/rocking.md): moving outward it overturns;
  moving inward it overturns unless ``E > B`` (it climbs back over the top), and then the
  previous case applies;
* at rest when the pulse ends (never lifted off, or already still): it survives;
* tipped away from the blast while the pulse still acts: it has overturned (the compiled
  solver stops there; gravity and the non-negative pressure both push it on).

The pulse phase alone is integrated, with the compiled rocking kernel
(:func:`blastscale.rocking._kernel.solve_batch`, impacts included, vectorised over cases):
a pulse lasts ``p t_o ~ 1e-3..1e-1`` in dimensionless time against ``~ 1..10`` for the first
swing, so one evaluation costs a few tens of steps instead of a full simulation. The signed
*first-swing margin* ``mu`` (``> 0``: overturns) is

=========================================  =============================================
state when the pulse ends                  mu
=========================================  =============================================
tipped away during the pulse               ``E / B - 1`` (``>= 0``; the kinetic energy at the top)
below the top, outward                     ``E / B - 1``
below the top, inward                      ``e^2 E / B - 1``
beyond the top, outward                    ``(theta_dot^2 / 2 + 1 - cos(s theta - alpha)) / B``
beyond the top, inward, ``E <= B``         ``(1 - cos(s theta - alpha) - theta_dot^2 / 2) / B``
beyond the top, inward, ``E > B``          ``e^2 E / B - 1``
at rest                                    ``-1``
=========================================  =============================================

It is 0 at the threshold on the common branches and increases with the load, so the critical
load is a root of mu. The test suite checks the criterion against the bisection on full
simulations (to rest, every impact) over random blocks, stand-offs and pulse shapes.

Search
------
The root is found in ``u = ln x`` (x the charge, the stand-off or the impulse), for all the
cases of a call at once: a starting point from the structure's own scale (the impulsive closed
form ``J_o theta_dot_c = i S l`` gives the critical impulse; the blast model is inverted for
the charge or stand-off that delivers it), a geometric bracket search within the blast model's
valid range of Z, then the Illinois variant of regula falsi with a bisection safeguard to a
relative tolerance ``xtol_rel`` (default 1e-9). A case whose outcome does not change within the
range gives NaN in the curves and a one-line error in the scalar functions.

References: paper Sec. "Equations of motion" (W_pc = 79.8 kg for the 10 m block at 2 m);
Housner (1963), Bull. Seismol. Soc. Am. 53(2) (energy and restitution); Masi et al. (2019),
Int. J. Mech. Sci. 157 (critical impulse); P-I diagrams: Krauthammer, *Modern Protective
Structures* (2008), Ch. 5; Illinois method: Dowell & Jarratt (1971), BIT 11, 168-174.
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass

import numpy as np

from .._validate import BlastscaleInputError, OutOfRangeError, check_positive, check_range
from ..blast.base import ExtrapolationWarning
from ..blast.faces import _check_shape
from ..blast.parameters import DEFAULT_BLAST_MODEL, blast_parameters, get_blast_model, valid_scaled_distance_range
from ..blast.pulses import Pulse, friedlander_impulse_ratio
from . import _kernel as K
from .encoding import PULSE_CODES, encode_pulse
from .solver import DEFAULT_SOLVER, RockingSolver, check_count
from .system import RockingSystem, as_rocking_system

__all__ = [
    "overturn_margin",
    "first_swing_margin",
    "overturns",
    "first_swing",
    "first_swing_blast",
    "first_swing_peak",
    "FirstSwing",
    "critical_charge",
    "critical_standoff",
    "critical_charge_by_bisection",
    "CriticalResult",
    "capacity_curve",
    "CapacityCurve",
    "charge_for_impulse",
    "model_capacity_curve",
    "ModelCapacity",
    "pi_diagram",
    "PIDiagram",
]

# widening of the blast model's valid Z range with extrapolate=True (factor each side)
_EXTRAPOLATE_WIDENING = 5.0


# ----------------------------------------------------------------------------- criterion
def first_swing_margin(alpha, e, theta, w, tipped):
    """First-swing margin mu [-] from the state when the pulse ends (module docstring table).

    Parameters
    ----------
    alpha : array_like
        Slenderness angle [rad].
    e : array_like
        Restitution on the angular velocity [-].
    theta : array_like
        Angle when the pulse ends [rad].
    w : array_like
        Angular velocity when the pulse ends, divided by p [-].
    tipped : array_like of bool
        Whether the body tipped away from the blast while the pulse acted.

    Returns
    -------
    mu : ndarray
        > 0 where the body overturns, <= 0 where it survives.
    """
    alpha, e, th, w = (np.asarray(x, dtype=float) for x in (alpha, e, theta, w))
    s = np.sign(th)
    s = np.where(s == 0.0, np.sign(w), s)
    u = s * th  # distance from upright in the current rocking mode [rad]
    v = s * w  # outward angular velocity
    B = 1.0 - np.cos(alpha)
    E = 0.5 * w * w + np.cos(alpha - u) - np.cos(alpha)
    below = (E / B - 1.0, e * e * E / B - 1.0)
    past = 1.0 - np.cos(u - alpha)  # depth below the top once beyond it
    mu = np.where(
        u < alpha,
        np.where(v >= 0.0, below[0], below[1]),
        np.where(v >= 0.0, (0.5 * w * w + past) / B, np.where(E > B, below[1], (past - 0.5 * w * w) / B)),
    )
    mu = np.where(np.asarray(tipped, dtype=bool), np.maximum(below[0], np.finfo(float).tiny), mu)
    return np.where(s == 0.0, -1.0, mu)


def first_swing_peak(alpha, e, theta, w, pulse_max, rest_velocity: float = 0.0):
    """Largest |theta| [rad] of the whole motion of a body that survives, from the state when
    the pulse ends (first-swing energy argument, module docstring).

    After the pulse the motion is free: between impacts the energy ``E = w^2/2 + cos(alpha -
    s theta) - cos(alpha)`` is conserved and each impact multiplies it by ``e^2`` (Housner 1963),
    so every later peak is lower than the first free one. With ``y = alpha - |theta_peak|`` the
    distance of a peak below the top, ``w = 0`` there gives ``1 - cos(y) = B - E``, i.e.
    ``sin^2(y / 2) = sin^2((alpha - s theta) / 2) - w^2 / 4``, written without cancellation:

    * moving outward (below the top): the peak of this swing, ``|theta_peak| = alpha - y``;
    * moving inward (or beyond the top, climbing back over it): the body impacts with
      ``w^2 = 2 E``, rebounds with ``e w`` (at rest if ``e |w| <= rest_velocity``) and peaks on
      the other side, ``sin^2(y / 2) = sin^2(alpha / 2) - e^2 E / 2``;
    * at rest: no further peak.

    The result is the larger of that peak and ``pulse_max`` (the largest |theta| while the pulse
    acted). Where the body overturns (:func:`first_swing_margin` > 0) the value is meaningless;
    :func:`first_swing` returns pi/2 there (it ends lying on its side).

    Parameters
    ----------
    alpha, e : array_like
        Slenderness [rad] and restitution [-].
    theta, w : array_like
        Angle [rad] and angular velocity / p [-] when the pulse ends.
    pulse_max : array_like
        Largest |theta| [rad] while the pulse acted.
    rest_velocity : float
        Rebound velocity / p [-] below which the body is at rest (the solver's ``rest_velocity``).

    Returns
    -------
    ndarray
        Largest |theta| [rad] over the whole motion.
    """
    alpha, e, th, w = (np.asarray(x, dtype=float) for x in (alpha, e, theta, w))
    s = np.sign(th)
    s = np.where(s == 0.0, np.sign(w), s)
    u, v = s * th, s * w
    ha = np.sin(0.5 * alpha) ** 2  # B / 2
    r_out = np.sin(0.5 * (alpha - u)) ** 2 - 0.25 * w * w  # (B - E) / 2
    E = 2.0 * (ha - r_out)
    r_in = ha - 0.5 * e * e * E
    with np.errstate(invalid="ignore"):
        y_out = 2.0 * np.arcsin(np.sqrt(np.maximum(r_out, 0.0)))
        y_in = 2.0 * np.arcsin(np.sqrt(np.maximum(r_in, 0.0)))
    rebound = e * np.sqrt(np.maximum(2.0 * E, 0.0))
    inward_peak = np.where((rebound > rest_velocity) & (e > 0.0), alpha - y_in, 0.0)
    peak = np.where((u < alpha) & (v >= 0.0), alpha - y_out, inward_peak)
    peak = np.where(s == 0.0, 0.0, peak)
    return np.maximum(np.asarray(pulse_max, dtype=float), peak)


@dataclass(frozen=True)
class FirstSwing:
    """Outcome of n bodies at rest under n pulses, from the pulse phase and the first free swing.

    ``overturned`` (n,) bool: at any time; ``max_rotation`` (n,) [rad]: the largest |theta| of the
    whole motion (pi/2 where it overturns: it ends lying on its side); ``margin`` (n,) [-]: the
    first-swing margin mu (> 0 overturns)."""

    overturned: np.ndarray
    max_rotation: np.ndarray
    margin: np.ndarray


def _pulse_phase(solver: RockingSolver, alpha, e, w0, kind, par, tab_t=None, tab_f=None, off=None) -> FirstSwing:
    """Integrate the pulse phase of n encoded cases with the compiled kernel; the first free swing
    from there in closed form.

    ``kind`` (n,) pulse codes, ``par`` (n, 3) kernel parameters, ``w0`` (n,) initial theta_dot / p
    (the jump of an impulsive load); tabulated pulses concatenated as in ``solve_batch``.
    """
    n = kind.size
    tab_t = np.zeros(0) if tab_t is None else tab_t
    tab_f = np.zeros(0) if tab_f is None else tab_f
    off = np.zeros(n + 1, dtype=np.int64) if off is None else off
    tau_end = np.where(kind == 1, par[:, 1], np.where(kind == 2, par[:, 1], 0.0))
    if np.any(kind == 3):
        tau_end = np.where(kind == 3, tab_t[np.maximum(off[1:] - 1, 0)], tau_end)
    summ, _, _ = K.solve_batch(
        np.ascontiguousarray(alpha, dtype=float), np.ascontiguousarray(e, dtype=float), np.zeros(n),
        np.ascontiguousarray(w0, dtype=float), np.ascontiguousarray(tau_end), kind.astype(np.int64),
        np.ascontiguousarray(par), tab_t, tab_f, off, np.empty((n, 0)),
        float(solver.rtol), float(solver.atol), float(solver.rest_velocity), -1, True, int(solver.max_steps), False,
    )
    bad = summ[:, K.S_STATUS] != 0
    if np.any(bad):
        solver._check_status(summ[np.argmax(bad), K.S_STATUS], int(np.argmax(bad)))
    th, w = summ[:, K.S_FINAL_THETA], summ[:, K.S_FINAL_W]
    mu = first_swing_margin(alpha, e, th, w, summ[:, K.S_OVERTURNED] == 1.0)
    over = mu > 0.0
    peak = first_swing_peak(alpha, e, th, w, summ[:, K.S_MAX_ABS_THETA], float(solver.rest_velocity))
    return FirstSwing(over, np.where(over, 0.5 * math.pi, peak), mu)


def overturn_margin(body, pulse: Pulse, *, solver: RockingSolver | None = None, gravity=None, restitution=None) -> float:
    """First-swing overturning margin mu [-] of ``body`` at rest under ``pulse`` (module docstring).

    Parameters
    ----------
    body : RockingSystem or RectangularBlock
        The body (a block is converted with ``gravity`` [m/s^2] and ``restitution`` [-]).
    pulse : Pulse
        Pressure pulse on the loaded face from the shock arrival (any kind: Friedlander,
        triangular, impulsive, tabulated).
    solver : RockingSolver, optional
        Solver of the pulse phase (default rtol 1e-10, atol 1e-12).

    Returns
    -------
    mu : float
        > 0 iff the body overturns (0 at the threshold; in units of the potential barrier
        ``m g r (1 - cos alpha)``).
    """
    system = as_rocking_system(body, gravity, restitution)
    kind, par, tt, tf, dw = encode_pulse(pulse, system)
    off = np.array([0, tt.size], dtype=np.int64)
    fs = _pulse_phase(
        solver or DEFAULT_SOLVER, np.array([system.alpha]), np.array([system.coefficient_of_restitution]),
        np.array([dw]), np.array([kind]), par[None, :], tt, tf, off,
    )
    return float(fs.margin[0])


# ----------------------------------------------------------------------------- root finder
def _vector_root(evaluate, u0, ulo, uhi, xtol: float, max_iter: int = 200):
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


# ----------------------------------------------------------------------------- blast search
def _model_name(model) -> str:
    return model if isinstance(model, str) else getattr(model, "name", str(model))


def _z_range(model, extrapolate: bool) -> tuple[float, float]:
    zlo, zhi = valid_scaled_distance_range(model)
    if extrapolate:
        return zlo / _EXTRAPOLATE_WIDENING, zhi * _EXTRAPOLATE_WIDENING
    return zlo * (1.0 + 1e-12), zhi * (1.0 - 1e-12)


def _system_arrays(systems, n: int):
    """(alpha, e, p, q) arrays of length n from one RockingSystem (broadcast) or a sequence of n."""
    if isinstance(systems, RockingSystem):
        systems = [systems]
    vals = np.array([(s.alpha, s.coefficient_of_restitution, s.frequency_parameter, s.load_ratio_per_pascal)
                     for s in systems])
    if len(systems) not in (1, n):
        raise BlastscaleInputError(f"systems: {len(systems)} bodies for {n} cases (give 1 or {n})")
    return tuple(np.broadcast_to(vals[:, j], (n,)) for j in range(4))


def first_swing_blast(alpha, restitution, frequency, load_ratio, blast, pulse: str = "friedlander", *,
                      solver: RockingSolver | None = None) -> FirstSwing:
    """:class:`FirstSwing` of n bodies given as arrays under n reflected blast pulses (vectorised:
    the pulse phases in one compiled kernel call, the first free swings in numpy).

    Parameters
    ----------
    alpha, restitution, frequency, load_ratio : array_like
        Per body (broadcast to n): slenderness [rad], restitution e [-], frequency parameter p
        [rad/s], load-to-weight ratio per pascal ``S l / (m g r cos alpha)`` [1/Pa].
    blast : BlastParameters
        Reflected pressure [Pa], positive duration [s], Friedlander decay [-] and reflected
        impulse [Pa*s] of the n cases (:func:`~blastscale.blast.blast_parameters` on arrays).
    pulse : {"friedlander", "triangular", "impulsive"}
        Pulse shape (paper Eqs. 1, 3, impulsive limit).
    solver : RockingSolver, optional
        Solver of the pulse phase (default rtol 1e-10, atol 1e-12).
    """
    _check_shape(pulse)
    n = np.size(blast.reflected_impulse)
    a, e, p, q = (np.broadcast_to(np.asarray(x, dtype=float), (n,)) for x in (alpha, restitution, frequency, load_ratio))
    par = np.zeros((n, 3))
    w0 = np.zeros(n)
    if pulse == "friedlander":
        par[:, 0] = q * blast.reflected_pressure
        par[:, 1] = p * blast.positive_duration
        par[:, 2] = blast.friedlander_decay
    elif pulse == "triangular":
        par[:, 0] = q * blast.reflected_pressure
        par[:, 1] = p * (2.0 * blast.reflected_impulse / blast.reflected_pressure)
    else:  # impulsive: theta_dot_0 / p = i S l cos(alpha) / (J_o p cos(alpha)) (encode_pulse)
        w0[:] = q * p * blast.reflected_impulse * np.cos(a)
    kind = np.full(n, PULSE_CODES[pulse], dtype=np.int64)
    return _pulse_phase(solver or DEFAULT_SOLVER, a, e, w0, kind, par)


def first_swing(systems, charge, standoff, *, pulse: str = "friedlander", model=DEFAULT_BLAST_MODEL,
                extrapolate: bool = False, solver: RockingSolver | None = None) -> FirstSwing:
    """Outcome and largest rotation of each body at rest under the reflected pulse of
    ``charge`` [kg TNT] at ``standoff`` [m], at any time (first-swing energy criterion and peak;
    arrays of n cases, vectorised).

    Parameters
    ----------
    systems : RockingSystem or sequence of RockingSystem
        One body for every case, or one per case.
    charge, standoff : array_like
        Charges W [kg] and stand-offs R [m], broadcast to n cases.
    pulse, model, extrapolate, solver
        As in :func:`critical_charge`.

    Returns
    -------
    FirstSwing
        ``overturned`` (n,), ``max_rotation`` (n,) [rad] (pi/2 where it overturns), ``margin``.
    """
    _check_shape(pulse)
    W, R = np.broadcast_arrays(np.atleast_1d(check_positive("charge", charge, "kg")).astype(float),
                               np.atleast_1d(check_positive("standoff", standoff, "m")).astype(float))
    W, R = W.ravel(), R.ravel()
    a, e, p, q = _system_arrays(systems, W.size)
    bp = blast_parameters(W, R, model, extrapolate=extrapolate)
    return first_swing_blast(a, e, p, q, bp, pulse, solver=solver)


def overturns(systems, charge, standoff, *, pulse: str = "friedlander", model=DEFAULT_BLAST_MODEL,
              extrapolate: bool = False, solver: RockingSolver | None = None) -> np.ndarray:
    """Whether each body overturns, at any time, under the reflected pulse of ``charge`` [kg TNT]
    at ``standoff`` [m] (first-swing energy criterion; arrays of n cases, vectorised; the
    ``overturned`` of :func:`first_swing`).

    Returns
    -------
    ndarray of bool, shape (n,)
    """
    return first_swing(systems, charge, standoff, pulse=pulse, model=model, extrapolate=extrapolate,
                       solver=solver).overturned


def _invert_impulse(target, model, by_charge: bool, fixed, lo, hi, extrapolate: bool):
    """ln of the charge [kg] (``by_charge``, ``fixed`` the stand-offs [m]) or of the stand-off [m]
    (``fixed`` the charges [kg]) whose reflected impulse is ``target`` [Pa*s], by bisection on the
    blast model alone between ``lo`` and ``hi`` (ln x; the result is clipped to them). The
    reflected impulse grows with the charge and falls with the distance (Hopkinson-Cranz)."""
    bm = get_blast_model(model)
    lo, hi = np.array(lo, dtype=float), np.array(hi, dtype=float)

    def impulse(u):
        W, R = (np.exp(u), fixed) if by_charge else (fixed, np.exp(u))
        w13 = np.cbrt(W)
        return bm.scaled_reflected_impulse(R / w13, extrapolate=extrapolate) * w13

    for _ in range(45):  # the ln-range is < 40 wide: 45 halvings leave < 1e-12
        mid = 0.5 * (lo + hi)
        more = impulse(mid) > target  # too much impulse: less load
        if by_charge:
            hi, lo = np.where(more, mid, hi), np.where(more, lo, mid)
        else:
            lo, hi = np.where(more, mid, lo), np.where(more, hi, mid)
    return 0.5 * (lo + hi)


def charge_for_impulse(impulse, standoff, model=DEFAULT_BLAST_MODEL, *, extrapolate: bool = False, z_range=None):
    """TNT charge [kg] whose reflected impulse at ``standoff`` [m] is ``impulse`` [Pa*s] (arrays
    broadcast), inverting the blast model over its valid range of Z (NaN where out of it), or over
    ``z_range`` (Z_min, Z_max) [m/kg^(1/3)] when given.

    Used to up-scale a model's critical charge to the prototype: under the paper's general law
    only the impulse is matched (Eq. 8), so the prototype charge that corresponds to a model
    charge is the one delivering the model's impulse divided by the impulse factor
    ``gamma sqrt(varsigma lambda^3)``.
    """
    i, R = np.broadcast_arrays(check_positive("impulse", impulse, "Pa*s"), check_positive("standoff", standoff, "m"))
    i, R = i.astype(float).ravel(), R.astype(float).ravel()
    zlo, zhi = _z_range(model, extrapolate) if z_range is None else (float(z_range[0]), float(z_range[1]))
    ulo, uhi = 3.0 * np.log(R / zhi), 3.0 * np.log(R / zlo)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        u = _invert_impulse(i, model, True, R, ulo, uhi, extrapolate)
    W = np.where((u - ulo > 1e-9) & (uhi - u > 1e-9), np.exp(u), np.nan)
    return W.reshape(np.shape(np.broadcast_arrays(impulse, standoff)[0]))


def _critical_arrays(system, searched, fixed, pulse, model, extrapolate, solver, xtol_rel, guess=None):
    """Vectorised critical charge (``searched="charge"``, ``fixed`` stand-offs [m]) or stand-off
    (``"standoff"``, ``fixed`` charges [kg]). Returns (x_critical, bracket_lo, bracket_hi,
    evaluations, status) arrays; x is the survive side of the final bracket."""
    _check_shape(pulse)
    check_range("xtol_rel", xtol_rel, 1e-14, 0.1)
    by_charge = searched == "charge"
    fixed = np.atleast_1d(np.asarray(fixed, dtype=float))
    zlo, zhi = _z_range(model, extrapolate)
    if by_charge:  # W = (R / Z)^3: large Z, small charge
        ulo, uhi = 3.0 * np.log(fixed / zhi), 3.0 * np.log(fixed / zlo)
    else:  # R = Z W^(1/3): the margin decreases with R, so search in -ln R
        ulo, uhi = -np.log(zhi * np.cbrt(fixed)), -np.log(zlo * np.cbrt(fixed))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        if guess is None:
            u0 = _invert_impulse(system.critical_impulse, model, by_charge, fixed, ulo if by_charge else -uhi,
                                 uhi if by_charge else -ulo, extrapolate)
            u0 = u0 if by_charge else -u0
        else:
            u0 = np.full(fixed.size, math.log(guess) if by_charge else -math.log(guess))

        def evaluate(idx, u):
            x = np.exp(u if by_charge else -u)
            W, R = (x, fixed[idx]) if by_charge else (fixed[idx], x)
            return first_swing(system, W, R, pulse=pulse, model=model, extrapolate=extrapolate, solver=solver).margin

        lo, hi, nev, status = _vector_root(evaluate, u0, ulo, uhi, xtol_rel)
    # the search visits many points: pass on one warning of each other kind (extrapolation is
    # reported once for the results, by _check_extrapolated)
    seen = set()
    for w in caught:
        if w.category is not ExtrapolationWarning and w.category not in seen:
            seen.add(w.category)
            warnings.warn(w.message, w.category, stacklevel=4)
    if not by_charge:
        lo, hi = -lo, -hi
    x = np.where(status == 0, np.exp(lo), np.nan)
    return x, np.exp(np.minimum(lo, hi)), np.exp(np.maximum(lo, hi)), nev, status


def _check_extrapolated(model, values_z, extrapolate):
    if extrapolate:
        zlo, zhi = valid_scaled_distance_range(model)
        z = np.asarray(values_z)[np.isfinite(values_z)]
        if np.any((z < zlo) | (z > zhi)):
            warnings.warn(
                f"critical scenarios at Z outside the {_model_name(model)} fits' range [{zlo:g}, {zhi:g}] m/kg^(1/3): "
                "extrapolated", ExtrapolationWarning, stacklevel=3,
            )


@dataclass(frozen=True)
class CriticalResult:
    """Result of a critical charge / stand-off search (SI).

    ``charge_kg`` [kg] and ``standoff_m`` [m] define the critical scenario (the one searched
    for and the one held fixed); ``pulse`` the pulse shape; ``relative_tolerance`` the
    relative accuracy of the searched quantity; ``evaluations`` the number of pulse-phase
    integrations (first-swing criterion); ``bracket`` the final bracket of the searched quantity.
    """

    charge_kg: float
    standoff_m: float
    searched: str
    pulse: str
    model: str
    relative_tolerance: float
    evaluations: int
    bracket: tuple[float, float]

    def to_dict(self) -> dict:
        """Plain dict with unit-suffixed keys (``critical_charge_kg`` or ``critical_standoff_m``)."""
        return {
            "critical_charge_kg" if self.searched == "charge" else "critical_standoff_m": (
                self.charge_kg if self.searched == "charge" else self.standoff_m
            ),
            "charge_kg": self.charge_kg,
            "standoff_m": self.standoff_m,
            "pulse": self.pulse,
            "model": self.model,
            "relative_tolerance": self.relative_tolerance,
            "evaluations": self.evaluations,
        }


def critical_charge(
    body,
    standoff: float,
    *,
    pulse: str = "friedlander",
    model=DEFAULT_BLAST_MODEL,
    gravity: float | None = None,
    restitution: float | None = None,
    solver: RockingSolver | None = None,
    guess: float | None = None,
    xtol_rel: float = 1e-9,
    extrapolate: bool = False,
) -> CriticalResult:
    """Largest TNT charge [kg] at ``standoff`` [m] that the body survives without overturning.

    The reflected pulse of shape ``pulse`` from ``blast_parameters(W, standoff, model)`` loads
    the front face uniformly (paper Method A, Eq. eom); the first-swing energy criterion
    (module docstring) decides the outcome, and the search starts from the charge that
    delivers the impulsive critical impulse (the structure's own scale).

    Parameters
    ----------
    body : RockingSystem or RectangularBlock
        The body (a block is converted with ``gravity`` [m/s^2] and ``restitution`` [-]).
    standoff : float
        Stand-off R [m], > 0.
    pulse : {"friedlander", "triangular", "impulsive"}
        Reflected pulse shape (paper Eqs. 1, 3, impulsive limit).
    model : str
        Blast model, ``"kingery-bulmash"`` (Swisdak 1994) or ``"masi2021"`` (paper App. A);
        searched over its valid range of scaled distance Z (widened 5x each way with
        ``extrapolate``).
    solver : RockingSolver, optional
        Solver of the pulse phase (default rtol 1e-10, atol 1e-12).
    guess : float, optional
        Starting charge [kg], > 0 (default: from the impulsive closed form).
    xtol_rel : float
        Relative tolerance on the charge [-], in [1e-14, 0.1].
    extrapolate : bool
        Allow the blast fits outside their ranges.

    Returns
    -------
    CriticalResult
        ``charge_kg`` [kg] (the critical charge), ``standoff_m`` [m], evaluations, bracket.

    Raises
    ------
    BlastscaleInputError
        If no change of outcome is found within the blast model's valid range of Z.

    Examples
    --------
    The paper's 10 m block (alpha = 15 deg) at 2 m: 79.8 kg (paper Sec. "Equations of motion").

    >>> import math
    >>> from blastscale.structures import RectangularBlock
    >>> blk = RectangularBlock.from_slenderness(10.0, math.radians(15.0))
    >>> round(critical_charge(blk, 2.0, model="masi2021").charge_kg, 2)
    79.87
    """
    R = float(check_positive("standoff", standoff, "m"))
    if guess is not None:
        check_positive("guess", guess, "kg")
    return _critical(body, "charge", R, pulse, model, gravity, restitution, solver, guess, xtol_rel, extrapolate)


def critical_standoff(
    body,
    charge: float,
    *,
    pulse: str = "friedlander",
    model=DEFAULT_BLAST_MODEL,
    gravity: float | None = None,
    restitution: float | None = None,
    solver: RockingSolver | None = None,
    guess: float | None = None,
    xtol_rel: float = 1e-9,
    extrapolate: bool = False,
) -> CriticalResult:
    """Smallest stand-off [m] at which the body survives ``charge`` [kg TNT] without
    overturning (same method and parameters as :func:`critical_charge`, with ``charge`` W
    [kg] > 0 fixed and ``guess`` an optional starting stand-off [m]; the margin decreases with
    distance). Returns a :class:`CriticalResult` whose ``standoff_m`` [m] is the critical
    (safe) stand-off. References: paper Sec. "Equations of motion"; Masi et al. (2019)."""
    W = float(check_positive("charge", charge, "kg"))
    if guess is not None:
        check_positive("guess", guess, "m")
    return _critical(body, "standoff", W, pulse, model, gravity, restitution, solver, guess, xtol_rel, extrapolate)


def _critical(body, searched, fixed, pulse, model, gravity, restitution, solver, guess, xtol_rel, extrapolate):
    system = as_rocking_system(body, gravity, restitution)
    by_charge = searched == "charge"
    x, blo, bhi, nev, status = _critical_arrays(
        system, searched, fixed, pulse, model, extrapolate, solver or DEFAULT_SOLVER, xtol_rel, guess
    )
    if status[0] != 0:
        zlo, zhi = _z_range(model, extrapolate)
        what = ("survives up to" if status[0] == 1 else "overturns down to") + (
            f" Z = {zlo if status[0] == 1 else zhi:.6g} m/kg^(1/3)"
        )
        raise BlastscaleInputError(
            f"no critical {searched} within the blast model's valid range of Z [{zlo:.6g}, {zhi:.6g}] m/kg^(1/3) "
            f"({'stand-off' if by_charge else 'charge'} = {fixed:.6g} {'m' if by_charge else 'kg'}): the body {what}"
            + ("" if extrapolate else "; --extrapolate (extrapolate=True) widens the range")
        )
    W, R = (float(x[0]), fixed) if by_charge else (fixed, float(x[0]))
    _check_extrapolated(model, [R / np.cbrt(W)], extrapolate)
    return CriticalResult(W, R, searched, pulse, _model_name(model), xtol_rel, int(nev[0]), (float(blo[0]), float(bhi[0])))


def critical_charge_by_bisection(body, standoff: float, guess: float, *, pulse: str = "friedlander",
                                 model=DEFAULT_BLAST_MODEL, rel: float = 1e-8, solver: RockingSolver | None = None,
                                 gravity: float | None = None, restitution: float | None = None) -> float:
    """The slow reference: critical charge [kg] by bisection in ln W on full simulations (to rest:
    ``pulse + 200 / p`` of motion, every impact, no early stop), independent of the first-swing
    criterion. The bracket ``[guess / 1.5, 1.5 guess]`` [kg] must straddle the threshold (checked);
    ``rel`` is the relative width at which it stops. For tests and benchmarks."""
    system = as_rocking_system(body, gravity, restitution)
    solver = solver or DEFAULT_SOLVER

    def over(W):
        p = blast_parameters(W, standoff, model).pulse(pulse)
        return solver.simulate(system, p, p.duration + 200.0 / system.frequency_parameter).overturned

    lo, hi = guess / 1.5, guess * 1.5
    if over(lo) or not over(hi):
        raise BlastscaleInputError(f"guess = {guess:.6g} kg: [guess/1.5, 1.5 guess] does not straddle the critical charge")
    while math.log(hi / lo) > rel:
        mid = math.sqrt(lo * hi)
        lo, hi = (lo, mid) if over(mid) else (mid, hi)
    return math.sqrt(lo * hi)


# ----------------------------------------------------------------------------- capacity curve
def _finite_or_none(values) -> list:
    """Plain list of floats, None for NaN (JSON)."""
    return [None if not math.isfinite(w) else float(w) for w in values]


@dataclass(frozen=True)
class CapacityCurve:
    """Critical charge against stand-off, W_c(R), of one body (SI).

    ``standoff_m`` (n,) [m], ``critical_charge_kg`` (n,) [kg] (NaN where the outcome does not
    change within the blast model's range), ``evaluations`` (n,) pulse-phase integrations per
    case, ``seconds`` [s] the wall time of the search, ``pulse``, ``model``.
    """

    standoff_m: np.ndarray
    critical_charge_kg: np.ndarray
    evaluations: np.ndarray
    seconds: float
    pulse: str
    model: str

    @property
    def seconds_per_case(self) -> float:
        """Wall time per stand-off [s]."""
        return self.seconds / max(1, self.standoff_m.size)

    def safe_standoff(self, charge: float) -> float:
        """Stand-off [m] beyond which ``charge`` [kg] no longer overturns the body, interpolated
        on the curve (log-log linear; NaN outside it). For an exact value use
        :func:`critical_standoff`."""
        ok = np.isfinite(self.critical_charge_kg)
        R, W = self.standoff_m[ok], self.critical_charge_kg[ok]
        if R.size < 2:
            return float("nan")
        order = np.argsort(W)
        lw, lr = np.log(W[order]), np.log(R[order])
        x = math.log(float(check_positive("charge", charge, "kg")))
        return float(np.exp(np.interp(x, lw, lr))) if lw[0] <= x <= lw[-1] else float("nan")

    def to_dict(self) -> dict:
        """Plain dict (lists; None for NaN)."""
        return {
            "standoff_m": self.standoff_m.tolist(),
            "critical_charge_kg": _finite_or_none(self.critical_charge_kg),
            "seconds_per_case": self.seconds_per_case,
            "pulse": self.pulse,
            "model": self.model,
        }


def capacity_curve(
    body,
    standoffs,
    *,
    pulse: str = "friedlander",
    model=DEFAULT_BLAST_MODEL,
    gravity: float | None = None,
    restitution: float | None = None,
    solver: RockingSolver | None = None,
    xtol_rel: float = 1e-9,
    extrapolate: bool = False,
) -> CapacityCurve:
    """Critical charge W_c(R) [kg] at every stand-off R [m] of ``standoffs``, vectorised.

    Same method and parameters as :func:`critical_charge` (first-swing energy criterion, the
    cases searched together); ``standoffs`` a non-empty 1-D array of stand-offs [m] > 0. A
    stand-off whose outcome does not change within the blast model's range of Z gives NaN.
    """
    R = np.atleast_1d(check_positive("standoffs", standoffs, "m")).astype(float)
    if R.ndim != 1 or R.size == 0:
        raise BlastscaleInputError(f"standoffs must be a non-empty 1-D list of stand-offs [m], got shape {R.shape}")
    system = as_rocking_system(body, gravity, restitution)
    t0 = time.perf_counter()
    W, _, _, nev, _ = _critical_arrays(system, "charge", R, pulse, model, extrapolate, solver or DEFAULT_SOLVER, xtol_rel)
    dt = time.perf_counter() - t0
    _check_extrapolated(model, R / np.cbrt(W), extrapolate)
    return CapacityCurve(R, W, nev, dt, pulse, _model_name(model))


@dataclass(frozen=True)
class ModelCapacity:
    """Capacity curve of a reduced-scale model and its up-scaling to the prototype (SI).

    ``curve`` is the model's own W_c at the model stand-offs ``lambda R`` [m] (model charges
    [kg]); ``upscaled_charge_kg`` (n,) [kg] the prototype charges they correspond to under the
    paper's general law (equal impulse up to the factor ``gamma sqrt(varsigma lambda^3)``, Eq. 8),
    to be read against the prototype's W_c(R); ``scale``, ``density_ratio``, ``gravity_ratio``
    are lambda, gamma, varsigma [-].
    """

    curve: CapacityCurve
    upscaled_charge_kg: np.ndarray
    scale: float
    density_ratio: float
    gravity_ratio: float

    def to_dict(self) -> dict:
        """Plain dict (lists; None for NaN)."""
        d = self.curve.to_dict()
        return {
            "scale": self.scale,
            "density_ratio": self.density_ratio,
            "gravity_ratio": self.gravity_ratio,
            "standoff_m": d["standoff_m"],
            "critical_charge_kg": d["critical_charge_kg"],
            "upscaled_critical_charge_kg": _finite_or_none(self.upscaled_charge_kg),
            "seconds_per_case": d["seconds_per_case"],
        }


def model_capacity_curve(
    body,
    standoffs,
    scale: float,
    density_ratio: float = 1.0,
    gravity_ratio: float = 1.0,
    *,
    pulse: str = "friedlander",
    model=DEFAULT_BLAST_MODEL,
    gravity: float | None = None,
    restitution: float | None = None,
    solver: RockingSolver | None = None,
    xtol_rel: float = 1e-9,
    extrapolate: bool = False,
) -> ModelCapacity:
    """Capacity curve of the reduced-scale model of ``body`` and its up-scaling to the prototype.

    The model is the prototype with lengths x ``scale`` (lambda), density x ``density_ratio``
    (gamma) and gravity x ``gravity_ratio`` (varsigma), same restitution; its critical charges
    are searched at the stand-offs ``scale * standoffs`` [m] (as :func:`capacity_curve`) and each
    is up-scaled to the prototype charge that delivers, at the prototype stand-off, the model's
    reflected impulse divided by ``gamma sqrt(varsigma lambda^3)`` (paper Eq. 8, Table 1).
    In the impulsive limit the up-scaled curve equals the prototype's exactly; finite pulses
    depart from it by the effect of the pulse duration, which the law does not match.
    """
    from dataclasses import replace

    from ..similitude import scaling_factors

    lam = float(check_positive("scale", scale))
    gam = float(check_positive("density ratio", density_ratio))
    sig = float(check_positive("gravity ratio", gravity_ratio))
    R = np.atleast_1d(check_positive("standoffs", standoffs, "m")).astype(float)
    proto = as_rocking_system(body, gravity, restitution)
    m_sys = replace(
        proto,
        mass=proto.mass * gam * lam**3,
        inertia_pivot=proto.inertia_pivot * gam * lam**5,
        radius=proto.radius * lam,
        loaded_area=proto.loaded_area * lam**2,
        lever_arm=proto.lever_arm * lam,
        gravity=proto.gravity * sig,
        restitution=proto.coefficient_of_restitution,
    )
    curve = capacity_curve(m_sys, lam * R, pulse=pulse, model=model, solver=solver, xtol_rel=xtol_rel, extrapolate=extrapolate)
    ok = np.isfinite(curve.critical_charge_kg)
    up = np.full(R.size, np.nan)
    if np.any(ok):
        im = blast_parameters(curve.critical_charge_kg[ok], lam * R[ok], model, extrapolate=extrapolate).reflected_impulse
        up[ok] = charge_for_impulse(im / scaling_factors(lam, gam, sig).impulse, R[ok], model, extrapolate=extrapolate)
    return ModelCapacity(curve, up, lam, gam, sig)


# ----------------------------------------------------------------------------- P-I diagram
@dataclass(frozen=True)
class PIDiagram:
    """Pressure-impulse overturning curve of a body (SI).

    ``peak_pressure`` [Pa] and ``critical_impulse`` [Pa*s] are the points of the curve (a
    pulse of that peak overturns the body when its impulse exceeds the critical one);
    ``impulse_asymptote`` [Pa*s] is the impulsive limit ``J_o theta_dot_c / (S l)`` and
    ``pressure_asymptote`` [Pa] the uplift pressure (``P S h = m g b``), the quasi-static limit.
    """

    peak_pressure: np.ndarray
    critical_impulse: np.ndarray
    impulse_asymptote: float
    pressure_asymptote: float
    shape: str


def pi_diagram(
    body,
    peak_pressures=None,
    *,
    n: int = 25,
    shape: str = "triangular",
    decay: float = 1.0,
    gravity: float | None = None,
    restitution: float | None = None,
    solver: RockingSolver | None = None,
    xtol_rel: float = 1e-6,
) -> PIDiagram:
    """Pressure-impulse (P-I) overturning diagram of a body.

    For each peak pressure P the critical impulse i_c(P) that just overturns the body is found
    with the first-swing criterion (module docstring), all pressures at once, in ln i. i_c
    tends to the impulsive asymptote ``J_o p sqrt(2 (1 - cos alpha)) / (S l)`` as P grows and
    diverges as P falls to the uplift pressure ``m g r sin(alpha) / (S l)`` (``P S h = m g b``
    for a block).

    Parameters
    ----------
    body : RockingSystem or RectangularBlock
        The body (a block is converted with ``gravity`` [m/s^2] and ``restitution`` [-]).
    peak_pressures : array_like, optional
        Non-empty 1-D peak pressures [Pa], each above the uplift pressure; default ``n``
        values log-spaced from 1.02 to 1e4 times the uplift pressure.
    n : int
        Number of default pressures (>= 1).
    shape : {"triangular", "friedlander"}
        Pulse shape: triangular (paper Eq. 3, duration ``2 i / P``) or Friedlander with decay
        ``decay`` d [-] (duration ``i / (P k(d))``, paper Eq. 2).
    solver : RockingSolver, optional
        Solver (default rtol 1e-10, atol 1e-12).
    xtol_rel : float
        Relative tolerance on each critical impulse [-].

    Returns
    -------
    PIDiagram
        ``peak_pressure`` [Pa], ``critical_impulse`` [Pa*s] and the two asymptotes.

    References: Krauthammer (2008), *Modern Protective Structures*, Ch. 5 (P-I diagrams);
    Masi et al. (2019), Int. J. Mech. Sci. 157 (impulsive limit).
    """
    system = as_rocking_system(body, gravity, restitution)
    solver = solver or DEFAULT_SOLVER
    check_range("xtol_rel", xtol_rel, 1e-14, 0.1)
    p_up = system.uplift_pressure
    i_imp = system.critical_impulse
    if peak_pressures is None:
        P = p_up * np.logspace(math.log10(1.02), 4.0, check_count("n", n, 1))
    else:
        P = np.atleast_1d(check_positive("peak pressure", peak_pressures, "Pa")).astype(float)
        if P.ndim != 1 or P.size == 0:
            raise BlastscaleInputError(f"peak_pressures must be a non-empty 1-D list of pressures [Pa], got shape {P.shape}")
        if np.any(P <= p_up):
            raise BlastscaleInputError(
                f"peak pressure = {float(P[P <= p_up][0]):.6g} Pa is out of range: must exceed the uplift "
                f"pressure {p_up:.6g} Pa (below it the body never lifts off)"
            )
    if shape == "triangular":
        kind, dur_per_impulse, d = PULSE_CODES[shape], 2.0 / P, 0.0
    elif shape == "friedlander":
        kind, dur_per_impulse, d = PULSE_CODES[shape], 1.0 / (P * float(friedlander_impulse_ratio(decay))), float(decay)
    else:
        raise BlastscaleInputError(f"P-I pulse shape = {shape!r} is not known: valid values are triangular, friedlander")
    pf, q = system.frequency_parameter, system.load_ratio_per_pascal

    def evaluate(idx, u):
        m = idx.size
        par = np.empty((m, 3))
        par[:, 0] = q * P[idx]
        par[:, 1] = pf * np.exp(u) * dur_per_impulse[idx]
        par[:, 2] = d
        return _pulse_phase(
            solver, np.full(m, system.alpha), np.full(m, system.coefficient_of_restitution), np.zeros(m),
            np.full(m, kind, dtype=np.int64), par,
        ).margin

    u0 = np.full(P.size, math.log(i_imp))
    lo, hi, _, status = _vector_root(evaluate, u0, u0 - 1.0, u0 + 40.0, xtol_rel)
    if np.any(status != 0):
        raise BlastscaleInputError(
            f"peak pressure = {float(P[status != 0][0]):.6g} Pa: no critical impulse found up to e^40 times the impulsive one"
        )
    return PIDiagram(P, np.exp(hi), i_imp, p_up, shape)
