"""The engine's reference units: THE one place where a structure's absolute size is removed.

The 3D engine integrates every structure geometrically scaled to the reference height
``REFERENCE_LENGTH`` = 10 m under ``REFERENCE_GRAVITY`` = 9.81 m/s^2, same density
(:func:`reference_factors`): the exact similitude of rigid bodies under gravity, so the
equations of motion are unchanged, while MuJoCo's *absolute* thresholds (mjMINVAL on masses and
inertias, collision tolerances in metres) never see the structure's size. The structure's
parameters are rounded to ``REFERENCE_DIGITS`` significant digits there (:func:`to_reference`)
and the default contact settings are the reference ones themselves (:func:`reference_settings`),
so a specimen and its prototype are the *same* MuJoCo model.

Consequence for similarity: a model experiment and its prototype differ in the engine only by
their loads (the model's pulse is not an exact copy of the prototype's: the general law matches
the impulse, not the pulse shape). The 3D similarity figures therefore measure load
dissimilarity, not engine scale effects, and the "exact scaling" tests (an exactly scaled pulse
reproduces the prototype to round-off) are regression tests of this normalisation.

Inputs (loads, gravity) and outputs (recorded states) stay in physical units: the integration
loop (:func:`~.integrate.integrate`) converts wrenches in and states out with the factors.
"""

from __future__ import annotations

import copy
import math
import threading
from collections import OrderedDict
from dataclasses import fields, is_dataclass, replace

from .contact import (
    REFERENCE_GRAVITY,
    REFERENCE_LENGTH,
    ContactSettings,
    length_time_factors,
    reference_contact,
    structure_length,
)
from .model import compile_scene, structure_scene

__all__ = [
    "REFERENCE_DIGITS",
    "SCENE_CACHE_SIZE",
    "clear_scene_cache",
    "reference_factors",
    "reference_scene",
    "reference_settings",
    "to_reference",
]


def reference_factors(structure, gravity: float) -> tuple:
    """Length and time factors (a, b) from a structure's own units to the engine's reference units.

    The engine always integrates the structure geometrically scaled to the reference height
    ``REFERENCE_LENGTH`` (10 m) under ``REFERENCE_GRAVITY`` (9.81 m/s^2), same density:

    .. math:: a = L_{ref} / L,\\qquad b = \\sqrt{a\\, g / g_{ref}},

    lengths x a, times x b, velocities x a/b, angular velocities / b, forces x a^4/b^2, moments
    x a^5/b^2. This is the exact similitude of rigid bodies under gravity, so the equations of
    motion are unchanged; what it removes is MuJoCo's *absolute* thresholds (mjMINVAL on masses
    and inertias, collision tolerances in metres), which otherwise make a 1/100 model and its
    prototype differ by ~1e-8 of the response after the first contact transitions (growing to
    ~1e-3 of the peak over 8 s), and crash for bodies of a few milligrams. A structure of 10 m
    under 9.81 m/s^2 runs with a = b = 1 exactly.
    """
    L = structure_length(structure)
    a = REFERENCE_LENGTH / L
    return a, math.sqrt(a * gravity / REFERENCE_GRAVITY)


#: Significant digits of a structure's parameters in reference units (:func:`to_reference`).
REFERENCE_DIGITS = 12


def to_reference(structure, a: float):
    """The structure in reference units, its float parameters rounded to ``REFERENCE_DIGITS``
    significant digits (dataclass structures): a structure and its exactly scaled model then
    give bitwise the same bodies, faces and mesh vertices (their scaled inputs differ only by
    round-off), so MuJoCo integrates the same model. The rounding moves the geometry by
    < 5e-13 relative."""
    ref = structure if a == 1.0 else structure.scaled(length_time_factors(a, 1.0))
    if hasattr(ref, "rounded"):  # assemblies: coordinates quantised on the reference length
        return ref.rounded(REFERENCE_LENGTH, REFERENCE_DIGITS)
    if not is_dataclass(ref):
        return ref
    changes = {}
    for f in fields(ref):
        v = getattr(ref, f.name)
        if isinstance(v, float):
            changes[f.name] = float(f"{v:.{REFERENCE_DIGITS}g}")
        elif isinstance(v, tuple) and v and all(isinstance(x, float) for x in v):
            changes[f.name] = tuple(float(f"{x:.{REFERENCE_DIGITS}g}") for x in v)
    return replace(ref, **changes)


