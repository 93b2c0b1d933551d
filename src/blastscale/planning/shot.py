"""The shot of one design: the charge in the lab's explosive, the safety envelope, the timing of the
rocking response, shared by the planner (:mod:`.planner`) and the test card (:mod:`.card`)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from .._validate import BlastscaleInputError
from ..blast.explosive_library import Explosive
from ..blast.explosives import ChargeEquivalence, charge_equivalence, get_explosive
from ..blast.inverse import model_name
from ..blast.safety import QD_K_FACTORS, SAFETY_THRESHOLDS, far_field, safety_distances
from ..blast.sources import SourceShot
from ..io.source_file import read_source
from ..scenario.lab import SAME_MATERIAL, LabSpec
from ..similitude.rigidity import rigidity_check
from ..structures.materials import MATERIALS, friction_card_line, prototype_material, specimen_material

__all__ = [
    "lab_explosives",
    "lab_charge",
    "lab_source",
    "lab_shot",
    "source_card",
    "card_charge",
    "fireability",
    "licence_limit",
    "SafetyEnvelope",
    "safety_envelope",
    "threshold_meanings",
    "candidate_materials",
    "specimen_friction_card",
    "specimen_rigidity",
    "Timing",
    "rocking_timing",
    "timing_of",
    "DEFAULT_LAB",
]


def _default_lab():

    return LabSpec()


#: The defaults of every ``[lab]`` key (docs/planning.md), for a scenario without a ``[lab]`` table.
DEFAULT_LAB = _default_lab()


def lab_explosives(lab) -> dict:
    """The user-defined explosives of a ``[lab]`` table (``[lab.explosives.NAME]``) as :class:`Explosive`."""
    return {
        name: Explosive(
            name,
            e.pressure_factor,
            e.impulse_factor,
            e.density_kg_m3,
            e.source,
            "user-defined: as stated by its source",
            e.min_charge_kg,
            f"[lab.explosives.{name}] min_charge_kg" if e.min_charge_kg else "not stated",
        )
        for name, e in lab.explosives.items()
    }


def lab_charge(tnt_kg: float, lab):
    """The specimen's charge in the lab's explosive (:func:`~blastscale.blast.explosives.charge_equivalence`),
    the initiator on both bases (its pressure equivalent in the safety mass)."""
    return charge_equivalence(
        tnt_kg, lab.explosive, lab.initiator_tnt_kg, lab_explosives(lab), lab.initiator_tnt_pressure_kg
    )


def lab_source(lab):
    """The lab's calibrated source (``[lab] source``: :func:`blastscale.io.source_file.read_source`), None for a
    chemical explosive."""
    path = getattr(lab, "source", None)
    return None if path is None else read_source(path)


def lab_shot(tnt_kg: float, lab) -> "SourceShot | ChargeEquivalence":
    """The shot that delivers ``tnt_kg`` [kg TNT, impulse basis] in the lab: with ``[lab] source`` the calibrated
    source's (:meth:`~blastscale.blast.sources.CalibratedSource.shot`: the control value to set, its limits and
    uncertainty; no initiator), else the chemical charge (:func:`lab_charge`)."""
    src = lab_source(lab)
    return lab_charge(tnt_kg, lab) if src is None else src.shot(tnt_kg)


def source_card(design, lab) -> "dict | None":
    """The test card's ``source`` block: the calibrated source's shot of the design (:meth:`SourceShot.to_dict`: the
    control value to set and the line the lab reads, both TNT equivalents, the law's band, one shot's scatter, its
    limits checked in ``violations``), None for a chemical explosive."""
    src = lab_source(lab)
    if src is None or design is None:
        return None
    m = design.specimen
    shot = src.shot(design.specimen_charge_kg, model_name(m.blast_model), float(m.scaled_distance))
    return {**shot.to_dict(), "violations": [v[3] for v in shot.violations]}


def card_charge(tnt_kg: float, lab):
    """:func:`lab_charge` for a scale the user chose: an initiator that alone delivers the whole TNT
    charge [kg] is not refused but fired alone (no explosive to weigh, its own TNT equivalent on both
    bases, its fraction above 1), for :func:`fireability` to warn about."""

    try:
        return lab_charge(tnt_kg, lab)
    except BlastscaleInputError:
        w0 = float(lab.initiator_tnt_kg)
        if not (w0 >= float(tnt_kg) > 0):
            raise
    ex = get_explosive(lab.explosive, lab_explosives(lab))
    w0p = max(float(lab.initiator_tnt_pressure_kg), w0)
    return ChargeEquivalence(
        ex,
        0.0,
        w0,
        w0,
        w0p,
        w0 / float(tnt_kg),
        (
            f"the initiator alone ({w0:.4g} kg TNT) delivers more than the design's whole charge "
            f"({float(tnt_kg):.4g} kg TNT): no {ex.name} to weigh, and the shot is "
            f"{w0 / float(tnt_kg):.3g} x the design's; use a smaller initiator (initiator_tnt_kg; "
            'initiator = "none" for a laser) or a larger scale',
        ),
        None if w0p == w0 else w0p,
    )


def licence_limit(ch, lab) -> list:
    """The licence limit ``lab.tnt_max_kg`` [kg TNT] against the shot's TNT equivalent on the stricter basis
    (initiator included; a chemical charge or a calibrated source's shot): ``(key, value, limit, sentence)``."""
    w = ch.tnt_equivalent_safety_kg
    if lab.tnt_max_kg is None or w <= lab.tnt_max_kg:
        return []
    return [
        (
            "tnt_max_kg",
            w,
            lab.tnt_max_kg,
            f"the charge with its initiator is {w:.4g} kg TNT on the stricter basis (pressure "
            f"{ch.tnt_equivalent_pressure_kg:.4g}, impulse {ch.tnt_equivalent_impulse_kg:.4g}) > the licence "
            f"limit tnt_max_kg = {lab.tnt_max_kg:g} kg",
        )
    ]


def fireability(ch, lab) -> list:
    """What makes the charge ``ch`` (a :class:`~blastscale.blast.explosives.ChargeEquivalence`) a shot
    the lab cannot rely on: ``(key, value, limit, sentence)`` for an explosive mass below the
    explosive's minimum reliable charge [kg] (:mod:`blastscale.blast.initiation`) and for an
    initiator whose share of the TNT-equivalent impulse exceeds ``lab.initiator_max_fraction`` [-].
    The planner rejects such designs; the test card of a scale the user chose warns. Also the licence limit
    (:func:`licence_limit`).
    """
    out = licence_limit(ch, lab)
    ex, m = ch.explosive, ch.explosive_mass_kg
    if m < ex.min_charge_kg:
        out.append(
            (
                "explosive_min_charge_kg",
                m,
                ex.min_charge_kg,
                f"{m:.4g} kg of {ex.name} is below its minimum reliable charge {ex.min_charge_kg:.4g} kg "
                f"({ex.min_charge_source}): it may not detonate",
            )
        )
    if ch.initiator_fraction > lab.initiator_max_fraction:
        out.append(
            (
                "initiator_max_fraction",
                ch.initiator_fraction,
                lab.initiator_max_fraction,
                f"the initiator ({ch.initiator_tnt_kg:.4g} kg TNT) is {100 * ch.initiator_fraction:.3g} % of the "
                f"charge's TNT-equivalent impulse > initiator_max_fraction = {lab.initiator_max_fraction:g}",
            )
        )
    return out


@dataclass(frozen=True)
class SafetyEnvelope:
    """Safety distances of one charge (pressure-equivalent TNT): ``distances_m`` {key: m} for every
    threshold and K-factor, ``radius_m`` (the lab's ``safety_threshold``), ``threshold``, and the keys
    whose distance lies in the far field (anchored Kinney-Graham, less certain)."""

    tnt_kg: float
    distances_m: dict
    radius_m: float
    threshold: str
    far_field: tuple

    def to_dict(self) -> dict:
        return {
            "tnt_equivalent_pressure_kg": self.tnt_kg,
            "safety_distances_m": dict(self.distances_m),
            "safety_radius_m": self.radius_m,
            "safety_threshold": self.threshold,
            "far_field": list(self.far_field),
        }


def safety_envelope(tnt_pressure_kg: float, threshold: str = "6.9 kPa") -> SafetyEnvelope:
    """Safety distances of ``tnt_pressure_kg`` [kg TNT, pressure basis] (:mod:`blastscale.blast.safety`)."""
    d = safety_distances(tnt_pressure_kg)
    ff = tuple(t.key for t in SAFETY_THRESHOLDS if far_field(tnt_pressure_kg, d[t.key]))
    return SafetyEnvelope(float(tnt_pressure_kg), d, d[threshold], threshold, ff)


def threshold_meanings() -> list:
    """Every safety key with its pressure (None for K-factors), meaning and source."""
    out = [
        {"key": t.key, "pressure_Pa": t.pressure_Pa, "meaning": t.meaning, "source": t.source}
        for t in SAFETY_THRESHOLDS
    ]
    out += [
        {
            "key": k,
            "pressure_Pa": None,
            "meaning": f"D = {v:g} W^(1/3) ft/lb^(1/3): {what}",
            "source": "DoD 6055.09-M Vol. 3",
        }
        for k, (v, what) in QD_K_FACTORS.items()
    ]
    return out


def candidate_materials(lab, prototype_density: float) -> list:
    """(name, gamma) of the lab's candidate materials (``"same"``: the prototype's, gamma = 1)."""

    names = list(lab.materials) if lab.materials is not None else [SAME_MATERIAL] + list(MATERIALS)
    return [(n, 1.0 if n == SAME_MATERIAL else MATERIALS[n].density / prototype_density) for n in names]


def specimen_friction_card(scenario, lab) -> dict:
    """The test card's friction of ``scenario``'s specimen: its material's joint friction
    (``scale.specimen_material``; the prototype's own without one, ``structure.friction``) against the
    prototype's, to be measured by a tilt test. Keys: ``pair`` (``"lead on lead"``), ``nominal``, ``low``,
    ``high`` (the range its sources give), ``prototype`` [-], and ``line``, the whole sentence
    (:func:`~blastscale.structures.materials.friction_card_line`)."""
    sc = scenario
    proto = prototype_material(sc.structure.density_kg_m3, sc.structure.friction, lab.prototype_material)
    name = None if sc.scale is None else sc.scale.specimen_material
    m = specimen_material(name, proto)
    pair = "the prototype's material on itself" if name is None else f"{m.name} on {m.name}"
    return {
        "pair": pair,
        "nominal": m.friction,
        "low": m.friction_low,
        "high": m.friction_high,
        "prototype": proto.friction,
        "line": friction_card_line(m, proto.friction, pair),
    }


def specimen_rigidity(scenario, design, lab):
    """The rigidity check (:func:`~blastscale.similitude.rigidity.rigidity_check`) of ``scenario``'s specimen
    material (the prototype's own without ``scale.specimen_material``) in ``design``'s scaled motion (its
    ``factors.pressure``), against the prototype's (``lab.prototype_material``, or the library stone nearest its
    density): for the card of a scale the user chose, where the planner would have refused it."""
    sc = scenario
    proto = prototype_material(sc.structure.density_kg_m3, sc.structure.friction, lab.prototype_material)
    name = None if sc.scale is None else sc.scale.specimen_material
    return rigidity_check(float(design.factors.pressure), specimen_material(name, proto), proto)


@dataclass(frozen=True)
class Timing:
    """Times of a rocking response from the shock's arrival [s]: to the first peak of the rotation (or
    to the tipping point when it overturns), and of the whole response (to rest or the collapse)."""

    rise_s: float
    response_s: float


def rocking_timing(t, theta, alpha: float, collapsed: bool, collapse_time: Optional[float]) -> Timing:
    """:class:`Timing` from a rotation history ``theta`` [rad] at times ``t`` [s] (from the arrival):
    the rise ends at the first local maximum of |theta| (or, overturning, where |theta| passes
    alpha); the response ends at the collapse, or the last time |theta| exceeds 1 % of its largest
    value (the end of the history when it rocks to the end)."""
    t, a = np.asarray(t, dtype=float), np.abs(np.asarray(theta, dtype=float))
    if collapsed:
        k = np.flatnonzero(a >= alpha)
        tip = float(t[k[0]]) if k.size else float(t[-1])
        return Timing(
            tip, float(collapse_time) if collapse_time is not None and math.isfinite(collapse_time) else float(t[-1])
        )
    if a.max() <= 0.0:
        return Timing(float(t[-1]), float(t[-1]))
    k = np.flatnonzero((a[1:-1] >= a[:-2]) & (a[1:-1] > a[2:]) & (a[1:-1] > 0.0))
    rise = float(t[k[0] + 1]) if k.size else float(t[int(np.argmax(a))])
    moving = np.flatnonzero(a > 0.01 * a.max())
    return Timing(rise, float(t[moving[-1]]))


def timing_of(result) -> Timing:
    """:class:`Timing` of a :class:`~blastscale.rocking.RockingResult` (its solver steps; the first
    peak from its recorded peaks)."""
    alpha = result.system.alpha if result.system is not None else 0.5 * math.pi
    tm = rocking_timing(result.t, result.theta, alpha, result.collapsed, result.collapse_time)
    if not result.collapsed and len(result.peak_times):
        return Timing(float(result.peak_times[0]), tm.response_s)
    return tm
