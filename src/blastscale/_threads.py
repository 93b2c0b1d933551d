"""Independent runs in parallel native threads: 3D runs (ensemble members, the 3D cases of a sweep
chunk) and the slices of a planar batch (:mod:`blastscale.rocking.batch`).

Vectorised evaluations over many cases (the first swings of a sweep's outcome mode, of fragility, of
capacity searches) split their cases into interleaved shares, one per thread (:func:`map_interleaved`): numpy's
array loops and the compiled kernels release the GIL, and the cost of a case follows its place in a grid
(the charge order), so alternate cases balance the threads where contiguous halves would not.

The runs must release Python's GIL to gain anything: MuJoCo does inside ``mj_step`` (measured: 4 runs
of the 10-drum column on 2 threads take 1/1.94 of their serial time), and after the pulse the 3D engine
steps in native chunks (``mj_step(m, d, nstep)``, :mod:`blastscale.sim3d.integrate`), so 3D runs that each
own their ``MjModel`` and ``MjData`` proceed in parallel, the short Python load phase of one interleaving
with the native stepping of the others (MuJoCo's own thread pool is not used, so no reduction order
changes); so do the compiled planar kernels (``nogil=True``, :mod:`blastscale.rocking.kernel`). Each run is
the same sequence of floating-point operations as in a serial loop (no state is shared), so the
results are bitwise those of the serial run (tests/integration/test_parallel_members.py,
tests/unit/rocking/test_batch_threads.py).

One knob, ``threads``: the runs that one process may have in flight. Default
(:func:`default_threads`): the cores this process may use (``os.sched_getaffinity``) divided by
the local Dask workers sharing them (a local cluster gives each worker ``cores // workers`` through
the environment variable :data:`THREADS_ENV`); a run started inside a parallel run gets 1 (no
nested pools).
"""

from __future__ import annotations

import os
import threading
from concurrent.futures import ThreadPoolExecutor, as_completed
from typing import Callable, Optional

import numpy as np

from ._validate import BlastscaleInputError

__all__ = [
    "THREADS_ENV",
    "available_cores",
    "default_threads",
    "resolve_threads",
    "map_threads",
    "map_interleaved",
    "interleave",
]

#: Environment variable holding a process's default number of threads (set for local Dask workers).
THREADS_ENV = "BLASTSCALE_THREADS"

_local = threading.local()


def available_cores() -> int:
    """CPU cores this process may run on (its affinity mask where the OS has one)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - macOS, Windows
        return max(1, os.cpu_count() or 1)


def default_threads() -> int:
    """Threads for independent runs: 1 inside a parallel run; else :data:`THREADS_ENV` when set (a
    local Dask worker: cores // workers); else every available core."""
    if getattr(_local, "inside", False):
        return 1
    env = os.environ.get(THREADS_ENV, "").strip()
    if env:
        try:
            return max(1, int(env))
        except ValueError:
            pass
    return available_cores()


def resolve_threads(threads: Optional[int]) -> int:
    """``threads`` checked (a whole number >= 1), or :func:`default_threads` when None."""
    if threads is None:
        return default_threads()
    if isinstance(threads, bool) or not float(threads).is_integer() or threads < 1:
        raise BlastscaleInputError(f"threads = {threads!r} is out of range: must be a whole number >= 1")
    return int(threads)


def _inside(fn):
    def run(x):
        _local.inside = True
        try:
            return fn(x)
        finally:
            _local.inside = False

    return run


def map_threads(
    fn: Callable, items, threads: Optional[int] = None, done: Optional[Callable[[int], None]] = None
) -> list:
    """``[fn(x) for x in items]``, on up to ``threads`` threads (default :func:`default_threads`).

    Parameters
    ----------
    fn : callable
        One independent run (it must not share mutable state with the others).
    items : iterable
        Its arguments.
    threads : int, optional
        Threads [-], >= 1; 1 runs in this thread, in order.
    done : callable, optional
        ``done(k)`` in the calling thread after each completed run (k runs done so far).

    Returns
    -------
    list
        The results in the order of ``items``; the first exception of a run is raised.
    """
    items = list(items)
    n = min(resolve_threads(threads), len(items))
    done = done or (lambda k: None)
    if n <= 1:
        out = []
        for x in items:
            out.append(fn(x))
            done(len(out))
        return out
    with ThreadPoolExecutor(max_workers=n, thread_name_prefix="blastscale") as ex:
        futs = [ex.submit(_inside(fn), x) for x in items]
        for k, f in enumerate(as_completed(futs), start=1):
            f.result()
            done(k)
        return [f.result() for f in futs]


def map_interleaved(fn: Callable, n: int, threads: Optional[int], min_per_thread: int) -> list:
    """``fn(share)`` for the interleaved shares ``share = slice(j, None, k)`` of ``n`` cases, on ``k`` threads:
    ``k`` = ``threads`` (default :func:`default_threads`), at most ``n // min_per_thread``; with ``k = 1``
    one call ``fn(slice(None))`` in this thread.

    Returns
    -------
    list of (slice, result)
        Each share and ``fn``'s result on it (reassemble arrays with :func:`interleave`).
    """
    k = max(1, min(resolve_threads(threads), int(n) // max(1, int(min_per_thread))))
    shares = [slice(None)] if k == 1 else [slice(j, None, k) for j in range(k)]
    return list(zip(shares, map_threads(fn, shares, k)))


def interleave(parts: list, n: int) -> np.ndarray:
    """The array of ``n`` cases from :func:`map_interleaved`'s ``(share, array)`` pairs (the dtype of the
    first share's)."""
    out = np.empty(int(n), dtype=np.asarray(parts[0][1]).dtype)
    for share, values in parts:
        out[share] = values
    return out
