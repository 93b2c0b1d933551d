"""Scenario files: TOML text in (:func:`load_scenario`) and out (:func:`to_toml`, the subset of TOML
that scenarios use; ``load_scenario`` reads it back)."""

from __future__ import annotations

import tomllib
from pathlib import Path
from .._validate import BlastscaleInputError
from .scenario import Scenario
from .text import to_toml

__all__ = ["load_scenario", "to_toml"]


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
