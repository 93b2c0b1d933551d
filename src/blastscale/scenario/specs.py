"""The scenario schema: the tables of a scenario file as pydantic models (SI, unit in each key).

Names of blast models, load methods and incidence models are checked against the library's own
registries (imported directly: a model registered there is accepted here with no change). The
structure table: :mod:`.structure_specs`; the conventions every table shares: :mod:`.fields`; the
whole scenario, its variants and its defaults: :mod:`.scenario`; reading a file: :mod:`.files`;
the one-line error messages: :mod:`.messages`.
"""

from __future__ import annotations

import re
from fractions import Fraction
from typing import Annotated, Any, Literal, Optional

import annotated_types as at
from pydantic import AliasChoices, BaseModel, Field, field_validator, model_validator

from .._validate import BlastscaleInputError
from ..blast.incidence import INCIDENCE_MODELS
from ..blast.negative_phase import NEGATIVE_PHASE_MODEL, NEGATIVE_PHASE_MODELS
from ..blast.parameters import BLAST_MODELS, BURSTS, DEFAULT_BLAST_MODEL, DEFAULT_BURST
from ..blast.pulses import PULSE_SHAPES
from ..constants import STANDARD_GRAVITY
from ..sim3d.contact_ranges import CONES, JACOBIANS, SETTLINGS, SOLVERS, STEPS_AFTER_LOAD
from ..sim3d.load_methods import LOAD_METHODS
from ..structures.materials import MATERIALS
from .fields import SPEC_CONFIG, at_most_one, check_name, engine_limits
from .messages import value_in_message

__all__ = [
    "parse_ratio",
    "BlastSpec",
    "ScaleSpec",
    "SimulationSpec",
    "ContactSpec",
    "VerdictSpec",
    "DamageSpec",
    "LEGACY_SCENARIO_KEYS",
]

#: Deprecated scenario keys, still accepted when read (files, ``with_values``, ``--set``) and never
#: written: old dotted path -> new dotted path (CHANGELOG.md, docs/glossary.md).
LEGACY_SCENARIO_KEYS = {
    "blast.model": "blast.blast_model",
    "blast.pulse": "blast.pulse_shape",
    "scale.model_material": "scale.specimen_material",
}


def _renamed(path: str) -> AliasChoices:
    """The new key of ``path`` first, then its deprecated name (:data:`LEGACY_SCENARIO_KEYS`)."""
    old = next(o for o, n in LEGACY_SCENARIO_KEYS.items() if n == path)
    return AliasChoices(path.split(".")[-1], old.split(".")[-1])


def parse_ratio(value: Any, name: str = "scale") -> float:
    """A dimensionless ratio from a number or a fraction string (``"1/200"``, ``"0.005"``) [-].

    Raises :class:`BlastscaleInputError` naming ``name`` for anything else (a finite, > 0 number
    is checked by the caller).

    >>> parse_ratio("1/200")
    0.005
    """
    if isinstance(value, bool):
        raise BlastscaleInputError(f"{name} = {value!r} is not a number: give a ratio such as 0.005 or 1/200")
    if isinstance(value, (int, float)):
        return float(value)
    text = str(value).strip()
    try:
        if re.fullmatch(r"[0-9.eE+-]+\s*/\s*[0-9.eE+-]+", text):
            num, den = (float(x) for x in text.split("/"))
            if den == 0:
                raise ZeroDivisionError
            return num / den
        return float(Fraction(text)) if "/" in text else float(text)
    except (ValueError, ZeroDivisionError):
        raise BlastscaleInputError(
            f"{name} = {value!r} is not a ratio: give a number such as 0.005 or a fraction such as 1/200"
        ) from None


Pos = Annotated[float, at.Gt(0)]


