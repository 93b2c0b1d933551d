"""TOML text of a scenario (the subset of TOML that scenarios use; :func:`~.files.load_scenario`
reads it back). Text only: writing it to a file is the caller's business."""

from __future__ import annotations

from typing import Any

__all__ = ["to_toml"]


def _toml_value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    s = str(v).replace("\\", "\\\\").replace('"', '\\"')
    return f'"{s}"'


def to_toml(data: dict, prefix: str = "") -> str:
    """TOML text of a nested dict of plain values (tables for sub-dicts)."""
    lines = [f"{k} = {_toml_value(v)}" for k, v in data.items() if not isinstance(v, dict)]
    for k, v in data.items():
        if isinstance(v, dict):
            sub = to_toml(v, f"{prefix}{k}.")
            lines.append(f"\n[{prefix}{k}]\n{sub}" if sub else f"\n[{prefix}{k}]")
    return "\n".join(lines).strip("\n") + ("\n" if not prefix else "")
