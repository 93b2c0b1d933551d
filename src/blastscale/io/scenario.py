"""Scenario files: one blast experiment described in TOML, validated by pydantic.

A scenario names the prototype structure, the charge and its stand-off, the scales of the
model and how to simulate. Keys carry their unit in their name (``height_m``, ``charge_kg``,
``duration_s``; ratios are dimensionless); every key but the four that define the experiment
(``structure.kind``, ``blast.charge_kg``, ``blast.standoff_m``, ``scale.length``) has the
paper's default. The paper's 10 m block at 1/200::

    title = "Slender block, 50 kg TNT at 2 m, lambda = 1/200"

    [structure]
    kind = "block"          # "block" | "column"
    height_m = 10.0         # 2h
    alpha_deg = 15.0        # slenderness (or width_m, not both)
    depth_m = 1.0
    density_kg_m3 = 2000.0
    friction = 0.7          # Coulomb, tan 35 deg

    [blast]
    charge_kg = 50.0        # TNT equivalent
    standoff_m = 2.0
    model = "masi2021"      # blast model: "masi2021" | "kingery-bulmash"
    load = "A"              # load method (3D): "A" | "B" | "C"
    pulse = "friedlander"   # "friedlander" | "triangular" | "impulsive"

    [scale]
    length = "1/200"        # lambda (a number or a fraction)
    model_material = "marble"   # or density_ratio = 1.0 (gamma); default gamma = 1
    gravity_ratio = 1.0

    [simulation]
    engine = "both"         # "planar" | "3d" | "both"
    duration_s = 5.0

    [simulation.contact]    # 3D contact (optional; defaults derived from the structure)
    time_constant_s = 0.002

Unknown keys, wrong types, NaN and values out of range are refused with one line that names
the field path, the value and the valid range (:class:`~blastscale._validate.BlastscaleInputError`).
See ``docs/scenarios.md`` for every key.
"""

from __future__ import annotations

import math
import re
import tomllib
from fractions import Fraction
from pathlib import Path
from typing import Annotated, Any, Literal, Mapping, Optional, Union

import annotated_types as at
from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator, model_validator

from .._validate import BlastscaleInputError
from ..blast.pulses import PULSE_SHAPES
from .materials import MATERIALS

__all__ = ["Scenario", "load_scenario", "parse_ratio", "BlockSpec", "ColumnSpec", "BlastSpec", "ScaleSpec",
           "SimulationSpec", "ContactSpec"]

_CONFIG = ConfigDict(extra="forbid", allow_inf_nan=False, strict=True, frozen=True, validate_default=True)


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


def _registry_names(module: str, attr: str, fallback: tuple[str, ...]) -> tuple[str, ...]:
    """Names accepted by a registry of the library (dict keys or tuple), read when validating so
    that a newly registered model or load method needs no change here."""
    import importlib

    try:
        reg = getattr(importlib.import_module(module), attr)
    except (ImportError, AttributeError):
        return fallback
    return tuple(reg)


def _check_name(value: str, names: tuple[str, ...]) -> str:
    if value not in names:
        raise ValueError(f"= {value!r} is not known: valid values are {', '.join(names)}")
    return value


def _at_most_one(model: BaseModel, a: str, b: str) -> BaseModel:
    """Refuse two keys that say the same thing (width and slenderness; density ratio and material)."""
    va, vb = getattr(model, a), getattr(model, b)
    if va is not None and vb is not None:
        raise ValueError(f"{a} = {_show(va)} and {b} = {_show(vb)}: give one of them, not both")
    return model


Pos = Annotated[float, at.Gt(0)]


class BlockSpec(BaseModel):
    """A monolithic rectangular block (paper Sec. "Equations of motion")."""

    model_config = _CONFIG
    kind: Literal["block"] = Field(description="Structure kind")
    height_m: float = Field(10.0, gt=0, le=1000, description="Height 2h [m]")
    alpha_deg: Optional[float] = Field(None, gt=0, lt=90, description="Slenderness angle atan(b/h) [deg]")
    width_m: Optional[float] = Field(None, gt=0, le=1000, description="Width 2b along the blast [m]")
    depth_m: float = Field(1.0, gt=0, le=1000, description="Depth 2w across the blast [m]")
    density_kg_m3: float = Field(2000.0, gt=0, le=25000, description="Density [kg/m^3]")
    friction: float = Field(0.7, ge=0, le=10, description="Coulomb friction coefficient mu [-] (3D)")

    @model_validator(mode="before")
    @classmethod
    def _default_slenderness(cls, data: Any) -> Any:
        if isinstance(data, dict) and data.get("alpha_deg") is None and data.get("width_m") is None:
            data = {**data, "alpha_deg": 15.0}  # the paper's slender block
        return data

    @model_validator(mode="after")
    def _one_width(self) -> "BlockSpec":
        return _at_most_one(self, "alpha_deg", "width_m")


