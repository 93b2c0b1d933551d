"""First-swing energy criterion: does a rocking body at rest overturn under a pulse, at any time?

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
(:func:`blastscale.rocking._batch.solve_batch`, impacts included, over cases and threads):
a pulse lasts ``p t_o ~ 1e-3..1e-1`` in dimensionless time against ``~ 1..10`` for the first
swing, so one evaluation costs a Taylor expansion per piece of the pulse (:mod:`._series`; a few
tens of steps where an event may fall in it) instead of a full simulation. The signed
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

The margin and :func:`first_swing_peak` (from the same state, the largest rotation of a body that
survives) are closed forms of :mod:`blastscale.rocking.free_swing`. The critical loads
(:mod:`blastscale.rocking.critical`), the capacity curves (:mod:`blastscale.rocking.capacity`) and
the P-I diagram (:mod:`blastscale.rocking.pressure_impulse`) are roots of the margin mu.

References: paper Sec. "Equations of motion"; Housner (1963), Bull. Seismol. Soc. Am. 53(2)
(energy and restitution); Masi et al. (2019), Int. J. Mech. Sci. 157.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace

import numpy as np

from .._threads import interleave, map_interleaved
from .._validate import BlastscaleInputError, check_positive
from ..blast.parameters import DEFAULT_BLAST_MODEL, blast_parameters_unchecked
from ..blast.pulses import Pulse, check_pulse_shape
from .encoding import encode_blast_batch, encode_pulse, kernel_pulse_end
from .free_swing import first_swing_margin, first_swing_peak
from .layout import S_FINAL_THETA, S_FINAL_W, S_MAX_ABS_THETA, S_OVERTURNED, S_STATUS
from .solver import DEFAULT_SOLVER, RockingSolver
from .system import RockingSystem, as_rocking_system

__all__ = [
    "overturn_margin",
    "overturns",
    "first_swing",
    "first_swing_blast",
    "first_swing_checked",
    "pulse_phase",
    "FirstSwing",
]


@dataclass(frozen=True)
class FirstSwing:
    """Outcome of n bodies at rest under n pulses, from the pulse phase and the first free swing.

    ``collapsed`` (n,) bool: at any time; ``max_rotation`` (n,) [rad]: the largest |theta| of the
    whole motion (pi/2 where it overturns: it ends lying on its side); ``margin`` (n,) [-]: the
    first-swing margin mu (> 0 overturns)."""

    collapsed: np.ndarray
    max_rotation: np.ndarray
    margin: np.ndarray


FIRST_SWING_FIELDS = tuple(f.name for f in fields(FirstSwing))


def pulse_phase(solver: RockingSolver, alpha, e, w0, kind, par, tab_t=None, tab_f=None, off=None) -> FirstSwing:
    """Integrate the pulse phase of n encoded cases with the compiled kernel; the first free swing
    from there in closed form.

    ``kind`` (n,) pulse codes, ``par`` (n, 3) kernel parameters, ``w0`` (n,) initial theta_dot / p
    (the jump of an impulsive load); tabulated pulses concatenated as in ``solve_batch``.
    """
    n = kind.size
    tab_t = np.zeros(0) if tab_t is None else tab_t
    tab_f = np.zeros(0) if tab_f is None else tab_f
    off = np.zeros(n + 1, dtype=np.int64) if off is None else off
    tau_end = kernel_pulse_end(kind, par, tab_t, off)
    from ._batch import solve_batch  # noqa: PLC0415 -- start-up: numba loads on the first solve, not with `import blastscale.cli`

    summ, _, _ = solve_batch(
        np.ascontiguousarray(alpha, dtype=float),
        np.ascontiguousarray(e, dtype=float),
        np.zeros(n),
        np.ascontiguousarray(w0, dtype=float),
        np.ascontiguousarray(tau_end),
        kind.astype(np.int64),
        np.ascontiguousarray(par),
        tab_t,
        tab_f,
        off,
        np.empty((n, 0)),
        *solver._kernel_settings(None, True, False),
        threads=solver.threads,
    )
    bad = summ[:, S_STATUS] != 0
    if np.any(bad):
        solver._check_status(summ[np.argmax(bad), S_STATUS], int(np.argmax(bad)))
    th, w = summ[:, S_FINAL_THETA], summ[:, S_FINAL_W]
    mu = first_swing_margin(alpha, e, th, w, summ[:, S_OVERTURNED] == 1.0)
    over = mu > 0.0
    peak = first_swing_peak(alpha, e, th, w, summ[:, S_MAX_ABS_THETA], float(solver.rest_velocity))
    return FirstSwing(over, np.where(over, 0.5 * math.pi, peak), mu)


def overturn_margin(
    body, pulse: Pulse, *, solver: RockingSolver | None = None, gravity=None, restitution=None
) -> float:
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
    fs = pulse_phase(
        solver or DEFAULT_SOLVER,
        np.array([system.alpha]),
        np.array([system.coefficient_of_restitution]),
        np.array([dw]),
        np.array([kind]),
        par[None, :],
        tt,
        tf,
        off,
    )
    return float(fs.margin[0])


def _system_arrays(systems, n: int):
    """(alpha, e, p, q) arrays of length n from one RockingSystem (broadcast) or a sequence of n."""
    if isinstance(systems, RockingSystem):
        systems = [systems]
    vals = np.array(
        [(s.alpha, s.coefficient_of_restitution, s.frequency_parameter, s.load_ratio_per_pascal) for s in systems]
    )
    if len(systems) not in (1, n):
        raise BlastscaleInputError(f"systems: {len(systems)} bodies for {n} cases (give 1 or {n})")
    return tuple(np.broadcast_to(vals[:, j], (n,)) for j in range(4))


def first_swing_blast(
    alpha,
    restitution,
    frequency,
    load_ratio,
    blast,
    pulse_shape: str = "friedlander",
    *,
    solver: RockingSolver | None = None,
    load_model=None,
    extrapolate: bool = False,
) -> FirstSwing:
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
    pulse_shape : {"friedlander", "triangular", "impulsive"}
        Pulse shape (paper Eqs. 1, 3, impulsive limit).
    solver : RockingSolver, optional
        Solver of the pulse phase (default rtol 1e-10, atol 1e-12).
    load_model : LoadModel, optional
        Clearing of the front face and the negative phase (:mod:`blastscale.blast.load_model`); the
        pulse phase then lasts until the negative phase ends. None: the paper's load.
    extrapolate : bool
        Let the negative-phase calibration run outside its range (with a warning).
    """
    check_pulse_shape(pulse_shape)
    n = np.size(blast.reflected_impulse)
    a, e, p, q = (
        np.broadcast_to(np.asarray(x, dtype=float), (n,)) for x in (alpha, restitution, frequency, load_ratio)
    )
    kind, par, tab_t, tab_f, off, w0 = encode_blast_batch(
        a, p, q, blast, pulse_shape, load_model, extrapolate=extrapolate
    )
    return pulse_phase(solver or DEFAULT_SOLVER, a, e, w0, kind, par, tab_t, tab_f, off)


