"""One candidate design of the planner, evaluated against every constraint of the lab.

A candidate is a scaling law, a geometric scale lambda and a specimen material (gamma = its
density over the prototype's; the Hopkinson-Cranz law imposes gamma = 1/sqrt(varsigma lambda), so a
material fixes lambda = 1 / (varsigma gamma^2)). :func:`evaluate` designs it
(:func:`~blastscale.similitude.design_model`), turns the TNT charge into the lab's explosive, sizes the
safety envelope and the instruments, and lists every constraint it breaks, each with the value that
would admit it (docs/planning.md, "Constraints"). The material's own constraints
(:func:`material_checks`, docs/planning.md "Materials"): its stresses and elastic deflection in the
prototype's scaled motion against its strength and stiffness (``"rigidity"``,
:func:`~blastscale.similitude.rigidity.rigidity_check`) and, for a block on the planar path, its joint
friction's regime against the prototype's (``"friction"``, :func:`~blastscale.similitude.friction.friction_check`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Optional

from .._validate import BlastscaleInputError
from ..blast.explosives import get_explosive
from ..blast.inverse import model_name
from ..blast.sources import SourceShot
from ..scenario.lab import SAME_MATERIAL
from ..similitude.experiment import DEFAULT_IMPULSIVE_THRESHOLD, ImpulsiveCheck
from ..similitude.factors import to_specimen
from ..similitude.friction import friction_check
from ..similitude.rigidity import rigidity_check
from ..structures.block import RectangularBlock
from ..structures.from_spec import is_block
from ..structures.materials import get_material
from .build import spec_dims, specimen_density, specimen_mass
from .debris import planar_reach
from .instruments import FRAMES_PER_RISE, instrument_settings, negative_duration_s, top_corner_displacement
from .shot import (
    candidate_materials,
    fireability,
    lab_charge,
    lab_explosives,
    lab_source,
    licence_limit,
    safety_envelope,
)

__all__ = [
    "LAMBDA_DENOMINATORS",
    "Candidate",
    "Violation",
    "Evaluated",
    "candidates",
    "evaluate",
    "material_checks",
    "scale_label",
    "envelope_block",
    "envelope_impulsive",
    "shot_dict",
]

#: The geometric scales the planner tries: lambda = 1/n (the fractions a lab builds and reports).
LAMBDA_DENOMINATORS = (1, 2, 4, 5, 8, 10, 15, 20, 25, 40, 50, 75, 100, 150, 200, 250, 400, 500, 1000)


def scale_label(scale: float) -> str:
    """``"1/20"`` for 0.05, ``"1/32.49"`` for any other scale."""
    f = Fraction(scale).limit_denominator(100000)
    if f.numerator == 1 and abs(float(f) - scale) <= 1e-9 * scale:
        return f"1/{f.denominator}"
    return f"1/{1.0 / scale:.4g}"


@dataclass(frozen=True)
class Candidate:
    """A law, a scale lambda [-], a material (name) and its density ratio gamma [-]."""

    law: str
    scale: float
    material: str
    density_ratio: float
    burst: str = "surface"

    def describe(self) -> dict:
        return {
            "law": self.law,
            "scale": self.scale,
            "scale_fraction": scale_label(self.scale),
            "material": self.material,
            "density_ratio": self.density_ratio,
            "burst": self.burst,
        }


@dataclass(frozen=True)
class Violation:
    """A broken constraint: the ``[lab]`` key (or ``"blast fits"``, ``"impulsive"``), the candidate's
    ``value`` and the ``limit`` in the key's unit, and the sentence."""

    key: str
    value: Optional[float]
    limit: Optional[float]
    text: str


@dataclass
class Evaluated:
    """A candidate with everything the cheap stage computed (SI); ``violations`` empty: feasible."""

    candidate: Candidate
    violations: list = field(default_factory=list)
    design: object = None
    specimen: object = None
    charge: object = None
    safety: object = None
    instruments: object = None
    rise_s: float = math.nan
    response_s: float = math.nan
    charge_height_m: float = 0.0  # the specimen charge's centre above the floor [m] (0: on it)
    impulsive: object = None  # the design's t_o p check (a block's own; any other kind's envelope block's)
    rigidity: object = None  # the material's RigidityCheck against the prototype's
    friction: object = None  # the material's FrictionCheck (a block on the planar path; None elsewhere)


