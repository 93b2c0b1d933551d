"""Kernel form of a pressure pulse for a rocking body: pulse codes and :func:`encode_pulse`.

The compiled kernel (:mod:`blastscale.rocking._kernel`) integrates paper Eq. (eq:eom) divided
by ``m g r`` in the dimensionless time ``tau = p t`` (p the frequency parameter [rad/s]); the
load enters as the load-to-weight ratio ``f = q P(t)`` [-] with ``q = S l / (m g r cos alpha)``
[1/Pa] (:attr:`RockingSystem.load_ratio_per_pascal`). A pulse is passed as a code
(:data:`PULSE_CODES`) and plain arrays: Friedlander ``par = (q P_ro, p t_o, d)`` (paper Eq. 1),
triangular ``par = (q P_ro, p t_d, 0)`` (paper Eq. 3), tabulated ``(p t_k, q P_k)``; an
impulsive load is the jump of the angular velocity it gives (impulse-momentum about the pivot).
"""

from __future__ import annotations

import math

import numpy as np

from .._validate import BlastscaleInputError
from ..blast.pulses import Friedlander, Impulsive, Pulse, Tabulated, Triangular
from ._load import FRIEDLANDER, NO_PULSE, TABULATED, TRIANGULAR
from .system import RockingSystem

__all__ = ["PULSE_CODES", "encode_pulse"]

#: The kernel's pulse code of each pulse kind (``Pulse.kind``; an impulsive load exerts no
#: pressure over time: it enters as an initial angular velocity).
PULSE_CODES = {"impulsive": NO_PULSE, "friedlander": FRIEDLANDER, "triangular": TRIANGULAR, "tabulated": TABULATED}


def encode_pulse(pulse: Pulse, system: RockingSystem, theta0: float = 0.0):
    """Kernel form of a pulse for ``system``: ``(kind, par[3], tab_t, tab_f, dw0)``.

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
    par : ndarray, shape (3,)
        Peak load ratio [-], dimensionless duration [-], Friedlander decay [-] (zeros when unused).
    tab_t, tab_f : ndarray
        Dimensionless times [-] and load ratios [-] of a tabulated pulse (empty otherwise).
    dw0 : float
        Jump of ``theta_dot / p`` [-] of an impulsive load (0 otherwise).
    """
    if not isinstance(pulse, Pulse):
        raise BlastscaleInputError(f"pulse must be a blastscale Pulse, got {type(pulse).__name__}")
    p = system.frequency_parameter
    q = system.load_ratio_per_pascal
    empty = np.zeros(0)
    par = np.zeros(3)
    if isinstance(pulse, Impulsive):
        s = -1.0 if theta0 < 0.0 else 1.0
        a = system.alpha * s - theta0
        dw = q * p * pulse.impulse * math.cos(a)
        return NO_PULSE, par, empty, empty, dw
    if not (pulse.duration > 0.0 and math.isfinite(pulse.duration)):
        raise BlastscaleInputError(f"pulse duration = {pulse.duration:.6g} s is out of range: must be > 0 s")
    if isinstance(pulse, Friedlander):
        par[:] = (q * pulse.peak_pressure, p * pulse.positive_duration, pulse.decay)
        return FRIEDLANDER, par, empty, empty, 0.0
    if isinstance(pulse, Triangular):
        par[:] = (q * pulse.peak_pressure, p * pulse.duration, 0.0)
        return TRIANGULAR, par, empty, empty, 0.0
    if isinstance(pulse, Tabulated):
        return TABULATED, par, np.ascontiguousarray(pulse.times * p), np.ascontiguousarray(pulse.pressures * q), 0.0
    raise BlastscaleInputError(
        f"pulse kind {pulse.kind!r} is not supported by the rocking solver: "
        "use Friedlander, Triangular, Impulsive or Tabulated"
    )