class ColumnSpec(BaseModel):
    """A multi-drum column (paper Sec. "Application to multi-drum masonry columns")."""

    model_config = _CONFIG
    kind: Literal["column"] = Field(description="Structure kind")
    section: Literal["square", "circular"] = Field("square", description="Drum cross-section")
    drums: int = Field(10, ge=1, le=200, description="Number of drums [-]")
    height_m: float = Field(10.0, gt=0, le=1000, description="Total height [m]")
    base_width_m: float = Field(1.65, gt=0, le=100, description="Side or diameter at the base [m]")
    top_width_m: float = Field(1.28, gt=0, le=100, description="Side or diameter at the top [m]")
    sides: int = Field(32, ge=3, le=256, description="Polygon sides of a circular drum [-]")
    density_kg_m3: float = Field(2700.0, gt=0, le=25000, description="Density [kg/m^3] (marble)")
    friction: float = Field(0.7, ge=0, le=10, description="Coulomb friction coefficient mu [-]")


class BlastSpec(BaseModel):
    """The prototype's charge, where it stands and how its load is modelled."""

    model_config = _CONFIG
    charge_kg: Pos = Field(description="TNT-equivalent charge W [kg]")
    standoff_m: Pos = Field(description="Stand-off R from the front face [m]")
    model: str = Field("masi2021", description="Blast model (the paper's Appendix A fits by default)")
    load: str = Field("A", description="Load method of the 3D engine (paper Methods A, B, C)")
    pulse: Literal[PULSE_SHAPES] = Field("friedlander", description="Pulse shape")
    incidence: str = Field("ufc", description="Angle-of-incidence model (Methods B, C)")
    extrapolate: bool = Field(False, description="Evaluate the blast fits outside their ranges (warns)")

    @field_validator("model")
    @classmethod
    def _model(cls, v: str) -> str:
        return _check_name(v, _registry_names("blastscale.blast.parameters", "BLAST_MODELS",
                                              ("kingery-bulmash", "masi2021")))

    @field_validator("load")
    @classmethod
    def _load(cls, v: str) -> str:
        return _check_name(v, _registry_names("blastscale.sim3d.loads", "LOAD_METHODS", ("A", "B", "C")))

    @field_validator("incidence")
    @classmethod
    def _incidence(cls, v: str) -> str:
        return _check_name(v, _registry_names("blastscale.blast.incidence", "INCIDENCE_MODELS",
                                              ("ufc", "closed-form")))


class ScaleSpec(BaseModel):
    """The model's scales: lambda, the density ratio (or the model's material), varsigma."""

    model_config = _CONFIG
    length: Annotated[float, at.Gt(0), at.Le(1000)] = Field(
        description="Geometric scale lambda = l_model / l_prototype [-] (a number or a fraction \"1/200\")")
    density_ratio: Optional[float] = Field(None, gt=0, le=100,
                                           description="gamma = rho_model / rho_prototype [-] (default 1)")
    model_material: Optional[str] = Field(None, description="Model material from the density library")
    gravity_ratio: float = Field(1.0, gt=0, le=1000, description="varsigma = g_model / g_prototype [-]")
    law: Literal["general", "hopkinson-cranz"] = Field("general", description="Scaling law")

    @field_validator("length", mode="before")
    @classmethod
    def _fraction(cls, v: Any) -> Any:
        if isinstance(v, str):
            try:
                return parse_ratio(v, "length")
            except BlastscaleInputError as exc:
                raise ValueError(f"= {v!r} is not a ratio: give a number such as 0.005 or a fraction such as "
                                 "\"1/200\"") from exc
        return v

    @field_validator("model_material")
    @classmethod
    def _material(cls, v: Optional[str]) -> Optional[str]:
        return None if v is None else _check_name(v, tuple(MATERIALS))

    @model_validator(mode="after")
    def _one_density(self) -> "ScaleSpec":
        return _at_most_one(self, "density_ratio", "model_material")