def first_swing(
    systems,
    charge,
    standoff,
    *,
    pulse_shape: str = "friedlander",
    blast_model=DEFAULT_BLAST_MODEL,
    extrapolate: bool = False,
    solver: RockingSolver | None = None,
    load_model=None,
) -> FirstSwing:
    """Outcome and largest rotation of each body at rest under the reflected pulse of
    ``charge`` [kg TNT] at ``standoff`` [m], at any time (first-swing energy criterion and peak;
    arrays of n cases, vectorised).

    Parameters
    ----------
    systems : RockingSystem or sequence of RockingSystem
        One body for every case, or one per case.
    charge, standoff : array_like
        Charges W [kg] and stand-offs R [m], broadcast to n cases.
    pulse_shape, blast_model, extrapolate, solver, load_model
        As in :func:`critical_charge`.

    Returns
    -------
    FirstSwing
        ``collapsed`` (n,), ``max_rotation`` (n,) [rad] (pi/2 where it overturns), ``margin``.
    """
    check_pulse_shape(pulse_shape)
    W, R = np.broadcast_arrays(
        np.atleast_1d(check_positive("charge", charge, "kg")).astype(float),
        np.atleast_1d(check_positive("standoff", standoff, "m")).astype(float),
    )
    return first_swing_checked(systems, W.ravel(), R.ravel(), pulse_shape, blast_model, extrapolate, solver, load_model)


#: Fewest cases a thread of :func:`first_swing_checked` takes (below, the threads cost more than they save).
MIN_CASES_PER_THREAD = 256


def first_swing_checked(systems, W, R, pulse_shape, blast_model, extrapolate, solver, load_model=None) -> FirstSwing:
    """:func:`first_swing` of checked inputs (1-D arrays of positive charges [kg] and stand-offs [m]
    of one length): the capacity searches check once and evaluate many times. The cases are dealt out
    over the solver's threads, alternately (:func:`~blastscale._threads.map_interleaved`: the blast
    parameters, pulse phases and first swings of each share on a thread of their own; bitwise one
    thread)."""
    solver = solver or DEFAULT_SOLVER
    a, e, p, q = _system_arrays(systems, W.size)
    one = replace(solver, threads=1)

    def share(s):
        bp = blast_parameters_unchecked(W[s], R[s], blast_model, extrapolate=extrapolate)
        return first_swing_blast(
            a[s], e[s], p[s], q[s], bp, pulse_shape, solver=one, load_model=load_model, extrapolate=extrapolate
        )

    parts = map_interleaved(share, W.size, solver.threads, MIN_CASES_PER_THREAD)
    if len(parts) == 1:
        return parts[0][1]
    return FirstSwing(*(interleave([(s, getattr(fs, f)) for s, fs in parts], W.size) for f in FIRST_SWING_FIELDS))


def overturns(
    systems,
    charge,
    standoff,
    *,
    pulse_shape: str = "friedlander",
    blast_model=DEFAULT_BLAST_MODEL,
    extrapolate: bool = False,
    solver: RockingSolver | None = None,
    load_model=None,
) -> np.ndarray:
    """Whether each body overturns, at any time, under the reflected pulse of ``charge`` [kg TNT]
    at ``standoff`` [m] (first-swing energy criterion; arrays of n cases, vectorised; the
    ``collapsed`` of :func:`first_swing`).

    Returns
    -------
    ndarray of bool, shape (n,)
    """
    return first_swing(
        systems,
        charge,
        standoff,
        pulse_shape=pulse_shape,
        blast_model=blast_model,
        extrapolate=extrapolate,
        solver=solver,
        load_model=load_model,
    ).collapsed
