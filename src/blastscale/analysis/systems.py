"""Run one side of a model experiment in 3D: the prototype, or the reduced-scale specimen at its own size.

The one place where a system (:class:`System3D`: a structure, its blast parameters, gravity, contact, duration and
load model) becomes a load and a run of the 3D engine under a study's settings (:class:`Settings3D`: load method,
pulse shape, incidence, recording interval, extrapolation), both frozen and resolved once by the caller (the
Study's plan, :class:`blastscale.study.StudyPlan`).

The design produces the two systems (:class:`Systems3D`, :meth:`Systems3D.of_design`): the prototype is the
structure under ``design.prototype``; the specimen is the one the design carries (scaled once by
:func:`~blastscale.similitude.design_model`):

* the structure ``design.specimen_structure``;
* its own blast parameters ``design.specimen`` (never recomputed) and load model ``design.specimen_load_model``;
* gravity ``design.specimen_gravity``, contact ``design.specimen_contact`` (None: the engine's scale-consistent
  defaults for its size);
* run for ``design.specimen_duration``.

A design made without the structure, contact or duration (a user's ``design_model(W, R, lam)``) is completed
by the function the design itself uses, :func:`~blastscale.similitude.specimen.specimen_system`
(``structure.scaled(factors)``, ``contact.scaled(factors)``, ``duration * lambda_t``): there is no second
scaling path.

Used by :func:`~.structure3d.compare_structure3d`, :func:`~.prototype3d.prototype_structure3d` and
:func:`~.ensemble.ensemble_compare`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, NamedTuple, Optional

from .._validate import BlastscaleInputError, check_positive
from ..blast.incidence import DEFAULT_INCIDENCE
from ..constants import STANDARD_GRAVITY
from ..sim3d.load_methods import make_load
from ..sim3d.loads import PerturbedLoad
from ..sim3d.rest import rest_check
from ..sim3d.simulate import simulate_structure
from ..similitude.specimen import SpecimenSystem, specimen_system

__all__ = ["SYSTEMS", "Settings3D", "System3D", "Systems3D", "SystemRun", "rest_of", "run_system"]

#: The two systems of a model experiment.
SYSTEMS = ("prototype", "model")


@dataclass(frozen=True)
class Settings3D:
    """The 3D engine's settings shared by both systems of a study (frozen, resolved once).

    Attributes
    ----------
    load : str
        Load method, a key of :data:`blastscale.sim3d.load_methods.LOAD_METHODS` (``"A"``: the paper's Method A,
        uniform and simultaneous reflected pulse on the front faces).
    pulse_shape : {"friedlander", "triangular", "impulsive"}
        Pulse shape.
    incidence : str or None
        Incidence model passed to ``make_load`` (None: :data:`~blastscale.blast.incidence.DEFAULT_INCIDENCE`).
    record_every : int
        Recording interval in steps (the same at both scales, so the grids correspond).
    extrapolate : bool
        Let the blast fits run outside their ranges (with a warning), for every load.
    """

    load: str = "A"
    pulse_shape: str = "friedlander"
    incidence: Optional[str] = None
    record_every: int = 4
    extrapolate: bool = False

    def record(self) -> dict:
        """The first keys of a result's settings record: ``load_method``, ``pulse_shape``, ``incidence``."""
        return {
            "load_method": self.load,
            "pulse_shape": self.pulse_shape,
            "incidence": self.incidence or "default",
        }


@dataclass(frozen=True)
class System3D:
    """One system of a model experiment as it runs, in its own units [SI].

    Attributes
    ----------
    structure : structure
        The structure simulated (:mod:`blastscale.structures`).
    blast : BlastParameters or None
        Its blast parameters (a design's ``prototype`` or ``specimen``, never recomputed); None: gravity alone.
    gravity : float
        Gravity [m/s^2].
    contact : ContactSettings or None
        Its contact settings; None: the engine's scale-consistent defaults for the structure.
    duration : float
        Simulated time after the first arrival [s].
    load_model : LoadModel or None
        Clearing and the negative phase (:class:`~blastscale.blast.load_model.LoadModel`); None or the paper's:
        the paper's load.
    """

    structure: Any
    blast: Any = None
    gravity: float = STANDARD_GRAVITY
    contact: Any = None
    duration: float = 8.0
    load_model: Any = None

    def __post_init__(self):
        object.__setattr__(self, "duration", float(check_positive("duration", self.duration, "s")))


