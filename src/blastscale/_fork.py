"""Python work in a forked child process while this one goes on (Linux), for the one place where a command's
two halves are both Python and both long: a result folder's figures (matplotlib) beside its histories and 3D
view (h5py, plotly). Threads cannot share such work (it holds the GIL); a forked child starts with everything
already in memory, so nothing is pickled but the answer.

Safe by construction: the child only computes and sends back a pickled value through a pipe, then leaves with
``os._exit`` (no ``atexit``, no buffered output flushed twice, no file of the parent's touched). Whatever goes
wrong -- no ``fork`` on this platform, the variable :data:`FORK_ENV` set to ``0``, the child raising, being
killed, sending nothing within ``timeout`` -- the caller gets the same value computed here instead
(:meth:`Forked.result`), so a result never depends on the child. A child not collected (the parent interrupted
or failing) is killed when the ``with`` block ends.
"""

from __future__ import annotations

import logging
import os
import pickle
import select
import signal
import sys
import time
import warnings
from typing import Callable

__all__ = ["FORK_ENV", "Forked", "fork_available"]

#: Environment variable that turns the forked child off when set to ``0`` (the work then runs in the caller).
FORK_ENV = "BLASTSCALE_FORK"


def fork_available() -> bool:
    """Whether work may go to a forked child: Linux (``fork`` is safe there with the libraries used here; macOS
    and Windows run it in the caller) and :data:`FORK_ENV` not ``0``."""
    return sys.platform.startswith("linux") and hasattr(os, "fork") and os.environ.get(FORK_ENV, "").strip() != "0"


def _quiet_child() -> None:
    """Nothing printed from the child (the parent owns the terminal): warnings and logging off, and standard
    output and error fresh objects on the null device, so that no lock of the parent's streams (held by another
    thread at the fork, e.g. a progress display's) is ever taken here."""
    warnings.simplefilter("ignore")
    logging.disable(logging.CRITICAL)
    sys.stdout = sys.stderr = open(os.devnull, "w")  # noqa: SIM115 -- lives until os._exit


class Forked:
    """``fn(*args)`` computed in a forked child; :meth:`result` its value (or the same computed here).

    Use as a context manager: ``with Forked(fn, x) as job: ...; value = job.result()``.

    Attributes
    ----------
    forked : bool
        Whether a child was started.
    fell_back : str
        Why the value was computed here after all ("" when the child's value was used or none was started).
    """

    def __init__(self, fn: Callable, *args):
        self._fn, self._args = fn, args
        self._pid: int | None = None
        self._read: int | None = None
        self.fell_back = ""
        if fork_available():
            self._start()
        self.forked = self._pid is not None

    def _start(self) -> None:
        r, w = os.pipe()
        with warnings.catch_warnings():  # Python >= 3.12 warns of fork beside other threads (BLAS's idle pool)
            warnings.simplefilter("ignore", DeprecationWarning)
            try:
                pid = os.fork()
            except OSError:
                os.close(r)
                os.close(w)
                return
        if pid == 0:  # the child: compute, send, leave
            os.close(r)
            code = 0
            try:
                _quiet_child()
                payload = pickle.dumps((True, self._fn(*self._args)), protocol=pickle.HIGHEST_PROTOCOL)
            except BaseException as exc:  # noqa: BLE001 -- reported to the parent, which computes it itself
                payload, code = pickle.dumps((False, f"{type(exc).__name__}: {exc}")), 1
            try:
                view = memoryview(payload)
                while view:
                    view = view[os.write(w, view) :]
            except BaseException:  # noqa: BLE001 -- the parent is gone: nothing to tell
                code = 1
            finally:
                os._exit(code)
        os.close(w)
        self._pid, self._read = pid, r

    def result(self, timeout: float = 120.0):
        """The value: the child's (waiting up to ``timeout`` seconds for it) or, failing that, computed here."""
        if self._pid is None:
            return self._fn(*self._args)
        try:
            ok, value = pickle.loads(self._receive(timeout))
        except Exception as exc:  # noqa: BLE001 -- any failure of the child: compute here
            ok, value = False, f"{type(exc).__name__}: {exc}"
        finally:
            self._stop()
        if ok:
            return value
        self.fell_back = str(value)
        return self._fn(*self._args)

    def _receive(self, timeout: float) -> bytes:
        chunks, end = [], time.monotonic() + timeout
        while True:
            left = end - time.monotonic()
            if left <= 0 or not select.select([self._read], [], [], left)[0]:
                raise TimeoutError(f"no answer from the child in {timeout:g} s")
            chunk = os.read(self._read, 1 << 20)
            if not chunk:
                return b"".join(chunks)
            chunks.append(chunk)

    def _stop(self) -> None:
        """Close the pipe; kill the child if it still runs; reap it."""
        if self._read is not None:
            os.close(self._read)
            self._read = None
        if self._pid is not None:
            pid, self._pid = self._pid, None
            try:
                if os.waitpid(pid, os.WNOHANG) == (0, 0):
                    os.kill(pid, signal.SIGKILL)
                    os.waitpid(pid, 0)
            except ChildProcessError:
                pass

    def __enter__(self) -> "Forked":
        return self

    def __exit__(self, *exc) -> None:
        self._stop()
