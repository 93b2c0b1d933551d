"""``Study``: one scenario from the structure to the similarity verdict (like pvlib's ModelChain).

The data flow of the method, once, in one direction::

    scenario -> structure -> model design (once) -> engines (planar rocking, 3D rigid bodies):
    prototype and model runs, the model up-scaled and compared -> StudyResult

Every choice of the scenario passes through (blast model, load method, pulse, incidence
model, scaling law, contact settings, time step, solver settings). What is built is chosen
from small registries, so that a new structure kind or engine needs no change here:

* :data:`blastscale.structures.STRUCTURE_BUILDERS` -- ``structure.kind`` -> builder(structure table) -> structure;
* :data:`ENGINES` -- ``"planar"`` (rocking, :func:`~blastscale.analysis.rocking_similarity.compare_rocking`,
  single blocks) and ``"3d"`` (MuJoCo, :func:`~blastscale.analysis.structure3d.compare_structure3d`,
  any structure), plus :data:`ENSEMBLE` (:func:`~blastscale.analysis.ensemble.ensemble_compare`)
  when ``simulation.ensemble_members >= 2``.

The plan (:class:`StudyPlan`, :meth:`Study.check`) resolves every engine setting once, as frozen typed objects
(planar settings, the 3D settings and each system with its load model, the ensembles, the run's size); the
engines read it, never the scenario. A study may also start from a design (like pvlib's
``ModelChain.run_model_from_poa``): :meth:`Study.from_design` runs one system of a design alone (the fired
test's prediction and refit, a calibration, the planner's specimen ensembles) and :meth:`Study.from_candidate`
a candidate's design (the planner): no scenario is written to get back in.

No CLI code: the ``blastscale run`` command and the sweeps only call :class:`Study` and read
the :class:`StudyResult`. Example (the built-in default, shortened):

>>> from blastscale.scenario import Scenario
>>> sc = Scenario.default().with_values({"duration_s": 0.05, "engine": "planar", "critical_charge": False})
>>> r = Study(sc).run()
>>> round(r.design.specimen_charge_kg * 1e6, 3)     # mg of TNT for the 1/200 model (paper: 0.233)
0.233
"""

from __future__ import annotations

import functools
import time
import warnings
from dataclasses import dataclass, replace
from typing import Any, Callable, Optional

from .._validate import BlastscaleInputError
from ..scenario import Scenario, ScaleSpec
from ..structures import from_spec
from .engines import (
    ENGINES,
    ENSEMBLE,
    Engine,
    EnsembleSettings,
    PlanarSettings,
    contact_settings,
    critical_charge_of,
    load_model_of,
    planar_settings,
    settings_3d,
    systems_3d,
)
from .memory import RunSize, check_study_budget, contacts_of, estimate_run
from .result import StudyResult
from ..similitude import design_model
from ..similitude.effects import front_face, structure_top
from ..blast import blast_parameters
from ..analysis.systems import System3D, Systems3D
from ..similitude.specimen import specimen_system

__all__ = ["Study", "StudyPlan", "StudyWarning", "Progress", "DesignSystem", "DESIGN_SYSTEMS"]

#: The systems of a design that :meth:`Study.from_design` runs alone.
DESIGN_SYSTEMS = ("specimen", "prototype")


class StudyWarning(UserWarning):
    """What a study noticed about its own result (load not impulsive, outcomes that disagree, an
    engine skipped, a chaotic structure compared by single trajectories)."""


#: Progress callback: ``progress(stage, done, total)`` with a short stage description.
Progress = Callable[[str, int, int], None]


