"""The planner's designs for any structure: each candidate's design (its specimen burst, a charge on a
stand at a height chosen here), the screening estimates that need no simulation, and the 3D stage
of the best screened designs (docs/planning.md, "Any structure").

A structure without a planar path (a column, a wall, an arch, a portal, a block-model file; or a
block under a load model the planar kernels lack: clearing, the negative phase) is screened on its
envelope block (:func:`~.candidates.envelope_block`: the impulsive check t_o p, the timing of the
instruments) and on what the design gives in closed form: the lab's limits, the safety radius, the
blast model's range, and the spread of the shock's arrival over the front at model scale. The designs
chosen for 3D (:func:`~.plan3d_designs.choose_3d`: the best ``lab.top_3d`` screened, by screening error then
safety radius; the best screened of each material; the best at the largest admissible scale) then get the
prototype-vs-specimen 3D comparison (the candidate's Study on the 3D engine,
:meth:`~blastscale.study.Study.from_candidate`) and a 3D Monte Carlo ensemble of the lab's tolerances
(``lab.ensemble_3d`` members, default :data:`ENSEMBLE_3D_DEFAULT`; :func:`~.odds.ensemble_odds_3d`: the design's
specimen through :meth:`~blastscale.study.Study.from_design`, on threads or Dask).

The screening error of a design (lower first) is the larger of two closed-form estimates:

* the finite-pulse departure: the general law matches the impulse, not the duration, and a
  finite pulse moves the response by about (t_o p) of the impulsive answer (docs/design.md: "with
  finite pulses the up-scaled model departs from the prototype by ~1e-4 rad, the same size as the
  prototype's own finite-pulse effect"), so a duration off by delta = t_o,s / (lambda_t t_o,p) - 1
  moves it by about |delta| (t_o p)_prototype;
* for Methods B and C (faces loaded at their own arrival), the arrival-time spread over the front
  (dt from the front's foot to its top corner, the blast model's arrival-time fit) in the same
  measure: the blast's times scale as the charge's cube root, the rocking's as lambda_t, so the
  specimen's spread, up-scaled, is off by delta_a = dt_s / (lambda_t dt_p) - 1 (about sqrt(lambda) - 1
  for Hopkinson-Cranz), and it moves the response by about |delta_a| dt_p p (p the envelope's
  frequency parameter, as t_o p).
"""

from __future__ import annotations

import math
import warnings
from typing import Callable, Optional

import numpy as np

from .._validate import BlastscaleInputError
from ..blast.bursts import lab_burst
from ..blast.parameters import get_blast_model
from ..scenario.lab import SAME_MATERIAL
from ..scenario.specs import ScaleSpec
from ..similitude.effects import structure_top
from ..similitude.factors import to_specimen
from ..structures.from_spec import is_block
from ..study.study import Study
from .build import spec_dims
from .debris import reach_3d
from .odds import ensemble_odds_3d

__all__ = [
    "ENSEMBLE_3D_DEFAULT",
    "STAND_HEIGHTS",
    "design_scenario",
    "candidate_scale",
    "candidate_design",
    "stand_height",
    "front_arrival_spread",
    "screening_error",
    "similarity_3d",
    "planar_path",
    "ensemble_members",
    "run_3d",
]

#: 3D ensemble members per design for a structure without a planar path, unless ``lab.ensemble_3d`` says.
ENSEMBLE_3D_DEFAULT = 32
#: Heights of the stand the planner tries for a free-air specimen charge, x the specimen's height; the
#: lowest whose floor reflection reaches the face's mid-height after the positive phase is taken.


def planar_path(scenario, structure) -> bool:
    """Whether the planner searches ``scenario`` on the planar kernels: a block (``structure``, built from it)
    on the paper's load (no clearing, no negative phase); everything else is screened, then run in 3D."""
    return is_block(structure) and not (scenario.blast.clearing or scenario.blast.negative_phase)


def ensemble_members(scenario, structure, lab) -> int:
    """The 3D ensemble members per design the plan runs: ``lab.ensemble_3d`` when given, else 0 on the planar
    path and :data:`ENSEMBLE_3D_DEFAULT` off it."""
    if lab.ensemble_3d is not None:
        return int(lab.ensemble_3d)
    return 0 if planar_path(scenario, structure) else ENSEMBLE_3D_DEFAULT


