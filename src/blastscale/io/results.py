"""Result files: JSON (strict, NaN -> null), tidy CSV of the histories, provenance, and an
output folder that appears complete or not at all.

:func:`output_folder` writes into a temporary sibling folder and renames it into place at the
end; an error or Ctrl-C (``KeyboardInterrupt``) removes the temporary folder, so a reader never
sees a half-written result. The rename itself runs with SIGINT blocked.
"""

from __future__ import annotations

import contextlib
import datetime as _dt
import json
import math
import os
import platform
import shutil
import signal
import subprocess
import tempfile
from pathlib import Path
from typing import Any, Iterator

from .. import __version__
from .._validate import BlastscaleInputError

__all__ = ["jsonable", "write_json", "versions", "git_commit", "provenance", "output_folder",
           "check_output_folder", "write_atomic", "LEGACY_KEYS", "legacy_name", "with_legacy_keys"]

#: Marker file of a blastscale output folder (``--force`` replaces only such folders or empty ones).
MARKER = "summary.json"


def jsonable(obj: Any) -> Any:
    """``obj`` with numpy scalars/arrays converted, NaN -> None and +-inf -> "inf"/"-inf" (strict JSON)."""
    if isinstance(obj, dict):
        return {str(k): jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [jsonable(v) for v in obj]
    if hasattr(obj, "tolist") and getattr(obj, "ndim", 0) > 0:  # numpy arrays
        return jsonable(obj.tolist())
    if hasattr(obj, "item") and callable(obj.item):  # numpy scalars
        obj = obj.item()
    if isinstance(obj, float) and not math.isfinite(obj):
        return None if math.isnan(obj) else ("inf" if obj > 0 else "-inf")
    return obj


#: The deprecated names of result keys (CHANGELOG.md, docs/glossary.md): {(engine, new key): old key}. An
#: engine of None: in any part of a result; "planar" or "3d": in that engine's part only (the section
#: ``planar`` or ``3d`` of a study's summary, the first part of a flat ``scalars`` key, or the engine the
#: command ran, :func:`with_legacy_keys`). ``--json`` and ``summary.json`` print each old key beside its
#: new one; everything else (sweep stores, the Python API) knows the new names only.
LEGACY_KEYS: dict = {
    (None, "blast_model"): "model",
    (None, "pulse_shape"): "pulse",
    (None, "specimen_material"): "model_material",
    (None, "first_peak_ratio_error"): "peak_ratio_error",
    ("planar", "collapsed"): "overturned",
    ("planar", "collapse_time_s"): "overturn_time_s",
    ("planar", "collapse_time_diff_s"): "overturn_time_diff_s",
    ("planar", "max_rotation_rad"): "max_angle_rad",
    ("planar", "max_abs_rotation_diff_rad"): "max_abs_angle_diff_rad",
    ("planar", "max_abs_rotation_diff_to_tipping_rad"): "max_abs_angle_diff_to_tipping_rad",
    ("planar", "max_rotation_ratio"): "max_angle_ratio",
    ("planar", "first_peak_ratio"): "peak_ratio",
    ("3d", "collapsed"): "overturned",
    ("3d", "collapse_time_s"): "overturn_time_s",
    ("3d", "max_rotation_rad"): "max_tilt_rad",
}

#: Keys of a result whose content belongs to one engine.
_ENGINE_SECTIONS = {"planar": "planar", "3d": "3d", "ensemble": "3d"}


def _old_name(key: str, engine: "str | None") -> "str | None":
    """The deprecated name of ``key`` in ``engine``'s part of a result, or None. A flat dotted key
    (``planar.model.collapsed``) is renamed part by part, its engine read from its first part."""
    if "." not in key:
        return LEGACY_KEYS.get((engine, key)) or LEGACY_KEYS.get((None, key))
    parts = key.split(".")
    engine = _ENGINE_SECTIONS.get(parts[0], engine)
    old = [LEGACY_KEYS.get((engine, p)) or LEGACY_KEYS.get((None, p)) or p for p in parts]
    return ".".join(old) if old != parts else None


def legacy_name(key: str, engine: "str | None" = None) -> str:
    """The deprecated name of a result key (:data:`LEGACY_KEYS`), or ``key`` itself when it was not
    renamed: for outputs whose *value* names a key (``similarity-map --json``'s ``error_definition``)."""
    return _old_name(key, engine) or key


def with_legacy_keys(obj: Any, engine: "str | None" = None) -> Any:
    """``obj`` with, beside each renamed key, its deprecated name carrying the same value
    (:data:`LEGACY_KEYS`), in nested dicts and lists and in flat dotted keys; an existing key is
    never replaced (the design's ``model`` section keeps its meaning beside ``blast_model``).

    Parameters
    ----------
    obj : dict, list or value
        A result as printed by ``--json`` or written to ``summary.json``.
    engine : {None, "planar", "3d"}
        The engine of the result's outcome keys (the command's); within it a section ``planar``
        or ``3d`` (``ensemble``: 3d) sets its own.

    Returns
    -------
    The same structure with the old keys added (a new dict; ``obj`` is not modified).
    """
    if isinstance(obj, list):
        return [with_legacy_keys(v, engine) for v in obj]
    if not isinstance(obj, dict):
        return obj
    out: dict = {}
    for k, v in obj.items():
        sub = _ENGINE_SECTIONS.get(k, engine) if isinstance(k, str) else engine
        out[k] = with_legacy_keys(v, sub)
        old = _old_name(k, engine) if isinstance(k, str) else None
        if old is not None and old not in obj and old not in out:
            out[old] = out[k]
    return out


def write_atomic(path: "str | Path", data: "str | bytes") -> None:
    """Write a file through a temporary sibling renamed into place (permissions from the umask,
    like any file the user creates)."""
    path = Path(path)
    tmp = path.with_name(f".{path.name}.partial")
    with open(tmp, "wb") as fh:
        fh.write(data.encode("utf-8") if isinstance(data, str) else data)
    os.replace(tmp, path)


def write_json(path: "str | Path", obj: Any) -> None:
    """Write ``obj`` as indented strict JSON (:func:`jsonable`), atomically."""
    write_atomic(path, json.dumps(jsonable(obj), indent=2) + "\n")


def versions() -> dict:
    """Versions of blastscale, Python and the numerical libraries that shape the results."""
    import importlib.metadata as md

    out = {"blastscale": __version__, "python": platform.python_version()}
    for pkg in ("numpy", "scipy", "numba", "mujoco", "xarray", "pydantic"):
        try:
            out[pkg] = md.version(pkg)
        except md.PackageNotFoundError:
            out[pkg] = None
    return out


def git_commit() -> str | None:
    """The git commit of the blastscale source tree (``+dirty`` when modified), or None when it
    is not a git checkout or git is missing."""
    here = Path(__file__).resolve().parent
    try:
        head = subprocess.run(["git", "rev-parse", "HEAD"], cwd=here, capture_output=True, text=True, timeout=5)
        if head.returncode != 0:
            return None
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], cwd=here,
                               capture_output=True, text=True, timeout=5)
        return head.stdout.strip() + ("+dirty" if dirty.stdout.strip() else "")
    except (OSError, subprocess.SubprocessError):
        return None


