"""Kernel form of a pressure pulse for a rocking body: pulse codes and :func:`encode_pulse`.

The compiled kernel (:mod:`blastscale.rocking.kernel`) integrates paper Eq. (eq:eom) divided
by ``m g r`` in the dimensionless time ``tau = p t`` (p the frequency parameter [rad/s]); the
load enters as the load-to-weight ratio ``f = q P(t)`` [-] with ``q = S l / (m g r cos alpha)``
[1/Pa] (:attr:`RockingSystem.load_ratio_per_pascal`). A pulse is passed as a code
(:data:`PULSE_CODES`) and plain arrays: Friedlander ``par = (q P_ro, p t_o, d)`` (paper Eq. 1),
triangular ``par = (q P_ro, p t_d, 0)`` (paper Eq. 3), tabulated ``(p t_k, q P_k)``; an
impulsive load is the jump of the angular velocity it gives (impulse-momentum about the pivot).
A negative phase (:class:`~blastscale.blast.load_model.PhasedPulse`) adds ``par[3:6] = (q P_r-,
p t_-s, p t_o-)`` to any of them (:mod:`._load`); ``par`` has :data:`PAR_SIZE` entries.
"""

from __future__ import annotations

import math

import numpy as np

from .._validate import BlastscaleInputError
from ..blast.load_model import PhasedPulse, front_face_clearing, front_face_negative
from ..blast.pulses import Friedlander, Impulsive, Pulse, Tabulated, Triangular
from .layout import FRIEDLANDER, NO_PULSE, PAR_SIZE, TABULATED, TRIANGULAR
from .system import RockingSystem

__all__ = ["PULSE_CODES", "encode_pulse", "kernel_pulse_end"]

#: The kernel's pulse code of each pulse kind (``Pulse.kind``; an impulsive load exerts no
#: pressure over time: it enters as an initial angular velocity).
PULSE_CODES = {"impulsive": NO_PULSE, "friedlander": FRIEDLANDER, "triangular": TRIANGULAR, "tabulated": TABULATED}


def kernel_pulse_end(kind, par, tab_t, off):
    """End of n encoded pulses [-] (dimensionless; their negative phases included): ``kind`` (n,),
    ``par`` (n, PAR_SIZE), tables concatenated with offsets ``off`` (n + 1,)."""
    kind = np.asarray(kind)
    end = np.where((kind == FRIEDLANDER) | (kind == TRIANGULAR), par[:, 1], 0.0)
    if np.any(kind == TABULATED):
        end = np.where(kind == TABULATED, tab_t[np.maximum(off[1:] - 1, 0)], end)
    tail = par[:, 5] > 0.0
    return np.where(tail, np.maximum(end, par[:, 4] + par[:, 5]), end)


def encode_pulse(pulse: Pulse, system: RockingSystem, theta0: float = 0.0):
    """Kernel form of a pulse for ``system``: ``(kind, par[PAR_SIZE], tab_t, tab_f, dw0)``.

    Times are made dimensionless with p, pressures turned into load-to-weight ratios;
    ``dw0`` is the jump of ``theta_dot / p`` given by an impulsive load at ``theta0``
    (impulse-momentum about the pivot: ``J_o dtheta_dot = i S l cos(alpha s - theta0)/cos alpha``).

    Parameters
    ----------
    pulse : Pulse
        Friedlander, Triangular, Impulsive or Tabulated pulse (pressures [Pa], times [s] from
        the shock arrival).
    system : RockingSystem
        The body (frequency parameter p [rad/s], load ratio per pascal q [1/Pa], alpha [rad]).
    theta0 : float
        Angle [rad] at which an impulsive load strikes (its sign picks the pivot).

    Returns
    -------
    kind : int
        Pulse code (:data:`PULSE_CODES`).
    par : ndarray, shape (PAR_SIZE,)
        Peak load ratio [-], dimensionless duration [-], Friedlander decay [-], then the negative
        phase's peak suction ratio [-], dimensionless start and duration [-] (zeros when unused).
    tab_t, tab_f : ndarray
        Dimensionless times [-] and load ratios [-] of a tabulated pulse (empty otherwise).
    dw0 : float
        Jump of ``theta_dot / p`` [-] of an impulsive load (0 otherwise).
    """
    if not isinstance(pulse, Pulse):
        raise BlastscaleInputError(f"pulse must be a blastscale Pulse, got {type(pulse).__name__}")
    p = system.frequency_parameter
    q = system.load_ratio_per_pascal
    if isinstance(pulse, PhasedPulse):
        kind, par, tt, tf, dw = encode_pulse(pulse.positive, system, theta0)
        par[3:6] = (q * pulse.negative_peak, p * pulse.negative_start, p * pulse.negative_duration)
        return kind, par, tt, tf, dw
    empty = np.zeros(0)
    par = np.zeros(PAR_SIZE)
    if isinstance(pulse, Impulsive):
        s = -1.0 if theta0 < 0.0 else 1.0
        a = system.alpha * s - theta0
        dw = q * p * pulse.impulse * math.cos(a)
        return NO_PULSE, par, empty, empty, dw
    if not (pulse.duration > 0.0 and math.isfinite(pulse.duration)):
        raise BlastscaleInputError(f"pulse duration = {pulse.duration:.6g} s is out of range: must be > 0 s")
    if isinstance(pulse, Friedlander):
        par[:3] = (q * pulse.peak_pressure, p * pulse.positive_duration, pulse.decay)
        return FRIEDLANDER, par, empty, empty, 0.0
    if isinstance(pulse, Triangular):
        par[:3] = (q * pulse.peak_pressure, p * pulse.duration, 0.0)
        return TRIANGULAR, par, empty, empty, 0.0
    if isinstance(pulse, Tabulated):
        return TABULATED, par, np.ascontiguousarray(pulse.times * p), np.ascontiguousarray(pulse.pressures * q), 0.0
    raise BlastscaleInputError(
        f"pulse kind {pulse.kind!r} is not supported by the rocking solver: "
        "use Friedlander, Triangular, Impulsive, Tabulated or a PhasedPulse of one of them"
    )


