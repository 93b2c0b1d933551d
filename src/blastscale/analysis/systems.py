"""Run one side of a model experiment in 3D: the prototype, or the reduced-scale model at its own size.

The one place where a designed experiment (:func:`blastscale.similitude.design_model`) becomes
a structure, a load and a run of the 3D engine. The model system is the one the design carries
(scaled once, by :func:`~blastscale.similitude.design_model`):

* the structure ``design.specimen_structure``;
* its own load, built by :func:`blastscale.sim3d.load_methods.make_load` from ``design.specimen``
  (the design's blast parameters of the specimen: never recomputed);
* gravity ``design.specimen_gravity``, contact ``design.specimen_contact`` (or the engine's
  scale-consistent defaults for its size when ``contact`` is None);
* run for ``design.specimen_duration``.

A design made without the structure, or with other contact settings or another duration than the
ones given here, is completed for each run by the function the design itself uses,
:func:`~blastscale.similitude.specimen.specimen_system` (``structure.scaled(factors)``,
``contact.scaled(factors)``, ``duration * lambda_t``): there is no second scaling path.

The prototype system is the structure itself, loaded from ``design.prototype`` or, for a
prototype-only study (no design), from the prototype's own blast parameters.

Used by :func:`~.structure3d.compare_structure3d`, :func:`~.structure3d.prototype_structure3d`
and :func:`~.ensemble.ensemble_compare` (internal: not part of the package's listed API; the
Study and the comparisons are the way in).
"""

from __future__ import annotations

from typing import NamedTuple

from .._validate import BlastscaleInputError
from ..constants import STANDARD_GRAVITY

__all__ = ["SYSTEMS", "SystemRun", "run_system"]

#: The two systems of a model experiment.
SYSTEMS = ("prototype", "model")


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


def run_system(
    structure,
    design,
    system: str = "prototype",
    *,
    blast=None,
    gravity: float = STANDARD_GRAVITY,
    load: str = "A",
    pulse_shape: str = "friedlander",
    incidence: str | None = None,
    contact=None,
    duration: float = 8.0,
    record_every: int = 4,
    load_factor: float = 1.0,
    extrapolate: bool = False,
    load_model=None,
) -> SystemRun:
    """Simulate the prototype, or the model at its own size (module docstring).

    Parameters
    ----------
    structure : structure
        Prototype structure.
    design : ModelDesign or None
        The model experiment; None for the prototype alone (then ``blast`` and ``gravity``).
    system : {"prototype", "model"}
        Which one.
    blast : BlastParameters, optional
        The prototype's blast parameters when there is no design (with a design: ``design.prototype``
        and ``design.specimen``); None without a design: gravity alone.
    gravity : float
        The prototype's gravity [m/s^2] when there is no design (with one: ``design.gravity``).
    load, pulse_shape, incidence, contact, record_every
        See :func:`~.structure3d.compare_structure3d`.
    duration : float
        Prototype simulated time [s] (the model runs ``duration * lambda_t``).
    load_factor : float
        Multiplier of the load's wrenches [-] (ensembles, :class:`~blastscale.sim3d.loads.PerturbedLoad`).
    extrapolate : bool
        Let the blast fits run outside their ranges (with a warning), passed to ``make_load``
        (Methods B and C evaluate the fits at each face's distance).
    load_model : LoadModel, optional
        Clearing and the negative phase, passed to ``make_load`` (each system's faces are its own).

    Returns
    -------
    SystemRun
    """
    from ..sim3d.load_methods import make_load
    from ..sim3d.loads import PerturbedLoad
    from ..sim3d.simulate import simulate_structure

    if system not in SYSTEMS:
        raise BlastscaleInputError(f"system = {system!r} is not known: valid values are {', '.join(SYSTEMS)}")
    if design is None:
        if system != "prototype":
            raise BlastscaleInputError(
                f"design = None with system = {system!r}: without a model design only the prototype runs, from its "
                "blast parameters (blast=blast_parameters(W, R)), or under gravity alone (blast=None)"
            )
        struct, bp, dur, g, cont = structure, blast, duration, gravity, contact
    elif system == "prototype":
        struct, bp, dur, g, cont = structure, design.prototype, duration, design.gravity, contact
    else:
        struct, bp, dur, g, cont = _specimen_system(design, structure, contact, duration)
    if bp is None:  # gravity alone (a stability check)
        resp = simulate_structure(struct, None, dur, contact=cont, gravity=g, record_every=record_every)
        return SystemRun(struct, resp, 0.0, None)
    inc = {} if incidence is None else {"incidence": incidence}
    ld = make_load(
        load, struct, bp, pulse_shape=pulse_shape, extrapolate=bool(extrapolate), load_model=load_model, **inc
    )
    run_load = ld if load_factor == 1.0 else PerturbedLoad(ld, load_factor)
    resp = simulate_structure(struct, run_load, dur, contact=cont, gravity=g, record_every=record_every)
    return SystemRun(struct, resp, float(ld.end_time - ld.first_arrival), ld)


def _specimen_system(design, structure, contact, duration: float) -> tuple:
    """(structure, blast parameters, duration [s], gravity [m/s^2], contact) of the specimen: the design's
    (a Study's design carries this prototype, contact and duration); the parts it does not carry (a design made
    without them, or with others) by :func:`~blastscale.similitude.specimen.specimen_system`, the one function
    that scales a specimen, as the design itself does."""
    from ..similitude.specimen import specimen_system

    same_structure = design.prototype_structure is structure
    same_contact = contact is None or design.contact is contact
    same_duration = design.duration == duration
    other = None
    if not (same_structure and same_contact and same_duration):  # what the design does not carry, scaled once
        other = specimen_system(
            design.factors,
            structure=None if same_structure else structure,
            contact=None if same_contact else contact,
            duration=None if same_duration else duration,
        )
    struct = design.specimen_structure if same_structure else other.structure
    cont = None if contact is None else (design.specimen_contact if same_contact else other.contact)
    dur = design.specimen_duration if same_duration else other.duration
    return struct, design.specimen, dur, design.specimen_gravity, cont
