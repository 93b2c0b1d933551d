"""The ``[lab]`` table of a scenario: what the laboratory can make, fire, build and measure, and how
precisely (the test planner's constraints, docs/planning.md), and user-defined explosives."""

from __future__ import annotations

import warnings
from typing import Any, Optional

from pydantic import BaseModel, Field, PrivateAttr, field_validator, model_serializer, model_validator

from .._validate import check_choice
from ..blast.explosive_library import EXPLOSIVES
from ..blast.explosives import canonical_name, initiator_tnt_kg
from ..blast.initiation import DEFAULT_INITIATOR, INITIATORS
from ..blast.parameters import BURSTS
from ..blast.safety import QD_K_FACTORS, SAFETY_THRESHOLDS
from ..structures.materials import MATERIALS
from .fields import SPEC_CONFIG, check_name
from .messages import value_in_message

__all__ = ["ExplosiveSpec", "LabSpec", "SAME_MATERIAL"]


#: The planner's name for "the prototype's own material" (gamma = 1) among ``[lab] materials``.
SAME_MATERIAL = "same"


class ExplosiveSpec(BaseModel):
    """A user-defined explosive (``[lab.explosives.NAME]``): its TNT equivalence for peak pressure and
    for impulse (as in UFC 3-340-02 Table 2-1), its density and where the numbers come from."""

    model_config = SPEC_CONFIG
    pressure_factor: float = Field(gt=0, le=10, description="TNT-equivalent mass per unit mass, peak pressure [-]")
    impulse_factor: float = Field(gt=0, le=10, description="TNT-equivalent mass per unit mass, impulse [-]")
    density_kg_m3: Optional[float] = Field(None, gt=0, le=25000, description="Density [kg/m^3]")
    source: str = Field("user-defined", description="Where the factors come from")
    min_charge_kg: float = Field(
        0.0, ge=0, le=10000, description="Smallest charge that detonates reliably [kg] (0: not stated)"
    )


