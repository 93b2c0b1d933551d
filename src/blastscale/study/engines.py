"""The response engines of a study, chosen by name (:data:`ENGINES`): planar rocking and 3D rigid
bodies (MuJoCo), plus 3D ensembles (:data:`ENSEMBLE`) for chaotic structures. Each engine says
whether it supports a structure and runs prototype and specimen from the study's one design."""

from __future__ import annotations

import functools
from dataclasses import dataclass, replace
from typing import Any, Callable, Optional

from .._validate import BlastscaleInputError
from ..scenario.scenario import Scenario
from ..structures.from_spec import is_block
from ..blast.load_model import PAPER_LOAD, LoadModel
import numpy as np
from ..blast.load_model import front_face_pulse
from ..sim3d.contact import ContactSettings
from ..sim3d.contact import time_constant_for_step
from ..sim3d.contact import default_contact
from ..sim3d.contact import reference_contact
from ..analysis.structure3d import compare_structure3d
from ..analysis.prototype3d import prototype_structure3d
from ..analysis.ensemble import ensemble_compare
from ..blast.parameters import model_for_burst
from ..similitude.effects import front_face
from ..analysis.rocking_similarity import PrototypeRocking, compare_rocking
from ..rocking.system import RockingSystem
from ..rocking.solver import DEFAULT_SOLVER
from ..rocking.critical import critical_charge

__all__ = [
    "Engine",
    "ENGINES",
    "ENSEMBLE",
    "Context",
    "contact_settings",
    "critical_charge_of",
    "record_every",
    "REFERENCE_RECORD_INTERVAL",
    "load_model_of",
]


@dataclass(frozen=True)
class Context:
    """What every engine receives: the scenario, the built prototype, the one design (None for a
    prototype-only scenario; it carries the specimen system), the prototype's blast parameters (the
    design's when there is one) and the prototype's 3D contact settings (resolved once, by the check)."""

    scenario: Scenario
    structure: Any
    design: Any
    blast: Any
    contact: Any = None


def load_model_of(scenario: Scenario, structure):
    """The prototype's load model of a scenario (:class:`~blastscale.blast.load_model.LoadModel`):
    ``blast.clearing`` on the structure's front (:func:`~blastscale.similitude.effects.front_face`)
    and ``blast.negative_phase``; the paper's load when neither is asked for."""

    bl = scenario.blast
    if not (bl.clearing or bl.negative_phase):
        return PAPER_LOAD
    face = (None, None)
    if bl.clearing:
        face = front_face(structure)
    return LoadModel(
        clearing=bl.clearing,
        face_width_m=face[0],
        face_height_m=face[1],
        negative_phase=bl.negative_phase,
        negative_phase_model=bl.negative_phase_model,
    )


def _planar_supports(structure) -> Optional[str]:
    return None if is_block(structure) else "planar rocking applies to a single rectangular block"