STAND_HEIGHTS = (0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0, 12.0, 16.0)


def stand_height(design) -> float:
    """The lowest stand [m] of :data:`STAND_HEIGHTS` at which the specimen's charge is a free-air burst
    at its face (:func:`~blastscale.blast.bursts.lab_burst`); one line when none is."""

    s = design.specimen
    top = structure_top(design.specimen_structure)
    for k in STAND_HEIGHTS:
        if lab_burst(s.charge_kg, s.standoff_m, k * top, top, extrapolate=True).kind == "free-air":
            return k * top
    raise BlastscaleInputError(
        f"specimen_charge_height_m: no stand up to {STAND_HEIGHTS[-1]:g} x the specimen's "
        f"height ({STAND_HEIGHTS[-1] * top:.3g} m) makes the charge a free-air burst at its face"
    )


def candidate_scale(scenario, candidate, charge_height: Optional[float] = None) -> ScaleSpec:
    """The ``[scale]`` of a planned design (typed): the candidate's law, lambda, material or density ratio, the
    specimen's burst where it is not the prototype's, the charge's height on its stand [m]; the scenario's
    gravity ratio."""

    scale = {
        "length": candidate.scale,
        "law": candidate.law,
        "gravity_ratio": scenario.scale.gravity_ratio if scenario.scale is not None else 1.0,
    }
    if candidate.burst != scenario.blast.burst:
        scale["specimen_burst"] = candidate.burst
    if charge_height:
        scale["specimen_charge_height_m"] = float(charge_height)
    if candidate.material != SAME_MATERIAL:  # Hopkinson-Cranz: the material's density is the one the law imposes
        scale["specimen_material"] = candidate.material
    elif candidate.law == "general":
        scale["density_ratio"] = 1.0
    return ScaleSpec(**scale)


def design_scenario(scenario, candidate, lab_spec=None, charge_height: Optional[float] = None):
    """The scenario of a planned design, for the user (the plan's ``best_scenario``, a file to run): the
    prototype's, with ``[scale]`` set to the candidate (:func:`candidate_scale`) and the lab table (``lab_spec``)
    kept. The planner's own runs start from the candidate's scale (:meth:`blastscale.study.Study.from_candidate`),
    never from this scenario."""

    data = scenario.model_dump(exclude_none=True)
    data["scale"] = candidate_scale(scenario, candidate, charge_height).model_dump(exclude_none=True)
    if lab_spec is not None:
        data["lab"] = lab_spec.model_dump(exclude_none=True)
    with warnings.catch_warnings():  # validated once already: its warnings were said
        warnings.simplefilter("ignore")
        return type(scenario).from_dict(data, source="plan")


def candidate_design(scenario, structure, lab) -> Callable:
    """``design(candidate) -> (ModelDesign, charge height [m])``: the Study's design of the candidate
    (:meth:`~blastscale.study.Study.from_candidate` with :func:`candidate_scale`; the load model, bursts, contact
    and duration as the Study's, one door), on ``structure`` built once. A free-air candidate stands on the scenario's
    ``scale.specimen_charge_height_m`` or, without one, on :func:`stand_height`'s."""

    given = scenario.scale.specimen_charge_height_m if scenario.scale is not None else None

    def design(c):
        h = given if c.burst != "surface" else None
        d = Study.from_candidate(scenario, candidate_scale(scenario, c, h)).design(structure)
        if c.burst != "surface" and h is None:
            h = stand_height(d)
            d = Study.from_candidate(scenario, candidate_scale(scenario, c, h)).design(structure)
        return d, float(h or 0.0)

    return design


def front_arrival_spread(params, structure, factors=None) -> float:
    """Arrival-time spread [s] over the front of ``structure`` (prototype dimensions; with ``factors``, a
    :class:`~blastscale.similitude.ScalingFactors`, the specimen's: :func:`~blastscale.similitude.factors.to_specimen`): from the front's foot (the stand-off) to its top corner (height, half its width
    across the blast), with the blast model's arrival-time fit at ``params`` (charge, stand-off): an estimate
    before any load is built (a built load's own spread: :func:`blastscale.sim3d.face_loads.load_arrival_spread`)."""

    dims = spec_dims(structure)
    h, _, dp = dims if factors is None else (to_specimen(x, factors, "length") for x in dims)
    m = get_blast_model(params.blast_model) if isinstance(params.blast_model, str) else params.blast_model
    w13 = float(params.charge_kg) ** (1.0 / 3.0)
    r0 = float(params.standoff_m)
    z = np.array([r0, math.sqrt(r0 * r0 + h * h + 0.25 * dp * dp)]) / w13
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ta = np.asarray(m.scaled_arrival_time(z, extrapolate=True), dtype=float) * w13
    return float(ta[1] - ta[0])


