"""The load methods by name (:data:`LOAD_METHODS`: the paper's Methods A, B and C, and any method
registered by :func:`register_load_method`), :func:`make_load`, and the arrival-time spreads of a
model experiment."""

from __future__ import annotations

from .._validate import check_choice
from .face_loads import method_b, method_c
from .loads import LoadStrategy, method_a

__all__ = ["LOAD_METHODS", "make_load", "register_load_method"]


#: Load methods by name: factory(structure, blast, *, pulse, incidence, extrapolate) -> LoadStrategy,
#: ``blast`` the system's :class:`~blastscale.blast.BlastParameters` (and ``load_model=`` when a
#: load model other than the paper's is asked for: A, B and C take it).
LOAD_METHODS: dict = {"A": method_a, "B": method_b, "C": method_c}


def register_load_method(name: str, factory) -> None:
    """Add (or replace) a load method in :data:`LOAD_METHODS`: ``factory(structure, blast, *, pulse,
    incidence, extrapolate)`` returns a :class:`~.loads.LoadStrategy`."""
    LOAD_METHODS[str(name)] = factory


def make_load(
    method: str,
    structure,
    blast,
    *,
    pulse_shape: str = "friedlander",
    incidence: str = "ufc",
    extrapolate: bool = False,
    load_model=None,
) -> LoadStrategy:
    """The blast load of a system's charge on its structure.

    Parameters
    ----------
    method : str
        "A" (:mod:`.loads`), "B", "C" (:mod:`.face_loads`), or one registered by
        :func:`register_load_method`.
    structure : structure
        Any structure of :mod:`blastscale.structures`; the charge lies on the ground at
        ``x = structure.front_x - blast.standoff_m``, y = 0.
    blast : BlastParameters
        The system's blast parameters (:func:`blastscale.blast.blast_parameters` of its charge W [kg]
        and stand-off R [m], or a design's ``prototype`` / ``model``): Method A uses them as they
        are (the reflected pulse at R, its arrival time); B and C take the charge, the stand-off
        and the blast model from them and evaluate the model at each face's own distance.
    pulse_shape : str
        "friedlander", "triangular" or "impulsive".
    incidence : str
        Angle-of-incidence model for B and C ("ufc" or "closed-form").
    extrapolate : bool
        B and C: evaluate the blast fits outside their ranges (with a warning).
    load_model : LoadModel, optional
        Clearing and the negative phase (:class:`~blastscale.blast.load_model.LoadModel`; the
        clearing face is the structure's own front); None or the paper's: the paper's load, and a
        registered method is called exactly as before.

    Returns
    -------
    LoadStrategy

    Examples
    --------
    >>> from blastscale.blast import blast_parameters
    >>> from blastscale.structures import MultiDrumColumn
    >>> load = make_load("A", MultiDrumColumn(), blast_parameters(250.0, 10.0))
    >>> round(load.first_arrival * 1e3, 3)    # arrival time at 10 m [ms]
    6.928
    """
    check_choice("load method", method, LOAD_METHODS)
    kw = {} if load_model is None or load_model.is_paper else {"load_model": load_model}
    return LOAD_METHODS[method](
        structure, blast, pulse_shape=pulse_shape, incidence=incidence, extrapolate=extrapolate, **kw
    )
