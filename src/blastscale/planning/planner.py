"""``plan``: from a prototype of any kind and a lab to the designs the lab can fire, best first.

The planner searches the geometric scale lambda (the fractions of
:data:`~.candidates.LAMBDA_DENOMINATORS`), the density ratio gamma through the lab's materials, the
scaling law (general; Hopkinson-Cranz where a material's density allows it) and the specimen's burst
(``lab.bursts``), designs each candidate (the Study's design of the candidate, :meth:`~blastscale.study.Study.from_candidate`: the load
model as the scenario's), rejects those that break a constraint of the lab or of the material (not rigid
enough, a friction regime other than the prototype's: docs/planning.md "Materials"; each rejection with its
reasons, :func:`screen`), and for the feasible ones propagates the lab's tolerances by Monte Carlo: a block
on the paper's load through the planar kernels (:mod:`.odds`), any other structure or load model
through the 3D stage of its best screened designs (:mod:`.plan3d`, :mod:`.plan3d_designs`). The
Pareto-optimal designs are marked (:mod:`.pareto`). Ranking and recommendation (:mod:`.recommend`,
docs/planning.md): the designs are judged by the one similarity criterion (their Study's ``verdict``:
the 3D path's comparisons; the planar path's leaders in rank order until one passes); the designs it
passes rank first (by the odds that the outcome agrees, to 0.01, then the simulated error, then the
safety radius), then those it rejects, closest first (the worst judged quantity's ratio), then the
designs not judged, then those screened only. A design the criterion rejects is never recommended:
``Plan.recommendation`` says so in one line, with the closest design and the binding quantity.

A lab no design fits raises :class:`PlanInfeasible`: one line naming the constraint that cannot be
met and the value that would relax it.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Callable, Optional

from .._validate import BlastscaleInputError
from ..blast.explosive_library import EXPLOSIVES
from ..blast.explosives import get_explosive
from ..blast.parameters import blast_parameters, get_blast_model, model_for_burst
from ..structures import from_spec
from ..structures.materials import prototype_material
from ..study.study import Study
from .candidates import Evaluated, candidates, envelope_block, evaluate, scale_label, shot_dict, specimen_displacement
from .card import specimen_timing
from .debris import planar_reach
from .instruments import GAUGE_HEADROOM
from .odds import Tolerances, ensemble_odds_3d, outcome_odds_text, planar_odds
from .pareto import mark_pareto
from .plan3d import candidate_design, design_scenario, planar_path, screening_error
from .plan3d_designs import designs_3d
from .recommend import rank_key, ranked_after, recommend, verdict_of, verdict_tolerances
from .shot import DEFAULT_LAB, lab_explosives, lab_source, safety_envelope, timing_of

__all__ = ["plan", "screen", "Plan", "PlanInfeasible", "QUICK_SAMPLES", "FULL_DESIGNS"]

#: Draws per feasible design in the first pass of the odds; the leading :data:`FULL_DESIGNS` (after it)
#: get the lab's ``samples`` and their weighing precision.
QUICK_SAMPLES = 200
FULL_DESIGNS = 10


class PlanInfeasible(BlastscaleInputError):
    """No candidate satisfies every constraint of the lab (the message says which and what would relax it)."""


@dataclass(frozen=True)
class Plan:
    """The planner's answer: ``designs`` (dicts, best first), ``rejected`` (dicts with ``reasons``),
    the ``prototype`` reference, the ``lab`` used, the first design's scenario (``best_scenario``: the
    recommended design, or the closest when the criterion passes none), ``recommendation``
    (:func:`~.recommend.recommend`: ``design`` 0 or None, ``line``, the binding quantity and limit) and
    ``best_result``, the Study result that judged the first design (None when none did; ``plan --out``
    writes it, so the report's verdict is the plan's)."""

    designs: list
    rejected: list
    prototype: dict
    lab: dict
    best_scenario: object = None
    notes: list = field(default_factory=list)
    recommendation: dict = field(default_factory=dict)
    best_result: object = None

    def to_dict(self) -> dict:
        return {
            "designs": self.designs,
            "rejected": self.rejected,
            "prototype": self.prototype,
            "lab": self.lab,
            "ranking": "designs the criterion passes (verdict.similar true) first, by p_outcome_agree (0.01), "
            "the simulated error predicted_first_peak_error (2 significant digits), safety_radius_m; then the "
            "designs it rejects or cannot establish, by verdict.worst.ratio (closest first), simulated error, "
            "safety_radius_m; then designs simulated but not judged (simulated_by set, verdict null), by odds, "
            "simulated error, safety_radius_m; then designs screened only (simulated_by null), by screening_error "
            "(2 significant digits), safety_radius_m; pareto: optimal over odds, simulated error, safety radius "
            "and charge",
            "notes": list(self.notes),
            "recommendation": dict(self.recommendation),
        }


def load_assumed(scenario, planar: bool) -> dict:
    """The load the plan assumed, for its table, card and JSON (issue #39): ``load_method`` ("A", "B", "C"),
    ``load_clearing`` (bool) and ``load_assumed`` in words. The planar path loads the block's front with the
    reflected pulse, uniform and simultaneous: Method A's load, whatever ``blast.load`` says (a 3D key);
    the 3D path runs ``blast.load``. docs/face_loads.md ("Which load method") says when each fits."""
    bl = scenario.blast
    method = "A" if planar else bl.load
    how = "planar rocking: the reflected pulse on the front" if planar else "3D"
    clear = " with clearing" if bl.clearing else ""
    return {
        "load_method": method,
        "load_clearing": bool(bl.clearing),
        "load_assumed": f"load: Method {method}{clear} ({how}; docs/face_loads.md, 'Which load method')",
    }


def _prototype(scenario, block):
    """The prototype's block (or any structure's envelope block), its nominal first swing, timing and
    safety envelope."""
    from ..analysis.planar import first_swing_of, history_of, planar_system  # noqa: PLC0415 -- start-up: at module top `blastscale` would load numba, scipy

    bl, sim = scenario.blast, scenario.simulation
    system = planar_system(block, sim.gravity_m_s2, sim.restitution)

    bm = model_for_burst(bl.blast_model, bl.burst)
    bp = blast_parameters(bl.charge_kg, bl.standoff_m, bm, extrapolate=bl.extrapolate)
    fs = first_swing_of(
        system, bl.charge_kg, bl.standoff_m, pulse_shape=bl.pulse_shape, blast_model=bm, extrapolate=bl.extrapolate
    )
    res = history_of(system, bp.pulse(bl.pulse_shape), float(sim.duration_s))
    collapsed, rot = bool(fs.collapsed[0]), float(fs.max_rotation[0])
    reach = planar_reach(block.width, block.height, rot, collapsed)
    env = safety_envelope(bl.charge_kg, DEFAULT_LAB.safety_threshold)
    return (
        block,
        system,
        timing_of(res),
        {
            "height_m": block.height,
            "width_m": block.width,
            "depth_m": block.depth,
            "mass_kg": block.mass,
            "charge_kg": bl.charge_kg,
            "standoff_m": bl.standoff_m,
            "collapsed": collapsed,
            "first_peak_rotation_rad": None if collapsed else rot,
            "reach_m": reach,
            "safety_distances_m": env.distances_m,
        },
    )


def _rank_key(d: dict) -> tuple:
    err = d["predicted_first_peak_error"]
    err2 = float(f"{err:.2g}") if err is not None and math.isfinite(err) else math.inf
    return (-round(d["p_outcome_agree"], 2), err2, d["safety_radius_m"])


def _design_dict(ev: Evaluated, odds, proto: dict, lab, scenario) -> dict:
    spec = ev.specimen
    collapsed_s = odds.first_peak_nominal_rad is None
    top, reach = specimen_displacement(spec, odds.first_peak_nominal_rad, collapsed_s)
    th_p = proto["first_peak_rotation_rad"]
    if proto["collapsed"] != collapsed_s:
        err = 1.0
    elif collapsed_s:
        err = 0.0
    else:
        err = abs(odds.first_peak_nominal_rad / th_p - 1.0)
    spread = odds.first_peak_spread or 0.0
    tol = odds.charge_tolerance_needed
    return {
        **shot_dict(ev, lab, top, reach),
        "screening_error": screening_error(ev, scenario.blast.load),
        "simulated_by": "planar",
        "p_outcome_agree": odds.p_outcome_agree,
        "p_outcome_agree_low": odds.p_outcome_agree_low,
        "p_outcome_agree_high": odds.p_outcome_agree_high,
        "first_peak_spread": odds.first_peak_spread,
        "similarity_error": err,
        "predicted_first_peak_error": math.hypot(err, spread),
        "charge_tolerance_needed": tol,
        "weighing_precision_kg": None
        if tol is None or getattr(ev.charge, "explosive_mass_kg", None) is None
        else tol * ev.charge.explosive_mass_kg,
        "odds": odds.to_dict(),
    }


def _reasons(d: dict, best: Optional[dict], tolerances: str) -> list:
    v = d.get("verdict")
    out = [
        "not judged by the similarity criterion (a design ranked before it passes)"
        if v is None
        else v["line"].removesuffix(".") + f" (tolerances [verdict]: {tolerances})",
        f"outcome agrees with the prototype's (draws of the lab's tolerances): {outcome_odds_text(d['odds'])}",
        f"simulated (planar) first-peak error {100 * d['predicted_first_peak_error']:.2g} % (similarity "
        f"{100 * d['similarity_error']:.2g} %, spread under the lab's tolerances "
        f"{'-' if d['first_peak_spread'] is None else format(100 * d['first_peak_spread'], '.2g')} %; "
        f"screening error {100 * d['screening_error']:.2g} %)",
        f"safety radius ({d['safety_threshold']}) {d['safety_radius_m']:.3g} m",
    ]
    if best is not None and d is not best:
        out.append(ranked_after(best, d))
    return out


def _infeasible(evs: list, lab) -> str:
    """The one line of a lab that no candidate fits."""
    alone: dict = {}
    for ev in evs:
        keys = {v.key for v in ev.violations}
        if len(keys) == 1:
            alone.setdefault(next(iter(keys)), []).append(ev)
    if not alone:
        ev = min(evs, key=lambda e: len(e.violations))
        return (
            f"no design fits the lab: the closest ({ev.candidate.law}, lambda = {scale_label(ev.candidate.scale)}, "
            f"{ev.candidate.material}) breaks {len(ev.violations)} constraints: "
            + "; ".join(v.text for v in ev.violations)
        )
    key, group = max(alone.items(), key=lambda kv: len(kv[1]))
    if key in ("blast fits", "impulsive", "rigidity", "friction"):
        return f"no design fits the lab: {group[0].violations[0].text}"
    if key in _RELAXERS:
        return _RELAXERS[key](group, len(evs), lab)
    lower = key in ("charge_min_kg", "standoff_min_m")
    pick = (max if lower else min)(group, key=lambda e: e.violations[0].value)
    v, c = pick.violations[0], pick.candidate
    rel = "at most" if lower else "at least"
    return (
        f"no design fits the lab: {key} = {v.limit:g} cannot be met ({len(group)} of {len(evs)} candidates "
        f"fail on it alone); {key} {rel} {v.value:.4g} would admit {c.law}, lambda = {scale_label(c.scale)}, "
        f"{c.material}"
    )


def _below_min_charge(group: list, n: int, lab) -> str:
    """Every charge the other limits allow is below the explosive's minimum reliable charge."""

    pick = max(group, key=lambda e: e.violations[0].value / e.violations[0].limit)
    v, c, ex = pick.violations[0], pick.candidate, get_explosive(lab.explosive, lab_explosives(lab))
    small = min(EXPLOSIVES.values(), key=lambda e: e.min_charge_kg if e.name != "lead-azide" else math.inf)
    return (
        f"no design fits the lab: the charge is below {ex.name}'s minimum reliable charge {v.limit:.4g} kg "
        f"({len(group)} of {n} candidates fail on it alone; the largest, {v.value:.4g} kg, at {c.law}, "
        f"lambda = {scale_label(c.scale)}, {c.material}); a larger specimen (specimen_max_height_m, "
        f"specimen_max_mass_kg) or an explosive with a smaller minimum charge ({small.name}: "
        f"{small.min_charge_kg:.3g} kg) would relax it"
    )