@dataclass(frozen=True)
class StudyPlan:
    """What a study checked before simulating (:meth:`Study.check`), every piece built once.

    Attributes
    ----------
    structure : structure
        The prototype structure (:data:`blastscale.structures.STRUCTURE_BUILDERS`).
    engines : tuple of Engine
        The engines to run (:data:`~.engines.ENGINES`, plus :data:`~.engines.ENSEMBLE`).
    skipped : tuple of str
        Why an engine of ``engine = "both"`` is not run.
    design : ModelDesign or None
        The one design (None for a prototype-only scenario or gravity alone): the specimen structure,
        load model, contact, gravity and duration of both systems.
    blast : BlastParameters or None
        The prototype's blast parameters (``design.prototype`` with a design; None under gravity alone).
    contact : ContactSettings or None
        The prototype's 3D contact settings (:func:`~.engines.contact_settings`), when a 3D engine runs.
    planar : PlanarSettings or None
        The planar engine's settings (:func:`~.engines.planar_settings`), when it runs.
    settings3d : Settings3D or None
        The 3D engine's settings shared by both systems (:func:`~.engines.settings_3d`: load method, pulse
        shape, incidence, recording interval, extrapolation), when a 3D engine runs.
    systems3d : Systems3D or None
        The 3D systems (:func:`~.engines.systems_3d`): the design's prototype and specimen, each with its
        structure, blast parameters, gravity, contact, duration and load model; or the prototype alone.
    ensemble : EnsembleSettings or None
        Members and perturbation of the 3D ensembles, when they run.
    threads : int or None
        Runs in flight at once (``simulation.threads``; None: this process's share of the cores).
    scenario : Scenario or None
        The scenario checked.
    critical : bool
        Whether the prototype's critical charge is searched (``simulation.critical_charge`` and the planar engine).
    contacts : int
        The prototype's contacts at rest (:func:`~.memory.contacts_of`, counted once; 0 without a 3D engine).
    """

    structure: Any
    engines: tuple
    skipped: tuple
    design: Any
    blast: Any
    contact: Any = None
    planar: Optional[PlanarSettings] = None
    settings3d: Any = None
    systems3d: Any = None
    ensemble: Optional[EnsembleSettings] = None
    threads: Optional[int] = None
    scenario: Any = None
    contacts: int = 0
    critical: bool = False

    @functools.cached_property
    def size(self) -> RunSize:
        """The run's size, said before it starts (:func:`~.memory.estimate_run`, result folder included), computed
        once, on first use, from the plan's structure, contact settings and contacts."""
        return estimate_run(self.scenario, self.structure, self.contact, contacts=self.contacts or None)


