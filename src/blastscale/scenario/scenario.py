"""The whole scenario: one blast experiment (structure, blast, scales, simulation), its built-in
default, its variants (:meth:`Scenario.with_values`) and its derived values."""

from __future__ import annotations

from typing import Any, Mapping, Optional

from pydantic import BaseModel, Field, PrivateAttr, ValidationError, field_validator

from .._validate import BlastscaleInputError
from ..constants import DEFAULT_FRICTION
from ..structures.materials import MATERIALS
from .fields import SPEC_CONFIG
from .fired import FiredSpec
from .lab import LabSpec
from .messages import one_line, submodels
from .paths import PATH_KEYS, path_in
from .specs import LEGACY_SCENARIO_KEYS, BlastSpec, DamageSpec, ScaleSpec, SimulationSpec, VerdictSpec
from .structure_specs import KINDS, BlockSpec, Structure
from .text import to_toml

__all__ = ["Scenario"]

#: Keys of which at most one may be given: setting one through ``with_values`` clears the other.
EXCLUSIVE_KEYS = {
    "structure.alpha_deg": "structure.width_m",
    "structure.width_m": "structure.alpha_deg",
    "scale.density_ratio": "scale.specimen_material",
    "scale.specimen_material": "scale.density_ratio",
}

#: The deprecated bare keys (``model``, ``pulse``, ``model_material``) -> the new ones.
_LEGACY_BARE = {old.split(".")[-1]: new.split(".")[-1] for old, new in LEGACY_SCENARIO_KEYS.items()}


def current_key(key: str) -> str:
    """``key`` with a deprecated scenario name replaced by its new one (:data:`LEGACY_SCENARIO_KEYS`:
    ``"blast.model"`` -> ``"blast.blast_model"``, ``"pulse"`` -> ``"pulse_shape"``); others unchanged."""
    if key in LEGACY_SCENARIO_KEYS:
        return LEGACY_SCENARIO_KEYS[key]
    return _LEGACY_BARE.get(key, key)


