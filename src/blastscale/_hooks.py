"""Pause points for the project's own signal tests (Ctrl-C, SIGTERM, kill -9 at a chosen moment).

A test that must interrupt a run at a given moment cannot rely on the clock (the run may finish
first, or not have started). With ``BLASTSCALE_PAUSE_AT=<point>`` and ``BLASTSCALE_PAUSE_MARKER=<file>``
in the environment, the run writes the marker file when it reaches that point and waits there (at
most :data:`MAX_PAUSE` seconds) for the test's signal. Without those variables a pause point costs one
dictionary lookup. Points: ``run:started``, ``run:simulating``, ``run:writing`` (``blastscale run``),
``sweep:chunks=N`` (a sweep store after its N-th chunk file), ``sweep:consolidating`` (the store's
partial folder made, before it is filled) and ``output:between-renames`` (an existing output set aside,
the new one not yet renamed into place; the signals are held there: only kill -9 stops it).
"""

from __future__ import annotations

import os
import time
from pathlib import Path

__all__ = ["pause_point", "pausing", "MAX_PAUSE"]

#: Longest pause [s]: a test that never sends its signal does not hang the run.
MAX_PAUSE = 120.0


def pausing(prefix: str) -> bool:
    """Whether a pause point starting with ``prefix`` is asked for (to skip computing its name)."""
    return os.environ.get("BLASTSCALE_PAUSE_AT", "").startswith(prefix)


def pause_point(name: str) -> None:
    """Wait here when the environment asks to (module docstring); return at once otherwise."""
    if os.environ.get("BLASTSCALE_PAUSE_AT") != name:
        return
    marker = os.environ.get("BLASTSCALE_PAUSE_MARKER")
    if marker:
        Path(marker).write_text(name)
    t0 = time.monotonic()
    while time.monotonic() - t0 < MAX_PAUSE:
        time.sleep(0.01)
