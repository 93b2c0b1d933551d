"""The resumable Zarr store of a sweep: finished chunks wait in ``STORE.parts/`` (one ``.npz`` per
chunk, written atomically, with the sweep's fingerprint in ``sweep.json``); a sweep killed and run
again skips the chunks already there; at the end they are consolidated into the store (written
to ``STORE.tmp`` and renamed into place): an ``xarray.DataTree`` (a group per engine or section,
:mod:`blastscale.sweeps.dataset`) in Zarr format 2 with consolidated metadata, so that
``xarray.open_datatree(STORE, engine="zarr")`` opens it without a warning."""

from __future__ import annotations

import json
import math
import os
import shutil
import tempfile
import time
from pathlib import Path
from typing import Callable, Optional

import numpy as np

from .._hooks import pause_point, pausing
from .._validate import BlastscaleInputError
from ..sweeps.runner import SweepRun, default_chunk, run_chunks
from ..sweeps.dataset import STORE_VERSION, assemble, metadata
from ..sweeps.spec import SweepSpec

__all__ = ["run_sweep", "open_sweep"]


def _chunk_path(parts: Path, i: int) -> Path:
    return parts / f"chunk-{i:07d}.npz"


def _write_chunk(parts: Path, i: int, result: dict) -> None:
    """Atomically write one chunk (temp file + rename: a killed sweep leaves whole files only)."""
    arrays = {"__start": np.array(result["start"]), "__stop": np.array(result["stop"])}
    for k, v in result["values"].items():
        arrays["v:" + k] = np.asarray(v)
    fd, tmp = tempfile.mkstemp(dir=parts, suffix=".tmp")
    with os.fdopen(fd, "wb") as fh:
        np.savez(fh, **arrays)
    os.replace(tmp, _chunk_path(parts, i))
    if pausing("sweep:"):
        pause_point(f"sweep:chunks={len(list(parts.glob('chunk-*.npz')))}")


def _read_chunk(path: Path) -> dict:
    with np.load(path, allow_pickle=False) as z:
        return {"start": int(z["__start"]), "stop": int(z["__stop"]),
                "values": {k[2:]: z[k] for k in z.files if k.startswith("v:")}}