class LabSpec(BaseModel):
    """What the laboratory can make, fire, build and measure, and how precisely (docs/planning.md).
    Every key is optional; the defaults are a university blast laboratory's."""

    model_config = SPEC_CONFIG
    explosive: str = Field("tnt", description="The explosive of the specimen's charge (library or [lab.explosives])")
    explosives: dict[str, ExplosiveSpec] = Field(default_factory=dict, description="User-defined explosives")
    source: Optional[str] = Field(
        None,
        description="A calibrated source's file (written by `blastscale source calibrate`; relative to the scenario "
        "file): the planner plans in its control value (an exploding-wire bank's stored energy); default: the "
        "chemical explosive",
    )
    initiator: str = Field(
        DEFAULT_INITIATOR,
        description="The initiator (detonator) by name: rp-80 (Teledyne RISI EBW, 80 mg PETN + 123 mg RDX), "
        "rp-83 (80 mg PETN + 1031 mg RDX), no-8 (a commercial No. 8 detonator, 1 g) or none",
    )
    initiator_tnt_kg: Optional[float] = Field(
        None,
        ge=0,
        le=1000,
        description="The initiator's TNT-equivalent mass [kg] (default: the named initiator's, impulse basis; "
        "given: it stands for both bases)",
    )
    initiator_max_fraction: float = Field(
        0.5,
        gt=0,
        le=1,
        description="Largest share of the charge's TNT-equivalent "
        "impulse the initiator may carry; designs above it are rejected [-]",
    )
    charge_min_kg: float = Field(
        0.0, ge=0, le=10000, description="Smallest mass of the explosive the lab can make and fire [kg]"
    )
    charge_max_kg: float = Field(1.0, gt=0, le=10000, description="Largest mass of the explosive the lab may fire [kg]")
    specimen_max_height_m: float = Field(2.0, gt=0, le=1000, description="Tallest specimen the lab can build [m]")
    specimen_max_mass_kg: float = Field(500.0, gt=0, le=1e7, description="Heaviest specimen the lab can handle [kg]")
    materials: Optional[list[str]] = Field(
        None,
        description="Candidate specimen materials from the materials library "
        '("same": the prototype\'s); default: all of them',
    )
    prototype_material: Optional[str] = Field(
        None,
        description="The prototype's material in the materials library, for the rigidity check (its compressive "
        "strength and Young's modulus); default: the library stone or masonry nearest the prototype's density",
    )
    charge_tolerance: float = Field(
        0.02, ge=0, le=1, description="Charge mass, one standard deviation, relative (lognormal) [-]"
    )
    standoff_tolerance_m: float = Field(0.001, ge=0, le=10, description="Stand-off, one standard deviation [m]")
    friction_tolerance: float = Field(0.05, ge=0, le=1, description="Friction coefficient, one standard deviation [-]")
    density_tolerance: float = Field(
        0.02, ge=0, le=1, description="Specimen density, one standard deviation, relative [-]"
    )
    samples: int = Field(2000, ge=10, le=1_000_000, description="Monte Carlo samples per design [-]")
    seed: int = Field(0, ge=0, le=2**63 - 1, description="Seed of the Monte Carlo draws [-]")
    standoff_min_m: Optional[float] = Field(
        None, gt=0, le=1e4, description="Shortest stand-off the lab can set up [m] (None: no limit)"
    )
    standoff_max_m: Optional[float] = Field(
        None, gt=0, le=1e4, description="Longest stand-off the lab can set up [m] (None: no limit)"
    )
    gauge_rate_max_hz: Optional[float] = Field(
        None,
        gt=0,
        le=1e10,
        description="Fastest sampling rate of the lab's pressure gauges [1/s]: a design whose positive phase it samples "
        "fewer than 10 (1 + d) times is rejected (planning.instruments.gauge_rate_needed_hz; None: no limit)",
    )
    tnt_max_kg: Optional[float] = Field(
        None,
        gt=0,
        le=1e6,
        description="Licence limit of the range in TNT equivalent [kg]: the charge with its initiator, on the "
        "stricter of the pressure and impulse bases (None: no limit)",
    )
    camera_max_fps: float = Field(100000.0, gt=0, le=1e9, description="Fastest frame rate of the lab's camera [1/s]")
    space_radius_m: float = Field(20.0, gt=0, le=1e5, description="Radius of the cleared space around the charge [m]")
    safety_threshold: str = Field(
        "6.9 kPa",
        description="The safety distance that must fit in the space: a "
        "threshold key (34.5 kPa, 6.9 kPa, 1.03 kPa, 200 Pa) or K24, K40, K50",
    )
    first_peak_target: float = Field(
        0.05,
        gt=0,
        le=1,
        description="Largest relative error of the specimen's first peak that the weighing must keep (95 %) [-]",
    )
    debris_margin: float = Field(
        2.0, ge=1, le=100, description="Factor on the largest simulated excursion of the blocks for the debris zone [-]"
    )
    ensemble_3d: Optional[int] = Field(
        None,
        ge=0,
        le=256,
        description="3D Monte Carlo members for the odds of each "
        "design run in 3D (0: none; default 0 for a block planned on the planar "
        "kernels, 32 for every other kind) [-]",
    )
    top_3d: int = Field(
        3,
        ge=1,
        le=50,
        description="Screening leaders of a structure without a planar path (or a load model "
        "the planar kernels lack) that get the 3D comparison and ensemble; the best screened design of each "
        "material and the one at the largest admissible scale get them too [-]",
    )
    bursts: list[str] = Field(
        default_factory=lambda: ["surface"],
        description="Specimen charges the planner tries: "
        "surface (on the floor), free-air (on a stand at a height it chooses)",
    )

    @model_validator(mode="before")
    @classmethod
    def _names(cls, data: Any) -> Any:
        """The explosive by the name users give it ("C4", "Comp B"); the initiator's TNT equivalent
        from its name unless stated; a user table that redefines a library explosive warns."""
        if not isinstance(data, dict):
            return data
        data = dict(data)
        mine = data.get("explosives") or {}
        for name in mine if isinstance(mine, dict) else ():
            lib = canonical_name(name)
            if lib is not None:
                warnings.warn(
                    f"lab.explosives.{name} redefines the library's explosive {lib!r} "
                    f"({EXPLOSIVES[lib].source}): the [lab] table's factors are used",
                    UserWarning,
                    stacklevel=2,
                )
        ex = data.get("explosive")
        if isinstance(ex, str):
            data["explosive"] = canonical_name(ex, mine if isinstance(mine, dict) else None) or ex
        ini = data.get("initiator", DEFAULT_INITIATOR)
        if isinstance(ini, str):
            check_choice("initiator", ini, INITIATORS, "or give initiator_tnt_kg")
        return data

    #: True when ``initiator_tnt_kg`` is the named initiator's (not written back: a new ``initiator`` in
    #: ``with_values`` or ``--set`` brings its own).
    _derived_tnt: bool = PrivateAttr(False)

    @model_validator(mode="after")
    def _initiator_tnt(self) -> "LabSpec":
        if self.initiator_tnt_kg is None:  # frozen: set once, here
            object.__setattr__(self, "initiator_tnt_kg", initiator_tnt_kg(self.initiator))
            self._derived_tnt = True
        return self

    @model_serializer(mode="wrap")
    def _dump(self, handler):
        d = handler(self)
        if self._derived_tnt and isinstance(d, dict):
            d.pop("initiator_tnt_kg", None)
        elif isinstance(d, dict) and "initiator" not in self.model_fields_set:
            d.pop("initiator", None)  # a stated initiator_tnt_kg: the written file names no detonator it did not use
        return d

    @property
    def initiator_tnt_pressure_kg(self) -> float:
        """The initiator's TNT-equivalent mass by peak pressure [kg]: the named initiator's, or the stated
        ``initiator_tnt_kg`` (one figure for both bases)."""
        return initiator_tnt_kg(self.initiator, "pressure") if self._derived_tnt else float(self.initiator_tnt_kg)

    @property
    def initiator_named(self) -> Optional[str]:
        """The name of the initiator whose figures are used (:data:`~blastscale.blast.initiation.INITIATORS`), or
        None when only its TNT equivalent is stated (``initiator_tnt_kg`` without ``initiator``)."""
        return self.initiator if self._derived_tnt or "initiator" in self.model_fields_set else None

    @property
    def initiator_used(self) -> str:
        """The initiator actually used, in words: the named one (its contents), or the stated TNT equivalent."""
        if self._derived_tnt:
            return INITIATORS[self.initiator].description or INITIATORS[self.initiator].source
        named = f" ({self.initiator})" if "initiator" in self.model_fields_set else ""
        return f"stated: initiator_tnt_kg = {self.initiator_tnt_kg:g} kg TNT{named}"

    @field_validator("materials")
    @classmethod
    def _materials(cls, v: Optional[list[str]]) -> Optional[list[str]]:
        if v is None:
            return v
        if not v:
            raise ValueError("= [] is empty: give at least one material, or leave the key out for all of them")
        for name in v:
            check_name(name, (SAME_MATERIAL,) + tuple(MATERIALS))
        return v

    @field_validator("prototype_material")
    @classmethod
    def _prototype_material(cls, v: Optional[str]) -> Optional[str]:
        return v if v is None else check_name(v, tuple(MATERIALS))

    @field_validator("bursts")
    @classmethod
    def _bursts(cls, v: list[str]) -> list[str]:
        if not v:
            raise ValueError("= [] is empty: give surface, free-air or both")
        for name in v:
            check_name(name, BURSTS)
        return list(dict.fromkeys(v))

    @field_validator("safety_threshold")
    @classmethod
    def _threshold(cls, v: str) -> str:
        return check_name(v, tuple(t.key for t in SAFETY_THRESHOLDS) + tuple(QD_K_FACTORS))

    @model_validator(mode="after")
    def _consistent(self) -> "LabSpec":
        check_choice(
            "explosive",
            self.explosive,
            (*EXPLOSIVES, *self.explosives),
            "or define it in a [lab.explosives.NAME] table",
        )
        if (
            self.standoff_min_m is not None
            and self.standoff_max_m is not None
            and self.standoff_min_m > self.standoff_max_m
        ):
            raise ValueError(
                f"standoff_min_m = {value_in_message(self.standoff_min_m)} m is above standoff_max_m = "
                f"{value_in_message(self.standoff_max_m)} m: give a minimum at or below the maximum"
            )
        if self.charge_min_kg > self.charge_max_kg:
            raise ValueError(
                f"charge_min_kg = {value_in_message(self.charge_min_kg)} kg is above charge_max_kg = "
                f"{value_in_message(self.charge_max_kg)} kg: give a minimum at or below the maximum"
            )
        return self
