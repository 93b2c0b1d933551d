"""Run one side of a model experiment in 3D: the prototype, or the reduced-scale model at its own size.

The one place where a designed experiment (:func:`blastscale.similitude.design_model`) becomes
a structure, a load and a run of the 3D engine. The model system is

* the structure ``structure.scaled(factors)``;
* its own load, built by :func:`blastscale.sim3d.load_methods.make_load` from ``design.model``'s
  charge, stand-off and blast fit;
* gravity ``varsigma g``, contact ``contact.scaled(factors)`` (or the engine's
  scale-consistent defaults for its size when ``contact`` is None);
* run for ``duration * lambda_t``.

Used by :func:`~.structure3d.compare_structure3d` and :func:`~.ensemble.ensemble_compare`
(internal: not part of the package's listed API; the Study and the comparisons are the way in).
"""

from __future__ import annotations

from typing import NamedTuple

from .._validate import BlastscaleInputError

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
    """

    structure: object
    response: object
    load_duration_s: float


def run_system(structure, design, system: str = "prototype", *, load: str = "A", pulse: str = "friedlander",
               incidence: str | None = None, contact=None, duration: float = 8.0, record_every: int = 4,
               load_factor: float = 1.0, extrapolate: bool = False) -> SystemRun:
    """Simulate the prototype, or the model at its own size (module docstring).

    Parameters
    ----------
    structure : structure
        Prototype structure.
    design : ModelDesign
        The model experiment.
    system : {"prototype", "model"}
        Which one.
    load, pulse, incidence, contact, record_every
        See :func:`~.structure3d.compare_structure3d`.
    duration : float
        Prototype simulated time [s] (the model runs ``duration * lambda_t``).
    load_factor : float
        Multiplier of the load's wrenches [-] (ensembles, :class:`~blastscale.sim3d.loads.PerturbedLoad`).
    extrapolate : bool
        Let the blast fits run outside their ranges (with a warning), passed to ``make_load``.

    Returns
    -------
    SystemRun
    """
    from ..sim3d.load_methods import make_load
    from ..sim3d.loads import PerturbedLoad
    from ..sim3d.simulate import simulate_structure

    f = design.factors
    if system == "prototype":
        struct, blast, dur, g, cont = structure, design.prototype, duration, design.gravity, contact
    elif system == "model":
        struct, blast = structure.scaled(f), design.model
        dur, g = duration * f.time, design.gravity * f.gravity
        cont = None if contact is None else contact.scaled(f)
    else:
        raise BlastscaleInputError(f"system = {system!r} is not known: valid values are {', '.join(SYSTEMS)}")
    inc = {} if incidence is None else {"incidence": incidence}
    ld = make_load(load, struct, charge_kg=blast.charge_kg, standoff_m=blast.standoff_m, blast_model=blast.model,
                   pulse=pulse, extrapolate=bool(extrapolate), **inc)
    if load_factor != 1.0:
        ld = PerturbedLoad(ld, load_factor)
    resp = simulate_structure(struct, ld, dur, contact=cont, gravity=g, record_every=record_every)
    return SystemRun(struct, resp, float(ld.end_time - ld.first_arrival))
