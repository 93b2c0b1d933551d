"""Which load a face receives beyond the paper's: the load model (clearing, negative phase) and the
pulse of a front face under it.

The paper loads the front face with the positive phase of the normally reflected pressure of a
surface burst, on an unbounded face. A :class:`LoadModel` says what is added (each opt-in; the
default is the paper's load, bit for bit):

* ``clearing`` with the loaded face's ``face_width_m`` and ``face_height_m``: the reflected
  pressure relieves to the stagnation pressure (UFC 3-340-02 Sec. 2-15.3.2; :mod:`.clearing`);
* ``negative_phase``: Granström's cubic suction after the positive phase with UFC Fig. 2-16's peak
  and impulse (:mod:`.negative_phase`).

The burst type (surface or free-air) is the blast parameters' own (:mod:`.bursts`): it chooses the
fits, so it is part of the blast, not of the face's load model.

:func:`front_face_pulse` builds the pulse of a front face (planar rocking, Method A) and
:class:`PhasedPulse` carries a positive pulse followed by the negative phase.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from .._validate import BlastscaleInputError, check_choice, check_positive_scalar
from .clearing import CLEARING_MODEL, Clearing, clearing
from .negative_phase import (
    CUBIC_IMPULSE_FACTOR,
    NEGATIVE_PHASE_MODEL,
    NEGATIVE_PHASE_MODELS,
    NegativePhase,
    cubic_cumulative,
    cubic_pressure,
    face_negative_phase,
    negative_phase,
)
from .parameters import get_blast_model
from .pulses import Impulsive, Pulse

__all__ = [
    "LoadModel",
    "PAPER_LOAD",
    "PhasedPulse",
    "front_face_pulse",
    "front_face_clearing",
    "front_face_negative",
    "load_model_record",
]


@dataclass(frozen=True)
class LoadModel:
    """What a face's load includes beyond the paper's positive reflected phase (module docstring).

    Attributes
    ----------
    clearing : bool
        Relief of the reflected pressure on a finite face (UFC 3-340-02 Sec. 2-15.3.2).
    face_width_m, face_height_m : float or None
        The loaded face's width W and height above the ground H [m], needed with ``clearing`` (None:
        taken from the structure where a structure is loaded, :func:`blastscale.sim3d.loads.with_structure_face`).
    negative_phase : bool
        Add the negative phase (UFC Fig. 2-16, Granström's cubic), bounded by the positive impulse.
    negative_phase_model : str
        Which (:data:`~.negative_phase.NEGATIVE_PHASE_MODELS`): the chart-calibrated cubic (default) or
        the Friedlander pulse continued past its zero crossing.
    """

    clearing: bool = False
    face_width_m: float | None = None
    face_height_m: float | None = None
    negative_phase: bool = False
    negative_phase_model: str = NEGATIVE_PHASE_MODEL

    def __post_init__(self):
        if (self.face_width_m is None) != (self.face_height_m is None):
            raise BlastscaleInputError(
                f"face width = {self.face_width_m}, face height = {self.face_height_m}: give both (m) or neither "
                "(CLI --face-width, --face-height)"
            )
        for name, v in (("face width", self.face_width_m), ("face height", self.face_height_m)):
            if v is not None and not (float(v) > 0.0):  # > 0, inf allowed (an unbounded face)
                raise BlastscaleInputError(f"{name} = {v!r} m is out of range: must be > 0 m")
        check_choice("negative phase model", self.negative_phase_model, NEGATIVE_PHASE_MODELS)

    def require_face(self) -> "LoadModel":
        """``self`` when clearing has its face (or there is no clearing); one line otherwise."""
        if self.clearing and self.face_width_m is None:
            raise BlastscaleInputError(
                "clearing needs the loaded face's width and height: give both in m (CLI --face-width, --face-height)"
            )
        return self

    @property
    def is_paper(self) -> bool:
        """True for the paper's load (no clearing, no negative phase)."""
        return not (self.clearing or self.negative_phase)

    def scaled(self, factors) -> "LoadModel":
        """The same load model on a specimen's face: its width and height x ``factors.length`` (lambda).

        Parameters
        ----------
        factors : ScalingFactors
            The design's factors (:class:`blastscale.similitude.ScalingFactors`; the one ``scaled(factors)``
            signature of structures, contact settings, pulses and load models, docs/contracts.md section 4).
        """
        if self.face_width_m is None:
            return self
        lam = check_positive_scalar("scale", factors.length)
        return replace(self, face_width_m=self.face_width_m * lam, face_height_m=self.face_height_m * lam)

    def to_dict(self) -> dict:
        """The load model's record (its models' names, the face when clearing)."""
        d = {"clearing": self.clearing, "negative_phase": self.negative_phase}
        if self.clearing and self.face_width_m is not None:
            d.update(clearing_model=CLEARING_MODEL, face_width_m=self.face_width_m, face_height_m=self.face_height_m)
        if self.negative_phase:
            d["negative_phase_model"] = self.negative_phase_model
        return d


#: The paper's load: the positive phase of the normally reflected pressure on an unbounded face.
PAPER_LOAD = LoadModel()


def load_model_record(blast_model: str, burst: str, load_model: "LoadModel | None" = None, **extra) -> dict:
    """Which load model produced a result: ``{"blast_model", "burst", "clearing", "negative_phase", ...}``
    (the one record every result carries)."""
    lm = load_model or PAPER_LOAD
    return {"blast_model": str(blast_model), "burst": str(burst), **lm.to_dict(), **extra}


class PhasedPulse(Pulse):
    """A positive pulse followed by the negative phase (Granström's cubic), t = 0 at arrival.

    Parameters
    ----------
    positive : Pulse
        The positive phase (Friedlander, triangular, impulsive or a cleared tabulated pulse).
    negative_peak : float
        Peak suction P_r- [Pa], > 0 (the pressure's trough is -P_r-).
    negative_duration : float
        Duration of the negative phase t_o- [s], > 0.
    negative_start : float, optional
        Start of the negative phase [s] after arrival (default the positive pulse's end; for an
        impulsive positive phase give the blast's positive duration).

    ``impulse`` is the net area (positive minus negative); ``positive_impulse`` and
    ``negative_impulse`` [Pa s] each phase's (the latter > 0).
    """

    kind = "phased"

    def __init__(self, positive: Pulse, negative_peak: float, negative_duration: float, negative_start=None):
        if not isinstance(positive, Pulse):
            raise BlastscaleInputError(f"positive = {positive!r} is not a pulse")
        self.positive = positive
        self.negative_peak = check_positive_scalar("negative peak pressure", negative_peak, "Pa")
        self.negative_duration = check_positive_scalar("negative duration", negative_duration, "s")
        start = positive.duration if negative_start is None else negative_start
        self.negative_start = float(start)
        if not (np.isfinite(self.negative_start) and self.negative_start >= 0.0):
            raise BlastscaleInputError(f"negative start = {start!r} s is out of range: must be >= 0 s")

    @property
    def peak(self) -> float:
        return self.positive.peak

    @property
    def duration(self) -> float:
        return self.negative_start + self.negative_duration

    @property
    def positive_impulse(self) -> float:
        return self.positive.impulse

    @property
    def negative_impulse(self) -> float:
        return CUBIC_IMPULSE_FACTOR * self.negative_peak * self.negative_duration

    @property
    def impulse(self) -> float:
        return self.positive_impulse - self.negative_impulse

    def pressure(self, t):
        tt = np.asarray(t, dtype=float)
        p = self.positive.pressure(tt) + cubic_pressure(
            (tt - self.negative_start) / self.negative_duration, self.negative_peak
        )
        return p if np.ndim(t) else float(p)

    def cumulative_impulse(self, t):
        tt = np.asarray(t, dtype=float)
        c = self.positive.cumulative_impulse(tt) + cubic_cumulative(
            (tt - self.negative_start) / self.negative_duration, self.negative_peak, self.negative_duration
        )
        return c if np.ndim(t) else float(c)

    def _rescaled(self, pressure_factor: float, time_factor: float) -> "PhasedPulse":
        return PhasedPulse(
            self.positive._rescaled(pressure_factor, time_factor),
            self.negative_peak * pressure_factor,
            self.negative_duration * time_factor,
            self.negative_start * time_factor,
        )

    def __repr__(self) -> str:
        return (
            f"PhasedPulse({self.positive!r}, negative_peak={self.negative_peak:.6g} Pa, "
            f"negative_duration={self.negative_duration:.6g} s)"
        )


def front_face_clearing(bp, load_model: LoadModel) -> "Clearing | None":
    """Clearing of the normally reflected load of ``bp`` (one point) on the load model's face, or None
    without clearing. Needs the side-on values (every Kingery-Bulmash fit; masi2021 takes
    Kingery-Bulmash's at the same Z)."""
    if load_model is None or not load_model.clearing:
        return None
    load_model.require_face()
    P_so, i_s = bp.incident_pressure, bp.incident_impulse
    if P_so is None or i_s is None:
        kb = get_blast_model("kingery-bulmash")
        w13 = np.cbrt(bp.charge_kg)
        P_so = kb.incident_pressure(bp.scaled_distance, extrapolate=True)
        i_s = kb.scaled_incident_impulse(bp.scaled_distance, extrapolate=True) * w13
    return clearing(
        bp.reflected_pressure, bp.reflected_impulse, P_so, i_s, load_model.face_width_m, load_model.face_height_m
    )


def front_face_negative(
    bp, load_model: LoadModel, *, extrapolate: bool = False, positive_impulse=None
) -> "NegativePhase | None":
    """Negative phase of the normally reflected load of ``bp`` under the load model's negative-phase
    model, bounded by the face's positive impulse [Pa s] (``positive_impulse``, default the reflected
    impulse of ``bp``; the cleared one where clearing acts), or None without it. The chart's Z range
    is checked for the chart's model (:func:`~.negative_phase.negative_phase`)."""
    if load_model is None or not load_model.negative_phase:
        return None
    burst = getattr(bp, "burst", "surface")
    if load_model.negative_phase_model == NEGATIVE_PHASE_MODEL:
        negative_phase(bp.scaled_distance, bp.charge_kg, burst, extrapolate=extrapolate)
    return face_negative_phase(
        bp.scaled_distance,
        bp.charge_kg,
        burst,
        reflected_pressure=bp.reflected_pressure,
        reflected_impulse=bp.reflected_impulse if positive_impulse is None else positive_impulse,
        positive_duration=bp.positive_duration,
        friedlander_decay=bp.friedlander_decay,
        model=load_model.negative_phase_model,
    )


def front_face_pulse(
    bp, shape: str = "friedlander", load_model: "LoadModel | None" = None, *, extrapolate: bool = False
) -> Pulse:
    """The pulse on a front face normal to the blast of ``bp`` (one charge and stand-off).

    Without a load model (or the paper's) this is ``bp.pulse(shape)`` itself. With clearing the
    cleared UFC pulse replaces it where its impulse is the smaller (for ``"impulsive"``: a Dirac of
    the smaller impulse); with the negative phase a :class:`PhasedPulse` adds the suction after it
    (after the blast's positive duration for an impulsive pulse).
    """
    base = bp.pulse(shape)
    if load_model is None or load_model.is_paper:
        return base
    c = front_face_clearing(bp, load_model)
    if c is not None and c.cleared:
        base = Impulsive(float(c.cleared_impulse)) if shape == "impulsive" else c.pulse()
    neg = front_face_negative(bp, load_model, extrapolate=extrapolate, positive_impulse=base.impulse)
    if neg is None:
        return base
    start = float(bp.positive_duration) if shape == "impulsive" else None
    return PhasedPulse(base, neg.pressure, neg.duration, start)
