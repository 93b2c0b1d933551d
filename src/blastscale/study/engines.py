"""The response engines of a study, chosen by name (:data:`ENGINES`): planar rocking and 3D rigid
bodies (MuJoCo), plus 3D ensembles (:data:`ENSEMBLE`) for chaotic structures. Each engine says
whether it supports a structure and runs prototype and specimen from the study's one design."""

from __future__ import annotations

import functools
from dataclasses import dataclass, replace
from typing import Any, Callable, Optional

import numpy as np

from .._validate import BlastscaleInputError
from ..analysis.ensemble import ensemble_compare
from ..analysis.prototype3d import prototype_structure3d
from ..analysis.rocking_similarity import PrototypeRocking, compare_rocking
from ..analysis.structure3d import compare_structure3d
from ..analysis.systems import Settings3D, System3D, Systems3D
from ..blast.load_model import PAPER_LOAD, LoadModel, front_face_pulse
from ..blast.parameters import model_for_burst
from ..rocking.critical import critical_charge
from ..rocking.solver import DEFAULT_SOLVER
from ..rocking.system import RockingSystem
from ..scenario.scenario import Scenario
from ..sim3d.contact import ContactSettings, default_contact, reference_contact, time_constant_for_step
from ..similitude.effects import front_face
from ..similitude.factors import to_specimen
from ..structures.from_spec import is_block

__all__ = [
    "Engine",
    "ENGINES",
    "ENSEMBLE",
    "PlanarSettings",
    "EnsembleSettings",
    "planar_settings",
    "settings_3d",
    "systems_3d",
    "contact_settings",
    "critical_charge_of",
    "record_every",
    "REFERENCE_RECORD_INTERVAL",
    "load_model_of",
]


@dataclass(frozen=True)
class PlanarSettings:
    """The planar rocking engine's settings of a study (frozen, resolved once by :meth:`~.study.Study.check`).

    Attributes
    ----------
    pulse_shape : str
        Pulse shape (``blast.pulse_shape``).
    duration : float
        Prototype simulated time [s] (the specimen's is the design's).
    samples : int
        Samples of each history.
    gravity : float
        The prototype's gravity [m/s^2] (the specimen's is the design's).
    restitution : float or None
        Coefficient of restitution at impacts (None: Housner's, from the block).
    extrapolate : bool
        Let the blast fits run outside their ranges (with a warning).
    load_model : LoadModel
        The prototype's load model (the design's, with a design; the specimen's is the design's).
    """

    pulse_shape: str
    duration: float
    samples: int
    gravity: float
    restitution: Optional[float]
    extrapolate: bool
    load_model: Any


@dataclass(frozen=True)
class EnsembleSettings:
    """The 3D ensembles' settings (``simulation.ensemble_members``, ``simulation.ensemble_perturbation``)."""

    members: int
    perturbation: float


def planar_settings(scenario: Scenario, structure, design=None) -> PlanarSettings:
    """The planar settings of a scenario: its simulation table's, the load model the design's (with one) or
    :func:`load_model_of` the prototype."""
    sim, bl = scenario.simulation, scenario.blast
    return PlanarSettings(
        pulse_shape=bl.pulse_shape,
        duration=float(sim.duration_s),
        samples=int(sim.samples),
        gravity=sim.gravity_m_s2,
        restitution=sim.restitution,
        extrapolate=bl.extrapolate,
        load_model=load_model_of(scenario, structure) if design is None else design.load_model,
    )


def settings_3d(scenario: Scenario, structure) -> Settings3D:
    """The 3D settings of a scenario shared by both systems (:class:`~blastscale.analysis.systems.Settings3D`):
    load method, pulse shape, incidence, recording interval (:func:`record_every`), extrapolation."""
    bl = scenario.blast
    return Settings3D(
        load=bl.load,
        pulse_shape=bl.pulse_shape,
        incidence=bl.incidence,
        record_every=record_every(scenario, structure),
        extrapolate=bl.extrapolate,
    )