def _initiator_too_large(group: list, n: int, lab) -> str:
    """The initiator carries more than ``initiator_max_fraction`` of every charge the other limits allow."""
    pick = min(group, key=lambda e: e.violations[0].value)
    v, c = pick.violations[0], pick.candidate
    w = lab.initiator_tnt_kg / v.value  # the candidate's TNT charge [kg]
    more = f", or initiator_max_fraction at least {v.value:.3g}" if v.value <= 1.0 else ""
    return (
        f"no design fits the lab: initiator_max_fraction = {v.limit:g} cannot be met with initiator_tnt_kg = "
        f"{lab.initiator_tnt_kg:.4g} kg ({len(group)} of {n} candidates fail on it alone); an initiator of at most "
        f'{v.limit * w:.3g} kg TNT (initiator_tnt_kg, or initiator = "none" for a laser) would admit '
        f"{c.law}, lambda = {scale_label(c.scale)}, {c.material}{more}"
    )


#: One-line answers for the constraints whose relaxation is not the lab key's own value.
_RELAXERS = {"explosive_min_charge_kg": _below_min_charge, "initiator_max_fraction": _initiator_too_large}


def plan(
    scenario,
    *,
    lab=None,
    workers: int = 0,
    scheduler: Optional[str] = None,
    progress: Optional[Callable[[str, int, int], None]] = None,
) -> Plan:
    """Plan the laboratory test of ``scenario``'s prototype (module docstring).

    Parameters
    ----------
    scenario : Scenario
        The prototype (any structure kind), its charge and stand-off, blast and load model, pulse and
        simulation settings; its ``[scale]`` is ignored (the planner chooses) but for
        ``specimen_burst`` and ``specimen_charge_height_m``, its ``[lab]`` gives the constraints.
    lab : LabSpec, optional
        Overrides the scenario's ``[lab]`` (default: it, or every key's default).
    workers, scheduler
        Where the 3D ensembles run (local Dask workers, a scheduler's address; 0 and None: native
        threads in this process).
    progress : callable, optional
        ``progress(stage, done, total)``.

    Returns
    -------
    Plan

    Raises
    ------
    PlanInfeasible
        No candidate meets every constraint.
    """
    tell = progress or (lambda *a: None)
    lab = lab or scenario.lab or DEFAULT_LAB
    planar, evs, proto = screen(scenario, lab, tell)
    ok = [e for e in evs if not e.violations]
    rejected = [
        {
            **e.candidate.describe(),
            "constraints": [v.key for v in e.violations],
            "reasons": [v.text for v in e.violations],
            "tnt_equivalent_kg": None if e.design is None else float(e.design.specimen_charge_kg),
            "rigidity": None if e.rigidity is None else e.rigidity.to_dict(),
        }
        for e in evs
        if e.violations
    ]
    if not ok:
        raise PlanInfeasible(_infeasible(evs, lab))
    tol = Tolerances.from_lab(lab)
    if planar:
        designs, notes, result = _planar_designs(scenario, ok, proto, lab, tol, tell)
    else:
        designs, proto, notes, result = designs_3d(
            scenario, ok, proto, lab, tol, tell, workers=workers, scheduler=scheduler
        )
    proto = {**proto, **load_assumed(scenario, planar)}
    best = next(e for e in ok if e.candidate.describe() == {k: designs[0][k] for k in e.candidate.describe()})
    best_sc = (
        result.scenario
        if result is not None
        else design_scenario(scenario, best.candidate, lab, best.charge_height_m or None)
    )
    rec = recommend(designs, rejected)
    if planar and lab.ensemble_3d:
        tell("3D ensemble of the best design", 0, 1)
        designs[0]["odds_3d"] = ensemble_odds_3d(
            scenario,
            best.design,
            prototype_collapsed=proto["collapsed"],
            tolerances=tol.for_shot(best.charge),
            members=lab.ensemble_3d,
            seed=lab.seed,
            workers=workers,
            scheduler=scheduler,
        )
        notes.append("odds_3d: the best design's 3D ensemble (friction and density tolerances included)")
    mark_pareto(designs)
    return Plan(
        designs,
        rejected,
        proto,
        {**lab.model_dump(mode="json"), "initiator_tnt_kg": lab.initiator_tnt_kg},
        best_sc,
        notes,
        rec,
        result,
    )


