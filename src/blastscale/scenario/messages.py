"""One-line error messages from pydantic's validation errors: the field path, the value and the
valid range (read from the field's constraints and the unit in its description)."""

from __future__ import annotations

import math
import re
import typing
from typing import Any

import annotated_types as at
from pydantic import BaseModel, ValidationError

__all__ = ["one_line", "value_in_message", "submodels"]


def submodels(annotation: Any) -> list[type[BaseModel]]:
    """The pydantic models inside an annotation (a model, Optional/Union/Annotated of models)."""
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return [annotation]
    out = []
    for arg in typing.get_args(annotation):
        out.extend(submodels(arg))
    return out


_TYPE_WORDS = {
    "float": "a number",
    "int": "a whole number",
    "bool": "true or false",
    "str": "a string",
    "model": "a table",
    "dict": "a table",
}


def _model_at(loc: tuple, root: type[BaseModel], kinds: dict) -> tuple[type[BaseModel] | None, Any]:
    """The model owning the last element of ``loc`` (union tags followed) and that field's info."""
    model: Any = root
    info = None
    for i, part in enumerate(loc):
        if model is None:
            return None, None
        if isinstance(part, str) and part in kinds and info is not None and model is _UNION:
            model = kinds[part]
            continue
        if (
            info is not None
            and typing.get_origin(info.annotation) is dict
            and i > 0
            and loc[i - 1] != part
            and part not in getattr(model, "model_fields", {})
            and isinstance(part, str)
            and model is not root
        ):
            info = None  # a key of a table of tables ([lab.explosives.NAME]): its model follows
            continue
        fields = getattr(model, "model_fields", {})
        if part not in fields:  # a deprecated key (a field's validation alias): its field
            part = next((n for n, f in fields.items() if part in getattr(f.validation_alias, "choices", ())), part)
        if part not in fields:
            return (model if i == len(loc) - 1 else None), None
        info = fields[part]
        if i == len(loc) - 1:
            return model, info
        subs = submodels(info.annotation)
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


def one_line(exc: ValidationError, root: type[BaseModel], kinds: dict, names: dict | None = None) -> str:
    """The first pydantic error of ``root`` as one line: field path, value, valid range (``kinds``:
    structure kind -> its table's model, to follow the structure union; ``names``: field path ->
    the name the user gave it, e.g. a command-line flag)."""
    err = exc.errors(include_url=False)[0]
    loc = tuple(err["loc"])
    # drop the discriminator tag of the structure union from the path
    shown = tuple(p for i, p in enumerate(loc) if not (i == 1 and loc[0] == "structure" and p in kinds))
    path = ".".join(str(p) for p in shown) or "scenario"
    path = (names or {}).get(path, path)
    kind, value, ctx = err["type"], err.get("input"), err.get("ctx") or {}
    model, info = _model_at(loc, root, kinds)
    rng = _constraint_text(info)
    rng_txt = f": valid range is {rng}" if rng else ""
    vtxt = value_in_message(value)
    if kind == "missing":
        what = f" ({info.description})" if info is not None and info.description else ""
        return f"{path} is missing{what}: give it in [{'.'.join(str(p) for p in shown[:-1]) or 'top level'}]"
    if kind == "extra_forbidden":
        table = ".".join(str(p) for p in shown[:-1])
        valid = ", ".join(model.model_fields) if model is not None and hasattr(model, "model_fields") else "?"
        return f"{path} = {vtxt} is not a known key: valid keys{' of [' + table + ']' if table else ''} are {valid}"
    if kind == "union_tag_invalid":
        return f"{path}.kind = {value_in_message(ctx.get('tag'))} is not known: valid values are {', '.join(kinds)}"
    if kind == "union_tag_not_found":
        return f"{path}.kind is missing: give kind = one of {', '.join(repr(k) for k in kinds)} in [{path}]"
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


def value_in_message(value: Any) -> str:
    """A value as a validation message quotes it: a string in quotes (its repr), a float with ``g``
    (``nan``), a table as "a table" (a value as the user typed it, unquoted:
    :func:`blastscale.cli.flags.value_as_typed`)."""
    if isinstance(value, float):
        return "nan" if math.isnan(value) else f"{value:g}"
    if isinstance(value, dict):
        return "a table"
    return repr(value)