def systems_3d(scenario: Scenario, structure, design, blast, contact) -> Systems3D:
    """The study's 3D systems: the design's prototype and specimen (:meth:`Systems3D.of_design`), or the prototype
    alone under ``blast`` (None: gravity alone) with the scenario's gravity, ``contact``, duration and
    :func:`load_model_of` it."""
    if design is not None:
        return Systems3D.of_design(design)
    sim = scenario.simulation
    lm = load_model_of(scenario, structure)
    return Systems3D(System3D(structure, blast, sim.gravity_m_s2, contact, sim.duration_s, lm))


def load_model_of(scenario: Scenario, structure, *, clearing: Optional[bool] = None):
    """The prototype's load model of a scenario (:class:`~blastscale.blast.load_model.LoadModel`):
    ``blast.clearing`` (or ``clearing`` where given: the load-choice check's other choice) on the structure's
    front (:func:`~blastscale.similitude.effects.front_face`) and ``blast.negative_phase``; the paper's load
    when neither is asked for."""

    bl = scenario.blast
    clearing = bl.clearing if clearing is None else bool(clearing)
    if not (clearing or bl.negative_phase):
        return PAPER_LOAD
    face = (None, None)
    if clearing:
        face = front_face(structure)
    return LoadModel(
        clearing=clearing,
        face_width_m=face[0],
        face_height_m=face[1],
        negative_phase=bl.negative_phase,
        negative_phase_model=bl.negative_phase_model,
    )


def _planar_supports(structure) -> Optional[str]:
    return None if is_block(structure) else "planar rocking applies to a single rectangular block"


def _run_planar(plan):
    """Planar rocking of the prototype block and, with a design, of its specimen (its block, pulse
    and gravity from the design: the blast parameters are the design's, never recomputed), sampled
    at corresponding times and compared (:func:`~blastscale.analysis.rocking_similarity.compare_rocking`)."""

    ps, d = plan.planar, plan.design
    shape, dur, ex = ps.pulse_shape, ps.duration, ps.extrapolate
    t = np.linspace(0.0, dur, ps.samples)
    sys_p = RockingSystem.from_block(plan.structure, ps.gravity, ps.restitution)
    res_p = DEFAULT_SOLVER.simulate(
        sys_p, front_face_pulse(plan.blast, shape, ps.load_model, extrapolate=ex), dur, t_eval=t
    )
    if d is None:
        return PrototypeRocking(res_p)
    # the specimen system as the design carries it: block, gravity, load model and duration, scaled once there
    sys_m = RockingSystem.from_block(d.specimen_block, d.specimen_gravity, ps.restitution)
    dur_m = d.specimen_duration
    res_m = DEFAULT_SOLVER.simulate(
        sys_m,
        front_face_pulse(d.specimen, shape, d.specimen_load_model, extrapolate=ex),
        dur_m,
        t_eval=np.minimum(to_specimen(t, d.factors, "time"), dur_m),
    )
    return compare_rocking(res_p, res_m, d, sys_p.frequency_parameter)


def contact_settings(scenario: Scenario, structure=None):
    """The prototype's 3D contact settings: the engine's defaults for the structure, the
    scenario's friction, time step and every ``[simulation.contact]`` key given.

    When the time step is given without a contact time constant, the time constant is kept
    at >= 4 steps (MuJoCo needs >= 2)."""

    sim = scenario.simulation
    # scale-consistent defaults derived from the structure (the full-scale ones without it)
    base = (
        ContactSettings()
        if structure is None
        else default_contact(structure, friction=scenario.structure.friction, gravity=sim.gravity_m_s2)
    )
    given = {k: v for k, v in sim.contact.model_dump().items() if v is not None}
    names = {
        "time_constant_s": "time_constant",
        "friction_time_constant_s": "friction_time_constant",
        "impedance_width_m": "impedance_width",
    }
    kw = {names.get(k, k): v for k, v in given.items()}
    if structure is None or base.friction != scenario.structure.friction:
        kw["friction"] = scenario.structure.friction
    if sim.step_after_load != base.step_after_load:
        kw["step_after_load"] = sim.step_after_load
    if sim.timestep_s is not None:
        kw["timestep"] = sim.timestep_s
        if "time_constant" not in kw:
            kw["time_constant"] = time_constant_for_step(base.time_constant, sim.timestep_s)
    try:
        return replace(base, **kw) if kw else base
    except BlastscaleInputError as exc:
        raise BlastscaleInputError(f"simulation.contact: {exc}") from None


