"""Running a sweep, from its spec to its tree: the budget check (:mod:`.budget`), the chunking, the
resume from the chunks a killed or interrupted run left, the chunks' run (:mod:`.runner`, in this
process or on Dask) and the assembly (:mod:`.dataset`); into a resumable Zarr store
(:func:`run_sweep`, written by the chunk store :mod:`blastscale.io.sweep_store`) or in memory
(:func:`run_in_memory`)."""

from __future__ import annotations

import math
import os
import time
from dataclasses import dataclass
from typing import Callable, Optional

import numpy as np

from .._extras import require
from .._validate import BlastscaleInputError
from ..io.output import claim
from ..io.sweep_store import (
    SWEEP_STORE,
    any_chunks,
    consolidate,
    discard_parts,
    has_chunk,
    parts_manifest,
    parts_of,
    read_chunks,
    remove_unfinished_writes,
    start_parts,
    store_fingerprint,
    write_chunk,
)
from .budget import check_sweep_budget
from .dataset import STORE_VERSION, assemble, metadata
from .runner import default_chunk, run_chunks
from .spec import SweepSpec

__all__ = ["SweepRun", "run_sweep", "run_in_memory"]


@dataclass(frozen=True)
class SweepRun:
    """What :func:`run_sweep` did: the store, the number of cases, chunks computed now and
    skipped (already written), ``seconds`` [s] computing them (on Dask: from the first submission
    to the last chunk written; the cluster's start and stop and the final consolidation are not
    counted), workers, and the rate of that computing."""

    store: str
    n_cases: int
    chunks_run: int
    chunks_skipped: int
    seconds: float
    workers: int
    cases_per_minute: float

    def to_dict(self) -> dict:
        return dict(self.__dict__)


def _check_chunk(chunk) -> None:
    if not isinstance(chunk, (int, np.integer)) or isinstance(chunk, bool) or chunk < 1:
        raise BlastscaleInputError(f"chunk = {chunk!r} is out of range: must be a whole number >= 1")


def _chunk_bounds(n: int, chunk: int) -> list:
    """``(index, start, stop)`` of every chunk of ``n`` cases, ``chunk`` cases each (the last one shorter)."""
    return [(i, s, min(n, s + chunk)) for i, s in enumerate(range(0, n, chunk))]


def run_sweep(
    spec: SweepSpec,
    store,
    *,
    scheduler: Optional[str] = None,
    workers: Optional[int] = None,
    chunk: Optional[int] = None,
    force: bool = False,
    progress: Optional[Callable[[int, int], None]] = None,
) -> SweepRun:
    """Run a sweep into a Zarr store, resumably, through the one output mechanism
    (:mod:`blastscale.io.output`: checked before any work, locked against a second writer, only a
    sweep store replaced, one line for an output fault).

    Parameters
    ----------
    spec : SweepSpec
        The sweep.
    store : str or path
        The Zarr store (a directory, ``*.zarr``); finished chunks wait in ``store + ".parts"`` (kept
        when the sweep is interrupted or killed: the same sweep run again resumes from them).
    scheduler : str, optional
        Address of a running Dask scheduler (``tcp://127.0.0.1:8786``): run there unchanged.
    workers : int, optional
        Without ``scheduler``: a ``LocalCluster`` of this many single-threaded worker processes on
        127.0.0.1, no dashboard (default: the machine's CPU count); 0 runs in this process.
    chunk : int, optional
        Cases per task (default: outcome mode ~n / (2 workers), at most 20000; planar sweeps
        ~n / (4 workers), at most 2000; else 1).
    force : bool
        Replace a store (or unfinished chunks) of a different sweep (else refused); never anything
        that is not a sweep store.
    progress : callable, optional
        ``progress(cases_done, n_cases)`` after each chunk.

    Returns
    -------
    SweepRun
    """
    given = str(store)
    fp = spec.fingerprint()
    nw = _checked_run(spec, scheduler, workers, chunk)
    same = lambda p: store_fingerprint(p, STORE_VERSION) == fp
    with claim(store, SWEEP_STORE, force, reuse=same) as c:
        if same(c.path):  # this sweep's finished store: nothing to do
            return SweepRun(given, spec.n_cases, 0, 0, 0.0, 0, math.nan)
        parts = parts_of(c.path)
        resumed = _resumed_chunk(parts, given, fp, force)
        if resumed is not None:  # resume with the chunking the chunks were written with
            chunk = resumed
        elif chunk is None:
            chunk = default_chunk(spec, max(1, nw))
        created = start_parts(parts, {"fingerprint": fp, "chunk": int(chunk), "n_cases": spec.n_cases})
        bounds = _chunk_bounds(spec.n_cases, chunk)
        todo = [b for b in bounds if not has_chunk(parts, b[0])]
        try:
            used, dt = _run_into(spec, parts, bounds, todo, scheduler, nw, progress)
            consolidate(assemble(spec, read_chunks(parts, len(bounds)), metadata(spec, chunk)), c)
        except BaseException as exc:  # interrupted or failed: finished chunks stay to resume from, else nothing;
            # a write fault (a full disk) of a sweep this run started leaves nothing either
            if not any_chunks(parts) or (created and isinstance(exc, OSError)):
                discard_parts(parts)
            raise
        discard_parts(parts)
    ran = sum(b - a for _, a, b in todo)
    rate = ran / dt * 60.0 if dt > 0 and ran else math.nan
    return SweepRun(given, spec.n_cases, len(todo), len(bounds) - len(todo), dt, used, rate)


