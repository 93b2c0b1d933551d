"""Clearing of a finite front face: the reflected pressure relieves to the stagnation pressure.

A face of finite size does not keep the reflected pressure for the whole positive phase: a
rarefaction runs in from its free edges and brings the pressure down to the stagnation pressure of
the flow around the face. UFC 3-340-02 (2008) Sec. 2-15.3.2 (front wall loads, Fig. 2-196):

* clearing distance ``S`` the smaller of the face's height H (the ground is a closed edge) and its
  half-width W/2, ``G`` the larger, ``R = S / G``;
* clearing time

  .. math:: t_c = \\frac{4 S}{(1 + R)\\,C_r},

  ``C_r`` the sound speed in the reflected region (Fig. 2-192; :func:`.air.reflected_sound_speed`);
* stagnation pressure ``P_s(t) = (P_so + C_D q_o)(1 - t/t_of)``, ``q_o`` the peak dynamic pressure
  (Fig. 2-3; :func:`.air.dynamic_pressure`), ``C_D = 1`` on a front wall, ``t_of = 2 i_s / P_so``
  the fictitious positive duration of the incident wave;
* the face's pulse falls linearly from the peak ``P`` at arrival to ``P_s(t_c)`` at ``t_c`` and
  follows ``P_s`` to zero at ``t_of`` (when ``t_c >= t_of``: a triangle to zero at ``t_c``); its
  impulse is ``i_c = (P + P_s(t_c)) t_c / 2 + P_s(t_c) (t_of - t_c) / 2``;
* "the pressure-time curve which gives the smaller impulse is used": the cleared pulse replaces the
  uncleared one only where ``i_c`` is below the uncleared impulse (an infinitely wide and tall face
  keeps its uncleared pulse exactly).

Checks (``tests/unit/blast/test_clearing.py``, ``docs/blast_physics.md``): a hand calculation of the
same procedure with UFC chart readings (Fig. 2-15 for P_so, i_s, P_r, i_r; Fig. 2-192, 2-3 readings);
the older design rule ``t_c = 3 S / U`` (Glasstone & Dolan 1977, Sec. 6.xx, same stagnation target)
as a second source.

References
----------
.. [1] UFC 3-340-02 (2008). *Structures to Resist the Effects of Accidental Explosions*,
       Sec. 2-15.3.2 and Figs. 2-3, 2-192, 2-196.
.. [2] Glasstone, S. & Dolan, P. J. (1977). *The Effects of Nuclear Weapons*, 3rd ed., ch. 6
       (diffraction loading of a closed structure: the reflected pressure decays to stagnation in ~3S/U).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validate import BlastscaleInputError
from .air import dynamic_pressure, reflected_sound_speed

__all__ = [
    "Clearing",
    "clearing",
    "FRONT_WALL_DRAG_COEFFICIENT",
    "bilinear_pressure",
    "bilinear_cumulative",
    "CLEARING_MODEL",
]

#: Drag coefficient of a front wall in the stagnation pressure (UFC 3-340-02 Sec. 2-15.3.2).
FRONT_WALL_DRAG_COEFFICIENT = 1.0
#: Name of the clearing model (recorded with every result that uses it).
CLEARING_MODEL = "ufc-3-340-02-2-15.3.2"


def _v(x):
    return x.tolist() if isinstance(x, np.ndarray) else float(x)


@dataclass(frozen=True)
class Clearing:
    """Clearing of finite faces (floats, or arrays of one shape), SI; see the module docstring.

    Attributes
    ----------
    clearing_distance, other_distance : float or ndarray
        S and G [m].
    sound_speed : float or ndarray
        C_r [m/s].
    clearing_time : float or ndarray
        t_c [s] after arrival.
    stagnation_pressure : float or ndarray
        P_so + C_D q_o at arrival [Pa].
    stagnation_duration : float or ndarray
        t_of = 2 i_s / P_so [s].
    pressure_at_clearing : float or ndarray
        P_s(t_c) [Pa] (0 when t_c >= t_of).
    peak : float or ndarray
        The face's peak pressure P [Pa] at arrival.
    uncleared_impulse, cleared_impulse : float or ndarray
        Impulse of the uncleared pulse and of the UFC construction [Pa s].
    cleared : bool or ndarray
        True where the cleared pulse is used (its impulse is the smaller).
    """

    clearing_distance: object
    other_distance: object
    sound_speed: object
    clearing_time: object
    stagnation_pressure: object
    stagnation_duration: object
    pressure_at_clearing: object
    peak: object
    uncleared_impulse: object
    cleared_impulse: object
    cleared: object

    @property
    def impulse(self):
        """The impulse the face receives: the smaller of cleared and uncleared [Pa s]."""
        return np.minimum(self.cleared_impulse, self.uncleared_impulse)

    @property
    def knots(self):
        """(t1, P1, t2) [s, Pa, s] of the cleared pulse ``(0, P) -> (t1, P1) -> (t2, 0)``."""
        tc, te = np.asarray(self.clearing_time), np.asarray(self.stagnation_duration)
        late = tc >= te
        return tc, np.where(late, 0.0, self.pressure_at_clearing), np.where(late, tc, te)

    def pulse(self):
        """The cleared pulse of one face as a :class:`~blastscale.blast.pulses.Tabulated` (3 knots)."""
        from .pulses import Tabulated

        if np.ndim(self.clearing_time):
            raise BlastscaleInputError("clearing of arrays: a pulse needs one face (index the arrays first)")
        t1, p1, t2 = (float(x) for x in self.knots)
        if t2 > t1:
            return Tabulated([0.0, t1, t2], [float(self.peak), p1, 0.0])
        return Tabulated([0.0, t1], [float(self.peak), 0.0])

    def to_dict(self) -> dict:
        """The CLI's keys (``clearing_time_s``, ``cleared_impulse_Pa_s`` ...)."""
        return {
            "clearing_model": CLEARING_MODEL,
            "clearing_distance_m": _v(self.clearing_distance),
            "reflected_sound_speed_m_s": _v(self.sound_speed),
            "clearing_time_s": _v(self.clearing_time),
            "stagnation_pressure_Pa": _v(self.stagnation_pressure),
            "stagnation_duration_s": _v(self.stagnation_duration),
            "cleared_impulse_Pa_s": _v(self.impulse),
            "uncleared_impulse_Pa_s": _v(self.uncleared_impulse),
            "clearing_construction_impulse_Pa_s": _v(self.cleared_impulse),
            "cleared": self.cleared.tolist() if isinstance(self.cleared, np.ndarray) else bool(self.cleared),
        }


