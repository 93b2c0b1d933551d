"""The load methods by name (:data:`LOAD_METHODS`: the paper's Methods A, B and C, and any method
registered by :func:`register_load_method`), :func:`make_load`, and the arrival-time spreads of a
model experiment."""

from __future__ import annotations

from .._validate import BlastscaleInputError
from .face_loads import arrival_spread, method_b, method_c
from .loads import LoadStrategy, method_a

__all__ = ["LOAD_METHODS", "make_load", "register_load_method", "arrival_spread_similarity"]


#: Load methods by name: factory(structure, *, charge_kg, standoff_m, blast_model, pulse, incidence,
#: extrapolate) -> LoadStrategy.
LOAD_METHODS: dict = {"A": method_a, "B": method_b, "C": method_c}


def register_load_method(name: str, factory) -> None:
    """Add (or replace) a load method in :data:`LOAD_METHODS`."""
    LOAD_METHODS[str(name)] = factory


def make_load(method: str, structure, *, charge_kg, standoff_m, blast_model: str = "kingery-bulmash",
              pulse: str = "friedlander", incidence: str = "ufc", extrapolate: bool = False) -> LoadStrategy:
    """The blast load of a charge on a structure.

    Parameters
    ----------
    method : str
        "A" (:mod:`.loads`), "B", "C" (:mod:`.face_loads`), or one registered by
        :func:`register_load_method`.
    structure : structure
        Any structure of :mod:`blastscale.structures`; the charge lies on the ground at
        ``x = structure.front_x - standoff_m``, y = 0.
    charge_kg : float
        TNT-equivalent charge W [kg].
    standoff_m : float
        Stand-off R from the charge to the front face [m].
    blast_model : str
        "kingery-bulmash" or "masi2021".
    pulse : str
        "friedlander", "triangular" or "impulsive".
    incidence : str
        Angle-of-incidence model for B and C ("ufc" or "closed-form").
    extrapolate : bool
        Use the blast fits outside their ranges (with a warning).

    Returns
    -------
    LoadStrategy
    """
    if method not in LOAD_METHODS:
        raise BlastscaleInputError(f"load method = {method!r} is not known: valid values are {', '.join(LOAD_METHODS)}")
    return LOAD_METHODS[method](structure, charge_kg=charge_kg, standoff_m=standoff_m, blast_model=blast_model,
                                pulse=pulse, incidence=incidence, extrapolate=extrapolate)


def arrival_spread_similarity(structure, design, load: str = "A", *, pulse: str = "friedlander",
                              incidence: str = "ufc", extrapolate: bool = False) -> dict:
    """Arrival-time spreads of a model experiment, for a comparison's ``similarity`` block.

    Parameters
    ----------
    structure : structure
        Prototype structure.
    design : ModelDesign
        The model experiment (:func:`blastscale.similitude.design_model`): prototype and model
        charge and stand-off, ``factors.length``, ``factors.density`` and ``factors.time``.
    load, pulse, incidence : str
        As for :func:`make_load`.
    extrapolate : bool
        As for :func:`make_load` (the blast fits outside their ranges, with a warning).

    Returns
    -------
    dict
        ``arrival_spread_prototype_s`` (first to last arrival over the loaded faces [s]) and
        ``arrival_spread_model_upscaled_s`` (the model's, divided by the time factor lambda_t,
        in prototype seconds [s]). Under exact similarity the two are equal; see
        ``docs/face_loads.md`` for why the general law's model does not keep them equal.
    """
    f = design.factors
    p, m = design.prototype, design.model
    kw = dict(blast_model=p.model, pulse=pulse, incidence=incidence, extrapolate=extrapolate)
    lp = make_load(load, structure, charge_kg=p.charge_kg, standoff_m=p.standoff_m, **kw)
    lm = make_load(load, structure.scaled(f), charge_kg=m.charge_kg, standoff_m=m.standoff_m, **kw)
    return {"arrival_spread_prototype_s": arrival_spread(lp),
            "arrival_spread_model_upscaled_s": arrival_spread(lm) / f.time}