class BlastSpec(BaseModel):
    """The prototype's charge, where it stands and how its load is modelled; no charge (the table
    left out, or ``charge_kg = 0``): gravity alone, a stability check."""

    model_config = SPEC_CONFIG
    charge_kg: float = Field(0.0, ge=0, description="TNT-equivalent charge W [kg]; 0: gravity alone")
    standoff_m: Optional[Pos] = Field(None, description="Stand-off R from the front face [m] (needed with a charge)")
    blast_model: str = Field(
        DEFAULT_BLAST_MODEL,
        validation_alias=_renamed("blast.blast_model"),
        description="Blast model (the empirical fit): kingery-bulmash (Swisdak 1994, the "
        "library-wide default) or masi2021 (the paper's Appendix A fits); deprecated key: model",
    )
    load: str = Field("A", description="Load method of the 3D engine (paper Methods A, B, C)")
    pulse_shape: Literal[PULSE_SHAPES] = Field(
        "friedlander", validation_alias=_renamed("blast.pulse_shape"), description="Pulse shape; deprecated key: pulse"
    )
    incidence: str = Field("ufc", description="Angle-of-incidence model (Methods B, C)")
    extrapolate: bool = Field(False, description="Evaluate the blast fits outside their ranges (warns)")
    burst: Literal[BURSTS] = Field(
        DEFAULT_BURST,
        description="The prototype's burst: surface (hemispherical, "
        "the paper's) or free-air (spherical, Kingery-Bulmash 1984, UFC 3-340-02 Fig. 2-7)",
    )
    clearing: bool = Field(
        False,
        description="Clear the reflected pressure on the loaded faces' finite size "
        "(UFC 3-340-02 Sec. 2-15.3.2; the faces are the structure's own)",
    )
    negative_phase: bool = Field(
        False,
        description="Add the negative phase (UFC 3-340-02 Fig. 2-16, Granström's "
        "cubic) after the positive one, bounded by the positive impulse",
    )
    negative_phase_model: str = Field(
        NEGATIVE_PHASE_MODEL,
        description="The negative phase's model: "
        "ufc-fig2-16-cubic (the chart's suction) or friedlander-continued (the positive "
        "pulse continued past its zero crossing)",
    )

    @field_validator("blast_model")
    @classmethod
    def _model(cls, v: str) -> str:
        return check_name(v, tuple(BLAST_MODELS))

    @model_validator(mode="after")
    def _burst_fits(self) -> "BlastSpec":
        if self.burst == "free-air" and self.blast_model == "masi2021":
            raise ValueError(
                "burst = 'free-air' with blast_model = 'masi2021': the paper's fits are surface-burst "
                "fits only; use blast_model = 'kingery-bulmash' for a free-air burst"
            )
        return self

    @field_validator("negative_phase_model")
    @classmethod
    def _negative_model(cls, v: str) -> str:
        return check_name(v, NEGATIVE_PHASE_MODELS)

    @field_validator("load")
    @classmethod
    def _load(cls, v: str) -> str:
        return check_name(v, tuple(LOAD_METHODS))

    @field_validator("incidence")
    @classmethod
    def _incidence(cls, v: str) -> str:
        return check_name(v, INCIDENCE_MODELS)

    @model_validator(mode="after")
    def _standoff(self) -> "BlastSpec":
        if "charge_kg" not in self.model_fields_set and self.model_fields_set:
            raise ValueError(
                "blast.charge_kg is missing: give the charge [kg] (0, or no [blast] table, for gravity alone)"
            )
        if self.charge_kg > 0 and self.standoff_m is None:
            raise ValueError(
                f"charge_kg = {value_in_message(self.charge_kg)} needs standoff_m (the stand-off R [m]); "
                "charge_kg = 0 is gravity alone"
            )
        if self.charge_kg == 0 and (self.clearing or self.negative_phase):
            raise ValueError(
                f"blast.{'clearing' if self.clearing else 'negative_phase'} = true needs a charge: "
                "charge_kg = 0 is gravity alone (valid: false)"
            )
        return self

    @property
    def gravity_only(self) -> bool:
        """No charge: the structure under gravity alone."""
        return self.charge_kg == 0.0


class ScaleSpec(BaseModel):
    """The specimen's scales: lambda, the density ratio (or the specimen's material), varsigma."""

    model_config = SPEC_CONFIG
    length: Annotated[float, at.Gt(0), at.Le(1000)] = Field(
        description='Geometric scale lambda = l_model / l_prototype [-] (a number or a fraction "1/200")'
    )
    density_ratio: Optional[float] = Field(
        None, gt=0, le=100, description="gamma = rho_model / rho_prototype [-] (default 1)"
    )
    specimen_material: Optional[str] = Field(
        None,
        validation_alias=_renamed("scale.specimen_material"),
        description="The specimen's material from the materials library (its density and joint friction); deprecated key: model_material",
    )
    gravity_ratio: float = Field(1.0, gt=0, le=1000, description="varsigma = g_model / g_prototype [-]")
    law: Literal["general", "hopkinson-cranz"] = Field("general", description="Scaling law")
    specimen_burst: Optional[Literal[BURSTS]] = Field(
        None,
        description="The specimen's burst when it differs from the prototype's (a lab charge on a stand: "
        "free-air); default blast.burst",
    )
    specimen_charge_height_m: Optional[float] = Field(
        None,
        ge=0,
        le=1000,
        description="Height of the lab charge's centre above the floor [m]: the design warns when "
        "the floor's reflection makes it neither a surface nor a free-air burst at the specimen",
    )

    @field_validator("length", mode="before")
    @classmethod
    def _fraction(cls, v: Any) -> Any:
        if isinstance(v, str):
            try:
                return parse_ratio(v, "length")
            except BlastscaleInputError as exc:
                raise ValueError(
                    f'= {v!r} is not a ratio: give a number such as 0.005 or a fraction such as "1/200"'
                ) from exc
        return v

    @field_validator("specimen_material")
    @classmethod
    def _material(cls, v: Optional[str]) -> Optional[str]:
        return None if v is None else check_name(v, tuple(MATERIALS))

    @model_validator(mode="after")
    def _one_density(self) -> "ScaleSpec":
        return at_most_one(self, "density_ratio", "specimen_material")


