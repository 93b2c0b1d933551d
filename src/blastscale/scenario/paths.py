"""The files a scenario names, and the one rule by which a scenario written elsewhere names them.

A scenario names four kinds of file: a block model (``structure.file``), a calibrated source (``lab.source``) and
the lab's records (``fired.gauges``, ``fired.tracks``). In a scenario file each is relative to that file
(:func:`resolve_against`, called by :func:`~blastscale.scenario.files.load_scenario`); the scenario keeps the path
resolved and remembers how the file wrote it.

A scenario written again into a folder (``scenario.toml`` of ``run --out``, ``plan --out``, ``fired --out``:
:meth:`~blastscale.scenario.scenario.Scenario.to_toml` with ``folder``) names each file by :func:`path_in`:

* as its scenario file wrote it: a relative path stays relative, now to the folder (``os.path.relpath``), so that
  the folder moved with its neighbours still reads the same file; an absolute one stays as written;
* a path no file wrote (a scenario made in Python, or a value changed since): relative to the folder when the
  file lies under the folder's parent (under the folder or next to it), else absolute;
* where no relative path exists (another drive on Windows), absolute.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Optional

__all__ = ["PATH_KEYS", "path_in", "resolve_against"]

#: The scenario keys whose value is a file path, as (table, key).
PATH_KEYS = (("structure", "file"), ("lab", "source"), ("fired", "gauges"), ("fired", "tracks"))


def resolve_against(data: dict, folder: Path) -> dict[str, tuple[str, str]]:
    """Resolve the file paths of a scenario's tables ``data`` (as read from a file in ``folder``) against
    ``folder``, in place (a relative path becomes ``folder / path``; tables are copied, not mutated). Returns
    ``"table.key" -> (as written, as resolved)`` for every path given."""
    written = {}
    for table, key in PATH_KEYS:
        node = data.get(table)
        if not isinstance(node, dict) or not isinstance(node.get(key), str):
            continue
        value = node[key]
        resolved = value if Path(value).is_absolute() else str(folder / value)
        data[table] = {**node, key: resolved}
        written[f"{table}.{key}"] = (value, resolved)
    return written


def path_in(folder, path: str, written: Optional[str] = None) -> str:
    """How a scenario file written into ``folder`` names the file ``path`` (module docstring): ``written`` is
    how the scenario's own file wrote it (None: no file did)."""
    if written is not None and Path(written).is_absolute():
        return written
    target, here = Path(path).resolve(), Path(folder).resolve()
    if written is None and not target.is_relative_to(here.parent):
        return path if Path(path).is_absolute() else str(target)
    try:
        return Path(os.path.relpath(target, here)).as_posix()
    except ValueError:  # another drive
        return str(target)
