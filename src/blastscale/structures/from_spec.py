"""Structures from the structure table of a scenario (any object with its attributes: ``kind``,
``height_m``, ...): one builder per kind, :data:`STRUCTURE_BUILDERS`, and :func:`from_spec`."""

from __future__ import annotations

import math
import threading
from collections import OrderedDict
from typing import Any, Callable

from .._validate import check_choice
from .block import RectangularBlock
from .block_files import read_block_model
from .column import Capital, MultiDrumColumn
from .generators import arch, portal, wall

__all__ = ["FROM_SPEC_CACHE_SIZE", "STRUCTURE_BUILDERS", "from_spec", "is_block"]


def _build_block(spec) -> RectangularBlock:
    if spec.width_m is not None:
        return RectangularBlock(
            height=spec.height_m, width=spec.width_m, depth=spec.depth_m, density=spec.density_kg_m3
        )
    return RectangularBlock.from_slenderness(
        spec.height_m, math.radians(spec.alpha_deg), depth=spec.depth_m, density=spec.density_kg_m3
    )


def _build_column(spec) -> MultiDrumColumn:
    cap, prof, hs = spec.capital, spec.width_profile_m, spec.drum_heights_m
    return MultiDrumColumn(
        section=spec.section,
        drums=spec.drums,
        height=spec.height_m,
        base_width=spec.base_width_m,
        top_width=spec.top_width_m,
        sides=spec.sides,
        density=spec.density_kg_m3,
        drum_heights=None if hs is None else tuple(hs),
        width_profile=None if prof is None else tuple(tuple(p) for p in prof),
        capital=None if cap is None else Capital(cap.abacus_width_m, cap.abacus_height_m, cap.echinus_height_m),
    )


def _build_wall(spec):
    return wall(
        spec.length_m,
        spec.height_m,
        spec.thickness_m,
        spec.courses,
        spec.units_per_course,
        spec.bond,
        spec.density_kg_m3,
    )


def _build_arch(spec):
    return arch(
        spec.radius_m,
        spec.thickness_m,
        spec.depth_m,
        spec.voussoirs,
        spec.embrace_deg,
        spec.pier_height_m,
        spec.density_kg_m3,
    )


def _build_portal(spec):
    return portal(
        spec.column_height_m,
        spec.column_width_m,
        spec.span_m,
        spec.lintel_height_m,
        spec.lintel_overhang_m,
        spec.drums,
        spec.density_kg_m3,
    )


def _build_assembly(spec):
    return read_block_model(spec.file, spec.density_kg_m3)


#: structure kind -> builder(structure table of the scenario) -> structure object.
STRUCTURE_BUILDERS: dict[str, Callable[[Any], Any]] = {
    "block": _build_block,
    "column": _build_column,
    "wall": _build_wall,
    "arch": _build_arch,
    "portal": _build_portal,
    "assembly": _build_assembly,
}


def is_block(structure) -> bool:
    """Whether ``structure`` is a single rectangular block (the planar engine's body)."""
    return isinstance(structure, RectangularBlock)


#: Generated structures kept by :func:`from_spec` (the most recent ones).
FROM_SPEC_CACHE_SIZE = 8
#: Kinds whose structure is a function of the table alone (an "assembly" reads a file, which may change).
_GENERATED = ("block", "column", "wall", "arch", "portal")
_BUILT: OrderedDict = OrderedDict()
_BUILT_LOCK = threading.Lock()


def _spec_key(spec):
    """The table as text (a pydantic model's JSON, else its attributes), or None when it cannot be written."""
    try:
        return spec.model_dump_json() if hasattr(spec, "model_dump_json") else repr(sorted(vars(spec).items()))
    except (TypeError, ValueError):
        return None


def from_spec(spec) -> Any:
    """The prototype structure described by a scenario's ``[structure]`` table.

    A generated structure (:data:`_GENERATED` kinds; structures are immutable) is built once per table and the same
    object returned for an equal table (:data:`FROM_SPEC_CACHE_SIZE` kept): its derived geometry (hulls, faces,
    interfaces) and the engine's model and settled state (:func:`~blastscale.sim3d.reference.reference_scene`) are
    then shared by every run of a study, ensemble, sweep or plan in the process (issue #41)."""
    kind = check_choice("structure.kind", spec.kind, STRUCTURE_BUILDERS)
    key = (kind, _spec_key(spec)) if kind in _GENERATED else None
    if key is None or key[1] is None:
        return STRUCTURE_BUILDERS[kind](spec)
    with _BUILT_LOCK:
        hit = _BUILT.get(key)
        if hit is not None:
            _BUILT.move_to_end(key)
            return hit
    built = STRUCTURE_BUILDERS[kind](spec)
    with _BUILT_LOCK:
        built = _BUILT.setdefault(key, built)
        while len(_BUILT) > FROM_SPEC_CACHE_SIZE:
            _BUILT.popitem(last=False)
    return built
