"""The resumable Zarr store of a sweep: finished chunks wait in ``STORE.parts/`` (one ``.npz`` per
chunk, written atomically, with the sweep's fingerprint in ``sweep.json``); a sweep killed and run
again skips the chunks already there; at the end they are consolidated into the store (written
to a partial folder beside it and renamed into place, :mod:`blastscale.io.output`): an ``xarray.DataTree`` (a group per engine or section,
:mod:`blastscale.sweeps.dataset`) in Zarr format 2 with consolidated metadata, so that
``xarray.open_datatree(STORE, engine="zarr")`` opens it without a warning."""

from __future__ import annotations

import contextlib
import json
import math
import os
import shutil
import tempfile
import time
from pathlib import Path
from typing import Callable, Optional

import numpy as np

from .._extras import require
from .._hooks import pause_point, pausing
from .._validate import BlastscaleInputError
from ..sweeps.budget import check_sweep_budget
from .targets import Kind
from .output import claim, signals_held, write_file
from ..sweeps.runner import SweepRun, default_chunk, run_chunks
from ..sweeps.dataset import STORE_VERSION, assemble, metadata
from ..sweeps.spec import SweepSpec

__all__ = ["run_sweep", "open_sweep", "unfinished_chunks", "SWEEP_STORE"]


def _chunk_path(parts: Path, i: int) -> Path:
    return parts / f"chunk-{i:07d}.npz"