class ContactSpec(BaseModel):
    """3D contact settings of the prototype (the model's are scaled from them); each key left
    out takes the engine's default for the structure (docs/sim3d.md)."""

    model_config = _CONFIG
    time_constant_s: Optional[float] = Field(None, gt=0, le=10, description="Normal contact time constant [s]")
    damping_ratio: Optional[float] = Field(None, gt=0, le=100, description="Normal contact damping ratio [-]")
    friction_time_constant_s: Optional[float] = Field(None, gt=0, le=10,
                                                      description="Friction reference time constant [s]")
    impedance_min: Optional[float] = Field(None, gt=0, lt=1, description="solimp dmin [-]")
    impedance_max: Optional[float] = Field(None, gt=0, lt=1, description="solimp dmax [-]")
    impedance_width_m: Optional[float] = Field(None, gt=0, le=10, description="solimp width [m]")
    cone: Optional[Literal["elliptic", "pyramidal"]] = Field(None, description="Friction cone")
    impratio: Optional[float] = Field(None, gt=0, le=1e4, description="Friction/normal impedance ratio [-]")
    solver: Optional[Literal["Newton", "CG", "PGS"]] = Field(None, description="Constraint solver")
    iterations: Optional[int] = Field(None, ge=1, le=10000, description="Solver iterations [-]")
    tolerance: Optional[float] = Field(None, gt=0, le=1, description="Solver tolerance [-]")
    noslip_iterations: Optional[int] = Field(None, ge=0, le=10000, description="No-slip iterations [-]")
    jacobian: Optional[Literal["dense", "sparse", "auto"]] = Field(
        None, description="Constraint Jacobian layout (dense by default; sparse is 2.5-3.4x faster on columns)")


class SimulationSpec(BaseModel):
    """Which engines run, for how long, and their numerical settings."""

    model_config = _CONFIG
    engine: Literal["planar", "3d", "both"] = Field("both", description="Planar rocking, 3D rigid bodies or both")
    duration_s: float = Field(5.0, gt=0, le=1e5, description="Prototype time simulated after the shock arrival [s]")
    timestep_s: Optional[float] = Field(None, gt=0, le=0.1,
                                        description="Prototype 3D time step [s] (default from the structure)")
    record_every: int = Field(5, ge=1, le=100000, description="Keep one 3D state every N steps [-]")
    samples: int = Field(2001, ge=2, le=10_000_000, description="Planar sampling times over the duration [-]")
    gravity_m_s2: float = Field(9.81, gt=0, le=1000, description="Prototype gravity g [m/s^2]")
    restitution: Optional[float] = Field(None, ge=0, le=1,
                                         description="Planar restitution e [-] (default Housner's)")
    critical_charge: bool = Field(True, description="Also search the prototype's critical charge (planar)")
    ensemble_members: int = Field(0, ge=0, le=64, description="Members per system of a 3D ensemble under slightly "
                                  "perturbed loads, for chaotic structures (circular columns); 0: none [-]")
    ensemble_perturbation: float = Field(1e-6, gt=0, le=0.1, description="Largest relative load change of an "
                                         "ensemble member [-]")
    contact: ContactSpec = Field(default_factory=ContactSpec, description="3D contact settings")

    @field_validator("ensemble_members")
    @classmethod
    def _members(cls, v: int) -> int:
        if v == 1:
            raise ValueError("= 1 is out of range: valid values are 0 (no ensemble) or 2 to 64 members")
        return v


Structure = Annotated[Union[BlockSpec, ColumnSpec], Field(discriminator="kind")]
_KINDS = {"block": BlockSpec, "column": ColumnSpec}

#: Keys of which at most one may be given: setting one through ``with_values`` clears the other.
_EXCLUSIVE = {
    "structure.alpha_deg": "structure.width_m",
    "structure.width_m": "structure.alpha_deg",
    "scale.density_ratio": "scale.model_material",
    "scale.model_material": "scale.density_ratio",
}