def candidates(
    lab, prototype_density: float, prototype_height: float, gravity_ratio: float = 1.0, bursts=("surface",)
) -> list:
    """Every candidate: the general law at each scale of :data:`LAMBDA_DENOMINATORS` up to the
    tallest specimen the lab builds (and 1), for each material; Hopkinson-Cranz at the one scale
    each material allows (gamma >= 1); each for every specimen burst of ``bursts``."""

    mats = candidate_materials(lab, prototype_density)
    out = [Candidate("general", 1.0 / n, name, g, b) for b in bursts for n in LAMBDA_DENOMINATORS for name, g in mats]
    for b in bursts:
        for name, g in mats:
            if g >= 1.0:
                out.append(Candidate("hopkinson-cranz", 1.0 / (gravity_ratio * g * g), name, g, b))
    return out


def _violations(ev: Evaluated, lab, spec_h: float, spec_m: float) -> list:
    out = []
    if spec_h > lab.specimen_max_height_m:
        out.append(
            Violation(
                "specimen_max_height_m",
                spec_h,
                lab.specimen_max_height_m,
                f"specimen {spec_h:.4g} m high > specimen_max_height_m = {lab.specimen_max_height_m:g} m",
            )
        )
    if spec_m > lab.specimen_max_mass_kg:
        out.append(
            Violation(
                "specimen_max_mass_kg",
                spec_m,
                lab.specimen_max_mass_kg,
                f"specimen {spec_m:.4g} kg > specimen_max_mass_kg = {lab.specimen_max_mass_kg:g} kg",
            )
        )
    if ev.charge is None:
        return out
    if isinstance(ev.charge, SourceShot):  # a calibrated source: its limits in place of the explosive's
        limits = [*ev.charge.violations, *licence_limit(ev.charge, lab)]
        return out + [Violation(*v) for v in limits] + _space_and_camera(ev, lab)
    out += [Violation(*f) for f in fireability(ev.charge, lab)]
    m = ev.charge.explosive_mass_kg
    if m < lab.charge_min_kg:
        out.append(
            Violation(
                "charge_min_kg",
                m,
                lab.charge_min_kg,
                f"{m:.4g} kg of {lab.explosive} < charge_min_kg = {lab.charge_min_kg:g} kg",
            )
        )
    if m > lab.charge_max_kg:
        out.append(
            Violation(
                "charge_max_kg",
                m,
                lab.charge_max_kg,
                f"{m:.4g} kg of {lab.explosive} > charge_max_kg = {lab.charge_max_kg:g} kg",
            )
        )
    return out + _space_and_camera(ev, lab)


def _space_and_camera(ev: Evaluated, lab) -> list:
    """The safety radius against the lab's space and the camera rate against its camera (any source)."""
    out = []
    if ev.safety.radius_m > lab.space_radius_m:
        out.append(
            Violation(
                "space_radius_m",
                ev.safety.radius_m,
                lab.space_radius_m,
                f"safety radius ({lab.safety_threshold}) {ev.safety.radius_m:.4g} m > space_radius_m = "
                f"{lab.space_radius_m:g} m",
            )
        )
    out += _window_violations(ev, lab)
    need = ev.instruments.camera_fps_required
    if need > lab.camera_max_fps:
        out.append(
            Violation(
                "camera_max_fps",
                need,
                lab.camera_max_fps,
                f"camera needs {need:.4g} frames/s > camera_max_fps = {lab.camera_max_fps:g}",
            )
        )
    return out


def material_checks(c: Candidate, factors, prototype, block=None) -> tuple:
    """(rigidity, friction) checks of a candidate's material against the prototype's.

    Parameters
    ----------
    c : Candidate
        Its ``material`` (``"same"``: the prototype's own, ``prototype``).
    factors : ScalingFactors
        The design's factors: ``pressure`` = gamma varsigma lambda is the stress factor.
    prototype : Material
        The prototype's material (:func:`~blastscale.structures.materials.prototype_material`: its friction the
        scenario's).
    block : RectangularBlock, optional
        The prototype block of the planar path, whose rocking model has no friction: the friction regimes are
        checked on it (None: not checked, the 3D engine carries the specimen's friction).

    Returns
    -------
    (RigidityCheck, FrictionCheck or None)
    """
    spec = prototype if c.material == SAME_MATERIAL else get_material(c.material)
    rig = rigidity_check(float(factors.pressure), spec, prototype)
    fr = None if block is None else friction_check(prototype.friction, spec.friction, block.width, block.height)
    return rig, fr


def _material_violations(ev: Evaluated, factors, prototype, block) -> list:
    """Set ``ev.rigidity`` and ``ev.friction`` (:func:`material_checks`) and return their violations."""
    ev.rigidity, ev.friction = material_checks(ev.candidate, factors, prototype, block)
    out = []
    r, f = ev.rigidity, ev.friction
    if not r.ok:
        worst = max(r.bearing_ratio, r.impact_ratio, r.deflection_ratio)
        out.append(Violation("rigidity", worst, r.threshold, r.reason))
    if f is not None and not f.ok:
        out.append(Violation("friction", f.specimen_friction, f.prototype_friction, f.reason))
    return out