#: Recording interval of the 3D histories at the 10 m reference [s]: one state per millisecond,
#: i.e. every 5 steps of a block (0.2 ms) and every 4 of a drum stack (0.25 ms), at any size (the
#: steps scale with the structure, docs/sim3d.md).
REFERENCE_RECORD_INTERVAL = 1e-3


def record_every(scenario: Scenario, structure) -> int:
    """The 3D recording interval in steps: ``simulation.record_every`` when given, else one state per
    :data:`REFERENCE_RECORD_INTERVAL` of the structure's reference time step (the same number of
    steps for the prototype and the specimen, so their grids correspond)."""

    given = scenario.simulation.record_every
    if given is not None:
        return int(given)
    return max(1, round(REFERENCE_RECORD_INTERVAL / reference_contact(structure).timestep))


def _3d_supports(structure) -> Optional[str]:
    return None  # every structure of blastscale.structures runs on the 3D engine


def _run_3d(plan):
    """Prototype and specimen in 3D from the plan's systems (the design's), compared
    (:func:`~blastscale.analysis.structure3d.compare_structure3d`); without a design the prototype
    alone (:func:`~blastscale.analysis.structure3d.prototype_structure3d`)."""

    if plan.design is None:
        return prototype_structure3d(plan.systems3d.prototype, plan.settings3d, threads=plan.threads)
    return compare_structure3d(plan.systems3d, plan.settings3d, threads=plan.threads)


def _run_ensemble(plan):
    """Ensembles under perturbed loads (:func:`~blastscale.analysis.ensemble.ensemble_compare`):
    prototype and specimen, or the prototype alone without a design."""

    e = plan.ensemble
    confidence = None if plan.scenario is None else plan.scenario.verdict.confidence  # [verdict] confidence
    return ensemble_compare(
        plan.systems3d,
        plan.settings3d,
        n=e.members,
        perturbation=e.perturbation,
        threads=plan.threads,
        confidence=confidence,
    )


@dataclass(frozen=True)
class Engine:
    """One response engine: ``supports(structure)`` returns None or why not; ``run(plan)`` runs it from the
    study's :class:`~.study.StudyPlan` (its settings resolved once)."""

    name: str
    label: str
    supports: Callable[[Any], Optional[str]]
    run: Callable[[Any], Any]


#: engine name -> Engine. ``simulation.engine = "both"`` runs every engine that supports the structure.
ENGINES: dict[str, Engine] = {
    "planar": Engine("planar", "planar rocking: prototype and model", _planar_supports, _run_planar),
    "3d": Engine("3d", "3D rigid bodies (MuJoCo): prototype and model", _3d_supports, _run_3d),
}

#: Runs added to the 3D engine when ``simulation.ensemble_members >= 2``: perturbed-load ensembles
#: of prototype and model (chaotic structures are compared by envelopes, not single trajectories).
ENSEMBLE = Engine("ensemble", "3D ensembles under perturbed loads: prototype and model", _3d_supports, _run_ensemble)


def critical_charge_of(plan):
    """The prototype block's critical charge at the scenario's stand-off (planar, first-swing criterion), from a
    study's plan (:class:`~.study.StudyPlan`: its planar settings, the scenario's stand-off and blast model).

    A pure function of the block, gravity, restitution, stand-off, pulse shape and blast model: a sweep
    over charges (or any other field) at one stand-off searches it once per process (memoised on these
    values, all frozen and hashable)."""
    ps, bl = plan.planar, plan.scenario.blast
    lm = ps.load_model
    blast_model = model_for_burst(bl.blast_model, bl.burst).name
    return _critical_charge(
        plan.structure,
        ps.gravity,
        ps.restitution,
        bl.standoff_m,
        ps.pulse_shape,
        blast_model,
        ps.extrapolate,
        None if lm.is_paper else lm,
    )


@functools.lru_cache(maxsize=4096)
def _critical_charge(structure, gravity, restitution, standoff, pulse_shape, blast_model, extrapolate, load_model=None):
    system = RockingSystem.from_block(structure, gravity, restitution)
    return critical_charge(
        system,
        standoff,
        pulse_shape=pulse_shape,
        blast_model=blast_model,
        extrapolate=extrapolate,
        load_model=load_model,
    )
