"""The structure table of a scenario file: one pydantic model per structure kind (SI, unit in each key).

Each kind is the prototype a generator of :mod:`blastscale.structures` builds (block, column, wall,
arch, portal) or a block-model file (assembly); :data:`Structure` picks the model by ``kind``,
:data:`KINDS` maps each kind to it. The other tables: :mod:`.specs`.
"""

from __future__ import annotations

from typing import Annotated, Any, Literal, Optional, Union

from pydantic import BaseModel, Field, model_validator

from ..constants import DEFAULT_FRICTION
from ..structures.column import MAX_DRUMS, MAX_SIDES, MIN_SIDES
from .fields import SPEC_CONFIG, at_most_one, engine_limits

__all__ = [
    "BlockSpec",
    "CapitalSpec",
    "ColumnSpec",
    "WallSpec",
    "ArchSpec",
    "PortalSpec",
    "AssemblySpec",
    "Structure",
    "KINDS",
]


class BlockSpec(BaseModel):
    """A monolithic rectangular block (paper Sec. "Equations of motion")."""

    model_config = SPEC_CONFIG
    kind: Literal["block"] = Field(description="Structure kind")
    height_m: float = Field(10.0, gt=0, le=1000, description="Height 2h [m]")
    alpha_deg: Optional[float] = Field(None, gt=0, lt=90, description="Slenderness angle atan(b/h) [deg]")
    width_m: Optional[float] = Field(None, gt=0, le=1000, description="Width 2b along the blast [m]")
    depth_m: float = Field(1.0, gt=0, le=1000, description="Depth 2w across the blast [m]")
    density_kg_m3: float = Field(2000.0, gt=0, le=25000, description="Density [kg/m^3]")
    friction: float = Field(
        DEFAULT_FRICTION, description="Coulomb friction coefficient mu [-] (3D)", **engine_limits("friction")
    )

    @model_validator(mode="before")
    @classmethod
    def _default_slenderness(cls, data: Any) -> Any:
        if isinstance(data, dict) and data.get("alpha_deg") is None and data.get("width_m") is None:
            data = {**data, "alpha_deg": 15.0}  # the paper's slender block
        return data

    @model_validator(mode="after")
    def _one_width(self) -> "BlockSpec":
        return at_most_one(self, "alpha_deg", "width_m")


class CapitalSpec(BaseModel):
    """A column's capital (``[structure.capital]``): the echinus, a frustum of the shaft's section from the top
    drum's top section to the abacus width, and the abacus, a square slab; both are bodies (docs/columns.md,
    "A monument's column")."""

    model_config = SPEC_CONFIG
    abacus_width_m: float = Field(gt=0, le=100, description="Side of the square abacus [m] (1-3 x top_width_m)")
    abacus_height_m: float = Field(gt=0, le=100, description="Height of the abacus slab [m]")
    echinus_height_m: float = Field(gt=0, le=100, description="Height of the echinus [m]")