def provenance() -> dict:
    """``versions``, ``git_commit`` and an ISO ``timestamp`` (UTC)."""
    return {"versions": versions(), "git_commit": git_commit(),
            "timestamp": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")}


def check_output_folder(out: "str | Path", force: bool = False, markers: tuple = (MARKER,)) -> Path:
    """Check, before any work, that ``out`` can become a result folder; returns it absolute.

    Refused (one line): an existing file; an existing folder without ``force``; with ``force``
    a folder that is neither empty nor a blastscale result (no ``summary.json``), or one that
    holds the current directory.
    """
    p = Path(out).expanduser()
    a = p.resolve()
    if a.exists() and not a.is_dir():
        raise BlastscaleInputError(f"out = {str(out)!r} is a file, not a folder: give the path of a new folder")
    if a.is_dir():
        if not force:
            raise BlastscaleInputError(f"out = {str(out)!r} exists: refused (give --force to replace it)")
        cwd = Path.cwd().resolve()
        if a == cwd or a in cwd.parents:
            raise BlastscaleInputError(f"out = {str(out)!r} holds the current folder: refused even with --force")
        if any(a.iterdir()) and not any((a / m).is_file() for m in markers):
            raise BlastscaleInputError(
                f"out = {str(out)!r} is not a blastscale result folder (no {' or '.join(markers)}): --force "
                "replaces only those or empty folders")
    return a


@contextlib.contextmanager
def _sigint_blocked() -> Iterator[None]:
    """SIGINT held back (delivered afterwards) while a few file-system calls must not be split."""
    can = hasattr(signal, "pthread_sigmask")
    if can:
        old = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        if can:
            signal.pthread_sigmask(signal.SIG_SETMASK, old)


@contextlib.contextmanager
def output_folder(out: "str | Path", force: bool = False, before_commit=None, after_commit=None,
                  markers: tuple = (MARKER,)) -> Iterator[Path]:
    """A temporary sibling folder of ``out`` to write into, renamed to ``out`` on success.

    On any exception (Ctrl-C included) the temporary folder is removed and the exception
    propagates; an existing ``out`` is replaced only with ``force`` (:func:`check_output_folder`),
    after the new folder is complete (``markers``: the files that make a folder replaceable). ``before_commit()`` (may raise to abandon the folder) and
    ``after_commit()`` run with SIGINT held back, just before and just after the rename.
    """
    dest = check_output_folder(out, force, markers)
    try:
        dest.parent.mkdir(parents=True, exist_ok=True)
        tmp = Path(tempfile.mkdtemp(prefix=f".{dest.name}.partial-", dir=dest.parent))
    except OSError as exc:
        raise BlastscaleInputError(
            f"out = {str(out)!r} cannot be created: {exc.strerror or exc} ({str(dest.parent)!r})") from None
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(tmp, 0o777 & ~umask)  # mkdtemp makes it 0700; a result folder is an ordinary folder
    try:
        yield tmp
        with _sigint_blocked():
            if before_commit is not None:
                before_commit()
            trash = None
            if dest.exists():
                trash = dest.with_name(f".{dest.name}.old-{os.getpid()}")
                os.rename(dest, trash)
            os.rename(tmp, dest)
            if trash is not None:
                shutil.rmtree(trash, ignore_errors=True)
            if after_commit is not None:
                after_commit()
    except OSError as exc:  # disk full, permissions changed underneath: one line, nothing left
        with _sigint_blocked():
            shutil.rmtree(tmp, ignore_errors=True)
        raise BlastscaleInputError(f"out = {str(out)!r} cannot be written: {exc.strerror or exc}") from None
    except BaseException:
        with _sigint_blocked():
            shutil.rmtree(tmp, ignore_errors=True)
        raise
