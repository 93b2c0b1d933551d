"""The chunk store of a sweep: finished chunks wait in ``STORE.parts/`` (one ``.npz`` per chunk,
written atomically, beside a manifest ``sweep.json`` with the sweep's fingerprint); at the end they
are consolidated into the store (written to a partial folder beside it and renamed into place,
:mod:`blastscale.io.output`): an ``xarray.DataTree`` in Zarr format 2 with consolidated metadata,
so that ``xarray.open_datatree(STORE, engine="zarr")`` opens it without a warning.

A store below the sweeps: it writes, reads, lists and fingerprints plain arrays, manifests and
trees, and knows nothing of a sweep's cases; the sweep (budget, chunking, resume, the run) is driven
by :func:`blastscale.sweeps.run.run_sweep`, the tree assembled by :mod:`blastscale.sweeps.dataset`."""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import tempfile
from pathlib import Path
from typing import Iterator, Optional

import numpy as np

from .._extras import require
from .._hooks import pause_point, pausing
from .._validate import BlastscaleInputError
from .output import Claim, signals_held, write_file
from .targets import Kind

__all__ = [
    "SWEEP_STORE",
    "parts_of",
    "parts_manifest",
    "start_parts",
    "discard_parts",
    "remove_unfinished_writes",
    "has_chunk",
    "any_chunks",
    "write_chunk",
    "read_chunks",
    "consolidate",
    "store_fingerprint",
    "unfinished_chunks",
    "open_sweep",
]


def parts_of(store) -> Path:
    """The folder of a store's unfinished chunks: ``STORE.parts`` beside it."""
    path = Path(store).expanduser()
    return path.with_name(path.name + ".parts")


def _chunk_path(parts: Path, i: int) -> Path:
    return parts / f"chunk-{i:07d}.npz"


def has_chunk(parts: Path, i: int) -> bool:
    """Whether chunk ``i`` is finished (written whole) in ``parts``."""
    return _chunk_path(parts, i).exists()


def any_chunks(parts: Path) -> bool:
    """Whether ``parts`` holds any finished chunk."""
    return any(parts.glob("chunk-*.npz"))


def write_chunk(parts: Path, i: int, result: dict) -> None:
    """Atomically write chunk ``i`` (temp file + rename: a killed sweep leaves whole files only; a failed
    write leaves no temp file).

    Parameters
    ----------
    parts : Path
        The folder of the unfinished chunks (:func:`parts_of`).
    i : int
        Chunk index.
    result : dict
        ``start`` and ``stop`` (the case range) and ``values`` (name -> array over the chunk's cases).
    """
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


def read_chunks(parts: Path, n_chunks: int) -> Iterator[dict]:
    """The chunks ``0 .. n_chunks - 1`` of ``parts`` read back, in order (each as :func:`write_chunk`
    was given it, the values as arrays)."""
    return (_read_chunk(_chunk_path(parts, i)) for i in range(n_chunks))


def parts_manifest(parts: Path, given: str) -> "dict | None":
    """The manifest of the unfinished chunks beside a store: None when there are none; ``{}`` for a
    folder of chunks without a readable manifest; refused (one line) when ``parts`` is a file or a
    folder that holds something else than a sweep's chunks (``given``: the store as the user wrote it)."""
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


def start_parts(parts: Path, manifest: dict) -> bool:
    """The folder of the unfinished chunks, made with its ``manifest`` (``sweep.json``) when it is not
    there yet (nothing is left of it when that fails). Returns whether it was made now."""
    created = not parts.exists()
    parts.mkdir(exist_ok=True)
    if created:
        try:
            write_file(parts / "sweep.json", json.dumps(manifest))
        except BaseException:  # nothing of this sweep is there yet: leave nothing
            shutil.rmtree(parts, ignore_errors=True)
            raise
    return created


def remove_unfinished_writes(parts: Path) -> None:
    """Remove the temporary files of chunks a killed writer had not finished."""
    for f in parts.glob(".chunk-*.tmp"):
        f.unlink()


def discard_parts(parts: Path, strict: bool = False) -> None:
    """Remove the folder of the unfinished chunks: ``strict``, any failure raises; else with the signals
    held and failures ignored (a sweep's own clean-up)."""
    if strict:
        shutil.rmtree(parts)
        return
    with signals_held():
        shutil.rmtree(parts, ignore_errors=True)


def consolidate(tree, claim: Claim) -> None:
    """Write an assembled ``xarray.DataTree`` as the claimed store: into the claim's partial folder,
    renamed into place (:meth:`blastscale.io.output.Claim.staged`)."""
    with claim.staged() as tmp:
        pause_point("sweep:consolidating")
        # Zarr format 2: its consolidated metadata (.zmetadata) is part of the format (zarr 3 warns that
        # format 3's is not yet), so a reader opens the whole tree with one read and no warning
        tree.to_zarr(tmp, mode="w", consolidated=True, zarr_format=2)


def store_fingerprint(store, version: Optional[int] = None) -> Optional[str]:
    """The sweep fingerprint of a finished store (None: not a sweep store); with ``version``, None also for
    a store of another layout (its ``store_version`` attribute), which is not this sweep's finished store."""
    if not (Path(store) / ".zattrs").is_file() and not (Path(store) / "zarr.json").is_file():
        return None
    zarr = require("zarr", "sweeps", "a sweep store")
    try:
        attrs = zarr.open_group(str(store), mode="r").attrs
        if version is None or attrs.get("store_version") == version:
            return attrs.get("fingerprint")
        return None
    except Exception:  # not a zarr store (or unreadable): treated as foreign
        return None


#: What a sweep writes (:mod:`blastscale.io.output`): an existing folder is its own kind when it is a
#: blastscale sweep store (its fingerprint attribute), whatever the sweep and its layout.
SWEEP_STORE = Kind("a blastscale sweep store (no sweep fingerprint)", lambda p: store_fingerprint(p) is not None)


def unfinished_chunks(store) -> int:
    """How many finished chunks of an unfinished sweep wait beside ``store`` (0 when none)."""
    parts = parts_of(store)
    return len(list(parts.glob("chunk-*.npz"))) if parts.is_dir() else 0


def open_sweep(store):
    """A sweep store read back into memory.

    Parameters
    ----------
    store : str or path
        The Zarr store written by :func:`blastscale.sweeps.run.run_sweep`.

    Returns
    -------
    xarray.DataTree
        The groups of :mod:`blastscale.sweeps.dataset`; a flat key's values over the case grid:
        :func:`blastscale.sweeps.layout.select`.
    """
    import xarray as xr

    require("zarr", "sweeps", "reading a sweep store")
    return xr.open_datatree(Path(store), engine="zarr", consolidated=True).load()