class Scenario(BaseModel):
    """One blast experiment: prototype structure, charge, model scales, simulation settings.

    Build it from a TOML file (:func:`load_scenario`), from a dict (:meth:`from_dict`) or take
    :meth:`default`; derive variants with :meth:`with_values`. Every value is SI or a
    dimensionless ratio; the unit is in each key's name.
    """

    model_config = SPEC_CONFIG
    title: str = Field(
        "",
        description="A one-line description (tabs and line breaks allowed; no other control "
        "characters: a NUL cannot be stored in the result files)",
    )
    structure: Structure
    blast: BlastSpec = Field(
        default_factory=BlastSpec,
        description="The charge; absent (or charge_kg = 0): the structure under gravity alone",
    )
    scale: Optional[ScaleSpec] = Field(
        None, description="The specimen's scales; absent: the prototype alone (no design, no comparison)"
    )
    simulation: SimulationSpec = Field(default_factory=SimulationSpec)
    verdict: VerdictSpec = Field(
        default_factory=VerdictSpec,
        description="The similarity criterion's tolerances (docs/verdict.md); absent: the defaults",
    )
    damage: DamageSpec = Field(
        default_factory=DamageSpec,
        description="The damage states' limits (intact, damaged slight / moderate / severe, collapse; "
        "docs/sweeps.md); absent: the defaults",
    )
    lab: Optional[LabSpec] = Field(
        None,
        description="What the laboratory can fire, build and measure: a test card "
        "in the report, and the constraints of `blastscale plan` (docs/planning.md)",
    )
    fired: Optional[FiredSpec] = Field(
        None,
        description="What the lab recorded after the shot: gauge traces, "
        "marker tracks, the charge as weighed, the stand-off as measured (docs/fired.md)",
    )

    #: The file paths as the scenario's file wrote them: "table.key" -> (as written, as resolved against its
    #: folder) (:func:`~.paths.resolve_against`); empty for a scenario made in Python.
    _as_written: dict = PrivateAttr(default_factory=dict)

    @field_validator("title")
    @classmethod
    def _printable(cls, value: str) -> str:
        bad = next((i for i, ch in enumerate(value) if (ord(ch) < 32 and ch not in "\t\n\r") or ord(ch) == 127), None)
        if bad is not None:
            raise ValueError(
                f"= {value[:40]!r} holds the control character U+{ord(value[bad]):04X} at position "
                f"{bad + 1}: a title is text (tabs and line breaks allowed)"
            )
        return value

    # -- construction ----------------------------------------------------------------
    @classmethod
    def from_dict(
        cls, data: Mapping[str, Any], source: Optional[str] = "scenario", names: Optional[Mapping[str, str]] = None
    ) -> "Scenario":
        """Validate a nested dict (as read from TOML); errors become one
        :class:`BlastscaleInputError` line prefixed with ``source`` (none when None), naming each
        field by its dotted path or by ``names[path]`` (e.g. the command-line flag that set it)."""
        prefix = "" if source is None else f"{source}: "
        if not isinstance(data, Mapping):
            raise BlastscaleInputError(f"{prefix}a scenario must be a table of keys, got {type(data).__name__}")
        try:
            return cls.model_validate(dict(data))
        except ValidationError as exc:
            raise BlastscaleInputError(f"{prefix}{one_line(exc, cls, KINDS, dict(names or {}))}") from None

    @classmethod
    def default(cls) -> "Scenario":
        """The built-in default: the paper's slender 10 m block (alpha = 15 deg, 2000 kg/m^3),
        50 kg TNT at 2 m, lambda = 1/200, same material, the paper's blast fits (masi2021),
        friction 0.7 (tan 35 deg), 5 s, planar and 3D."""
        return cls.from_dict(
            {
                "title": "The paper's slender block: 50 kg TNT at 2 m, lambda = 1/200 (model 2)",
                "structure": {
                    "kind": "block",
                    "height_m": 10.0,
                    "alpha_deg": 15.0,
                    "depth_m": 1.0,
                    "density_kg_m3": 2000.0,
                    "friction": DEFAULT_FRICTION,
                },
                "blast": {"charge_kg": 50.0, "standoff_m": 2.0, "blast_model": "masi2021"},
                "scale": {"length": 1.0 / 200.0, "density_ratio": 1.0},
            },
            source="default scenario",
        )

    # -- variants ----------------------------------------------------------------------
    @classmethod
    def field_paths(cls) -> list[str]:
        """Dotted paths of every scalar field (``"blast.charge_kg"``, ``"simulation.contact.cone"``);
        the structure's are the union over the structure kinds."""
        out: list[str] = []

        def walk(model: type[BaseModel], prefix: str) -> None:
            for name, info in model.model_fields.items():
                sub = submodels(info.annotation)
                if sub:
                    for m in sub:
                        walk(m, f"{prefix}{name}.")
                elif f"{prefix}{name}" not in out:
                    out.append(f"{prefix}{name}")

        walk(cls, "")
        return out

    def resolve_key(self, key: str) -> str:
        """The full dotted path of ``key``: itself when it is one, else the unique path ending in
        ``.key`` (``"friction"`` -> ``"structure.friction"``); a deprecated name gives its new path
        (``"blast.model"``, ``"model"`` -> ``"blast.blast_model"``)."""
        key = current_key(key)
        paths = self._paths()
        if key in paths:
            return key
        hits = [p for p in paths if p.endswith("." + key)]
        full_only = ("lab.", "fired.")  # [lab] and [fired] keys by full path only
        if len(hits) > 1 and sum(not p.startswith(full_only) for p in hits) == 1:
            hits = [p for p in hits if not p.startswith(full_only)]
        if len(hits) == 1:
            return hits[0]
        if not hits:
            raise BlastscaleInputError(
                f"key = {key!r} is not a scenario field of a {self.structure.kind}: valid keys are {', '.join(paths)}"
            )
        raise BlastscaleInputError(f"key = {key!r} is ambiguous: it may be {', '.join(hits)} (give the full path)")

    def _paths(self) -> list[str]:
        """The field paths of this scenario (the structure's of its own kind)."""
        kind = self.structure.kind
        others = [f"structure.{n}" for k, m in KINDS.items() if k != kind for n in m.model_fields]
        mine = {f"structure.{n}" for n in KINDS[kind].model_fields}
        return [p for p in self.field_paths() if p in mine or p not in others]

    def with_values(self, values: Mapping[str, Any]) -> "Scenario":
        """A validated copy with some values replaced.

        Parameters
        ----------
        values : mapping
            Dotted path (``"blast.charge_kg"``) or unambiguous bare key (``"friction"``) ->
            new value, in the key's unit. Setting ``structure.alpha_deg`` clears
            ``structure.width_m`` (and vice versa), likewise ``scale.density_ratio`` and
            ``scale.specimen_material``. Deprecated names (``blast.model``, ``pulse``, ...) are
            accepted. A new ``structure.kind`` starts that kind's defaults
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
        values = {current_key(k): v for k, v in values.items()}
        new_kind = values.get("structure.kind", values.get("kind"))
        if new_kind is not None and new_kind != self.structure.kind:
            data["structure"] = {"kind": new_kind}
            resolved["structure.kind"] = new_kind
        for key, value in values.items():
            if key in ("kind", "structure.kind"):
                continue
            path = (
                f"structure.{key.split('.')[-1]}"
                if new_kind is not None
                and new_kind != self.structure.kind
                and (key.startswith("structure.") or key in KINDS.get(str(new_kind), BlockSpec).model_fields)
                else self.resolve_key(key)
            )
            resolved[path] = value
        for path, value in resolved.items():
            node = data
            *parents, leaf = path.split(".")
            for p in parents:
                node = node.setdefault(p, {})
            if hasattr(value, "item") and callable(value.item):  # numpy scalars from sweeps
                value = value.item()
            node[leaf] = value
            other = EXCLUSIVE_KEYS.get(path)
            if other and other not in resolved:
                *op, ol = other.split(".")
                onode = data
                for p in op:
                    onode = onode.get(p, {})
                onode.pop(ol, None)
        out = type(self).from_dict(data, source=None)
        out._as_written.update(
            {k: w for k, w in self._as_written.items() if out.file_path(k) == w[1]}
        )  # unchanged ones
        return out

    def file_path(self, key: str) -> Optional[str]:
        """The file path at ``"table.key"`` (:data:`~.paths.PATH_KEYS`), None when not given."""
        table, name = key.split(".")
        return getattr(getattr(self, table, None), name, None)

    # -- derived values ----------------------------------------------------------------
    @property
    def density_ratio(self) -> float | None:
        """gamma [-]: from ``specimen_material`` (library density / prototype density), else
        ``scale.density_ratio``, else 1; None for Hopkinson-Cranz without one (the law imposes it)
        and for a prototype-only scenario (no ``[scale]``)."""
        sc = self.scale
        if sc is None:
            return None
        if sc.specimen_material is not None:
            return MATERIALS[sc.specimen_material].density / self.structure.density_kg_m3
        if sc.density_ratio is not None:
            return sc.density_ratio
        return None if sc.law == "hopkinson-cranz" else 1.0

    @property
    def friction_ratio(self) -> float:
        """lambda_mu = mu_specimen / mu_prototype [-]: the library friction of ``scale.specimen_material``
        (its joint against itself, :mod:`blastscale.structures.materials`) over ``structure.friction``; 1
        without a named material (the prototype's own, or a density ratio alone) or without ``[scale]``."""
        sc = self.scale
        if sc is None or sc.specimen_material is None:
            return 1.0
        mu = MATERIALS[sc.specimen_material].friction
        if self.structure.friction <= 0.0:
            raise BlastscaleInputError(
                f"structure.friction = 0 with scale.specimen_material = {sc.specimen_material!r} (friction {mu:g}): "
                "a frictionless prototype has no friction ratio; give scale.density_ratio instead of the material"
            )
        return mu / self.structure.friction

    def to_dict(self) -> dict:
        """Plain JSON-able dict (None for keys left to the engine's defaults)."""
        return self.model_dump(mode="json")

    def to_toml(self, folder=None) -> str:
        """The scenario as TOML text (keys left to defaults omitted); ``load_scenario`` reads it back. With
        ``folder``, the text of a file written into that folder: the files it names (block model, source,
        records) named by the one rule of :func:`~.paths.path_in` (as the scenario's file wrote them, relative
        to ``folder`` where they were relative), so that the folder can be moved with its neighbours."""
        data = self.model_dump(mode="json", exclude_none=True)
        if folder is not None:
            for table, name in PATH_KEYS:
                path = self.file_path(f"{table}.{name}")
                if path is not None:
                    written, resolved = self._as_written.get(f"{table}.{name}", (None, None))
                    data[table][name] = path_in(folder, path, written if resolved == path else None)
        return to_toml(data)