class Scenario(BaseModel):
    """One blast experiment: prototype structure, charge, model scales, simulation settings.

    Build it from a TOML file (:func:`load_scenario`), from a dict (:meth:`from_dict`) or take
    :meth:`default`; derive variants with :meth:`with_values`. Every value is SI or a
    dimensionless ratio; the unit is in each key's name.
    """

    model_config = _CONFIG
    title: str = Field("", description="A one-line description")
    structure: Structure
    blast: BlastSpec
    scale: ScaleSpec
    simulation: SimulationSpec = Field(default_factory=SimulationSpec)

    # -- construction ----------------------------------------------------------------
    @classmethod
    def from_dict(cls, data: Mapping[str, Any], source: str = "scenario") -> "Scenario":
        """Validate a nested dict (as read from TOML); errors become one
        :class:`BlastscaleInputError` line prefixed with ``source``."""
        if not isinstance(data, Mapping):
            raise BlastscaleInputError(f"{source}: a scenario must be a table of keys, got {type(data).__name__}")
        try:
            return cls.model_validate(dict(data))
        except ValidationError as exc:
            raise BlastscaleInputError(f"{source}: {_one_line(exc)}") from None

    @classmethod
    def default(cls) -> "Scenario":
        """The built-in default: the paper's slender 10 m block (alpha = 15 deg, 2000 kg/m^3),
        50 kg TNT at 2 m, lambda = 1/200, same material, the paper's blast fits (masi2021),
        friction 0.7 (tan 35 deg), 5 s, planar and 3D."""
        return cls.from_dict({
            "title": "The paper's slender block: 50 kg TNT at 2 m, lambda = 1/200 (model 2)",
            "structure": {"kind": "block", "height_m": 10.0, "alpha_deg": 15.0, "depth_m": 1.0,
                          "density_kg_m3": 2000.0, "friction": 0.7},
            "blast": {"charge_kg": 50.0, "standoff_m": 2.0, "model": "masi2021"},
            "scale": {"length": 1.0 / 200.0, "density_ratio": 1.0},
        }, source="default scenario")

    # -- variants ----------------------------------------------------------------------
    @classmethod
    def field_paths(cls) -> list[str]:
        """Dotted paths of every scalar field (``"blast.charge_kg"``, ``"simulation.contact.cone"``);
        the structure's are the union over the structure kinds."""
        out: list[str] = []

        def walk(model: type[BaseModel], prefix: str) -> None:
            for name, info in model.model_fields.items():
                sub = _submodels(info.annotation)
                if sub:
                    for m in sub:
                        walk(m, f"{prefix}{name}.")
                elif f"{prefix}{name}" not in out:
                    out.append(f"{prefix}{name}")

        walk(cls, "")
        return out

    def resolve_key(self, key: str) -> str:
        """The full dotted path of ``key``: itself when it is one, else the unique path ending in
        ``.key`` (``"friction"`` -> ``"structure.friction"``)."""
        paths = self._paths()
        if key in paths:
            return key
        hits = [p for p in paths if p.endswith("." + key)]
        if len(hits) == 1:
            return hits[0]
        if not hits:
            raise BlastscaleInputError(
                f"key = {key!r} is not a scenario field of a {self.structure.kind}: valid keys are "
                f"{', '.join(paths)}")
        raise BlastscaleInputError(f"key = {key!r} is ambiguous: it may be {', '.join(hits)} (give the full path)")

    def _paths(self) -> list[str]:
        """The field paths of this scenario (the structure's of its own kind)."""
        kind = self.structure.kind
        others = [f"structure.{n}" for k, m in _KINDS.items() if k != kind for n in m.model_fields]
        mine = {f"structure.{n}" for n in _KINDS[kind].model_fields}
        return [p for p in self.field_paths() if p in mine or p not in others]

    def with_values(self, values: Mapping[str, Any]) -> "Scenario":
        """A validated copy with some values replaced.

        Parameters
        ----------
        values : mapping
            Dotted path (``"blast.charge_kg"``) or unambiguous bare key (``"friction"``) ->
            new value, in the key's unit. Setting ``structure.alpha_deg`` clears
            ``structure.width_m`` (and vice versa), likewise ``scale.density_ratio`` and
            ``scale.model_material``. A new ``structure.kind`` starts that kind's defaults
            (plus the structure keys given in the same call).

        Returns
        -------
        Scenario

        Raises
        ------
        BlastscaleInputError
            An unknown or ambiguous key, or a value out of range (one line).
        """
        data = self.model_dump(exclude_none=True)
        resolved: dict[str, Any] = {}
        new_kind = values.get("structure.kind", values.get("kind"))
        if new_kind is not None and new_kind != self.structure.kind:
            data["structure"] = {"kind": new_kind}
            resolved["structure.kind"] = new_kind
        for key, value in values.items():
            if key in ("kind", "structure.kind"):
                continue
            path = f"structure.{key.split('.')[-1]}" if new_kind is not None and new_kind != self.structure.kind \
                and (key.startswith("structure.") or key in _KINDS.get(str(new_kind), BlockSpec).model_fields) \
                else self.resolve_key(key)
            resolved[path] = value
        for path, value in resolved.items():
            node = data
            *parents, leaf = path.split(".")
            for p in parents:
                node = node.setdefault(p, {})
            if hasattr(value, "item") and callable(value.item):  # numpy scalars from sweeps
                value = value.item()
            node[leaf] = value
            other = _EXCLUSIVE.get(path)
            if other and other not in resolved:
                *op, ol = other.split(".")
                onode = data
                for p in op:
                    onode = onode.get(p, {})
                onode.pop(ol, None)
        return type(self).from_dict(data, source="with_values")

    # -- derived values ----------------------------------------------------------------
    @property
    def density_ratio(self) -> float | None:
        """gamma [-]: from ``model_material`` (library density / prototype density), else
        ``scale.density_ratio``, else 1; None for Hopkinson-Cranz without one (the law imposes it)."""
        sc = self.scale
        if sc.model_material is not None:
            return MATERIALS[sc.model_material].density / self.structure.density_kg_m3
        if sc.density_ratio is not None:
            return sc.density_ratio
        return None if sc.law == "hopkinson-cranz" else 1.0

    def to_dict(self) -> dict:
        """Plain JSON-able dict (None for keys left to the engine's defaults)."""
        return self.model_dump(mode="json")

    def to_toml(self) -> str:
        """The scenario as TOML text (keys left to defaults omitted); ``load_scenario`` reads it back."""
        return _to_toml(self.model_dump(mode="json", exclude_none=True))