def screening_error(ev, load_method: str) -> float:
    """The screening error of an evaluated design [-] (module docstring)."""
    d = ev.design
    delta = (
        float(d.specimen.positive_duration) / to_specimen(float(d.prototype.positive_duration), d.factors, "time") - 1.0
    )
    err = abs(delta) * float(ev.impulsive.prototype_ratio)
    if load_method != "A":
        proto = d.prototype_structure
        dt_p = front_arrival_spread(d.prototype, proto)
        dt_s = front_arrival_spread(d.specimen, proto, d.factors)
        p = float(ev.impulsive.prototype_ratio) / float(d.prototype.positive_duration)  # rad/s
        if dt_p > 0:
            err = max(err, abs(dt_s / to_specimen(dt_p, d.factors, "time") - 1.0) * dt_p * p)
    return err


def similarity_3d(summary3d: dict) -> float:
    """The 3D similarity error of a design [-]: 1 when the specimen's outcome is not the prototype's,
    else the relative error of the up-scaled first peak of the top's displacement (``|ratio - 1|``; the
    largest difference over the peak where no first peak is found)."""
    sim = summary3d["similarity"]
    if not sim.get("outcomes_agree", True):
        return 1.0
    r = sim.get("top_first_peak_ratio")
    if r is not None and math.isfinite(float(r)):
        return abs(float(r) - 1.0)
    v = sim.get("max_abs_top_displacement_diff_rel_peak")
    return float(v) if v is not None else math.nan


def run_3d(
    scenario,
    ev,
    lab,
    *,
    members: int,
    tolerances,
    workers: int = 0,
    scheduler: Optional[str] = None,
    tick: Optional[Callable[[int], None]] = None,
) -> tuple:
    """The 3D stage of one screened design: the prototype-vs-specimen comparison (the candidate's Study on the
    3D engine, :meth:`~blastscale.study.Study.from_candidate`) and the specimen's ensemble of the lab's
    tolerances.

    Returns
    -------
    (StudyResult, dict, dict or None)
        The comparison's Study result (its ``summary()``: ``3d`` with ``prototype``, ``model``,
        ``similarity``; ``verdict``, the criterion's, :func:`~blastscale.study.criterion.judge`, under the
        scenario's ``[verdict]``), the similarity (``error``, ``specimen_top_m`` [m], ``specimen_reach_m``
        [m], ``prototype_reach_m`` [m]) and ``odds_3d`` (None with 0 members). The Study runs the scenario
        on the 3D engine alone (no critical charge searched; its ``simulation.ensemble_members`` kept: a chaotic
        structure is judged between ensembles) with ``lab`` as its ``[lab]``; its result is the one
        ``plan --out`` writes, test card included.
    """

    scale = candidate_scale(scenario, ev.candidate, ev.charge_height_m or None)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sim3 = scenario.simulation.model_copy(update={"engine": "3d", "critical_charge": False})
        res = Study.from_candidate(scenario.model_copy(update={"lab": lab, "simulation": sim3}), scale).run()
    s3 = res.summary()["3d"]
    cmp3 = res.response3d
    f = ev.design.factors
    up = getattr(cmp3, "upscaled_dataset", None)
    sim = {
        "error": similarity_3d(s3),
        "specimen_top_m": to_specimen(float(s3["model"]["max_top_displacement_m"]), f, "length"),
        "specimen_reach_m": to_specimen(reach_3d(up, res.structure), f, "length") if up is not None else math.nan,
        "prototype_reach_m": reach_3d(cmp3.prototype_dataset, res.structure),
    }
    odds = None
    if members:
        odds = ensemble_odds_3d(
            scenario,
            ev.design,
            prototype_collapsed=bool(s3["prototype"]["collapsed"]),
            tolerances=tolerances,
            members=members,
            seed=lab.seed,
            workers=workers,
            scheduler=scheduler,
            tick=tick,
        )
    return res, sim, odds
