"""The negative phase of the reflected blast load: peak suction, impulse and duration, and its shape.

After the positive phase the pressure on a face falls below ambient for a time much longer than
the positive phase (t_o- ~ 10-14 ms/kg^(1/3) against t_o ~ 0.2-3 ms/kg^(1/3)). The paper neglects it
("expected to have a stabilizing effect", Sec. "Problem statement"); :mod:`blastscale` can add it.

Parameters: UFC 3-340-02 (2008) Fig. 2-16 gives the peak negative reflected pressure P_r- and the
scaled negative reflected impulse i_r-/W^(1/3) against Z. We use S. E. Rigby's closed-form
calibrations of those curves (University of Sheffield, the ``Blast.m`` tool), for the hemispherical
surface burst and the spherical free-air burst, as published in the DYNAblast code (Reis et al.,
github.com/AnaWaldila/dynablast2.0, commit 6a5d1c9, ``2.Type_Load/Class_Blast.m``, "Rigby
calibration"): with Z [m/kg^(1/3)],

``P_r- = 1e6 (A Z^B + C Z + D)`` [Pa], ``i_r- / W^(1/3) = 1e3 (A Z^B + C Z + D)`` [Pa s / kg^(1/3)],

piecewise in Z (:data:`RIGBY_NEGATIVE_PHASE`; the pieces join within 1 %). Shape: Granström's (1956)
cubic, the form Rigby et al. (2014) found to reproduce measured negative phases best,

.. math:: p(t') = -P_{r-}\\,\\frac{27}{4}\\,\\frac{t'}{t_{o-}}\\Big(1 - \\frac{t'}{t_{o-}}\\Big)^2,
          \\quad 0 \\le t' \\le t_{o-},\\qquad t_{o-} = \\frac{16}{9}\\,\\frac{i_{r-}}{P_{r-}},

``t'`` the time since the end of the positive phase; it peaks at ``-P_r-`` at ``t' = t_o-/3`` and
carries exactly ``i_r- = 9 P_r- t_o- / 16``. The duration so implied agrees with the chart's own
t_o- (Rigby's calibration of it, :data:`RIGBY_NEGATIVE_DURATION`) within 25 % (surface; 34 % free-air) over Z = 0.2-30
(2.5 % at the paper's block, Z = 0.46; ``tests/unit/blast/test_negative_phase.py``).

Oblique faces (Methods B, C): there is no chart of the oblique negative phase; the acoustic limit of
a weak wave (reflection doubles it, Baker 1973 ch. 2) gives a face turned away from the charge half
the reflected values, and faces in between are blended with the weights of their positive impulse
(:func:`oblique_negative`).

Validity: Z in [0.07, 37.6] m/kg^(1/3) (the range of the chart's calibration in the same source).

**Bounded by the positive impulse.** Beyond Z ~ 8 m/kg^(1/3) (surface burst) the calibrated suction
impulse exceeds the positive reflected impulse of Kingery-Bulmash (1.15 x at Z = 15, 1.39 x at Z = 39
extrapolated): the face would be pulled toward the charge. No far-field blast wave does that: in the
acoustic limit the wave's net impulse tends to zero from above (Baker 1973, ch. 2; the chart itself
is drawn from sparse data beyond Z ~ 10, Rigby et al. 2014). blastscale therefore **bounds** the
suction impulse by the positive reflected impulse of the same face, ``i_r- <= i_r``: where the
bound acts the peak suction is scaled down with the impulse and the duration kept (the chart's own
duration, Rigby's calibration of Fig. 2-16, stays near 14 ms/kg^(1/3) there). Outside the
calibration's Z range it still refuses unless asked to extrapolate. :func:`face_negative_phase`
applies the bound; ``bounded`` says where it acted.

**Second model: the Friedlander pulse continued.** ``"friedlander-continued"`` takes the suction of
the positive phase's own modified Friedlander ``p = P (1 - x) e^(-d x)``, ``x = t / t_o``, continued
past its zero crossing (x > 1) to infinity: its peak suction ``P e^(-(d+1)) / d`` (at x = 1 + 1/d) and
impulse ``P t_o e^(-d) / d^2`` (exact integrals), carried by the cubic shape above (duration
``16 e t_o / (9 d)``), and bounded alike (for d < 1 the continued pulse's suction would exceed its
positive impulse, ``(d + e^(-d) - 1) / d^2``). Two models that bracket the suction: the
chart-calibrated one is the larger near the charge (model uncertainty, docs/blast_physics.md).

References
----------
.. [1] UFC 3-340-02 (2008). *Structures to Resist the Effects of Accidental Explosions*, Fig. 2-16.
.. [2] Granström, S. A. (1956). *Loading characteristics of air blasts from detonating charges*.
       Trans. Royal Institute of Technology, Stockholm, 100.
.. [3] Rigby, S. E., Tyas, A., Bennett, T., Clarke, S. D. & Fay, S. D. (2014). The negative phase of
       the blast load. Int. J. Protective Structures 5(1), 1-19.
.. [4] Reis, A. W. Q. R. et al., DYNAblast (MATLAB), Class_Blast.m (Rigby's calibrations).
.. [5] Baker, W. E. (1973). *Explosions in Air*. University of Texas Press, ch. 2 (the acoustic
       limit of a blast wave: its net impulse tends to zero).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validate import check_choice, check_positive
from .base import check_fit_range
from .friedlander import friedlander_decay as decay_of
from .parameters import check_burst

__all__ = [
    "NegativePhase",
    "negative_phase",
    "negative_phase_unchecked",
    "RIGBY_NEGATIVE_PHASE",
    "RIGBY_NEGATIVE_DURATION",
    "NEGATIVE_PHASE_RANGE",
    "CUBIC_IMPULSE_FACTOR",
    "cubic_pressure",
    "cubic_cumulative",
    "oblique_negative",
    "NEGATIVE_PHASE_MODEL",
    "NEGATIVE_PHASE_MODELS",
    "face_negative_phase",
    "friedlander_continued",
    "bounded_by_positive",
]

#: Name of the negative-phase model (recorded with every result that uses it).
NEGATIVE_PHASE_MODEL = "ufc-fig2-16-cubic"

#: The negative-phase models (module docstring): the chart-calibrated cubic (default) and the
#: Friedlander pulse continued past its zero crossing.
NEGATIVE_PHASE_MODELS = (NEGATIVE_PHASE_MODEL, "friedlander-continued")

#: Z range [m/kg^(1/3)] of the negative-phase calibration.
NEGATIVE_PHASE_RANGE = (0.07, 37.6)

#: Impulse of the cubic over P t_o-: 27/4 * 1/12 = 9/16.
CUBIC_IMPULSE_FACTOR = 9.0 / 16.0

#: Rigby's calibrations of UFC Fig. 2-16: ``burst -> quantity -> ((Z_upper, (A, B, C, D)), ...)``,
#: value ``A Z^B + C Z + D`` in MPa (``pressure``) or kPa ms / kg^(1/3) (``impulse``); a point on a
#: boundary belongs to the lower piece.
RIGBY_NEGATIVE_PHASE = {
    "surface": {
        "pressure": (
            (0.669, (0.0, 0.0, 0.0, 100e-3)),
            (1.27, (-32.91e-3, 2.0, 13e-3, 106e-3)),
            (2.78, (93e-3, -1.215, 0.0, 0.0)),
            (np.inf, (72.99e-3, -0.978, 0.0, 0.0)),
        ),
        "impulse": (
            (0.58, (-724.37e-3, 2.0, 445.34e-3, 553e-3)),
            (1.19, (11.356e-3, 2.0, -314.76e-3, 752e-3)),
            (5.25, (461.8e-3, -0.88, 0.0, 0.0)),
            (np.inf, (433.6e-3, -0.842, 0.0, 0.0)),
        ),
    },
    "free-air": {
        "pressure": (
            (0.7, (0.0, 0.0, 0.0, 100e-3)),
            (1.469, (-29.078e-3, 2.0, 0.0352e-3, 114e-3)),
            (2.754, (84.132e-3, -1.286, 0.0, 0.0)),
            (np.inf, (59.559e-3, -0.945, 0.0, 0.0)),
        ),
        "impulse": (
            (0.304, (0.0, 0.0, 0.0, 496e-3)),
            (1.44, (36.919e-3, 2.0, -298.72e-3, 583e-3)),
            (np.inf, (316.36e-3, -0.879, 0.0, 0.0)),
        ),
    },
}

#: Rigby's calibration of the chart's own negative duration t_o-/W^(1/3) [ms/kg^(1/3)], same form
#: (used only to check the cubic's implied duration).
RIGBY_NEGATIVE_DURATION = {
    "surface": ((0.267, (0.0, 0.0, 0.0, 10.57)), (2.9, (-0.474, 2.0, 2.745, 9.87)), (np.inf, (0.0, 0.0, 0.0, 13.9))),
    "free-air": (
        (0.537, (0.382, 2.0, 2.952, 7.917)),
        (2.83, (-0.309, 2.0, 1.6443, 8.818)),
        (np.inf, (0.0, 0.0, 0.0, 11.0)),
    ),
}


def rigby_fit(pieces, z) -> np.ndarray:
    """``A Z^B + C Z + D`` of the piece of ``pieces`` holding each Z [m/kg^(1/3)] (fit units)."""
    z = np.asarray(z, dtype=float)
    out = np.empty_like(z)
    lower = -np.inf
    for upper, (a, b, c, d) in pieces:
        sel = (z > lower) & (z <= upper)
        if np.any(sel):
            zs = z[sel]
            out[sel] = a * zs**b + c * zs + d
        lower = upper
    return out


@dataclass(frozen=True)
class NegativePhase:
    """Negative phase of the reflected load at one point or an array of them (SI; module docstring).

    Attributes
    ----------
    pressure : float or ndarray
        Peak suction P_r- [Pa] (> 0; the pressure is -P_r- at its trough).
    impulse : float or ndarray
        Negative impulse i_r- [Pa s] (> 0; the pressure's integral is -i_r-).
    duration : float or ndarray
        Duration t_o- = 16 i_r- / (9 P_r-) [s] of the cubic (Granström 1956).
    model : str
        One of :data:`NEGATIVE_PHASE_MODELS`.
    bounded : bool or ndarray
        Where the suction impulse was capped at the positive reflected impulse (module docstring).
    """

    pressure: object
    impulse: object
    duration: object
    model: str = NEGATIVE_PHASE_MODEL
    bounded: object = False

    def to_dict(self) -> dict:
        """The CLI's keys: ``negative_pressure_Pa``, ``negative_impulse_Pa_s``, ``negative_duration_s``."""

        def v(x):
            return x.tolist() if isinstance(x, np.ndarray) else float(x)

        b = self.bounded.tolist() if isinstance(self.bounded, np.ndarray) else bool(self.bounded)
        return {
            "negative_phase_model": self.model,
            "negative_pressure_Pa": v(self.pressure),
            "negative_impulse_Pa_s": v(self.impulse),
            "negative_duration_s": v(self.duration),
            "negative_impulse_bounded": b,
        }


def negative_phase_unchecked(scaled_distance, charge, burst: str = "surface") -> NegativePhase:
    """:func:`negative_phase` without input or range checks (Z [m/kg^(1/3)] and W [kg] arrays of one
    shape, ``burst`` "surface" or "free-air")."""
    z = np.asarray(scaled_distance, dtype=float)
    fits = RIGBY_NEGATIVE_PHASE[burst]
    P = 1e6 * rigby_fit(fits["pressure"], z)
    i = 1e3 * rigby_fit(fits["impulse"], z) * np.cbrt(np.asarray(charge, dtype=float))
    t = i / (CUBIC_IMPULSE_FACTOR * P)
    if z.ndim == 0:
        return NegativePhase(float(P), float(i), float(t))
    return NegativePhase(P, i, t)


def negative_phase(scaled_distance, charge, burst: str = "surface", *, extrapolate: bool = False) -> NegativePhase:
    """Negative phase of the normally reflected load at scaled distance Z from a charge W.

    Parameters
    ----------
    scaled_distance : float or array_like
        Z [m/kg^(1/3)], > 0.
    charge : float or array_like
        TNT-equivalent charge W [kg], > 0 (broadcast against Z).
    burst : {"surface", "free-air"}
        Hemispherical surface burst or spherical free-air burst (Rigby's calibrations of each).
    extrapolate : bool
        Evaluate outside :data:`NEGATIVE_PHASE_RANGE` (with an ExtrapolationWarning) instead of raising.

    Returns
    -------
    NegativePhase
        P_r- [Pa], i_r- [Pa s], t_o- [s] (module docstring for the formulas and sources).

    Raises
    ------
    OutOfRangeError
        Z outside [0.07, 37.6] m/kg^(1/3) without ``extrapolate``.
    """
    if burst not in RIGBY_NEGATIVE_PHASE:
        check_burst(burst)
    z = check_positive("scaled distance Z", scaled_distance, "m/kg^(1/3)")
    W = check_positive("charge", charge, "kg")
    check_fit_range(
        z, NEGATIVE_PHASE_RANGE, "negative phase", "the range of UFC 3-340-02 Fig. 2-16's calibration", extrapolate
    )
    z, W = np.broadcast_arrays(z, W)
    return negative_phase_unchecked(z if z.ndim else float(z), W if W.ndim else float(W), burst)


def friedlander_continued(peak, duration, decay) -> NegativePhase:
    """Suction of the modified Friedlander pulse (peak P [Pa], positive duration t_o [s], decay d [-])
    continued past its zero crossing: peak ``P e^(-(d+1)) / d`` [Pa], impulse ``P t_o e^(-d) / d^2``
    [Pa s], and the duration ``16 i / (9 P-)`` [s] of the cubic that carries them (module docstring).
    Unbounded; d is taken >= 1e-6 (a non-decaying pulse's suction never ends)."""
    P, to = np.asarray(peak, dtype=float), np.asarray(duration, dtype=float)
    d = np.maximum(np.asarray(decay, dtype=float), 1e-6)
    pn = P * np.exp(-(d + 1.0)) / d
    i = P * to * np.exp(-d) / d**2
    out = NegativePhase(pn, i, i / (CUBIC_IMPULSE_FACTOR * pn), "friedlander-continued")
    return out if np.ndim(pn) else NegativePhase(float(pn), float(i), float(out.duration), out.model)


def bounded_by_positive(neg: NegativePhase, positive_impulse) -> NegativePhase:
    """``neg`` with its impulse capped at ``positive_impulse`` [Pa s] (the net impulse >= 0, the
    acoustic limit; module docstring): peak scaled with the impulse, duration kept."""
    i = np.asarray(neg.impulse, dtype=float)
    cap = np.asarray(positive_impulse, dtype=float)
    over = i > cap
    f = np.where(over, cap / np.where(i > 0, i, 1.0), 1.0)
    if not np.ndim(f):
        return NegativePhase(float(neg.pressure * f), float(i * f), neg.duration, neg.model, bool(over))
    return NegativePhase(np.asarray(neg.pressure) * f, i * f, neg.duration, neg.model, over)


def face_negative_phase(
    scaled_distance,
    charge,
    burst: str = "surface",
    *,
    reflected_pressure,
    reflected_impulse,
    positive_duration,
    friedlander_decay=None,
    model: str = NEGATIVE_PHASE_MODEL,
) -> NegativePhase:
    """The negative phase of a face's normally reflected load under ``model`` (one of
    :data:`NEGATIVE_PHASE_MODELS`), bounded by the face's positive impulse (module docstring).

    ``scaled_distance`` Z [m/kg^(1/3)] and ``charge`` W [kg] (checked by the caller; the chart's
    range by :func:`negative_phase`); the positive phase's peak [Pa], impulse [Pa s], duration [s]
    and Friedlander decay [-] (computed from the three when None)."""
    check_choice("negative phase model", model, NEGATIVE_PHASE_MODELS)
    if model == NEGATIVE_PHASE_MODEL:
        neg = negative_phase_unchecked(scaled_distance, charge, burst)
    else:  # "friedlander-continued"
        if friedlander_decay is None:
            friedlander_decay = decay_of(reflected_pressure, positive_duration, reflected_impulse)
        neg = friedlander_continued(reflected_pressure, positive_duration, friedlander_decay)
    return bounded_by_positive(neg, reflected_impulse)


def cubic_pressure(x, peak):
    """Negative-phase pressure [Pa] at the fraction ``x = t'/t_o-`` of its duration (0 outside [0, 1])."""
    x = np.asarray(x, dtype=float)
    inside = (x >= 0.0) & (x <= 1.0)
    xc = np.clip(x, 0.0, 1.0)
    return np.where(inside, -peak * 6.75 * xc * (1.0 - xc) ** 2, 0.0)


def cubic_cumulative(x, peak, duration):
    """Running impulse [Pa s] of the negative phase up to ``x = t'/t_o-`` (clipped to [0, 1]):
    ``-P t_o- (27/4)(x^2/2 - 2 x^3/3 + x^4/4)``, ``-9/16 P t_o-`` at the end (exact)."""
    x = np.clip(np.asarray(x, dtype=float), 0.0, 1.0)
    return -peak * duration * 6.75 * (0.5 * x**2 - (2.0 / 3.0) * x**3 + 0.25 * x**4)


def oblique_negative(neg: NegativePhase, weight) -> NegativePhase:
    """The negative phase on faces whose positive impulse sits the fraction ``weight`` (0 side-on,
    1 normal reflection) between side-on and reflected: peak and impulse blended between half the
    reflected values (the acoustic limit of the side-on wave) and the reflected ones (module
    docstring); the duration is unchanged."""
    w = np.clip(np.asarray(weight, dtype=float), 0.0, 1.0)
    f = 0.5 + 0.5 * w
    return NegativePhase(neg.pressure * f, neg.impulse * f, neg.duration, neg.model, neg.bounded)