def _checked_run(spec: SweepSpec, scheduler: Optional[str], workers: Optional[int], chunk) -> int:
    """The number of local workers (default: the CPU count), after every check that comes before any work:
    the extras needed, ``workers`` and ``chunk`` in range, the sweep's budget."""
    nw = (os.cpu_count() or 1) if workers is None else int(workers)
    require("zarr", "sweeps", "a sweep store")  # before any work: nothing written without it
    if scheduler is not None or nw > 0:
        require("dask.distributed", "sweeps", "a sweep on Dask workers")
    if nw < 0:
        raise BlastscaleInputError(f"workers = {workers} is out of range: must be >= 0 (0: in this process)")
    if chunk is not None:
        _check_chunk(chunk)
    check_sweep_budget(spec, None if scheduler else nw)
    return nw


def _resumed_chunk(parts, given: str, fp: str, force: bool) -> Optional[int]:
    """The chunking of this sweep's unfinished chunks in ``parts`` (None: a fresh start). Those of another
    sweep (or of other code) are refused, or discarded with ``force``."""
    man = parts_manifest(parts, given)
    if man is None:
        return None
    if man.get("fingerprint") != fp:
        if man and not force:
            raise BlastscaleInputError(
                f"out = {given!r}: the unfinished chunks in {str(parts_of(given))!r} belong to another sweep, "
                "or to this one computed by other blastscale code (pass --force to discard them)"
            )
        discard_parts(parts, strict=True)
        return None
    chunk = int(man["chunk"])
    remove_unfinished_writes(parts)  # a chunk a killed writer had not finished
    return chunk


def _run_into(spec: SweepSpec, parts, bounds: list, todo: list, scheduler, nw: int, progress) -> tuple:
    """Run the chunks ``todo`` of ``bounds`` into ``parts`` (:func:`.runner.run_chunks`), ``progress`` told
    of the cases already done and after each chunk. Returns the workers used and the seconds computing."""
    n = spec.n_cases
    done_cases = sum(b - a for _, a, b in bounds) - sum(b - a for _, a, b in todo)
    t0 = time.perf_counter()
    payload = spec.to_payload()
    if progress:
        progress(done_cases, n)
    if not todo:
        return nw, time.perf_counter() - t0
    return run_chunks(
        payload,
        todo,
        lambda i, result: write_chunk(parts, i, result),
        scheduler=scheduler,
        workers=nw,
        tick=lambda k: progress(done_cases + k, n) if progress else None,
    )


def run_in_memory(
    spec: SweepSpec,
    *,
    scheduler: Optional[str] = None,
    workers: int = 0,
    chunk: Optional[int] = None,
    progress: Optional[Callable[[int, int], None]] = None,
):
    """Run every case of a sweep and return its tree (:func:`.dataset.assemble`: the layout of a
    sweep store), keeping the chunks in memory (nothing written, nothing resumable: for small
    sweeps and maps).

    Parameters
    ----------
    spec : SweepSpec
    scheduler, workers
        As :func:`.runner.run_chunks` (default: in this process).
    chunk : int, optional
        Cases per task (default :func:`.runner.default_chunk`).
    progress : callable, optional
        ``progress(cases_done, n_cases)``.

    Returns
    -------
    xarray.DataTree
    """

    if workers < 0:
        raise BlastscaleInputError(f"workers = {workers} is out of range: must be >= 0 (0: in this process)")
    chunk = default_chunk(spec, max(1, workers)) if chunk is None else chunk
    _check_chunk(chunk)
    check_sweep_budget(spec, None if scheduler else max(1, workers))
    n = spec.n_cases
    todo = _chunk_bounds(n, chunk)
    done: dict = {}
    run_chunks(
        spec.to_payload(),
        todo,
        done.__setitem__,
        scheduler=scheduler,
        workers=workers,
        tick=(lambda k: progress(k, n)) if progress else None,
    )
    return assemble(spec, (done[i] for i, _, _ in todo), metadata(spec, chunk))