def screen(scenario, lab, tell=None) -> tuple:
    """Every candidate of ``scenario``'s prototype designed and checked against ``lab``, no simulation
    beyond the prototype's (or its envelope block's) planar first swing.

    Returns
    -------
    (bool, list of Evaluated, dict)
        Whether the planar path plans it (a block on the paper's load), every candidate evaluated
        (``violations`` empty: feasible) and the prototype's record.
    """

    tell = tell or (lambda *a: None)
    sc = scenario
    lab_source(lab)  # [lab] source read (and checked) once, before any candidate
    structure = from_spec(sc.structure)
    planar = planar_path(sc, structure)
    block, _, timing, proto = _prototype(scenario, envelope_block(structure))
    if not planar:
        proto = {
            **proto,
            "kind": sc.structure.kind,
            "mass_kg": float(structure.mass),
            "collapsed": None,
            "first_peak_rotation_rad": None,
            "reach_m": None,
            "screening": "envelope block (planar first swing)",
        }
    kb = get_blast_model("kingery-bulmash")
    bursts = [sc.scale.specimen_burst] if sc.scale is not None and sc.scale.specimen_burst else lab.bursts
    cands = candidates(
        lab, sc.structure.density_kg_m3, block.height, sc.scale.gravity_ratio if sc.scale is not None else 1.0, bursts
    )
    design = candidate_design(scenario, structure, lab)
    proto_mat = prototype_material(sc.structure.density_kg_m3, sc.structure.friction, lab.prototype_material)
    proto = {**proto, "material": proto_mat.name, "friction": proto_mat.friction}
    evs = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for i, c in enumerate(cands):
            tell("designing the candidates", i, len(cands))
            evs.append(
                evaluate(
                    c,
                    lab=lab,
                    block=block,
                    timing=timing,
                    incident_model=kb,
                    design=design,
                    prototype=proto_mat,
                    planar=planar,
                )
            )
    return planar, evs, proto


