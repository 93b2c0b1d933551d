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

import time
import warnings
from dataclasses import replace
from typing import Callable, Optional

from .._validate import BlastscaleInputError, check_choice
from ..blast.parameters import blast_parameters
from ..scenario.scenario import Scenario
from ..scenario.specs import ScaleSpec
from ..similitude.design import design_model
from ..similitude.effects import front_face, structure_top
from ..structures import from_spec
from ..structures.from_spec import is_block
from .engines import (
    ENGINES,
    ENSEMBLE,
    Engine,
    contact_settings,
    critical_charge_of,
    load_model_of,
    planar_settings,
    systems_3d,
)
from .load_choice import load_choice
from .memory import check_study_budget, contacts_of
from .plan import DESIGN_SYSTEMS, DesignSystem, StudyPlan
from .result import StudyResult, study_warnings

__all__ = ["Study", "StudyWarning", "Progress", "design_of"]


class StudyWarning(UserWarning):
    """What a study noticed about its own result (load not impulsive, outcomes that disagree, an
    engine skipped, a chaotic structure compared by single trajectories)."""


#: Progress callback: ``progress(stage, done, total)`` with a short stage description.
Progress = Callable[[str, int, int], None]


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
        """A study of one system of a design run alone (no comparison), or of both compared (``system = "both"``).

        Parameters
        ----------
        scenario : Scenario
            The prototype's scenario: its engine settings (engine, load method, pulse shape, incidence, samples,
            restitution, friction and ``[simulation.contact]``, recording, ensembles, threads, extrapolation).
        design : ModelDesign
            The design (:func:`blastscale.similitude.design_model`, carrying both systems).
        system : {"specimen", "prototype", "both"}
            Which system runs: the specimen (the design's structure, gravity, duration and load model; its
            contact the scenario's for the prototype scaled once by
            :func:`~blastscale.similitude.specimen.specimen_system`, as the design's own), or the prototype;
            or ``both``: the prototype under the design's event and the specimen under ``charge_kg`` at
            ``standoff_m`` (a shot as fired), compared like a study of the scenario (the similarity blocks and
            the ``verdict`` of its summary; at the design's own load it is that study, its critical charge not
            searched).
        charge_kg, standoff_m : float, optional
            The load [kg TNT], [m] (given together); default the design's blast parameters of the system (for
            ``both``: the specimen's load).
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
            Its plan has no design when one system runs alone (``both``: the design, with the specimen's load
            the caller's); ``critical_charge`` is not searched.
        """
        check_choice("system", system, DESIGN_SYSTEMS)
        if system == "both" and (friction is not None or restitution is not None or structure is not None):
            raise BlastscaleInputError(
                "system = 'both' compares the design's two systems as designed: friction, restitution and structure "
                "are for one system run alone (valid with system = 'specimen' or 'prototype')"
            )
        if (charge_kg is None) != (standoff_m is None):
            raise BlastscaleInputError(
                f"charge_kg = {charge_kg}, standoff_m = {standoff_m}: give both (the caller's load) or neither "
                "(the design's)"
            )
        if engine is not None:
            check_choice("engine", engine, (*ENGINES, "both"))
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
            check_choice("engine", engine, (*ENGINES, "both"))
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
        return design_of(sc, self.structure() if structure is None else structure, contact=contact)

    def check(self) -> StudyPlan:
        """Everything that can be checked before simulating: the structure, the engines, the
        design (blast fits' ranges, scale range), the memory and the computing time
        (:func:`~blastscale.study.memory.check_study_budget`), the 3D contact settings. Returns the
        :class:`StudyPlan` (built once per study)."""
        system = self._system
        if self._checked is None and system is not None and not system.both:
            self._checked = system.plan(self.scenario, *self.engines(system.structure()))
        if self._checked is None:
            structure = self.structure()
            engines, skipped = self.engines(structure)
            sc = self.scenario
            has_3d = any(e.name != "planar" for e in engines)
            contact = contact_settings(sc, structure) if has_3d else None
            contacts = contacts_of(structure) if has_3d else 0
            check_study_budget(sc, structure, contact, contacts=contacts or None)
            d = self.design(structure, contact) if system is None else system.compared_design(sc, contact)
            blast = self._blast(d)
            planar = planar_settings(sc, structure, d) if any(e.name == "planar" for e in engines) else None
            self._checked = StudyPlan.resolve(
                sc,
                structure,
                engines,
                skipped,
                design=d,
                blast=blast,
                contact=contact,
                contacts=contacts,
                planar=planar,
                systems3d=systems_3d(sc, structure, d, blast, contact) if has_3d else None,
                critical=system is None
                and bool(sc.simulation.critical_charge)
                and any(e.name == "planar" for e in engines),
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
                crit = critical_charge_of(plan)
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
        notes = study_warnings(d, results, skipped, summary, sc)
        # the load method's and clearing's weight against the verdict's tolerance (a scenario's own 3D run of a
        # structure other than a single block only: a design's system run, e.g. the planner's candidates, shares
        # its scenario's choice; a block's Method A is the paper's planar load, its factor in docs/face_loads.md)
        checked = self._system is None and "3d" in results and not is_block(structure)
        choice = load_choice(sc, structure, blast, d) if checked else None
        if choice is not None:
            notes += list(choice.notes)
            summary["load_choice"] = choice.to_dict()
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


def _tell(progress: Optional[Progress], stage: str, done: int, total: int) -> None:
    if progress is not None:
        progress(stage, done, total)


def design_of(scenario: Scenario, structure, charge_kg=None, standoff_m=None, *, contact=None, effects: bool = True):
    """The one mapping from a scenario to its model experiment (:func:`~blastscale.similitude.design_model`),
    for :meth:`Study.design` and the sweeps' outcome mode: the scenario's scale, density and gravity
    ratios, the friction ratio of its specimen's material, law, blast model, bursts, gravity, load model (:func:`~.engines.load_model_of`), loaded face
    (the structure's front with clearing, else its top: the lab burst), lab charge height and duration.

    Parameters
    ----------
    scenario : Scenario
        A scenario with a ``[scale]`` section and a charge.
    structure : structure
        The prototype structure (:meth:`Study.structure`).
    charge_kg, standoff_m : float or array, optional
        Prototype charge W [kg] and stand-off R [m] (default: the scenario's). Arrays (broadcast together)
        design every case at once, NaN where a case cannot be designed (``valid``).
    contact : ContactSettings, optional
        The prototype's 3D contact settings, scaled once by the design.
    effects : bool
        Evaluate the blast effects and their notes (default); False for the systems alone (the outcome mode).

    Returns
    -------
    ModelDesign
    """
    sc = scenario
    lm = load_model_of(sc, structure)
    face = front_face(structure) if sc.blast.clearing else (None, structure_top(structure))  # top: the lab burst
    return design_model(
        sc.blast.charge_kg if charge_kg is None else charge_kg,
        sc.blast.standoff_m if standoff_m is None else standoff_m,
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
        effects=effects,
        friction_ratio=sc.friction_ratio,
    )