class ColumnSpec(BaseModel):
    """A multi-drum column (paper Sec. "Application to multi-drum masonry columns"); a monument's column with
    drums of given heights, entasis and a capital (docs/columns.md, "A monument's column")."""

    model_config = SPEC_CONFIG
    kind: Literal["column"] = Field(description="Structure kind")
    section: Literal["square", "circular"] = Field("square", description="Drum cross-section")
    drums: int = Field(10, ge=1, le=MAX_DRUMS, description="Number of drums [-] (with drum_heights_m: its length)")
    height_m: float = Field(
        10.0, gt=0, le=1000, description="Height of the shaft (the drums) [m] (with drum_heights_m: their sum)"
    )
    drum_heights_m: Optional[list[Annotated[float, Field(gt=0, le=1000)]]] = Field(
        None,
        min_length=1,
        max_length=MAX_DRUMS,
        description="Height of each drum from the base up [m] (None: equal drums); sums to height_m",
    )
    base_width_m: float = Field(1.65, gt=0, le=100, description="Side or diameter at the base [m]")
    top_width_m: float = Field(1.28, gt=0, le=100, description="Side or diameter at the shaft's top [m]")
    width_profile_m: Optional[list[list[float]]] = Field(
        None,
        min_length=2,
        description="Entasis: [[z/H, width_m], ...], the side or diameter [m] at relative heights z/H of the shaft "
        "from 0 to 1, piecewise linear between them, never growing with height (None: the linear taper "
        "base_width_m -> top_width_m); its ends are base_width_m and top_width_m",
    )
    capital: Optional[CapitalSpec] = Field(None, description="Echinus and abacus on the shaft (None: no capital)")
    sides: int = Field(32, ge=MIN_SIDES, le=MAX_SIDES, description="Polygon sides of a circular drum [-]")
    density_kg_m3: float = Field(2700.0, gt=0, le=25000, description="Density [kg/m^3] (marble)")
    friction: float = Field(
        DEFAULT_FRICTION, description="Coulomb friction coefficient mu [-]", **engine_limits("friction")
    )

    @model_validator(mode="before")
    @classmethod
    def _from_drums_and_profile(cls, data: Any) -> Any:
        """``drums`` and ``height_m`` from ``drum_heights_m``, ``base_width_m`` and ``top_width_m`` from
        ``width_profile_m``, where those keys are not given (given, they are checked after)."""
        if not isinstance(data, dict):
            return data
        hs, prof = data.get("drum_heights_m"), data.get("width_profile_m")
        extra = {}
        if isinstance(hs, list) and hs and all(isinstance(h, (int, float)) for h in hs):
            extra |= {"drums": len(hs)} if data.get("drums") is None else {}
            extra |= {"height_m": float(sum(hs))} if data.get("height_m") is None else {}
        if isinstance(prof, list) and len(prof) >= 2 and all(isinstance(p, list) and len(p) == 2 for p in prof):
            extra |= {"base_width_m": prof[0][1]} if data.get("base_width_m") is None else {}
            extra |= {"top_width_m": prof[-1][1]} if data.get("top_width_m") is None else {}
        return {**data, **extra} if extra else data

    @model_validator(mode="after")
    def _consistent(self) -> "ColumnSpec":
        hs = self.drum_heights_m
        if hs is not None:
            if len(hs) != self.drums:
                raise ValueError(f"drum_heights_m has {len(hs)} values and drums = {self.drums}: give one per drum")
            if abs(sum(hs) - self.height_m) > 1e-9 * self.height_m:
                raise ValueError(
                    f"drum_heights_m sum to {sum(hs):.9g} m and height_m = {self.height_m:.9g} m: "
                    "height_m is the shaft's height, the sum of drum_heights_m (give one, or both equal)"
                )
        prof = self.width_profile_m
        if prof is not None:
            if any(len(p) != 2 for p in prof):
                raise ValueError("width_profile_m must be a list of [z/H, width_m] pairs")
            for key, end in (("base_width_m", prof[0][1]), ("top_width_m", prof[-1][1])):
                if getattr(self, key) != end:
                    raise ValueError(
                        f"{key} = {getattr(self, key):.9g} m and width_profile_m's end {end:.9g} m: "
                        "give one of them, or both equal"
                    )
        return self


_DENSITY = dict(gt=0, le=25000, description="Density [kg/m^3]")
_FRICTION = dict(description="Coulomb friction coefficient mu [-] at every joint", **engine_limits("friction"))