def reference_settings(contact: ContactSettings | None, structure, a: float, b: float) -> ContactSettings:
    """The contact settings in reference units: the reference defaults themselves for
    ``contact=None`` (so that a structure and its scaled model get bitwise the same), else the
    explicit settings scaled by (a, b)."""
    if contact is None:
        return reference_contact(structure)
    return contact if (a == 1.0 and b == 1.0) else contact.scaled(length_time_factors(a, b))


#: Compiled models kept (:func:`reference_scene`), each with its settled state: the structures most recently run.
SCENE_CACHE_SIZE = 8

_LOCK = threading.Lock()
_SCENES: OrderedDict = OrderedDict()  # (MJCF text, settings) -> Scene (the compiled model and its settled state)
#: The attribute a structure object carries its reference structures in ({a: reference structure}).
_REFERENCES_ATTR = "_blastscale_references"


def clear_scene_cache() -> None:
    """Forget every compiled model and settled state (:func:`reference_scene`; a reference structure goes with
    the structure object that carries it)."""
    with _LOCK:
        _SCENES.clear()


def _reference_structure(structure, a: float):
    """:func:`to_reference` of ``structure``, computed once per structure object and factor and carried by it: the reference
    structure keeps its derived geometry (hulls, faces, interfaces, bodies: ``functools.cached_property`` of an
    assembly), so every later run of the same object skips it. Objects without a ``__dict__`` are not cached."""
    with _LOCK:
        ref = getattr(structure, _REFERENCES_ATTR, {}).get(a)
    if ref is not None:
        return ref
    ref = to_reference(structure, a)
    try:
        with _LOCK:
            if getattr(structure, _REFERENCES_ATTR, None) is None:
                object.__setattr__(structure, _REFERENCES_ATTR, {})
            getattr(structure, _REFERENCES_ATTR)[a] = ref
    except (AttributeError, TypeError):  # an object without a __dict__ (slots): computed on every run
        pass
    return ref


def _cached_scene(ref, settings: ContactSettings, rotation: float):
    """The scene of ``ref`` (:func:`~.model.structure_scene`), compiled once per MJCF text and settings and
    shared by every run that builds the same model (a structure and its exactly scaled specimen, the members of a
    load ensemble, the cases of a sweep): each caller gets its own copy of the MuJoCo model (the loop changes
    its step and tolerance) and the shared ``settled`` store (:func:`~.integrate.integrate` keeps the state at
    the end of settling there, the same for every run of the model)."""
    scene = structure_scene(ref, settings, REFERENCE_GRAVITY, rotation=rotation, compile=False)
    key = (scene.xml, settings)
    with _LOCK:
        hit = _SCENES.get(key)
        if hit is not None:
            _SCENES.move_to_end(key)
    if hit is None:
        hit = replace(compile_scene(scene), settled={})
        with _LOCK:
            hit = _SCENES.setdefault(key, hit)
            while len(_SCENES) > SCENE_CACHE_SIZE:
                _SCENES.popitem(last=False)
    return replace(hit, mj_model=copy.copy(hit.mj_model), settled=hit.settled)


def reference_scene(structure, contact: ContactSettings | None, gravity: float, rotation: float = 0.0) -> tuple:
    """The MuJoCo model the engine integrates for ``structure`` and the factors (a, b) to it.

    Parameters
    ----------
    structure : structure
        Any structure of :mod:`blastscale.structures`, in its own units [m].
    contact : ContactSettings or None
        Explicit settings in the structure's units, or None for the reference defaults.
    gravity : float
        g [m/s^2].
    rotation : float
        Initial tilt [rad] (:func:`~.model.structure_scene`).

    Returns
    -------
    (Scene, (a, b))
        The scene of :func:`to_reference` of the structure under ``REFERENCE_GRAVITY``
        (:func:`~.model.structure_scene`: each body's exact mass and inertia, masses in it x a^3 and
        lengths x a), and the length and time factors of :func:`reference_factors`.

    Notes
    -----
    The fixed cost of a run (issue #41: the reference structure's hulls, faces and interfaces, the MJCF text, the
    compiled model, the settling) is paid once: the reference structure is kept per structure object, the compiled
    model and its settled state per MJCF text and settings (:data:`SCENE_CACHE_SIZE` models,
    :func:`clear_scene_cache`). A run from the cache gives bitwise the states of a run without it
    (tests/integration/test_scene_cache.py).
    """

    a, b = reference_factors(structure, gravity)
    ref = _reference_structure(structure, a)
    return _cached_scene(ref, reference_settings(contact, ref, a, b), float(rotation)), (a, b)