def clearing(
    peak,
    impulse,
    incident_pressure,
    incident_impulse,
    width,
    height,
    *,
    drag_coefficient: float = FRONT_WALL_DRAG_COEFFICIENT,
) -> Clearing:
    """UFC 3-340-02 clearing of front faces (module docstring), vectorised.

    Parameters
    ----------
    peak, impulse : float or array_like
        The face's uncleared peak pressure P [Pa] and impulse [Pa s] (normal reflection: P_r, i_r).
    incident_pressure, incident_impulse : float or array_like
        Side-on P_so [Pa] and i_s [Pa s] at the face.
    width, height : float or array_like
        The face's width W and height H [m] (> 0; ``inf`` for an unbounded face).
    drag_coefficient : float
        C_D of the stagnation pressure (1 on a front wall).

    Returns
    -------
    Clearing
    """
    P, i = np.asarray(peak, dtype=float), np.asarray(impulse, dtype=float)
    Ps, i_s = np.asarray(incident_pressure, dtype=float), np.asarray(incident_impulse, dtype=float)
    W = _size("face width", width)
    H = _size("face height", height)
    half = 0.5 * W
    S, G = np.minimum(H, half), np.maximum(H, half)
    with np.errstate(invalid="ignore"):
        Rr = np.where(np.isinf(G), np.where(np.isinf(S), 1.0, 0.0), S / G)
    Cr = reflected_sound_speed(Ps)
    tc = 4.0 * S / ((1.0 + Rr) * Cr)
    stag = Ps + drag_coefficient * dynamic_pressure(Ps)
    tof = 2.0 * i_s / Ps
    late = tc >= tof
    with np.errstate(invalid="ignore", over="ignore"):
        ptc = np.where(late, 0.0, stag * (1.0 - np.minimum(tc, tof) / tof))
        ic = np.where(late, 0.5 * P * tc, 0.5 * (P + ptc) * tc + 0.5 * ptc * (tof - np.where(late, tof, tc)))
    cleared = ic < i
    out = dict(
        clearing_distance=S,
        other_distance=G,
        sound_speed=Cr,
        clearing_time=tc,
        stagnation_pressure=stag,
        stagnation_duration=tof,
        pressure_at_clearing=ptc,
        peak=P,
        uncleared_impulse=i,
        cleared_impulse=ic,
        cleared=cleared,
    )
    if all(np.ndim(x) == 0 for x in (P, i, Ps, i_s, W, H)):
        out = {k: (bool(v) if k == "cleared" else float(v)) for k, v in out.items()}
    return Clearing(**out)


def _size(name: str, value) -> np.ndarray:
    """A face dimension [m] as an array: > 0, ``inf`` allowed (an unbounded face); one line otherwise."""
    a = np.asarray(value, dtype=float)
    if np.any(np.isnan(a)) or np.any(a <= 0.0):
        bad = float(a[np.isnan(a) | (a <= 0.0)].ravel()[0])
        raise BlastscaleInputError(f"{name} = {bad:.6g} m is out of range: must be > 0 m (inf for an unbounded face)")
    return a


def bilinear_pressure(s, peak, t1, p1, t2):
    """Pressure [Pa] of the cleared pulse ``(0, P) -> (t1, P1) -> (t2, 0)`` at ``s`` [s] after arrival
    (0 outside [0, t2]); ``t1 = t2`` is the triangle to zero at t1."""
    s = np.asarray(s, dtype=float)
    with np.errstate(invalid="ignore", divide="ignore"):
        a = peak + (p1 - peak) * np.clip(s / t1, 0.0, 1.0)
        b = p1 * (1.0 - np.clip((s - t1) / np.where(t2 > t1, t2 - t1, 1.0), 0.0, 1.0))
    return np.where((s < 0.0) | (s > t2), 0.0, np.where(s <= t1, a, b))


def bilinear_cumulative(s, peak, t1, p1, t2):
    """Running impulse [Pa s] of the cleared pulse up to ``s`` [s] after arrival (exact, piecewise
    quadratic; the total ``(P + P1) t1 / 2 + P1 (t2 - t1) / 2`` after ``t2``)."""
    s = np.asarray(s, dtype=float)
    u = np.clip(s, 0.0, t1)
    first = peak * u - (peak - p1) * u * u / (2.0 * t1)
    d2 = np.where(t2 > t1, t2 - t1, 1.0)
    v = np.clip(s - t1, 0.0, np.where(t2 > t1, t2 - t1, 0.0))
    second = p1 * v - p1 * v * v / (2.0 * d2)
    return first + second
