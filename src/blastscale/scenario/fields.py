"""The conventions every table of a scenario file shares: strict pydantic models, names checked
against the library's registries, bounds taken from the 3D engine's own valid ranges, and one of two
keys that say the same thing. Used by the structure tables (:mod:`.structure_specs`), the other
tables (:mod:`.specs`), the lab (:mod:`.lab`) and the fired records (:mod:`.fired`).
"""

from __future__ import annotations

from pydantic import BaseModel, ConfigDict

from ..sim3d.contact_ranges import SETTING_RANGES
from .messages import value_in_message

__all__ = ["SPEC_CONFIG", "at_most_one", "check_name", "engine_limits"]

#: The configuration of every scenario table: unknown keys refused, no inf/NaN, no type coercion, frozen,
#: defaults validated too.
SPEC_CONFIG = ConfigDict(extra="forbid", allow_inf_nan=False, strict=True, frozen=True, validate_default=True)


def check_name(value: str, names: tuple[str, ...]) -> str:
    """``value`` when it is one of ``names`` (a registry's keys); else a ``ValueError`` listing the valid ones
    (pydantic prefixes the field's name)."""
    if value not in names:
        raise ValueError(f"= {value!r} is not known: valid values are {', '.join(names)}")
    return value


def at_most_one(model: BaseModel, a: str, b: str) -> BaseModel:
    """Refuse two keys that say the same thing (width and slenderness; density ratio and material)."""
    va, vb = getattr(model, a), getattr(model, b)
    if va is not None and vb is not None:
        raise ValueError(f"{a} = {value_in_message(va)} and {b} = {value_in_message(vb)}: give one of them, not both")
    return model


def engine_limits(setting: str) -> dict:
    """pydantic bounds of a field that sets the 3D engine's ``setting``: the engine's own valid range
    (:data:`blastscale.sim3d.contact_ranges.SETTING_RANGES`), one source for both."""
    r = SETTING_RANGES[setting]
    return {("gt" if r.lo_open else "ge"): r.lo, ("lt" if r.hi_open else "le"): r.hi}