def _standoff_violations(standoff: float, lab) -> list:
    """The stand-off [m] outside the lab's window ``standoff_min_m`` - ``standoff_max_m``."""
    out = []
    if lab.standoff_min_m is not None and standoff < lab.standoff_min_m:
        out.append(
            Violation(
                "standoff_min_m",
                standoff,
                lab.standoff_min_m,
                f"stand-off {standoff:.4g} m < standoff_min_m = {lab.standoff_min_m:g} m",
            )
        )
    if lab.standoff_max_m is not None and standoff > lab.standoff_max_m:
        out.append(
            Violation(
                "standoff_max_m",
                standoff,
                lab.standoff_max_m,
                f"stand-off {standoff:.4g} m > standoff_max_m = {lab.standoff_max_m:g} m",
            )
        )
    return out


def _window_violations(ev: Evaluated, lab) -> list:
    """The lab's gauges too slow to resolve the pulse (``gauge_rate_max_hz``, :func:`~.instruments.gauge_rate_needed_hz`)."""
    need = ev.instruments.pressure_sampling_needed_hz
    if lab.gauge_rate_max_hz is not None and need > lab.gauge_rate_max_hz:
        return [
            Violation(
                "gauge_rate_max_hz",
                need,
                lab.gauge_rate_max_hz,
                f"the gauges must sample at {need:.4g} Hz (10 (1 + d) samples over the {1e6 * ev.design.specimen.positive_duration:.3g} us "
                f"positive phase) > gauge_rate_max_hz = {lab.gauge_rate_max_hz:g} Hz: the peak would be read low by more than 10 %",
            )
        ]
    return []


def _initiator_alone(ev: Evaluated, lab, d, spec_h: float, spec_m: float) -> None:
    """The violations of a candidate whose whole TNT charge the initiator alone delivers (no explosive to weigh):
    the initiator's share, the other limits, no explosive above its minimum, the initiator's own licence mass and
    safety radius (stricter basis)."""
    ev.violations.append(
        Violation(
            "initiator_max_fraction",
            lab.initiator_tnt_kg / d.specimen_charge_kg,
            lab.initiator_max_fraction,
            f"initiator_tnt_kg = {lab.initiator_tnt_kg:g} kg >= the whole charge {d.specimen_charge_kg:.4g} kg TNT",
        )
    )
    ev.violations += _violations(ev, lab, spec_h, spec_m)
    ex = get_explosive(lab.explosive, lab_explosives(lab))  # no explosive left to weigh: below every minimum
    ev.violations.append(
        Violation(
            "explosive_min_charge_kg",
            0.0,
            ex.min_charge_kg,
            f"no {ex.name} left beside the initiator (its minimum reliable charge: {ex.min_charge_kg:.4g} kg)",
        )
    )
    if lab.charge_min_kg > 0:
        ev.violations.append(
            Violation(
                "charge_min_kg",
                0.0,
                lab.charge_min_kg,
                f"no {ex.name} left beside the initiator < charge_min_kg = {lab.charge_min_kg:g} kg",
            )
        )
    w0 = max(lab.initiator_tnt_kg, lab.initiator_tnt_pressure_kg)  # the initiator alone, stricter basis
    if lab.tnt_max_kg is not None and w0 > lab.tnt_max_kg:
        ev.violations.append(
            Violation(
                "tnt_max_kg",
                w0,
                lab.tnt_max_kg,
                f"the initiator alone is {w0:.4g} kg TNT > the licence limit tnt_max_kg = {lab.tnt_max_kg:g} kg",
            )
        )
    r = safety_envelope(w0, lab.safety_threshold).radius_m
    if r > lab.space_radius_m:
        ev.violations.append(
            Violation(
                "space_radius_m",
                r,
                lab.space_radius_m,
                f"safety radius of the initiator "
                f"alone ({lab.safety_threshold}) {r:.4g} m > space_radius_m = "
                f"{lab.space_radius_m:g} m",
            )
        )