def encode_blast_batch(
    alpha, frequency, load_ratio, blast, pulse_shape: str, load_model=None, *, extrapolate: bool = False
):
    """Kernel form of n front-face blast pulses at once (vectorised :func:`encode_pulse` of
    :func:`~blastscale.blast.load_model.front_face_pulse`): the reflected pulse of shape
    ``pulse_shape`` of every case of ``blast`` (arrays), cleared and followed by the negative phase
    as ``load_model`` says.

    Parameters
    ----------
    alpha, frequency, load_ratio : ndarray (n,)
        Slenderness [rad], frequency parameter p [rad/s], load ratio per pascal q [1/Pa].
    blast : BlastParameters
        Blast parameters of the n cases (arrays).
    pulse_shape : {"friedlander", "triangular", "impulsive"}
        Positive pulse shape.
    load_model : LoadModel, optional
        Clearing (cleared cases become 3-knot tabulated pulses) and negative phase; None: the paper's.
    extrapolate : bool
        Let the negative-phase calibration run outside its range.

    Returns
    -------
    kind (n,), par (n, PAR_SIZE), tab_t, tab_f, off (n + 1,), w0 (n,)
    """
    a, p, q = (np.asarray(x, dtype=float) for x in (alpha, frequency, load_ratio))
    n = a.size
    par = np.zeros((n, PAR_SIZE))
    w0 = np.zeros(n)
    P, i = np.asarray(blast.reflected_pressure, dtype=float), np.asarray(blast.reflected_impulse, dtype=float)
    if pulse_shape == "friedlander":
        par[:, 0], par[:, 1], par[:, 2] = q * P, p * blast.positive_duration, blast.friedlander_decay
    elif pulse_shape == "triangular":
        par[:, 0], par[:, 1] = q * P, p * (2.0 * i / P)
    kind = np.full(n, PULSE_CODES[pulse_shape], dtype=np.int64)
    off = np.zeros(n + 1, dtype=np.int64)
    tab_t = tab_f = np.zeros(0)
    i_pos = i
    if load_model is not None and load_model.clearing:
        c = front_face_clearing(blast, load_model)
        cl = np.atleast_1d(c.cleared)
        i_pos = np.where(cl, c.cleared_impulse, i)
        if pulse_shape != "impulsive" and np.any(cl):
            t1, p1, t2 = (np.broadcast_to(np.atleast_1d(x), (n,)) for x in c.knots)
            two = cl & (t2 > t1)
            npts = np.where(cl, np.where(two, 3, 2), 0)
            off[1:] = np.cumsum(npts)
            tab_t, tab_f = np.zeros(off[-1]), np.zeros(off[-1])
            s = off[:-1]
            tab_t[s[cl] + 1] = (p * t1)[cl]
            tab_f[s[cl]] = (q * P)[cl]
            tab_f[s[two] + 1] = (q * p1)[two]
            tab_t[s[two] + 2] = (p * t2)[two]
            kind = np.where(cl, PULSE_CODES["tabulated"], kind)
            par[cl, :3] = 0.0
    if pulse_shape == "impulsive":  # theta_dot_0 / p = i S l cos(alpha) / (J_o p cos(alpha)) (encode_pulse)
        w0[:] = q * p * i_pos * np.cos(a)
    if load_model is not None and load_model.negative_phase:
        neg = front_face_negative(blast, load_model, extrapolate=extrapolate, positive_impulse=i_pos)
        start = kernel_pulse_end(kind, par, tab_t, off)
        if pulse_shape == "impulsive":
            start = p * blast.positive_duration
        par[:, 3], par[:, 4], par[:, 5] = q * neg.pressure, start, p * neg.duration
    return kind, par, tab_t, tab_f, off, w0
