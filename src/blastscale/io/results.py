"""Result files: JSON (strict, NaN -> null), tidy CSV of the histories, provenance, and an
output folder that appears complete or not at all.

:func:`output_folder` writes into a temporary sibling folder and renames it into place at the
end, through the one output mechanism of :mod:`blastscale.io.output` (checks, a lock, stale partial
work removed; an error, Ctrl-C, SIGTERM or SIGHUP removes the temporary folder), so a reader never
sees a half-written result.
"""

from __future__ import annotations

import contextlib
import datetime as _dt
import importlib.metadata as md
import json
import math
import platform
import subprocess
from pathlib import Path
from typing import Any, Iterator

from .. import __version__
from .output import claim, write_file
from .targets import Kind, check_target

__all__ = [
    "jsonable",
    "write_json",
    "versions",
    "git_commit",
    "provenance",
    "output_folder",
    "check_output_folder",
    "result_kind",
    "write_atomic",
    "LEGACY_KEYS",
    "legacy_name",
    "with_legacy_keys",
]

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
    """Write a file through a unique temporary sibling renamed into place (permissions from the umask,
    like any file the user creates; nothing left on failure). An ``OSError`` propagates: the output
    it belongs to (:func:`blastscale.io.output.claim`) turns it into one line naming that output."""

    write_file(path, data, raw=True)


def write_json(path: "str | Path", obj: Any) -> None:
    """Write ``obj`` as indented strict JSON (:func:`jsonable`), atomically."""
    write_atomic(path, json.dumps(jsonable(obj), indent=2) + "\n")


def versions() -> dict:
    """Versions of blastscale, Python and the numerical libraries that shape the results."""

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
        dirty = subprocess.run(
            ["git", "status", "--porcelain", "--untracked-files=no"],
            cwd=here,
            capture_output=True,
            text=True,
            timeout=5,
        )
        return head.stdout.strip() + ("+dirty" if dirty.stdout.strip() else "")
    except (OSError, subprocess.SubprocessError):
        return None


def provenance() -> dict:
    """``versions``, ``git_commit`` and an ISO ``timestamp`` (UTC)."""
    return {
        "versions": versions(),
        "git_commit": git_commit(),
        "timestamp": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
    }


def _is_result_folder(folder: Path, markers: tuple = (MARKER,)) -> bool:
    """Whether ``folder`` is a blastscale result: its marker file, and for ``summary.json`` one that
    blastscale wrote (it names blastscale's version)."""
    for m in markers:
        f = folder / m
        if not f.is_file():
            continue
        if m != MARKER:
            return True
        try:
            return "blastscale" in (json.loads(f.read_text(encoding="utf-8")).get("versions") or {})
        except (OSError, ValueError, AttributeError):
            return False
    return False


def result_kind(markers: tuple = (MARKER,)):
    """The :class:`~blastscale.io.output.Kind` of a blastscale result folder (``markers``: its marker files)."""

    return Kind(
        f"a blastscale result folder (no blastscale {' or '.join(markers)})", lambda p: _is_result_folder(p, markers)
    )


def check_output_folder(out: "str | Path", force: bool = False, markers: tuple = (MARKER,)) -> Path:
    """Check, before any work, that ``out`` can become a result folder; returns it absolute
    (:func:`blastscale.io.output.check_target`: the parent must exist; an existing folder is replaced
    only with ``force``, and only when empty or a blastscale result, never a user's folder)."""

    return check_target(out, result_kind(markers), force)


@contextlib.contextmanager
def output_folder(
    out: "str | Path", force: bool = False, before_commit=None, after_commit=None, markers: tuple = (MARKER,)
) -> Iterator[Path]:
    """A partial folder beside ``out`` to write into, renamed to ``out`` on success
    (:mod:`blastscale.io.output`: checked, locked against a second writer, stale partial folders of
    dead runs removed; on any exception, Ctrl-C included, the partial folder is removed and the
    exception propagates, an ``OSError`` as one line). ``before_commit()`` (may raise to abandon the
    folder) and ``after_commit()`` run with SIGINT, SIGTERM and SIGHUP held back, just before and just
    after the rename."""

    with claim(out, result_kind(markers), force) as c, c.staged(before_commit, after_commit) as tmp:
        yield tmp
