"""The fingerprint of blastscale's own code, for results that are reused from one run to the next.

A resumed sweep reuses its finished chunks, and ``reproduce`` skips the items already done: both are
results computed by some blastscale code, valid for that code only. Their keys hold
:func:`code_fingerprint`, so that after a ``git pull`` into an editable install (the version unchanged)
nothing computed by the old code is taken for a result of the new one (issue #30; the compiled
kernels' own caches are keyed in :mod:`blastscale._jit`).
"""

from __future__ import annotations

import functools
import hashlib
from pathlib import Path

from . import __version__

__all__ = ["code_files", "code_fingerprint"]

_ROOT = Path(__file__).resolve().parent  # the blastscale package folder


def code_files(root: Path = _ROOT) -> list:
    """Every file of the package under ``root`` that its code is made of: sources and package data
    (scenarios, coefficient tables, templates), not Python's or numba's caches (``__pycache__``) nor
    hidden files; sorted."""
    return sorted(
        p
        for p in root.rglob("*")
        if p.is_file()
        and "__pycache__" not in p.relative_to(root).parts
        and not any(s.startswith(".") for s in p.relative_to(root).parts)
        and p.suffix not in (".pyc", ".pyo")
    )


@functools.cache
def code_fingerprint(root: Path = _ROOT) -> str:
    """SHA-256 (hex) of the blastscale version and of the path and bytes of every :func:`code_files`
    (memoised per process: 10-60 ms for the ~175 files on the 2-core machine)."""
    h = hashlib.sha256(f"blastscale {__version__}\0".encode())
    for f in code_files(root):
        h.update(f.relative_to(root).as_posix().encode() + b"\0")
        h.update(hashlib.sha256(f.read_bytes()).digest())
    return h.hexdigest()
