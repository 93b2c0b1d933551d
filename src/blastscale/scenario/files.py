"""Scenario files: TOML text in (:func:`load_scenario`) and out (:func:`to_toml`, the subset of TOML
that scenarios use; ``load_scenario`` reads it back)."""

from __future__ import annotations

import tomllib
from pathlib import Path

from .._validate import BlastscaleInputError
from .library import library_names, library_source, library_text
from .paths import resolve_against
from .scenario import Scenario

__all__ = ["load_scenario"]


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
    if not _exists(p) and str(path) in (stem, p.name) and stem in shipped:
        return _from_text(library_text(stem), library_source(stem))
    try:
        if p.exists() and not p.is_file():  # checked before opening: a FIFO's open waits for a writer
            raise BlastscaleInputError(
                f"scenario = {str(p)!r} cannot be read: not a file (a folder, a FIFO or a device); give a .toml "
                "scenario file"
            )
        with open(p, "rb") as f:
            raw = f.read(MAX_SCENARIO_BYTES + 1)
        if len(raw) > MAX_SCENARIO_BYTES:
            raise BlastscaleInputError(
                f"scenario = {str(p)!r} is larger than {MAX_SCENARIO_BYTES // 10**6} MB: not a scenario file"
            )
        text = raw.decode("utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
        if isinstance(exc, UnicodeDecodeError):
            reason = f"not UTF-8 text (byte {exc.start}: {exc.object[exc.start : exc.start + 1]!r})"
        hint = f" (or give a shipped scenario: {', '.join(shipped)})" if not _exists(p) else ""
        raise BlastscaleInputError(f"scenario = {str(p)!r} cannot be read: {reason}{hint}") from None
    return _from_text(text, p.name, p.resolve().parent)


#: The largest scenario file read (a scenario is a few kB; a device or a mistaken file is not read whole).
MAX_SCENARIO_BYTES = 10 * 10**6


def _exists(p: Path) -> bool:
    try:
        return p.exists()
    except OSError:  # a name too long: not there (reading it says why)
        return False


def _nesting(text: str) -> int:
    """The deepest run of opening brackets and braces outside strings and comments, roughly (a bound)."""
    depth = most = 0
    for ch in text:
        if ch in "[{":
            depth += 1
            most = max(most, depth)
        elif ch in "]}":
            depth = max(depth - 1, 0)
    return most


def _from_text(text: str, source: str, folder: "Path | None" = None) -> Scenario:
    text = text.removeprefix("\ufeff")  # a UTF-8 byte-order mark (Windows Notepad) is no part of the TOML
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise BlastscaleInputError(f"{source}: TOML syntax error: {exc}") from None
    except RecursionError:
        raise BlastscaleInputError(
            f"{source}: arrays or tables nested {_nesting(text)} deep: too deep for the "
            "TOML reader (a scenario nests 3 deep)"
        ) from None
    written = resolve_against(data, folder) if folder is not None else {}  # relative to the scenario file
    sc = Scenario.from_dict(data, source=source)
    sc._as_written.update(written)  # so that a scenario written again names them as its file did
    return sc