class Systems3D(NamedTuple):
    """The systems of a study: the prototype and, with a design, its specimen.

    Attributes
    ----------
    prototype : System3D
        The prototype.
    specimen : System3D or None
        The specimen at its own size (None: a prototype-only study).
    design : ModelDesign or None
        The design the specimen comes from (its ``factors`` up-scale the specimen's response).
    """

    prototype: System3D
    specimen: Optional[System3D] = None
    design: Any = None

    @classmethod
    def of_design(cls, design, structure=None, *, contact=None, duration: Optional[float] = None) -> "Systems3D":
        """The prototype and specimen systems of a design (module docstring).

        Parameters
        ----------
        design : ModelDesign
            The model experiment (:func:`blastscale.similitude.design_model`).
        structure : structure, optional
            The prototype structure; required when the design was made without one (default: the design's).
        contact : ContactSettings, optional
            The prototype's contact settings when the design carries none (default: the design's, or the
            engine's defaults).
        duration : float, optional
            The prototype's simulated time [s] when the design carries none (default: the design's, else 8 s).

        Returns
        -------
        Systems3D
            What the design carries is read as it is; the parts it lacks are given here and scaled once by
            :func:`~blastscale.similitude.specimen.specimen_system`.
        """
        if not hasattr(design, "factors") or not hasattr(design, "prototype"):
            raise BlastscaleInputError(
                f"design = {type(design).__name__} is not a model design: give blastscale.similitude.design_model(...)"
            )
        has_structure = design.prototype_structure is not None
        has_contact = design.contact is not None
        has_duration = design.duration is not None
        if structure is None and not has_structure:
            raise BlastscaleInputError("structure = None with a design made without one: give the prototype structure")
        proto_structure = design.prototype_structure if has_structure else structure
        proto_contact = design.contact if has_contact else contact
        proto_duration = design.duration if has_duration else (8.0 if duration is None else float(duration))
        missing = SpecimenSystem()  # what the design lacks, scaled once (nothing when it carries all)
        if not (has_structure and has_contact and has_duration):
            missing = specimen_system(
                design.factors,
                structure=None if has_structure else structure,
                contact=None if has_contact else contact,
                duration=None if has_duration else proto_duration,
            )
        prototype = System3D(
            proto_structure, design.prototype, design.gravity, proto_contact, proto_duration, design.load_model
        )
        specimen = System3D(
            design.specimen_structure if has_structure else missing.structure,
            design.specimen,
            design.specimen_gravity,
            design.specimen_contact if has_contact else missing.contact,
            design.specimen_duration if has_duration else missing.duration,
            design.specimen_load_model,
        )
        return cls(prototype, specimen, design)

    def runs(self) -> tuple:
        """``(name, system)`` of each system that runs (:data:`SYSTEMS`)."""
        return tuple((n, s) for n, s in zip(SYSTEMS, (self.prototype, self.specimen)) if s is not None)


class SystemRun(NamedTuple):
    """One system's run, in its own units.

    Attributes
    ----------
    structure : structure
        The structure simulated (the prototype, or the scaled model).
    response : Response3D
        Its response.
    load_duration_s : float
        The load's duration after its first arrival [s].
    load : LoadStrategy
        The load it ran under (unperturbed; its arrival spread feeds the similarity block).
    """

    structure: object
    response: object
    load_duration_s: float
    load: object = None


def run_system(system: System3D, settings: Settings3D, load_factor: float = 1.0) -> SystemRun:
    """Simulate one system under the study's 3D settings (module docstring).

    Parameters
    ----------
    system : System3D
        The prototype, or the specimen at its own size.
    settings : Settings3D
        Load method, pulse shape, incidence, recording interval, extrapolation.
    load_factor : float
        Multiplier of the load's wrenches [-] (ensembles, :class:`~blastscale.sim3d.loads.PerturbedLoad`).

    Returns
    -------
    SystemRun
    """
    st, ld = system.structure, None
    if system.blast is not None:  # else gravity alone (a stability check)
        ld = make_load(
            settings.load,
            st,
            system.blast,
            pulse_shape=settings.pulse_shape,
            incidence=DEFAULT_INCIDENCE if settings.incidence is None else settings.incidence,
            extrapolate=bool(settings.extrapolate),
            load_model=system.load_model,
        )
    run_load = ld if ld is None or load_factor == 1.0 else PerturbedLoad(ld, load_factor)
    resp = simulate_structure(
        st,
        run_load,
        system.duration,
        contact=system.contact,
        gravity=system.gravity,
        record_every=settings.record_every,
    )
    return SystemRun(st, resp, 0.0 if ld is None else float(ld.end_time - ld.first_arrival), ld)


def rest_of(system: System3D):
    """The system at rest before its blast (:func:`blastscale.sim3d.rest.rest_check`: under gravity alone over
    its rest time, its own contact settings and gravity; cached on the engine's model, so a specimen that is
    its prototype's exact model and every repeated run cost nothing); None under gravity alone (the run itself
    is the check: its ``stability``).

    Returns
    -------
    dict or None
        ``creep_m`` [m], ``creep_rel_height`` [-], ``final_speed_rel_sqrt_gh`` [-], ``equilibrium``,
        ``duration_s`` [s], in the system's own units.
    """
    if system.blast is None:
        return None
    return rest_check(system.structure, system.contact, system.gravity)