class Study:
    """Design the model of a scenario, run the engines, compare (``Study(scenario).run()``).

    Parameters
    ----------
    scenario : Scenario
        The experiment (see :mod:`blastscale.scenario`).

    A study may also start from a design (like pvlib's ``ModelChain.run_model_from_poa``, which starts past a
    stage): :meth:`from_design` runs one system of a design (the specimen under a load of the caller's: the fired
    test's prediction and refit, a calibration, the planner's specimen; or the prototype alone) with the
    scenario's engine settings, never writing a scenario to get back in.
    """

    def __init__(self, scenario: Scenario):
        if not isinstance(scenario, Scenario):
            raise BlastscaleInputError(f"scenario must be a Scenario, got {type(scenario).__name__}")
        self.scenario = scenario
        self._system: Optional[DesignSystem] = None  # from_design: which system of a design runs alone
        self._checked = None  # the StudyPlan once checked: the structure is built and the design runs once

    @classmethod
    def from_design(
        cls,
        scenario: Scenario,
        design,
        *,
        system: str = "specimen",
        charge_kg: Optional[float] = None,
        standoff_m: Optional[float] = None,
        engine: Optional[str] = None,
        structure=None,
        friction: Optional[float] = None,
        restitution: Optional[float] = None,
    ) -> "Study":
        """A study of one system of a design, run alone (no comparison).

        Parameters
        ----------
        scenario : Scenario
            The prototype's scenario: its engine settings (engine, load method, pulse shape, incidence, samples,
            restitution, friction and ``[simulation.contact]``, recording, ensembles, threads, extrapolation).
        design : ModelDesign
            The design (:func:`blastscale.similitude.design_model`, carrying both systems).
        system : {"specimen", "prototype"}
            Which system runs: the specimen (the design's structure, gravity, duration and load model; its
            contact the scenario's for the prototype scaled once by
            :func:`~blastscale.similitude.specimen.specimen_system`, as the design's own), or the prototype.
        charge_kg, standoff_m : float, optional
            The load [kg TNT], [m] (given together); default the design's blast parameters of the system.
        engine : str, optional
            ``simulation.engine`` of this run; default the scenario's.
        structure : structure, optional
            The system's structure when it is not the design's as built (a perturbed specimen of an ensemble:
            ``design.specimen_structure.scaled(factors)``); default the design's.
        friction : float, optional
            The friction coefficient [-] when not the scenario's (a perturbed member, a calibration).
        restitution : float, optional
            The planar coefficient of restitution [-] when not the scenario's (a calibration).

        Returns
        -------
        Study
            Its plan has no design (the system runs alone); ``critical_charge`` is not searched.
        """
        if system not in DESIGN_SYSTEMS:
            raise BlastscaleInputError(
                f"system = {system!r} is not known: valid values are {', '.join(DESIGN_SYSTEMS)}"
            )
        if (charge_kg is None) != (standoff_m is None):
            raise BlastscaleInputError(
                f"charge_kg = {charge_kg}, standoff_m = {standoff_m}: give both (the caller's load) or neither "
                "(the design's)"
            )
        if engine is not None and engine not in (*ENGINES, "both"):
            raise BlastscaleInputError(f"engine = {engine!r} is not known: valid values are {', '.join(ENGINES)}, both")
        study = cls(scenario)
        study._system = DesignSystem(design, system, charge_kg, standoff_m, engine, structure, friction, restitution)
        return study

    @classmethod
    def from_candidate(cls, scenario: Scenario, scale: ScaleSpec, *, engine: Optional[str] = None) -> "Study":
        """The study of a candidate design of the scenario's prototype (the planner's): its ``[scale]`` replaced by
        ``scale`` (typed; no scenario written and read back).

        Parameters
        ----------
        scenario : Scenario
            The prototype's scenario.
        scale : ScaleSpec
            The candidate's scales (lambda, law, density ratio or material, gravity ratio, specimen burst and
            charge height).
        engine : str, optional
            Run this engine alone (the planner's 3D comparison): ``simulation.engine`` replaced, no critical charge
            searched and no ensemble.

        Returns
        -------
        Study
        """
        if not isinstance(scale, ScaleSpec):
            raise BlastscaleInputError(f"scale must be a ScaleSpec, got {type(scale).__name__}")
        update: dict = {"scale": scale}
        if engine is not None:
            if engine not in (*ENGINES, "both"):
                raise BlastscaleInputError(
                    f"engine = {engine!r} is not known: valid values are {', '.join(ENGINES)}, both"
                )
            update["simulation"] = scenario.simulation.model_copy(
                update={"engine": engine, "critical_charge": False, "ensemble_members": 0}
            )
        return cls(scenario.model_copy(update=update))

    def structure(self):
        """The structure simulated: the prototype built by the registry entry of its kind
        (:data:`blastscale.structures.STRUCTURE_BUILDERS`), or the design's system's (:meth:`from_design`)."""
        if self._system is not None:
            return self._system.structure()
        return from_spec(self.scenario.structure)

    def engines(self, structure) -> tuple[list[Engine], list[str]]:
        """The engines to run and the reasons for those skipped (``engine = "both"``); a single
        engine asked for that does not support the structure is an error."""
        asked = self.scenario.simulation.engine if self._system is None else self._system.engine_or(self.scenario)
        names = list(ENGINES) if asked == "both" else [asked]
        run, skipped = [], []
        alone = self.scenario.blast.gravity_only
        for n in names:
            why = ENGINES[n].supports(structure)
            if why is None and alone and n != "3d":
                why = "gravity alone (no charge): the stability check runs on the 3D engine"
            if why is None:
                run.append(ENGINES[n])
            elif asked == "both":
                skipped.append(f"{n} engine skipped: {why}")
            else:
                raise BlastscaleInputError(
                    f"simulation.engine = {asked!r} is not available for a {self.scenario.structure.kind}: {why}"
                )
        if not run:
            raise BlastscaleInputError(
                f"structure.kind = {self.scenario.structure.kind!r} cannot be simulated here: {'; '.join(skipped)}"
            )
        members = self.scenario.simulation.ensemble_members
        if members >= 2 and alone:
            raise BlastscaleInputError(
                f"simulation.ensemble_members = {members} needs a charge: under gravity alone "
                "there is no load to perturb (valid: 0)"
            )
        if members >= 2:
            if not any(e.name == "3d" for e in run):
                raise BlastscaleInputError(
                    f"simulation.ensemble_members = {members} needs the 3D engine: valid "
                    'simulation.engine values are "3d" or "both" (or 0 members)'
                )
            run.append(ENSEMBLE)
        return run, skipped

    def design(self, structure=None, contact=None):
        """The model experiment (:func:`~blastscale.similitude.design_model`), once per study; None
        for a prototype-only scenario (no ``[scale]``). It carries the specimen system: the specimen
        structure (any kind), its load model, its contact (when ``contact``, the prototype's 3D
        settings, is given), gravity and duration, each scaled once."""

        sc = self.scenario
        if self._system is not None:  # a system of a design, run alone
            return None
        if sc.scale is None or sc.blast.gravity_only:  # gravity alone: no charge to scale
            return None
        structure = self.structure() if structure is None else structure
        lm = load_model_of(sc, structure)
        face = front_face(structure) if sc.blast.clearing else (None, structure_top(structure))  # top: the lab burst
        return design_model(
            sc.blast.charge_kg,
            sc.blast.standoff_m,
            sc.scale.length,
            sc.density_ratio,
            sc.scale.gravity_ratio,
            sc.scale.law,
            sc.blast.blast_model,
            structure,
            gravity=sc.simulation.gravity_m_s2,
            extrapolate=sc.blast.extrapolate,
            burst=sc.blast.burst,
            specimen_burst=sc.scale.specimen_burst,
            load_model=lm,
            face=face,
            specimen_charge_height=sc.scale.specimen_charge_height_m,
            contact=contact,
            duration=sc.simulation.duration_s,
        )

    def check(self) -> StudyPlan:
        """Everything that can be checked before simulating: the structure, the engines, the
        design (blast fits' ranges, scale range), the memory and the computing time
        (:func:`~blastscale.study.memory.check_study_budget`), the 3D contact settings. Returns the
        :class:`StudyPlan` (built once per study)."""
        if self._checked is None and self._system is not None:
            self._checked = self._system.plan(self)
        if self._checked is None:
            structure = self.structure()
            engines, skipped = self.engines(structure)
            sc = self.scenario
            has_3d = any(e.name != "planar" for e in engines)
            contact = contact_settings(sc, structure) if has_3d else None
            contacts = contacts_of(structure) if has_3d else 0
            check_study_budget(sc, structure, contact, contacts=contacts or None)
            d = self.design(structure, contact)
            blast = self._blast(d)
            members = sc.simulation.ensemble_members
            self._checked = StudyPlan(
                structure=structure,
                engines=tuple(engines),
                skipped=tuple(skipped),
                design=d,
                blast=blast,
                contact=contact,
                planar=planar_settings(sc, structure, d) if any(e.name == "planar" for e in engines) else None,
                settings3d=settings_3d(sc, structure) if has_3d else None,
                systems3d=systems_3d(sc, structure, d, blast, contact) if has_3d else None,
                ensemble=EnsembleSettings(members, sc.simulation.ensemble_perturbation) if members >= 2 else None,
                threads=sc.simulation.threads,
                scenario=sc,
                contacts=contacts,
                critical=bool(sc.simulation.critical_charge) and any(e.name == "planar" for e in engines),
            )
        return self._checked

    def _blast(self, design):
        """The prototype's blast parameters: the design's (never recomputed); without a design the scenario's
        charge and stand-off; None under gravity alone."""
        sc = self.scenario
        if sc.blast.gravity_only:  # no charge: the structure under gravity alone
            return None
        if design is not None:
            return design.prototype
        return blast_parameters(
            sc.blast.charge_kg,
            sc.blast.standoff_m,
            sc.blast.blast_model,
            extrapolate=sc.blast.extrapolate,
            burst=sc.blast.burst,
        )

    def run(self, progress: Optional[Progress] = None) -> StudyResult:
        """Run the study.

        Parameters
        ----------
        progress : callable, optional
            ``progress(stage, done, total)``, called before each stage and once at the end.

        Returns
        -------
        StudyResult
        """
        sc = self.scenario
        timings: dict = {}
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            t0 = time.perf_counter()
            plan = self.check()
            structure, engines, skipped, d, blast = plan.structure, plan.engines, plan.skipped, plan.design, plan.blast
            want_critical = plan.critical
            total = 1 + len(engines) + int(want_critical)
            step = 1
            timings["design"] = time.perf_counter() - t0
            results: dict = {}
            for eng in engines:
                _tell(progress, eng.label, step, total)
                t0 = time.perf_counter()
                results[eng.name] = eng.run(plan)
                timings[eng.name] = time.perf_counter() - t0
                step += 1
            crit = None
            if want_critical:
                _tell(progress, "critical charge of the prototype (planar)", step, total)
                t0 = time.perf_counter()
                crit = critical_charge_of(sc, structure)
                timings["critical"] = time.perf_counter() - t0
                step += 1
            _tell(progress, "done", total, total)
            specimen = None if d is None else d.specimen_structure
            partial = StudyResult(
                scenario=sc,
                structure=structure,
                specimen_structure=specimen,
                design=d,
                blast=blast,
                planar=results.get("planar"),
                critical=crit,
                response3d=results.get("3d"),
                ensemble=results.get("ensemble"),
            )
            summary = partial._compute_summary()  # inside the capture: its warnings are the study's
        notes = _study_warnings(d, results, skipped, summary, sc)
        lib = []
        for w in caught:
            msg = " ".join(str(w.message).split())
            if msg not in lib:
                lib.append(msg)
                warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)  # still seen by callers
        for note in notes:
            warnings.warn(note, StudyWarning, stacklevel=2)
        summary.update(warnings=list(lib + notes), timings_s=dict(timings))
        return replace(partial, warnings=tuple(lib + notes), timings=timings, _summary=summary)


