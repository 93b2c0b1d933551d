"""Scenario files: TOML text in (:func:`load_scenario`) and out (:func:`to_toml`, the subset of TOML
that scenarios use; ``load_scenario`` reads it back)."""

from __future__ import annotations

import tomllib
from pathlib import Path

from .._validate import BlastscaleInputError
from .library import library_names, library_source, library_text
from .scenario import Scenario
from .text import to_toml

__all__ = ["load_scenario", "to_toml"]


def load_scenario(path: "str | Path") -> Scenario:
    """Read and validate a scenario TOML file, or a scenario shipped with blastscale by name.

    Parameters
    ----------
    path : str or Path
        The ``.toml`` file; when no such file exists, the name of a shipped scenario
        (:func:`~.library.library_names`, e.g. ``"paper_column_square_250kg"``).

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
    shipped = library_names()
    stem = p.name[:-5] if p.name.endswith(".toml") else p.name
    if not p.exists() and str(path) in (stem, p.name) and stem in shipped:
        return _from_text(library_text(stem), library_source(stem))
    try:
        text = p.read_bytes().decode("utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
        hint = f" (or give a shipped scenario: {', '.join(shipped)})" if not p.exists() else ""
        raise BlastscaleInputError(f"scenario = {str(p)!r} cannot be read: {reason}{hint}") from None
    return _from_text(text, p.name, p.resolve().parent)


def _from_text(text: str, source: str, folder: "Path | None" = None) -> Scenario:
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise BlastscaleInputError(f"{source}: TOML syntax error: {exc}") from None
    st = data.get("structure")
    if (
        folder is not None
        and isinstance(st, dict)
        and isinstance(st.get("file"), str)
        and not Path(st["file"]).is_absolute()
    ):  # a block-model file is relative to its scenario file
        data["structure"] = {**st, "file": str(folder / st["file"])}
    return Scenario.from_dict(data, source=source)