def _run_planar(ctx: Context):
    """Planar rocking of the prototype block and, with a design, of its specimen (its block, pulse
    and gravity from the design: the blast parameters are the design's, never recomputed), sampled
    at corresponding times and compared (:func:`~blastscale.analysis.rocking_similarity.compare_rocking`)."""

    sc, sim, d = ctx.scenario, ctx.scenario.simulation, ctx.design
    shape, dur = sc.blast.pulse_shape, float(sim.duration_s)
    lm = load_model_of(sc, ctx.structure) if d is None else d.load_model
    ex = sc.blast.extrapolate
    t = np.linspace(0.0, dur, int(sim.samples))
    sys_p = RockingSystem.from_block(ctx.structure, sim.gravity_m_s2, sim.restitution)
    res_p = DEFAULT_SOLVER.simulate(sys_p, front_face_pulse(ctx.blast, shape, lm, extrapolate=ex), dur, t_eval=t)
    if d is None:
        return PrototypeRocking(res_p)
    # the specimen system as the design carries it: block, gravity, load model and duration, scaled once there
    sys_m = RockingSystem.from_block(d.specimen_block, d.specimen_gravity, sim.restitution)
    dur_m = d.specimen_duration
    res_m = DEFAULT_SOLVER.simulate(
        sys_m,
        front_face_pulse(d.specimen, shape, d.specimen_load_model, extrapolate=ex),
        dur_m,
        t_eval=np.minimum(t * d.factors.time, dur_m),
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


def _settings_3d(ctx: Context) -> dict:
    """The 3D settings of a study, shared by the 3D and the ensemble engines."""
    sc = ctx.scenario
    contact = contact_settings(sc, ctx.structure) if ctx.contact is None else ctx.contact
    out = dict(
        load=sc.blast.load,
        pulse_shape=sc.blast.pulse_shape,
        incidence=sc.blast.incidence,
        contact=contact,
        duration=sc.simulation.duration_s,
        record_every=record_every(sc, ctx.structure),
        extrapolate=sc.blast.extrapolate,
    )
    if sc.blast.clearing or sc.blast.negative_phase:  # each system's faces are its own (the structure's)
        out["load_model"] = LoadModel(
            clearing=sc.blast.clearing,
            negative_phase=sc.blast.negative_phase,
            negative_phase_model=sc.blast.negative_phase_model,
        )
    return out


def _run_3d(ctx: Context):
    """Prototype and specimen in 3D from the design's blast parameters, compared
    (:func:`~blastscale.analysis.structure3d.compare_structure3d`); without a design the prototype
    alone from ``ctx.blast`` (:func:`~blastscale.analysis.structure3d.prototype_structure3d`)."""

    if ctx.design is None:
        return prototype_structure3d(
            ctx.structure, ctx.blast, gravity=ctx.scenario.simulation.gravity_m_s2, **_settings_3d(ctx)
        )
    return compare_structure3d(ctx.structure, ctx.design, threads=ctx.scenario.simulation.threads, **_settings_3d(ctx))


def _run_ensemble(ctx: Context):
    """Ensembles under perturbed loads (:func:`~blastscale.analysis.ensemble.ensemble_compare`):
    prototype and specimen, or the prototype alone without a design."""

    sim = ctx.scenario.simulation
    return ensemble_compare(
        ctx.structure,
        ctx.design,
        n=sim.ensemble_members,
        perturbation=sim.ensemble_perturbation,
        blast=ctx.blast,
        gravity=sim.gravity_m_s2,
        threads=sim.threads,
        **_settings_3d(ctx),
    )


@dataclass(frozen=True)
class Engine:
    """One response engine: ``supports(structure)`` returns None or why not; ``run(ctx)``."""

    name: str
    label: str
    supports: Callable[[Any], Optional[str]]
    run: Callable[[Context], Any]


#: engine name -> Engine. ``simulation.engine = "both"`` runs every engine that supports the structure.
ENGINES: dict[str, Engine] = {
    "planar": Engine("planar", "planar rocking: prototype and model", _planar_supports, _run_planar),
    "3d": Engine("3d", "3D rigid bodies (MuJoCo): prototype and model", _3d_supports, _run_3d),
}

#: Runs added to the 3D engine when ``simulation.ensemble_members >= 2``: perturbed-load ensembles
#: of prototype and model (chaotic structures are compared by envelopes, not single trajectories).
ENSEMBLE = Engine("ensemble", "3D ensembles under perturbed loads: prototype and model", _3d_supports, _run_ensemble)


def critical_charge_of(sc: Scenario, structure):
    """The prototype block's critical charge at the scenario's stand-off (planar, first-swing criterion).

    A pure function of the block, gravity, restitution, stand-off, pulse shape and blast model: a sweep
    over charges (or any other field) at one stand-off searches it once per process (memoised)."""
    sim, bl = sc.simulation, sc.blast
    lm = load_model_of(sc, structure)

    blast_model = model_for_burst(bl.blast_model, bl.burst).name
    return _critical_charge(
        structure,
        sim.gravity_m_s2,
        sim.restitution,
        bl.standoff_m,
        bl.pulse_shape,
        blast_model,
        bl.extrapolate,
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