@dataclass(frozen=True)
class DesignSystem:
    """One system of a design run alone by a study (:meth:`Study.from_design`).

    Attributes
    ----------
    design : ModelDesign
        The design.
    system : {"specimen", "prototype"}
        Which system.
    charge_kg, standoff_m : float or None
        The caller's load [kg TNT], [m]; None: the design's blast parameters of the system.
    engine : str or None
        The engine asked for; None: the scenario's.
    given_structure : structure or None
        The system's structure when not the design's (a perturbed member).
    friction : float or None
        The friction coefficient [-] when not the scenario's (a perturbed member, a calibration).
    restitution : float or None
        The planar coefficient of restitution [-] when not the scenario's (a calibration).
    """

    design: Any
    system: str
    charge_kg: Optional[float] = None
    standoff_m: Optional[float] = None
    engine: Optional[str] = None
    given_structure: Any = None
    friction: Optional[float] = None
    restitution: Optional[float] = None

    @property
    def specimen(self) -> bool:
        return self.system == "specimen"

    def engine_or(self, scenario: Scenario) -> str:
        """The engine asked for, else the scenario's."""
        return scenario.simulation.engine if self.engine is None else self.engine

    def structure(self):
        """The system's structure (the design's, scaled once there; or the one given)."""
        d = self.design
        if self.given_structure is not None:
            return self.given_structure
        return d.specimen_structure if self.specimen else d.prototype_structure

    def blast(self, scenario: Scenario):
        """The system's blast parameters: the design's, or those of the caller's load with the scenario's blast
        model, extrapolation and the system's burst (the specimen's: the design's specimen burst)."""
        d = self.design
        params = d.specimen if self.specimen else d.prototype
        if self.charge_kg is None:
            return params
        bl = scenario.blast
        burst = bl.burst
        if self.specimen:
            burst = getattr(params, "burst", None) or (scenario.scale and scenario.scale.specimen_burst) or bl.burst
        return blast_parameters(
            float(self.charge_kg), float(self.standoff_m), bl.blast_model, extrapolate=bl.extrapolate, burst=burst
        )

    def plan(self, study: "Study") -> StudyPlan:
        """The plan of the system run alone: the design's structure, gravity, duration and load model, the
        scenario's contact settings for the prototype (scaled once for the specimen by
        :func:`~blastscale.similitude.specimen.specimen_system`) and engine settings."""
        sc, d = study.scenario, self.design
        structure = self.structure()
        engines, skipped = study.engines(structure)
        has_3d = any(e.name != "planar" for e in engines)
        contact = contacts = None
        if has_3d:  # the prototype's contact settings from the scenario (its friction), scaled once for the specimen
            contact = contact_settings(sc, d.prototype_structure)
            if self.friction is not None:
                contact = replace(contact, friction=float(self.friction))
            contacts = contacts_of(structure)  # the specimen's are the prototype's (scaled), counted once
            check_study_budget(sc, d.prototype_structure, contact, contacts=contacts)
            if self.specimen:
                contact = specimen_system(d.factors, contact=contact).contact
        blast = self.blast(sc)
        gravity = d.specimen_gravity if self.specimen else d.gravity
        duration = float(d.specimen_duration if self.specimen else d.duration)
        load_model = d.specimen_load_model if self.specimen else d.load_model
        members = sc.simulation.ensemble_members
        planar = None
        if any(e.name == "planar" for e in engines):
            planar = replace(
                planar_settings(sc, structure, d), duration=duration, gravity=gravity, load_model=load_model
            )
            if self.restitution is not None:
                planar = replace(planar, restitution=float(self.restitution))
        return StudyPlan(
            structure=structure,
            engines=tuple(engines),
            skipped=tuple(skipped),
            design=None,
            blast=blast,
            contact=contact,
            planar=planar,
            settings3d=settings_3d(sc, structure) if has_3d else None,
            systems3d=Systems3D(System3D(structure, blast, gravity, contact, duration, load_model)) if has_3d else None,
            ensemble=EnsembleSettings(members, sc.simulation.ensemble_perturbation) if members >= 2 else None,
            threads=sc.simulation.threads,
            scenario=sc,
            contacts=contacts or 0,
        )