def _planar_designs(scenario, ok: list, proto: dict, lab, tol, tell) -> tuple:
    """The feasible designs of a block on the paper's load, ranked by their planar Monte Carlo odds."""
    sim, bl = scenario.simulation, scenario.blast

    def odds_of(e, n, critical):
        return planar_odds(
            e.specimen,
            charge_kg=e.design.specimen_charge_kg,
            standoff_m=e.design.specimen_standoff_m,
            prototype_collapsed=proto["collapsed"],
            explosive_fraction=1.0 - e.charge.initiator_fraction,
            gravity=e.design.specimen_gravity,
            restitution=sim.restitution,
            pulse_shape=bl.pulse_shape,
            blast_model=e.design.specimen.blast_model,
            tolerances=tol.for_shot(e.charge),
            samples=n,
            seed=lab.seed,
            target=lab.first_peak_target,
            critical=critical,
        )

    quick = min(lab.samples, QUICK_SAMPLES)
    designs = []
    for i, e in enumerate(ok):  # every feasible design with a few draws, then the leaders with all of them
        tell("Monte Carlo odds of the feasible designs", i, len(ok) + FULL_DESIGNS)
        designs.append((_design_dict(e, odds_of(e, quick, False), proto, lab, scenario), e))
    designs.sort(key=lambda de: _rank_key(de[0]))
    for i, (_, e) in enumerate(designs[:FULL_DESIGNS]):
        tell("Monte Carlo odds of the leading designs", len(ok) + i, len(ok) + FULL_DESIGNS)
        designs[i] = (_design_dict(e, odds_of(e, lab.samples, True), proto, lab, scenario), e)
    designs.sort(key=lambda de: _rank_key(de[0]))
    result = _judge_leaders(scenario, designs, lab, tell)
    designs.sort(key=lambda de: rank_key(de[0]))
    designs = [d for d, _ in designs]
    words = verdict_tolerances(scenario.verdict)
    for d in designs:
        d["reasons"] = _reasons(d, designs[0], words)
    return designs, [], result