class WallSpec(BaseModel):
    """A dry-stone wall facing the blast (plane y-z): courses of equal units, running or stack bond
    (docs/assemblies.md)."""

    model_config = SPEC_CONFIG
    kind: Literal["wall"] = Field(description="Structure kind")
    length_m: float = Field(4.0, gt=0, le=1000, description="Wall length along y [m]")
    height_m: float = Field(3.0, gt=0, le=1000, description="Wall height [m]")
    thickness_m: float = Field(0.5, gt=0, le=1000, description="Wall thickness along x [m]")
    courses: int = Field(10, ge=1, le=1000, description="Number of courses [-]")
    units_per_course: int = Field(8, ge=1, le=1000, description="Full units per course [-]")
    bond: Literal["running", "stack"] = Field(
        "running", description="Bond: running (half units at the ends of every second course) or stack"
    )
    density_kg_m3: float = Field(2000.0, **_DENSITY)
    friction: float = Field(DEFAULT_FRICTION, **_FRICTION)


class ArchSpec(BaseModel):
    """A circular arch of voussoirs facing the blast (plane y-z), optionally on piers (docs/assemblies.md)."""

    model_config = SPEC_CONFIG
    kind: Literal["arch"] = Field(description="Structure kind")
    radius_m: float = Field(2.5, gt=0, le=1000, description="Radius of the centreline [m]")
    thickness_m: float = Field(0.5, gt=0, le=1000, description="Radial thickness [m] (< 2 x radius)")
    depth_m: float = Field(1.0, gt=0, le=1000, description="Depth along x [m]")
    voussoirs: int = Field(
        15, ge=2, le=1000, description="Number of voussoirs [-] (one voussoir is a block: kind = 'block')"
    )
    embrace_deg: float = Field(180.0, gt=0, lt=360, description="Angle spanned, symmetric about the crown [deg]")
    pier_height_m: float = Field(
        0.0,
        ge=0,
        le=1000,
        description="Height of the springing above the ground [m]; "
        "> 0 puts a pier under each springer (needed unless embrace_deg = 180)",
    )
    density_kg_m3: float = Field(2000.0, **_DENSITY)
    friction: float = Field(DEFAULT_FRICTION, **_FRICTION)


class PortalSpec(BaseModel):
    """A trilithon facing the blast: two square columns (monolithic or of drums) and a free lintel."""

    model_config = SPEC_CONFIG
    kind: Literal["portal"] = Field(description="Structure kind")
    column_height_m: float = Field(4.0, gt=0, le=1000, description="Column height [m]")
    column_width_m: float = Field(0.8, gt=0, le=1000, description="Column side (square), also the depth [m]")
    span_m: float = Field(3.0, gt=0, le=1000, description="Clear span between the columns [m]")
    lintel_height_m: float = Field(1.0, gt=0, le=1000, description="Lintel height [m]")
    lintel_overhang_m: float = Field(0.3, ge=0, le=1000, description="Lintel beyond each column [m]")
    drums: int = Field(1, ge=1, le=MAX_DRUMS, description="Drums per column (1: monolithic) [-]")
    density_kg_m3: float = Field(2000.0, **_DENSITY)
    friction: float = Field(DEFAULT_FRICTION, **_FRICTION)


class AssemblySpec(BaseModel):
    """Blocks from a block-model file: our JSON, a mesh (OBJ, STL, PLY) or COMPAS JSON (docs/assemblies.md)."""

    model_config = SPEC_CONFIG
    kind: Literal["assembly"] = Field(description="Structure kind")
    file: str = Field(description="Block-model file, relative to the scenario file")
    density_kg_m3: float = Field(
        2000.0,
        description="Density of blocks without their own [kg/m^3]",
        **{k: v for k, v in _DENSITY.items() if k != "description"},
    )
    friction: float = Field(DEFAULT_FRICTION, **_FRICTION)


Structure = Annotated[
    Union[BlockSpec, ColumnSpec, WallSpec, ArchSpec, PortalSpec, AssemblySpec], Field(discriminator="kind")
]
KINDS = {
    "block": BlockSpec,
    "column": ColumnSpec,
    "wall": WallSpec,
    "arch": ArchSpec,
    "portal": PortalSpec,
    "assembly": AssemblySpec,
}