def _tell(progress: Optional[Progress], stage: str, done: int, total: int) -> None:
    if progress is not None:
        progress(stage, done, total)


def _is_circular(cmp) -> bool:
    return getattr(getattr(cmp, "structure", None), "section", None) == "circular"


def _study_warnings(design, results: dict, skipped: list, summary: dict, scenario=None) -> list:
    """The study's own warnings, in words for the report (the 3D and ensemble figures read from
    the study's ``summary``, computed once)."""
    out = list(skipped)
    if scenario is not None and scenario.blast.gravity_only and scenario.scale is not None:
        out.append("gravity alone (no charge): no specimen is designed, the [scale] table is not used")
    imp = None if design is None else design.impulsive
    if imp is not None and not imp.impulsive:
        out.append(
            f"the load is not impulsive (t_o p = {imp.prototype_ratio:.3g} prototype, {imp.model_ratio:.3g} "
            f"model, threshold {imp.threshold:g}): the general law's similarity is not guaranteed"
        )
    planar = results.get("planar")
    if planar is not None and planar.outcomes_agree is False:
        out.append("planar rocking: prototype and model outcomes disagree (one overturns, the other does not)")
    ens = results.get("ensemble")
    if ens is None and results.get("3d") is not None and _is_circular(results["3d"]):
        out.append(
            "circular drums wobble chaotically: one trajectory after the first impact means little; compare "
            "first peaks, or set simulation.ensemble_members >= 2 for envelopes and collapse probabilities"
        )
    if ens is not None and summary["ensemble"]["collapse_probability_model"] is not None:
        e = summary["ensemble"]
        if (e["collapse_probability_prototype"] > 0) != (e["collapse_probability_model"] > 0):
            out.append(
                f"ensembles: collapse probability {e['collapse_probability_prototype']:.2g} (prototype) vs "
                f"{e['collapse_probability_model']:.2g} (model)"
            )
    s = summary["3d"]
    if s is not None:
        p, m = s.get("prototype") or {}, s.get("model") or {}
        for key in ("collapsed",):
            if key in p and key in m and bool(p[key]) != bool(m[key]):
                out.append(f"3D: prototype and model disagree on '{key}' ({p[key]} vs {m[key]})")
    return out