def _submodels(annotation: Any) -> list[type[BaseModel]]:
    """The pydantic models inside an annotation (a model, Optional/Union/Annotated of models)."""
    import typing

    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return [annotation]
    out = []
    for arg in typing.get_args(annotation):
        out.extend(_submodels(arg))
    return out


def load_scenario(path: "str | Path") -> Scenario:
    """Read and validate a scenario TOML file.

    Parameters
    ----------
    path : str or Path
        The ``.toml`` file.

    Returns
    -------
    Scenario

    Raises
    ------
    BlastscaleInputError
        Unreadable file, TOML syntax error (with line and column), or an invalid value (one
        line naming the field path, the value and the valid range).
    """
    p = Path(path)
    try:
        text = p.read_bytes().decode("utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
        raise BlastscaleInputError(f"scenario = {str(p)!r} cannot be read: {reason}") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise BlastscaleInputError(f"{p.name}: TOML syntax error: {exc}") from None
    return Scenario.from_dict(data, source=p.name)


# -- one-line errors -----------------------------------------------------------------------
_TYPE_WORDS = {"float": "a number", "int": "a whole number", "bool": "true or false", "str": "a string",
               "model": "a table", "dict": "a table"}


def _model_at(loc: tuple) -> tuple[type[BaseModel] | None, Any]:
    """The model owning the last element of ``loc`` (union tags followed) and that field's info."""
    model: Any = Scenario
    info = None
    for i, part in enumerate(loc):
        if model is None:
            return None, None
        if isinstance(part, str) and part in _KINDS and info is not None and model is _UNION:
            model = _KINDS[part]
            continue
        fields = getattr(model, "model_fields", {})
        if part not in fields:
            return (model if i == len(loc) - 1 else None), None
        info = fields[part]
        if i == len(loc) - 1:
            return model, info
        subs = _submodels(info.annotation)
        model = subs[0] if len(subs) == 1 else (_UNION if subs else None)
    return model, info


_UNION = object()


def _constraint_text(info: Any) -> str:
    """``"> 0 m"``, ``"[0, 10]"``, ``"(0, 90) deg"`` from a field's constraints and unit."""
    if info is None:
        return ""
    lo = hi = None
    lo_open = hi_open = False
    for m in list(info.metadata) + list(getattr(info.annotation, "__metadata__", ())):
        if isinstance(m, at.Gt):
            lo, lo_open = m.gt, True
        elif isinstance(m, at.Ge):
            lo, lo_open = m.ge, False
        elif isinstance(m, at.Lt):
            hi, hi_open = m.lt, True
        elif isinstance(m, at.Le):
            hi, hi_open = m.le, False
    unit = ""
    um = re.search(r"\[([^\]]+)\]", info.description or "")
    if um and um.group(1) != "-":
        unit = " " + um.group(1)
    if lo is None and hi is None:
        return ""
    if hi is None:
        return f"{'>' if lo_open else '>='} {lo:g}{unit}"
    if lo is None:
        return f"{'<' if hi_open else '<='} {hi:g}{unit}"
    return f"{'(' if lo_open else '['}{lo:g}, {hi:g}{')' if hi_open else ']'}{unit}"


def _one_line(exc: ValidationError) -> str:
    """The first pydantic error as one line: field path, value, valid range."""
    err = exc.errors(include_url=False)[0]
    loc = tuple(err["loc"])
    # drop the discriminator tag of the structure union from the path
    shown = tuple(p for i, p in enumerate(loc) if not (i == 1 and loc[0] == "structure" and p in _KINDS))
    path = ".".join(str(p) for p in shown) or "scenario"
    kind, value, ctx = err["type"], err.get("input"), err.get("ctx") or {}
    model, info = _model_at(loc)
    rng = _constraint_text(info)
    rng_txt = f": valid range is {rng}" if rng else ""
    vtxt = _show(value)
    if kind == "missing":
        what = f" ({info.description})" if info is not None and info.description else ""
        return f"{path} is missing{what}: give it in [{'.'.join(str(p) for p in shown[:-1]) or 'top level'}]"
    if kind == "extra_forbidden":
        table = ".".join(str(p) for p in shown[:-1])
        valid = ", ".join(model.model_fields) if model is not None and hasattr(model, "model_fields") else "?"
        return f"{path} = {vtxt} is not a known key: valid keys{' of [' + table + ']' if table else ''} are {valid}"
    if kind == "union_tag_invalid":
        return f"{path}.kind = {_show(ctx.get('tag'))} is not known: valid values are {', '.join(_KINDS)}"
    if kind == "union_tag_not_found":
        return f"{path}.kind is missing: give kind = \"block\" or \"column\" in [{path}]"
    if kind == "literal_error":
        expected = str(ctx.get("expected", "")).replace("'", "").replace(" or ", ", ")
        return f"{path} = {vtxt} is not known: valid values are {expected}"
    if kind == "finite_number":
        return f"{path} = {vtxt} is not a finite number{rng_txt}"
    if kind in ("greater_than", "greater_than_equal", "less_than", "less_than_equal"):
        return f"{path} = {vtxt} is out of range{rng_txt}"
    if kind.endswith("_type") or kind.endswith("_parsing") or kind == "model_attributes_type":
        want = _TYPE_WORDS.get(kind.split("_")[0], kind.split("_")[0])
        return f"{path} = {vtxt} has the wrong type: expected {want}{rng_txt.replace(': valid', ', valid')}"
    if kind == "value_error":
        msg = str(ctx.get("error", err["msg"]))
        if msg.startswith("="):
            return f"{path} {msg}"
        return f"{path}: {msg}" if path != "scenario" else msg
    return f"{path} = {vtxt}: {err['msg']}"


def _show(value: Any) -> str:
    if isinstance(value, float):
        return "nan" if math.isnan(value) else f"{value:g}"
    if isinstance(value, dict):
        return "a table"
    return repr(value)


# -- TOML writer (the subset scenarios use) ---------------------------------------------------
def _toml_value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    s = str(v).replace("\\", "\\\\").replace('"', '\\"')
    return f'"{s}"'


def _to_toml(data: dict, prefix: str = "") -> str:
    lines = [f"{k} = {_toml_value(v)}" for k, v in data.items() if not isinstance(v, dict)]
    for k, v in data.items():
        if isinstance(v, dict):
            sub = _to_toml(v, f"{prefix}{k}.")
            lines.append(f"\n[{prefix}{k}]\n{sub}" if sub else f"\n[{prefix}{k}]")
    return "\n".join(lines).strip("\n") + ("\n" if not prefix else "")