def _timed(d: dict, e, lab, res) -> None:
    """A judged design's instruments from its Study's simulated timing (:func:`~.card.specimen_timing`, the
    test card's), in place of the screening's: the plan table's camera rate is the card's."""
    timing = specimen_timing(res)
    if timing is not None:
        top = d["instruments"]["displacement_range_m"] / GAUGE_HEADROOM
        new = shot_dict(e, lab, top, d["specimen_reach_m"], timing)
        d.update({k: new[k] for k in ("camera_fps", "camera_fps_required", "pressure_sampling_hz", "instruments")})


def _judge_leaders(scenario, designs: list, lab, tell):
    """Judge the leading planar designs (``designs``: (dict, Evaluated) pairs, ranked by their odds) in rank order
    by the Study of each (its scenario as ``plan --out`` writes it: :func:`design_scenario`, the scenario's own
    engines) until the criterion passes one, at most :data:`FULL_DESIGNS`; each judged design gets ``verdict``
    (the others None). Returns the Study result of the one it passes, else of the closest judged (None: none
    judged)."""
    for d, _ in designs:
        d["verdict"] = None
    kept = None  # (design, its Study result), the closest so far: one result held, not all
    for i, (d, e) in enumerate(designs[:FULL_DESIGNS]):
        tell("the similarity criterion on the leading designs", i, min(FULL_DESIGNS, len(designs)))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = Study(design_scenario(scenario, e.candidate, lab, e.charge_height_m or None)).run()
        d["verdict"] = verdict_of(res.summary())
        _timed(d, e, lab, res)
        if d["verdict"]["similar"] is True:
            return res
        if kept is None or rank_key(d) < rank_key(kept[0]):
            kept = (d, res)
    return None if kept is None else kept[1]
