"""What ``blastscale reproduce`` will cost, stated before it starts, and which folders are its own.

:func:`expected_cost` adds, per item still to make, its wall time and the size of its folder as
measured on the 2-core development machine (:data:`MEASURED`, full and ``--quick`` runs; the
measurement is described in docs/report.md), and for an item not measured (a scenario added later)
the study's own estimate (:func:`blastscale.study.estimate_seconds`) plus the time to write its
figures and report.
"""

from __future__ import annotations

import json
from pathlib import Path

from ..scenario.files import load_scenario
from ..study.memory import estimate_seconds
from ..study.study import Study
from .reproduce import MARKER

__all__ = ["MEASURED", "SCRIPT_SECONDS", "expected_cost", "is_reproduce_folder"]

#: item -> (full run [s], full size [bytes], quick run [s], quick size [bytes]), measured (docs/report.md).
MEASURED: dict = {}

#: Writing a scenario item's figures, report and histories [s], and its size when not measured [bytes].
_WRITE_SECONDS, _SCENARIO_BYTES, _OTHER = 3.0, 2e6, (2.0, 2e5)

#: Full runs of the gallery's scripts that take longer than :data:`_OTHER` [s of wall time], measured on the 2-core
#: development machine (docs/report.md: the column script 155-162 s of the full reproduce's 4 min 16 s); the others
#: take seconds.
SCRIPT_SECONDS = {"example-paper-columns-method-a": 158.0}


def _estimate(item, quick: bool) -> tuple:
    if not quick and item.name in SCRIPT_SECONDS:
        return SCRIPT_SECONDS[item.name], _OTHER[1]
    if item.kind != "scenario" or not isinstance(item.source, str):
        return _OTHER

    sc = load_scenario(item.source)
    if quick:
        sc = sc.with_values({"duration_s": min(sc.simulation.duration_s, 0.2), "critical_charge": False})
    return estimate_seconds(sc, Study(sc).structure()) + _WRITE_SECONDS, _SCENARIO_BYTES


def expected_cost(items, quick: bool) -> tuple:
    """(seconds, bytes) that making ``items`` takes on the development machine (module docstring)."""
    secs = size = 0.0
    for it in items:
        m = MEASURED.get(it.name)
        s, b = (m[2], m[3]) if m and quick else (m[0], m[1]) if m else _estimate(it, quick)
        secs, size = secs + s, size + b
    return secs, size


def is_reproduce_folder(folder: Path) -> bool:
    """Whether ``folder`` is a reproduce folder: a ``summary.json`` listing items, or an item's marker."""

    folder = Path(folder)
    try:
        if "items" in json.loads((folder / "summary.json").read_text(encoding="utf-8")):
            return True
    except (OSError, ValueError, TypeError):
        pass
    return any((d / MARKER).is_file() for d in folder.iterdir() if d.is_dir())