def _write_chunk(parts: Path, i: int, result: dict) -> None:
    """Atomically write one chunk (temp file + rename: a killed sweep leaves whole files only; a failed
    write leaves no temp file)."""
    arrays = {"__start": np.array(result["start"]), "__stop": np.array(result["stop"])}
    for k, v in result["values"].items():
        arrays["v:" + k] = np.asarray(v)
    fd, tmp = tempfile.mkstemp(dir=parts, prefix=f".chunk-{i:07d}-{os.getpid()}-", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as fh:
            np.savez(fh, **arrays)
        os.replace(tmp, _chunk_path(parts, i))
    except BaseException:
        with signals_held(), contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
    if pausing("sweep:"):
        pause_point(f"sweep:chunks={len(list(parts.glob('chunk-*.npz')))}")


def _read_chunk(path: Path) -> dict:
    with np.load(path, allow_pickle=False) as z:
        return {
            "start": int(z["__start"]),
            "stop": int(z["__stop"]),
            "values": {k[2:]: z[k] for k in z.files if k.startswith("v:")},
        }


def _consolidate(spec: SweepSpec, parts: Path, n_chunks: int, claim, meta: dict) -> None:
    """The chunks in ``parts`` assembled into the store: written into the claim's partial folder and
    renamed into place (:meth:`blastscale.io.output.Claim.staged`)."""
    tree = assemble(spec, (_read_chunk(_chunk_path(parts, i)) for i in range(n_chunks)), meta)
    with claim.staged() as tmp:
        pause_point("sweep:consolidating")
        # Zarr format 2: its consolidated metadata (.zmetadata) is part of the format (zarr 3 warns that
        # format 3's is not yet), so a reader opens the whole tree with one read and no warning
        tree.to_zarr(tmp, mode="w", consolidated=True, zarr_format=2)


#: What a sweep writes (:mod:`blastscale.io.output`): an existing folder is its own kind when it is a
#: blastscale sweep store (its fingerprint attribute), whatever the sweep.
SWEEP_STORE = Kind(
    "a blastscale sweep store (no sweep fingerprint)", lambda p: _store_fingerprint(p, any_layout=True) is not None
)


def _parts_state(parts: Path, given: str) -> "dict | None":
    """The manifest of the unfinished chunks beside a store: None when there are none; refused (one
    line) when ``parts`` is a file or a folder that holds something else than a sweep's chunks."""
    if not (parts.exists() or parts.is_symlink()):
        return None
    if not parts.is_dir():
        raise BlastscaleInputError(
            f"out = {given!r}: {str(parts)!r} is a file, not a sweep's unfinished "
            "chunks: refused (move it or choose another --out)"
        )
    try:
        man = json.loads((parts / "sweep.json").read_text())
        if isinstance(man, dict) and "fingerprint" in man:
            return man
    except (OSError, ValueError):
        pass
    if any(f for f in parts.iterdir() if not (f.name.startswith(".chunk-") or f.name.startswith("chunk-"))):
        raise BlastscaleInputError(
            f"out = {given!r}: {str(parts)!r} holds something else than a sweep's "
            "unfinished chunks: refused, even with --force (move it or choose another --out)"
        )
    return {}


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
    nw = (os.cpu_count() or 1) if workers is None else int(workers)
    require("zarr", "sweeps", "a sweep store")  # before any work: nothing written without it
    if scheduler is not None or nw > 0:
        require("dask.distributed", "sweeps", "a sweep on Dask workers")
    if nw < 0:
        raise BlastscaleInputError(f"workers = {workers} is out of range: must be >= 0 (0: in this process)")
    if chunk is not None and (not isinstance(chunk, (int, np.integer)) or isinstance(chunk, bool) or chunk < 1):
        raise BlastscaleInputError(f"chunk = {chunk!r} is out of range: must be a whole number >= 1")
    check_sweep_budget(spec, None if scheduler else nw)
    same = lambda p: _store_fingerprint(p) == fp
    parts_given = Path(store).expanduser()
    parts_given = parts_given.with_name(parts_given.name + ".parts")
    with claim(store, SWEEP_STORE, force, reuse=same) as c:
        store = c.path
        if same(store):  # this sweep's finished store: nothing to do
            return SweepRun(given, spec.n_cases, 0, 0, 0.0, 0, math.nan)
        parts = store.with_name(store.name + ".parts")
        man = _parts_state(parts, given)
        if man is not None:
            if man.get("fingerprint") != fp:
                if man and not force:
                    raise BlastscaleInputError(
                        f"out = {given!r}: the unfinished chunks in {str(parts_given)!r} belong to another sweep, "
                        "or to this one computed by other blastscale code (pass --force to discard them)"
                    )
                shutil.rmtree(parts)
            else:
                chunk = int(man["chunk"])  # resume with the chunking the chunks were written with
                for f in parts.glob(".chunk-*.tmp"):  # a chunk a killed writer had not finished
                    f.unlink()
        if chunk is None:
            chunk = default_chunk(spec, max(1, nw))
        created = not parts.exists()
        parts.mkdir(exist_ok=True)
        try:
            if created:
                write_file(
                    parts / "sweep.json", json.dumps({"fingerprint": fp, "chunk": int(chunk), "n_cases": spec.n_cases})
                )
            n = spec.n_cases
            bounds = [(i, s, min(n, s + chunk)) for i, s in enumerate(range(0, n, chunk))]
            todo = [b for b in bounds if not _chunk_path(parts, b[0]).exists()]
            done_cases = sum(b[2] - b[1] for b in bounds) - sum(b[2] - b[1] for b in todo)
        except BaseException:
            if created:  # nothing of this sweep is there yet: leave nothing
                shutil.rmtree(parts, ignore_errors=True)
            raise
        t0 = time.perf_counter()
        payload = spec.to_payload()
        if progress:
            progress(done_cases, n)
        used, dt = nw, time.perf_counter() - t0
        try:
            if todo:
                used, dt = run_chunks(
                    payload,
                    todo,
                    lambda i, result: _write_chunk(parts, i, result),
                    scheduler=scheduler,
                    workers=nw,
                    tick=lambda k: progress(done_cases + k, n) if progress else None,
                )
            _consolidate(spec, parts, len(bounds), c, metadata(spec, chunk))
        except BaseException as exc:  # interrupted or failed: finished chunks stay to resume from, else nothing;
            # a write fault (a full disk) of a sweep this run started leaves nothing either
            if not any(parts.glob("chunk-*.npz")) or (created and isinstance(exc, OSError)):
                with signals_held():
                    shutil.rmtree(parts, ignore_errors=True)
            raise
        shutil.rmtree(parts, ignore_errors=True)
    ran = sum(b - a for _, a, b in todo)
    return SweepRun(
        given, n, len(todo), len(bounds) - len(todo), dt, used, ran / dt * 60.0 if dt > 0 and ran else math.nan
    )


def unfinished_chunks(store) -> int:
    """How many finished chunks of an unfinished sweep wait beside ``store`` (0 when none)."""
    parts = Path(store).expanduser()
    parts = parts.with_name(parts.name + ".parts")
    return len(list(parts.glob("chunk-*.npz"))) if parts.is_dir() else 0


def _store_fingerprint(store: Path, any_layout: bool = False) -> Optional[str]:
    """The sweep fingerprint of a finished store (None: not a sweep store); a store of an older layout
    (one flat dataset) is not this sweep's finished store unless ``any_layout``."""
    if not (Path(store) / ".zattrs").is_file() and not (Path(store) / "zarr.json").is_file():
        return None
    zarr = require("zarr", "sweeps", "a sweep store")
    try:
        attrs = zarr.open_group(str(store), mode="r").attrs
        if any_layout or attrs.get("store_version") == STORE_VERSION:
            return attrs.get("fingerprint")
        return None
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

    require("zarr", "sweeps", "reading a sweep store")
    return xr.open_datatree(Path(store), engine="zarr", consolidated=True).load()