def evaluate(c: Candidate, *, lab, block, timing, incident_model, design, prototype=None, planar=False) -> Evaluated:
    """Design ``c`` and check it against ``lab``.

    ``design(c)`` returns the candidate's :class:`~blastscale.similitude.ModelDesign` and the height of
    its specimen charge [m] (the planner's: the Study's design of the candidate, :meth:`~blastscale.study.Study.from_candidate`). ``block``
    is the prototype's block, or for any other structure its envelope block (:func:`envelope_block`):
    its t_o p is the impulsive check of every kind. ``timing`` is the prototype's (or the envelope
    block's) :class:`~.shot.Timing`: the specimen's times are its times x the time factor
    sqrt(lambda / varsigma); ``incident_model`` the blast model of the side-on gauge (Kingery-Bulmash:
    the paper's fits have no incident pressure). ``prototype`` is the prototype's
    :class:`~blastscale.structures.materials.Material` (None: the material is not checked); ``planar``
    checks the friction regime on ``block`` too (:func:`material_checks`).
    """

    ev = Evaluated(c)
    try:
        d, ev.charge_height_m = design(c)
    except BlastscaleInputError as exc:
        ev.violations.append(Violation("blast fits", None, None, " ".join(str(exc).split())))
        return ev
    spec = d.specimen_structure  # the design's specimen (scaled once, there)
    ev.design, ev.specimen = d, spec
    ev.violations += _standoff_violations(d.specimen_standoff_m, lab)
    spec_h, spec_m = spec_dims(spec)[0], specimen_mass(d)
    if prototype is not None:
        ev.violations += _material_violations(ev, d.factors, prototype, block if planar else None)
    ev.impulsive = d.impulsive if d.impulsive is not None else envelope_impulsive(block, d)
    if not ev.impulsive.impulsive:
        ev.violations.append(
            Violation(
                "impulsive",
                ev.impulsive.model_ratio,
                ev.impulsive.threshold,
                f"not impulsive: t_o p = {ev.impulsive.model_ratio:.3g} > {ev.impulsive.threshold:g}",
            )
        )
    source = lab_source(lab)  # a bad source file is one line of its own, not a rejected candidate
    try:
        ev.charge = _shot_of(d, lab, source)
    except BlastscaleInputError:
        _initiator_alone(ev, lab, d, spec_h, spec_m)
        return ev
    ev.safety = safety_envelope(ev.charge.tnt_equivalent_safety_kg, lab.safety_threshold)
    ev.rise_s, ev.response_s = (to_specimen(t, d.factors, "time") for t in (timing.rise_s, timing.response_s))
    m = d.specimen
    z = float(m.scaled_distance)
    inc = (
        float(incident_model.incident_pressure(z))
        if incident_model.valid_range("incident_pressure")[0] <= z <= incident_model.valid_range("incident_pressure")[1]
        else float("nan")
    )
    ev.instruments = instrument_settings(
        reflected_pressure_Pa=m.reflected_pressure,
        incident_pressure_Pa=inc,
        positive_duration_s=m.positive_duration,
        friedlander_decay=m.friedlander_decay,
        arrival_time_s=m.arrival_time,
        rise_time_s=ev.rise_s,
        response_time_s=ev.response_s,
        top_displacement_m=top_corner_displacement(*spec_dims(spec)[1::-1], 0.0),
        camera_max_fps=lab.camera_max_fps,
        gauge_rate_max_hz=lab.gauge_rate_max_hz,
        negative_duration_s=negative_duration_s(z, m.charge_kg, m.burst),
    )
    ev.violations += _violations(ev, lab, spec_h, spec_m)
    return ev


def _shot_of(d, lab, source):
    """The design's shot in the lab: its charge in the lab's explosive (:func:`~.shot.lab_charge`), or with
    ``[lab] source`` (``source``, :func:`~.shot.lab_source`) the calibrated source's shot (its control value,
    limits and uncertainty, warned of a blast model other than the source's or a scaled distance outside its
    calibration)."""
    if source is None:
        return lab_charge(d.specimen_charge_kg, lab)
    return source.shot(d.specimen_charge_kg, model_name(d.specimen.blast_model), float(d.specimen.scaled_distance))


def envelope_block(structure):
    """The structure's envelope as one rectangular block (its height, its extent along the blast, x,
    and across it, y; its mean density): the rigid rocking mode the screening's impulsive check and
    timing use for a structure without a planar path (docs/planning.md)."""

    if is_block(structure):
        return structure
    h, w, dp = spec_dims(structure)
    return RectangularBlock(height=h, width=w, depth=dp, density=float(structure.mass) / (h * w * dp))


def envelope_impulsive(envelope, d):
    """The impulsive check t_o p (:func:`~blastscale.similitude.experiment.impulsive_check`) of a design
    on the envelope block of its prototype and on that block scaled by the design's factors (the specimen's,
    ``structure.scaled(factors)``: its frequency parameter depends on its size alone)."""

    spec = envelope.scaled(d.factors)
    return ImpulsiveCheck(
        prototype_ratio=float(d.prototype.positive_duration * envelope.frequency_parameter(d.gravity)),
        model_ratio=float(d.specimen.positive_duration * spec.frequency_parameter(d.specimen_gravity)),
        threshold=DEFAULT_IMPULSIVE_THRESHOLD,
    )