class ContactSpec(BaseModel):
    """3D contact settings of the prototype (the model's are scaled from them); each key left
    out takes the engine's default for the structure (docs/sim3d.md). Valid ranges: the engine's
    own (:data:`blastscale.sim3d.contact_ranges.SETTING_RANGES`)."""

    model_config = SPEC_CONFIG
    time_constant_s: Optional[float] = Field(
        None, description="Normal contact time constant [s]", **engine_limits("time_constant")
    )
    damping_ratio: Optional[float] = Field(
        None, description="Normal contact damping ratio [-]", **engine_limits("damping_ratio")
    )
    friction_time_constant_s: Optional[float] = Field(
        None, description="Friction reference time constant [s]", **engine_limits("friction_time_constant")
    )
    impedance_min: Optional[float] = Field(None, description="solimp dmin [-]", **engine_limits("impedance_min"))
    impedance_max: Optional[float] = Field(None, description="solimp dmax [-]", **engine_limits("impedance_max"))
    impedance_width_m: Optional[float] = Field(None, description="solimp width [m]", **engine_limits("impedance_width"))
    cone: Optional[Literal[CONES]] = Field(None, description="Friction cone")
    impratio: Optional[float] = Field(
        None, description="Friction/normal impedance ratio [-]", **engine_limits("impratio")
    )
    solver: Optional[Literal[SOLVERS]] = Field(None, description="Constraint solver")
    iterations: Optional[int] = Field(None, description="Solver iterations [-]", **engine_limits("iterations"))
    tolerance: Optional[float] = Field(None, description="Solver tolerance [-]", **engine_limits("tolerance"))
    settle_tolerance: Optional[float] = Field(
        None,
        description="Solver tolerance while settling before the first arrival [-] (default 1e-8 above 10 bodies, "
        "else the tolerance; the tolerance itself gives the settling of before issue #28)",
        **engine_limits("settle_tolerance"),
    )
    settling: Optional[Literal[SETTLINGS]] = Field(
        None,
        description='How the structure settles before the first arrival: "plain" (20 contact time constants) or '
        '"kinetic" (80, kinetic damping: a tall stack at its static state; the default above 10 bodies)',
    )
    noslip_iterations: Optional[int] = Field(
        None, description="No-slip iterations [-]", **engine_limits("noslip_iterations")
    )
    jacobian: Optional[Literal[JACOBIANS]] = Field(
        None, description="Constraint Jacobian layout (dense by default; sparse is 2.5-3.4x faster on columns)"
    )


class SimulationSpec(BaseModel):
    """Which engines run, for how long, and their numerical settings."""

    model_config = SPEC_CONFIG
    engine: Literal["planar", "3d", "both"] = Field("both", description="Planar rocking, 3D rigid bodies or both")
    duration_s: float = Field(5.0, gt=0, le=1e5, description="Prototype time simulated after the shock arrival [s]")
    timestep_s: Optional[float] = Field(
        None, description="Prototype 3D time step [s] (default from the structure)", **engine_limits("timestep")
    )
    record_every: Optional[int] = Field(
        None,
        ge=1,
        le=100000,
        description="Keep one 3D state every N steps [-] "
        "(default: one per millisecond of the 10 m reference structure, 5 for a "
        "block and 4 for a column at any size)",
    )
    step_after_load: Literal[STEPS_AFTER_LOAD] = Field(
        "double",
        description='3D time step once every pulse has passed: "double" (up to 2 steps, at most half '
        'the contact time constant; 1.6-2x faster) or "same" (one step throughout, as before issue #28)',
    )
    samples: int = Field(2001, ge=2, le=10_000_000, description="Planar sampling times over the duration [-]")
    gravity_m_s2: float = Field(STANDARD_GRAVITY, gt=0, le=1000, description="Prototype gravity g [m/s^2]")
    restitution: Optional[float] = Field(None, ge=0, le=1, description="Planar restitution e [-] (default Housner's)")
    critical_charge: bool = Field(True, description="Also search the prototype's critical charge (planar)")
    ensemble_members: int = Field(
        0,
        ge=0,
        le=64,
        description="Members per system of a 3D ensemble under slightly "
        "perturbed loads, for chaotic structures (circular columns); 0: none [-]",
    )
    ensemble_perturbation: float = Field(
        1e-6, gt=0, le=0.1, description="Largest relative load change of an ensemble member [-]"
    )
    threads: Optional[int] = Field(
        None,
        ge=1,
        le=4096,
        description="Threads of one process: 3D runs in flight "
        "at once (ensemble members, the 3D cases of a sweep chunk), planar batches (outcome "
        "mode, fragility) split over them [-] (default: the cores this process may use, "
        "divided by the local Dask workers); results do not depend on it",
    )
    contact: ContactSpec = Field(default_factory=ContactSpec, description="3D contact settings")

    @field_validator("ensemble_members")
    @classmethod
    def _members(cls, v: int) -> int:
        if v == 1:
            raise ValueError("= 1 is out of range: valid values are 0 (no ensemble) or 2 to 64 members")
        return v


