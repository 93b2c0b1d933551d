"""Ctrl-C (SIGINT), SIGTERM (what ``timeout``, Slurm and systemd send) and SIGHUP (a closed terminal)
inside a command: each raises :class:`Interrupted`, so that the output mechanism
(:mod:`blastscale.io.output`) removes its partial work, and the command ends with one line and the
shell's status for that signal (130, 143, 129).

In the worker processes of a local Dask cluster (multiprocessing children, which import the
``blastscale`` script again) Ctrl-C and SIGHUP are ignored: the main process tears the cluster down,
and says so once.
"""

from __future__ import annotations

import multiprocessing
import os
import signal
import sys
from typing import Callable, Optional

__all__ = [
    "Interrupted",
    "SIGNALS",
    "install",
    "restore",
    "raise_if_interrupted",
    "ignore_interrupts",
    "interrupted_signal",
    "exit_status",
    "message",
    "set_interrupt_note",
    "in_worker_process",
]

#: The signals a command turns into :class:`Interrupted`.
SIGNALS = tuple(getattr(signal, s) for s in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, s))

_WORDS = {
    getattr(signal, "SIGINT", 2): "interrupted (Ctrl-C)",
    getattr(signal, "SIGTERM", 15): "terminated (SIGTERM)",
    getattr(signal, "SIGHUP", 1): "hung up (SIGHUP)",
}


class Interrupted(BaseException):
    """A signal of :data:`SIGNALS` inside a command. Raised instead of KeyboardInterrupt so that click
    does not turn it into its two-line "Aborted!"; a BaseException, so that no ``except Exception``
    swallows it; clean-ups (``finally``, the output folder) still run."""


_INTERRUPTED: list = []  # the signals received: an import that turns Interrupted into ImportError is still one
_NOTE: list = []  # a callable giving what was kept (a sweep's finished chunks), else "no partial results left"


def in_worker_process() -> bool:
    """Whether this is a multiprocessing child (a local Dask worker), not the command's own process."""
    return multiprocessing.current_process().name != "MainProcess"


def _raise_interrupted(signum, frame):
    _INTERRUPTED.append(signum)
    f, depth = frame, 0
    while f is not None and depth < 30:  # inside a finaliser Python would ignore the exception:
        if f.f_code.co_name == "__del__":  # the flag is checked at the next stage instead
            return
        f, depth = f.f_back, depth + 1
    raise Interrupted()


def _unraisable(info) -> None:
    """A signal that landed where Python cannot raise (a finaliser, a ctypes callback of the JIT): not
    printed; the flag stays set and :func:`raise_if_interrupted` raises at the next stage."""
    if isinstance(info.exc_value, Interrupted) or _INTERRUPTED:  # or a consequence of it (a half-made
        return  # file object closed at exit): the one line printed says what happened
    sys.__unraisablehook__(info)


def install() -> Optional[tuple]:
    """Turn the signals into :class:`Interrupted`; returns what :func:`restore` needs. A signal the
    command was started with ignored stays ignored (a background job's Ctrl-C, nohup's SIGHUP)."""
    _INTERRUPTED.clear()
    previous = {s: signal.getsignal(s) for s in SIGNALS}
    for s in SIGNALS:
        if previous[s] is not signal.SIG_IGN:
            signal.signal(s, _raise_interrupted)
    hook = sys.unraisablehook
    sys.unraisablehook = _unraisable
    return previous, hook


def restore(saved: Optional[tuple]) -> None:
    if saved is None:
        return
    previous, hook = saved
    for s, h in previous.items():
        signal.signal(s, h)
    if not _INTERRUPTED:  # after a signal, keep quiet about finalisers that run at exit
        sys.unraisablehook = hook


def raise_if_interrupted() -> None:
    """Raise :class:`Interrupted` when a signal came at a moment that could not raise (a finaliser)."""
    if _INTERRUPTED:
        raise Interrupted()


def ignore_interrupts() -> None:
    """From here on the signals are ignored: the results are in place, only the printing remains."""
    for s in SIGNALS:
        signal.signal(s, signal.SIG_IGN)


def interrupted_signal() -> Optional[int]:
    return _INTERRUPTED[0] if _INTERRUPTED else None


def exit_status(signum: Optional[int]) -> int:
    """The shell's status of a command ended by ``signum``: 128 + its number (130 for Ctrl-C)."""
    return 128 + int(signum if signum is not None else signal.SIGINT)


def set_interrupt_note(note: Optional[Callable[[], str]]) -> None:
    """What the one line says was kept when the command is interrupted (default: nothing)."""
    _NOTE[:] = [] if note is None else [note]


def message(signum: Optional[int]) -> str:
    """The one line printed: what happened and what was left."""
    what = _WORDS.get(signum if signum is not None else signal.SIGINT, f"stopped by signal {signum}")
    note = "no partial results left"
    if _NOTE:
        try:
            note = _NOTE[0]() or note
        except Exception:  # noqa: BLE001 - the line must be printed whatever the note does
            pass
    return f"{what}: {note}"


def _interrupted_while_starting(signum, frame):  # pragma: no cover - timing dependent
    """A signal while the command line tool is still importing: one line, nothing written."""

    os.write(2, f"error: {_WORDS.get(signum, 'interrupted')}: no partial results left\n".encode())
    os._exit(exit_status(signum))


def at_import() -> None:
    """Called once when the ``blastscale`` script imports the CLI: the command's process says one line for
    a signal before its command starts; a local Dask worker ignores Ctrl-C and SIGHUP."""
    if in_worker_process():  # SIGTERM stays: the cluster's own way to stop a worker that does not close
        for s in SIGNALS:
            if s != getattr(signal, "SIGTERM", None):
                signal.signal(s, signal.SIG_IGN)
        return
    if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
        for s in SIGNALS:
            if signal.getsignal(s) is signal.SIG_DFL:
                signal.signal(s, _interrupted_while_starting)
        signal.signal(signal.SIGINT, _interrupted_while_starting)  # replaced by the command's own handler