def _consolidate(spec: SweepSpec, parts: Path, n_chunks: int, store: Path, meta: dict) -> None:
    """The chunks in ``parts`` assembled into the store (written to ``STORE.tmp``, renamed into place)."""
    tree = assemble(spec, (_read_chunk(_chunk_path(parts, i)) for i in range(n_chunks)), meta)
    tmp = store.with_name(store.name + ".tmp")
    if tmp.exists():
        shutil.rmtree(tmp)
    # Zarr format 2: its consolidated metadata (.zmetadata) is part of the format (zarr 3 warns that
    # format 3's is not yet), so a reader opens the whole tree with one read and no warning
    tree.to_zarr(tmp, mode="w", consolidated=True, zarr_format=2)
    if store.exists():
        shutil.rmtree(store)
    os.replace(tmp, store)


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
    """Run a sweep into a Zarr store, resumably.

    Parameters
    ----------
    spec : SweepSpec
        The sweep.
    store : str or path
        The Zarr store (a directory, ``*.zarr``); finished chunks wait in ``store + ".parts"``.
    scheduler : str, optional
        Address of a running Dask scheduler (``tcp://127.0.0.1:8786``): run there unchanged.
    workers : int, optional
        Without ``scheduler``: a ``LocalCluster`` of this many single-threaded worker processes on
        127.0.0.1, no dashboard (default: the machine's CPU count); 0 runs in this process.
    chunk : int, optional
        Cases per task (default: outcome mode ~n / (2 workers), at most 20000; planar sweeps
        ~n / (4 workers), at most 2000; else 1).
    force : bool
        Replace a store of a different sweep (else refused).
    progress : callable, optional
        ``progress(cases_done, n_cases)`` after each chunk.

    Returns
    -------
    SweepRun
    """
    store = Path(store)
    fp = spec.fingerprint()
    if store.exists():
        old = _store_fingerprint(store)
        if old == fp:
            n = spec.n_cases
            return SweepRun(str(store), n, 0, 0, 0.0, 0, math.nan)
        if not force:
            raise BlastscaleInputError(
                f"out = {str(store)!r} already holds {'another sweep' if old else 'something else'}: "
                "choose another --out or pass --force to replace it")
    if not store.parent.is_dir():
        raise BlastscaleInputError(f"out = {str(store)!r}: the folder {str(store.parent)!r} does not exist")
    nw = (os.cpu_count() or 1) if workers is None else int(workers)
    if nw < 0:
        raise BlastscaleInputError(f"workers = {workers} is out of range: must be >= 0 (0: in this process)")
    parts = store.with_name(store.name + ".parts")
    manifest = parts / "sweep.json"
    if parts.exists():
        try:
            man = json.loads(manifest.read_text())
        except (OSError, ValueError):
            man = {}
        if man.get("fingerprint") != fp:
            if not force and man:
                raise BlastscaleInputError(
                    f"out = {str(store)!r}: the unfinished chunks in {str(parts)!r} belong to another sweep "
                    "(pass --force to discard them)")
            shutil.rmtree(parts)
        else:
            chunk = int(man["chunk"])  # resume with the chunking the chunks were written with
    if chunk is None:
        chunk = default_chunk(spec, max(1, nw))
    if not isinstance(chunk, (int, np.integer)) or chunk < 1:
        raise BlastscaleInputError(f"chunk = {chunk!r} is out of range: must be a whole number >= 1")
    parts.mkdir(exist_ok=True)
    if not manifest.exists():
        manifest.write_text(json.dumps({"fingerprint": fp, "chunk": int(chunk), "n_cases": spec.n_cases}))
    n = spec.n_cases
    bounds = [(i, s, min(n, s + chunk)) for i, s in enumerate(range(0, n, chunk))]
    todo = [b for b in bounds if not _chunk_path(parts, b[0]).exists()]
    done_cases = sum(b[2] - b[1] for b in bounds) - sum(b[2] - b[1] for b in todo)
    t0 = time.perf_counter()
    payload = spec.to_payload()
    if progress:
        progress(done_cases, n)
    used, dt = nw, time.perf_counter() - t0
    if todo:
        used, dt = run_chunks(payload, todo, lambda i, result: _write_chunk(parts, i, result), scheduler=scheduler,
                              workers=nw, tick=lambda k: progress(done_cases + k, n) if progress else None)
    _consolidate(spec, parts, len(bounds), store, metadata(spec, chunk))
    shutil.rmtree(parts, ignore_errors=True)
    ran = sum(b - a for _, a, b in todo)
    return SweepRun(str(store), n, len(todo), len(bounds) - len(todo), dt, used,
                    ran / dt * 60.0 if dt > 0 and ran else math.nan)


def _store_fingerprint(store: Path) -> Optional[str]:
    try:
        import zarr

        attrs = zarr.open_group(str(store), mode="r").attrs
        # a store of an older layout (one flat dataset) is not this sweep's finished store
        return attrs.get("fingerprint") if attrs.get("store_version") == STORE_VERSION else None
    except Exception:  # not a zarr store (or unreadable): treated as foreign
        return None


def open_sweep(store):
    """A sweep store read back into memory.

    Parameters
    ----------
    store : str or path
        The Zarr store written by :func:`run_sweep`.

    Returns
    -------
    xarray.DataTree
        The groups of :mod:`blastscale.sweeps.dataset`; a flat key's values over the case grid:
        :func:`blastscale.sweeps.layout.select`.
    """
    import xarray as xr

    return xr.open_datatree(Path(store), engine="zarr", consolidated=True).load()

