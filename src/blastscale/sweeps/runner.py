"""Running a sweep's chunks: in this process, on a local Dask cluster (single-threaded worker
processes on 127.0.0.1) or on any running scheduler. The runner writes nothing: each finished
chunk goes to a ``sink(index, result)`` (the chunk store of :mod:`blastscale.io.sweep_store`, or
memory: :mod:`.run` drives the sweep)."""

from __future__ import annotations

import hashlib
import json
import logging
import math
import signal
import sys
import threading
import time
import warnings
from multiprocessing import resource_tracker
from typing import Callable, Optional

from .._extras import require
from .._threads import THREADS_ENV, available_cores
from .._validate import BlastscaleInputError
from .cases import evaluate_chunk
from .spec import SweepSpec

__all__ = ["default_chunk", "run_chunks", "payload_hash"]


def default_chunk(spec: SweepSpec, workers: int) -> int:
    """Cases per task: outcome mode ~n / (2 workers), at most 20000; planar ~n / (4 workers), at most
    2000; else (3D) the threads of one worker, cores // workers (:mod:`blastscale._threads`: a
    chunk's 3D cases run in parallel threads), at most ~n / workers."""
    if spec.outcomes:  # ~70 us per case: 20000 cases are ~1.5 s per task
        return int(max(1, min(20000, math.ceil(spec.n_cases / max(1, 2 * workers)))))
    if spec.planar_only:  # enough cases per task to amortise the task overhead, enough tasks to balance
        return int(max(1, min(2000, math.ceil(spec.n_cases / max(1, 4 * workers)))))

    per_worker = max(1, available_cores() // max(1, workers))
    return int(max(1, min(per_worker, math.ceil(spec.n_cases / max(1, workers)))))


def run_chunks(
    payload: dict,
    todo,
    sink: Callable[[int, dict], None],
    *,
    scheduler: Optional[str] = None,
    workers: int = 0,
    tick: Optional[Callable[[int], None]] = None,
) -> tuple:
    """Evaluate the chunks ``todo`` (``(index, start, stop)`` each) of a sweep and hand each result
    to ``sink(index, result)`` as it completes.

    Parameters
    ----------
    payload : dict
        :meth:`SweepSpec.to_payload`.
    todo : list of (int, int, int)
        Chunk index and the case range ``start .. stop - 1``.
    sink : callable
        Receives every finished chunk (in completion order).
    scheduler : str, optional
        Address of a running Dask scheduler.
    workers : int
        Without ``scheduler``: local worker processes (0: in this process).
    tick : callable, optional
        ``tick(cases_done_now)`` after each chunk.

    Returns
    -------
    (int, float)
        Workers used and the seconds from the first submission to the last chunk handed over.
    """
    tick = tick or (lambda k: None)
    if scheduler is None and workers == 0:
        t0 = time.perf_counter()
        k = 0
        for i, a, b in todo:
            sink(i, evaluate_chunk(payload, a, b))
            k += b - a
            tick(k)
        return 0, time.perf_counter() - t0
    return _run_dask(payload, todo, sink, scheduler, workers, tick)


def _tracker_survives_hangup() -> None:
    """Start multiprocessing's resource tracker (shared by the local workers) with SIGHUP ignored, as it ignores
    SIGINT and SIGTERM itself: a hang-up of the process group then stops the workers and the sweep (one line)
    without killing the tracker, whose replacement would print a KeyError traceback for every semaphore it was
    never told about (Python 3.11-3.13)."""

    if not hasattr(signal, "SIGHUP") or threading.current_thread() is not threading.main_thread():
        return  # Windows; or a library caller's thread, where signals cannot be set
    old = signal.signal(signal.SIGHUP, signal.SIG_IGN)  # an ignored signal stays ignored across exec
    try:
        resource_tracker.ensure_running()
    finally:
        signal.signal(signal.SIGHUP, old)


def _run_dask(payload, todo, sink, scheduler, nw: int, tick) -> tuple:
    """Submit the chunks, write each as it completes; returns the number of workers used and the
    seconds from the first submission to the last chunk written (cluster start and stop excluded)."""
    distributed = require("dask.distributed", "sweeps", "a sweep on Dask workers")
    Client, LocalCluster, as_completed = distributed.Client, distributed.LocalCluster, distributed.as_completed

    cluster = None
    if scheduler is None:
        import dask

        # Dask's nannies set MALLOC_TRIM_THRESHOLD_=65536 in their workers: glibc then hands every
        # freed block above 64 kB back to the system, and the numpy temporaries of a planar chunk
        # come back as fresh pages each time (measured: +55 % CPU per outcome-mode chunk); the
        # local workers keep glibc's own (dynamic) threshold;
        # each worker's 3D runs share the cores with the other workers: cores // workers threads each;
        # the workers log only what is critical: a task cancelled while the cluster stops after Ctrl-C, or a
        # worker's "Failed to communicate with scheduler during heartbeat" (an error) when the scheduler stopped
        # first (seen on a loaded machine), is not news (the main process says what happened in one line); a
        # failing chunk still raises here, a lost worker too (KilledWorker)
        env = {
            "distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None,
            "distributed.nanny.pre-spawn-environ.DASK_LOGGING__DISTRIBUTED": "critical",
            f"distributed.nanny.pre-spawn-environ.{THREADS_ENV}": str(max(1, available_cores() // max(1, nw))),
        }
        with warnings.catch_warnings(), dask.config.set(env):
            # the scheduler's HTTP (health) server takes another port when 8787 is busy: not our concern
            warnings.filterwarnings("ignore", message="Port .* is already in use", category=UserWarning)
            _tracker_survives_hangup()
            cluster = LocalCluster(
                n_workers=nw, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
            )
        client = Client(cluster)
    else:
        try:
            client = Client(scheduler, timeout="20s")
        except (OSError, TimeoutError) as exc:
            raise BlastscaleInputError(f"scheduler = {scheduler!r} cannot be reached: {exc}") from None
    try:
        used = len(client.scheduler_info().get("workers", {})) or nw
        t0 = time.perf_counter()
        futs = {
            client.submit(
                evaluate_chunk, payload, a, b, key=f"blastscale-chunk-{i}-{payload_hash(payload)}", pure=False
            ): (i, a, b)
            for i, a, b in todo
        }
        k = 0
        for fut in as_completed(futs):
            i, a, b = futs[fut]
            sink(i, fut.result())
            k += b - a
            tick(k)
        return used, time.perf_counter() - t0
    finally:
        # stopping our own cluster, the nannies log "Worker process still alive after 4.0 seconds, killing" in
        # this process, and after an interrupt (an exception that is not an Exception: Ctrl-C, a signal) the
        # scheduler, the client and the nannies log their lost connections: our own teardown, not news (the
        # command says what happened in one line); distributed's loggers say only what is critical meanwhile
        interrupted = not isinstance(sys.exc_info()[1], (Exception, type(None)))
        every = [n for n in logging.root.manager.loggerDict if n.split(".")[0] == "distributed"]  # own levels too
        names = ["distributed", *every] if interrupted else ["distributed.nanny"]
        quiet = {n: logging.getLogger(n) for n in names}
        levels = {n: lg.level for n, lg in quiet.items()}
        for lg in quiet.values():
            lg.setLevel(logging.CRITICAL if interrupted else logging.ERROR)
        try:
            client.close()
            if cluster is not None:
                cluster.close()
        finally:
            for n, lg in quiet.items():
                lg.setLevel(levels[n])


def payload_hash(payload: dict) -> str:
    """Short hash of a sweep payload (task keys unique per sweep)."""
    return hashlib.sha1(json.dumps(payload, sort_keys=True, default=str).encode()).hexdigest()[:12]
