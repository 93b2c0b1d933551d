"""Progress off a terminal and the size of a run said first (issue #27, deliverable 3).

rich's progress bar is shown on a terminal only; a batch job or CI (standard error redirected to a file or a
pipe) gets plain lines instead, one every :func:`progress_seconds` (30 s; ``BLASTSCALE_PROGRESS_SECONDS``).
Before a study runs, :func:`announce_run` says its estimated time and result size
(:func:`blastscale.study.memory.estimate_run`, docs/performance.md).
"""

from __future__ import annotations

import contextlib
import os
import threading
import time

from ..study.memory import estimate_run, format_duration

__all__ = [
    "PROGRESS_SECONDS",
    "ANNOUNCE_SECONDS",
    "ANNOUNCE_BYTES",
    "progress_seconds",
    "plain_progress",
    "announce_run",
    "plain_lines",
]

#: Seconds between plain progress lines when standard error is not a terminal (``BLASTSCALE_PROGRESS_SECONDS``).
PROGRESS_SECONDS = 30.0
#: A run estimated to take at least this [s] or write at least :data:`ANNOUNCE_BYTES` says its size first off a
#: terminal (on a terminal every run does).
ANNOUNCE_SECONDS, ANNOUNCE_BYTES = 10.0, 20e6


def progress_seconds() -> float:
    """Seconds between plain progress lines: ``BLASTSCALE_PROGRESS_SECONDS`` (> 0), else :data:`PROGRESS_SECONDS`."""
    try:
        every = float(os.environ.get("BLASTSCALE_PROGRESS_SECONDS", ""))
    except ValueError:
        return PROGRESS_SECONDS
    return every if 0 < every < float("inf") else PROGRESS_SECONDS


def plain_progress(console, quiet: bool = False) -> bool:
    """Whether a command prints plain progress lines on ``console`` (standard error): it is not a terminal (a batch
    job, CI, a log file: rich's bar is not shown there), and not with ``--json`` (``quiet``)."""
    return not quiet and not console.is_terminal


def announce_run(study, console, writes: bool = False, quiet: bool = False) -> float | None:
    """Say the size of a checked study's run before it starts (:func:`blastscale.study.memory.estimate_run`): one
    line on stderr, ``about 40 s and 12 MB: 210 bodies, 1719 contacts, ...``, on a terminal always, elsewhere when
    the run is estimated at >= :data:`ANNOUNCE_SECONDS` or :data:`ANNOUNCE_BYTES`; nothing with ``--json``.
    Returns the estimated time [s] (None when quiet)."""
    if quiet:
        return None

    plan = study.check()
    size = (
        plan.size
        if writes
        else estimate_run(study.scenario, plan.structure, plan.contact, False, plan.contacts or None)
    )
    if console.is_terminal or size.seconds >= ANNOUNCE_SECONDS or size.result_bytes >= ANNOUNCE_BYTES:
        console.print(f"this run: {size.line()}", soft_wrap=True)
    return size.seconds


@contextlib.contextmanager
def plain_lines(state: dict, plain: bool, console):
    """While the job runs, when ``plain``: a line on ``console`` every :func:`progress_seconds`, from a daemon
    thread: ``progress: <stage> (2 of 4), 45 s elapsed of about 2 min`` (``state``: stage, done, total and
    expected_s, the run's estimate [s], updated by the job)."""

    if not plain:
        yield
        return

    stop, t0, every = threading.Event(), time.monotonic(), progress_seconds()

    def line() -> None:
        took = time.monotonic() - t0
        of = state.get("expected_s")
        total = state.get("total")
        where = f" ({state['done']} of {total})" if total else ""
        left = f" of about {format_duration(of)}" if of else ""
        console.print(
            f"progress: {state.get('stage', 'starting')}{where}, {format_duration(took)} elapsed{left}", soft_wrap=True
        )

    def loop() -> None:
        while not stop.wait(every):
            line()

    thread = threading.Thread(target=loop, name="blastscale-progress", daemon=True)
    thread.start()
    try:
        yield
    finally:
        stop.set()
        thread.join(timeout=1.0)