class VerdictSpec(BaseModel):
    """The similarity criterion's tolerances (:func:`blastscale.study.criterion.judge`, docs/verdict.md):
    relative errors of the up-scaled model against the prototype, and the thresholds of its outcomes."""

    model_config = SPEC_CONFIG
    peak: float = Field(
        0.05,
        gt=0,
        le=10,
        description="First peaks (3D points, planar rotation): largest relative error [-] "
        "(the first swing, before contacts and friction accumulate differences)",
    )
    displacement: float = Field(
        0.10,
        gt=0,
        le=10,
        description="Largest displacement at each point (planar: largest rotation): largest relative error [-]",
    )
    residual: float = Field(
        0.20,
        gt=0,
        le=10,
        description="Residual displacement and rotation of each body (the damage): largest relative error [-] "
        "(looser: they integrate the whole history)",
    )
    floor: float = Field(
        0.10,
        ge=0,
        le=1,
        description="A value is judged on at least this fraction of the structure's largest value of its quantity [-]",
    )
    moved_rel_height: float = Field(
        1e-3,
        gt=0,
        le=1,
        description="A body moved when its residual displacement exceeds this fraction of the structure's "
        "height [-] (also the scale below which a residual is not judged: H x this, and this in rad)",
    )
    creep_rel_height: float = Field(
        1e-4,
        gt=0,
        le=1,
        description="At rest before the blast: largest residual drift under gravity alone over the rest "
        "time, over the structure's height [-]",
    )
    confidence: float = Field(
        0.95, gt=0, lt=1, description="Confidence level of the probabilities' intervals (two-sided) [-]"
    )


class DamageSpec(BaseModel):
    """The damage states' limits (:func:`blastscale.analysis.damage.damage_state`, docs/sweeps.md "Damage
    states"): on the verdict's judged quantities, the residual drift (the largest residual displacement of a
    body over the structure's height H) and the largest residual rotation of a body; a body that fell is a
    collapse. Intact: drift <= ``intact_drift`` and rotation <= ``intact_rotation_rad``; damaged: slight from
    there, moderate from ``moderate_drift``, severe from ``severe_drift``. Defaults after the permanent drifts
    of unreinforced masonry in FEMA 356 (2000), Table C1-3, and the residual-dislocation performance levels of
    classical columns of Psycharis, Fragiadakis & Stefanou (2013), EESD 42(14), 2061-2079 (docs/sweeps.md)."""

    model_config = SPEC_CONFIG
    intact_drift: float = Field(
        1e-3,
        gt=0,
        lt=1,
        description="Intact up to this residual drift: largest residual displacement of a body / H [-] "
        "(FEMA 356 Table C1-3: 'negligible' permanent drift at Immediate Occupancy)",
    )
    intact_rotation_rad: float = Field(
        1e-3, gt=0, lt=1, description="Intact up to this residual rotation of every body [rad]"
    )
    moderate_drift: float = Field(
        6e-3,
        gt=0,
        lt=1,
        description="Damaged, moderate from this residual drift [-] (FEMA 356 Table C1-3, unreinforced "
        "masonry walls: 0.6 % permanent drift at Life Safety)",
    )
    severe_drift: float = Field(
        1e-2,
        gt=0,
        lt=1,
        description="Damaged, severe from this residual drift [-] (FEMA 356 Table C1-3, unreinforced masonry "
        "walls: 1 % permanent drift at Collapse Prevention)",
    )

    @model_validator(mode="after")
    def _ascending(self) -> "DamageSpec":
        if not self.intact_drift < self.moderate_drift < self.severe_drift:
            raise ValueError(
                f"intact_drift = {self.intact_drift:g}, moderate_drift = {self.moderate_drift:g}, severe_drift = "
                f"{self.severe_drift:g}: the limits must increase in that order"
            )
        return self
