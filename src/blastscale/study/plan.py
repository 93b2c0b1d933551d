"""What a study checked before simulating (:class:`StudyPlan`, built once by :meth:`~.study.Study.check`): the
structure, the engines, the design and every engine setting resolved once as frozen typed objects; and
:class:`DesignSystem`, one system of a design run alone (:meth:`~.study.Study.from_design`)."""

from __future__ import annotations

import functools
from dataclasses import dataclass, replace
from typing import Any, Optional

from ..analysis.systems import System3D, Systems3D
from ..blast.parameters import blast_parameters
from ..scenario.scenario import Scenario
from ..similitude.specimen import specimen_system
from .engines import EnsembleSettings, PlanarSettings, contact_settings, planar_settings, settings_3d
from .memory import RunSize, check_study_budget, contacts_of, estimate_run

__all__ = ["StudyPlan", "DesignSystem", "DESIGN_SYSTEMS"]

#: The systems of a design that :meth:`Study.from_design` runs: alone (``specimen``, ``prototype``), or both
#: compared (``both``: the prototype under the design's event, the specimen under the caller's load).
DESIGN_SYSTEMS = ("specimen", "prototype", "both")


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

    @classmethod
    def resolve(
        cls,
        scenario: Scenario,
        structure,
        engines,
        skipped,
        *,
        design,
        blast,
        contact,
        contacts: int,
        planar: Optional[PlanarSettings],
        systems3d: Optional[Systems3D],
        critical: bool = False,
    ) -> "StudyPlan":
        """The plan of a study of ``scenario`` on ``structure``: the parts given, and the settings shared by every
        study resolved here (the 3D settings when ``systems3d`` runs, the ensembles, the threads)."""
        members = scenario.simulation.ensemble_members
        return cls(
            structure=structure,
            engines=tuple(engines),
            skipped=tuple(skipped),
            design=design,
            blast=blast,
            contact=contact,
            planar=planar,
            settings3d=None if systems3d is None else settings_3d(scenario, structure),
            systems3d=systems3d,
            ensemble=EnsembleSettings(members, scenario.simulation.ensemble_perturbation) if members >= 2 else None,
            threads=scenario.simulation.threads,
            scenario=scenario,
            contacts=contacts,
            critical=critical,
        )

    @functools.cached_property
    def size(self) -> RunSize:
        """The run's size, said before it starts (:func:`~.memory.estimate_run`, result folder included), computed
        once, on first use, from the plan's structure, contact settings and contacts."""
        return estimate_run(self.scenario, self.structure, self.contact, contacts=self.contacts or None)


@dataclass(frozen=True)
class DesignSystem:
    """One system of a design run alone by a study, or both compared (:meth:`Study.from_design`).

    Attributes
    ----------
    design : ModelDesign
        The design.
    system : {"specimen", "prototype", "both"}
        Which system (``both``: the prototype under the design's event and the specimen under the caller's
        load, compared).
    charge_kg, standoff_m : float or None
        The caller's load [kg TNT], [m]; None: the design's blast parameters of the system.
    engine : str or None
        The engine asked for; None: the scenario's.
    given_structure : structure or None
        The system's structure when not the design's (a perturbed member).
    friction : float or None
        The system's own friction coefficient [-] when not the scenario's (for the specimen: in place of the
        prototype's x lambda_mu; a perturbed member, a calibration).
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

    @property
    def both(self) -> bool:
        return self.system == "both"

    def structure(self):
        """The system's structure (the design's, scaled once there; or the one given); for ``both`` the
        prototype's."""
        d = self.design
        if self.given_structure is not None:
            return self.given_structure
        return d.specimen_structure if self.specimen else d.prototype_structure

    def blast(self, scenario: Scenario):
        """The system's blast parameters: the design's, or those of the caller's load with the scenario's blast
        model, extrapolation and the system's burst (the specimen's: the design's specimen burst); for ``both``
        the specimen's."""
        d = self.design
        to_specimen = self.specimen or self.both
        params = d.specimen if to_specimen else d.prototype
        own = (float(self.charge_kg or 0.0), float(self.standoff_m or 0.0)) == (
            d.specimen_charge_kg,
            d.specimen_standoff_m,
        )
        if self.charge_kg is None or (self.both and own):
            return params  # the design's own load, compared: its parameters, never recomputed (the study's own)
        bl = scenario.blast
        burst = bl.burst
        if to_specimen:
            burst = getattr(params, "burst", None) or (scenario.scale and scenario.scale.specimen_burst) or bl.burst
        return blast_parameters(
            float(self.charge_kg), float(self.standoff_m), bl.blast_model, extrapolate=bl.extrapolate, burst=burst
        )

    def compared_design(self, scenario: Scenario, contact):
        """For ``both``: the design with the specimen's blast parameters those of the caller's load
        (:meth:`blast`; the design itself at its own load) and, when the 3D engine runs and the design was made
        without them, the prototype's contact settings ``contact`` and the specimen's (scaled once by
        :func:`~blastscale.similitude.specimen.specimen_system`)."""
        d = self.design
        spec = self.blast(scenario)
        if spec is not d.specimen:
            d = replace(d, specimen=spec)
        if contact is not None and d.contact is None:
            d = replace(d, contact=contact, specimen_contact=specimen_system(d.factors, contact=contact).contact)
        return d

    def plan(self, scenario: Scenario, engines: list, skipped: list) -> StudyPlan:
        """The plan of the system run alone: the design's structure, gravity, duration and load model, the
        scenario's contact settings for the prototype (scaled once for the specimen by
        :func:`~blastscale.similitude.specimen.specimen_system`) and engine settings."""
        sc, d = scenario, self.design
        structure = self.structure()
        has_3d = any(e.name != "planar" for e in engines)
        contact = contacts = None
        if has_3d:  # the prototype's contact settings from the scenario (its friction), scaled once for the specimen
            contact = contact_settings(sc, d.prototype_structure)
            contacts = contacts_of(structure)  # the specimen's are the prototype's (scaled), counted once
            check_study_budget(sc, d.prototype_structure, contact, contacts=contacts)
            if self.specimen:  # its friction x lambda_mu: the specimen material's
                contact = specimen_system(d.factors, contact=contact).contact
            if self.friction is not None:  # the run's own (the specimen's when it runs alone)
                contact = replace(contact, friction=float(self.friction))
        blast = self.blast(sc)
        gravity = d.specimen_gravity if self.specimen else d.gravity
        duration = float(d.specimen_duration if self.specimen else d.duration)
        load_model = d.specimen_load_model if self.specimen else d.load_model
        planar = None
        if any(e.name == "planar" for e in engines):
            planar = replace(
                planar_settings(sc, structure, d), duration=duration, gravity=gravity, load_model=load_model
            )
            if self.restitution is not None:
                planar = replace(planar, restitution=float(self.restitution))
        systems3d = Systems3D(System3D(structure, blast, gravity, contact, duration, load_model)) if has_3d else None
        return StudyPlan.resolve(
            sc,
            structure,
            engines,
            skipped,
            design=None,
            blast=blast,
            contact=contact,
            contacts=contacts or 0,
            planar=planar,
            systems3d=systems3d,
        )
