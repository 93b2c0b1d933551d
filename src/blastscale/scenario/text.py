"""TOML text of a scenario, written by ``tomli-w`` (a maintained TOML 1.0 writer: every string is
escaped as TOML requires, so a title over two lines, with quotes, backslashes or brackets, reads
back as it was written); :func:`~.files.load_scenario` reads it back. Text only: writing it to a
file is the caller's business."""

from __future__ import annotations

import tomli_w

__all__ = ["to_toml"]


def to_toml(data: dict) -> str:
    """TOML text of a nested dict of plain values (tables for sub-dicts), ending in a newline.

    Examples
    --------
    >>> import tomllib
    >>> title = 'two\\nlines "quoted" \\\\ [bracket'
    >>> tomllib.loads(to_toml({"title": title, "blast": {"charge_kg": 2.5}}))["title"] == title
    True
    """
    return tomli_w.dumps(data)