def specimen_displacement(spec, rotation: Optional[float], collapsed: bool) -> tuple:
    """(top-corner displacement [m], reach [m]) of a specimen block from its largest rotation."""
    if collapsed or rotation is None:
        return spec.width + spec.height, planar_reach(spec.width, spec.height, 0.0, True)
    return top_corner_displacement(spec.width, spec.height, rotation), planar_reach(
        spec.width, spec.height, rotation, False
    )


def frames_needed(rise_s: float) -> float:
    """Camera rate [1/s] for :data:`~.instruments.FRAMES_PER_RISE` frames over the rise."""
    return FRAMES_PER_RISE / rise_s


def shot_dict(ev: Evaluated, lab, top_m: float, reach_m: float, timing=None) -> dict:
    """What every planned design says, whatever its odds: the candidate, the charge in the lab's explosive,
    the stand-off and the charge's height, the specimen, the safety envelope, the debris zone (from the
    specimen's ``reach_m``) and the instruments (for a top displacement ``top_m``) [SI]. ``timing`` (a
    :class:`~.shot.Timing`, the specimen's simulated one: :func:`~.card.specimen_timing`) replaces the screening's
    for a design that was simulated, so that its camera rate is the test card's (one figure, one function)."""
    c, d, spec, ch, env = ev.candidate, ev.design, ev.specimen, ev.charge, ev.safety
    h, w, dp = spec_dims(spec)
    times = {} if timing is None else {"rise_time_s": timing.rise_s, "response_time_s": timing.response_s}
    ins = instrument_settings(
        **{
            **_ins_inputs(ev),
            **times,
            "top_displacement_m": top_m,
            "camera_max_fps": lab.camera_max_fps,
            "gauge_rate_max_hz": lab.gauge_rate_max_hz,
        }
    )
    source = isinstance(ch, SourceShot)
    return {
        **c.describe(),
        "explosive": ch.source.name if source else ch.explosive.name,
        "explosive_mass_kg": None if source else ch.explosive_mass_kg,
        "source": ch.to_dict() if source else None,
        "tnt_equivalent_kg": ch.tnt_equivalent_impulse_kg,
        "tnt_equivalent_pressure_kg": ch.tnt_equivalent_pressure_kg,
        "tnt_equivalent_safety_kg": ch.tnt_equivalent_safety_kg,
        "explosive_min_charge_kg": None if source else ch.explosive.min_charge_kg,
        "min_charge_source": None if source else ch.explosive.min_charge_source,
        "initiator_tnt_kg": ch.initiator_tnt_kg,
        "initiator_fraction": ch.initiator_fraction,
        "standoff_m": d.specimen_standoff_m,
        "charge_height_m": ev.charge_height_m,
        "specimen_height_m": h,
        "specimen_width_m": w,
        "specimen_depth_m": dp,
        "specimen_density_kg_m3": specimen_density(d),
        "specimen_mass_kg": specimen_mass(d),
        "safety_distances_m": env.distances_m,
        "safety_radius_m": env.radius_m,
        "safety_threshold": env.threshold,
        "far_field": list(env.far_field),
        "debris_radius_m": lab.debris_margin * reach_m,
        "specimen_reach_m": reach_m,
        "camera_fps": ins.camera_fps,
        "camera_fps_required": ins.camera_fps_required,
        "pressure_sampling_hz": ins.pressure_sampling_hz,
        "instruments": ins.to_dict(),
        "impulsive_ratio": ev.impulsive.model_ratio,
        "friction_ratio": float(d.factors.friction),
        "rigidity": None if ev.rigidity is None else ev.rigidity.to_dict(),
        "friction_regime": None if ev.friction is None else ev.friction.to_dict(),
        "warnings": list(ch.warnings),
    }


def _ins_inputs(ev: Evaluated) -> dict:
    i = ev.instruments
    m = ev.design.specimen
    return {
        "reflected_pressure_Pa": m.reflected_pressure,
        "incident_pressure_Pa": i.incident_gauge_range_Pa / 1.5,
        "positive_duration_s": m.positive_duration,
        "friedlander_decay": m.friedlander_decay,
        "arrival_time_s": m.arrival_time,
        "rise_time_s": ev.rise_s,
        "response_time_s": ev.response_s,
        "negative_duration_s": negative_duration_s(m.scaled_distance, m.charge_kg, m.burst),
    }
