"""Step 1 of the one output mechanism (:mod:`.output`): an output target checked before any work.

What a writer writes (:class:`Kind`: a noun for messages and how to recognise its own folders), the check of a
target (:func:`check_target`: the parent folder exists and is a folder, the target is not a file for a folder nor
holds the current folder, an existing one is refused without ``force`` and replaced with it only when empty or of
the writer's own kind), the check of name lengths against the file system (:func:`check_name_lengths`) and the one
line for an ``OSError`` (:func:`fault`). Re-exported by :mod:`.output`.
"""

from __future__ import annotations

import errno
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Optional

from .._validate import BlastscaleInputError

__all__ = ["Kind", "NAME_ROOM", "check_name_lengths", "check_target", "fault"]


@dataclass(frozen=True)
class Kind:
    """What a writer writes: ``noun`` for messages ("a blastscale result folder") and ``is_own(path)``:
    whether an existing, non-empty folder is one (``force`` replaces only those and empty folders)."""

    noun: str
    is_own: Callable[[Path], bool]
    folder: bool = True


def fault(out, exc: OSError, verb: str = "cannot be written", name: str = "out") -> BlastscaleInputError:
    """One line for an output fault: the target as given (``name = 'path'``), what failed and the system's
    reason."""
    why = exc.strerror or str(exc)
    if exc.errno == errno.ENOSPC:
        why = "no space left on the device"
    return BlastscaleInputError(f"{name} = {str(out)!r} {verb}: {why}")


#: Characters kept free in a file name for blastscale's temporary siblings (``.NAME.partial-PID-HOST-XXXXXXXX``,
#: ``.NAME.lock``, ``.NAME.old-PID``; the host name is cut at 40 characters).
NAME_ROOM = 80


def check_name_lengths(path: Path, name: str = "out") -> None:
    """Refuse, in one line, a path with a folder or file name longer than the file system allows (its
    ``NAME_MAX``, 255 bytes on most); the last name must leave :data:`NAME_ROOM` bytes for the temporary
    siblings of an atomic write."""
    up = next((q for q in [path.absolute(), *path.absolute().parents] if _exists(q)), Path("/"))
    try:
        most = os.pathconf(up, "PC_NAME_MAX")
    except (OSError, ValueError, AttributeError):
        most = 255
    for i, part in enumerate(reversed(path.parts)):
        limit = most - NAME_ROOM if i == 0 else most
        n = len(os.fsencode(part))
        if n > limit:
            which = "its file or folder name" if i == 0 else f"the folder name {part[:20]!r}..."
            raise BlastscaleInputError(
                f"{name} = {str(path)[:60]!r}... is too long: {which} has {n} bytes, the "
                f"most is {limit} (the file system allows {most}"
                f"{f', blastscale keeps {NAME_ROOM} for its temporary files' if i == 0 else ''})"
            )


def _exists(p: Path) -> bool:
    try:
        return p.exists()
    except OSError:
        return False


def check_target(
    out, kind: Kind, force: bool = False, reuse: Optional[Callable[[Path], bool]] = None, name: str = "out"
) -> Path:
    """Check, before any work, that ``out`` can be written as ``kind``; returns it absolute.

    ``reuse(path)``: an existing target it accepts is kept and written into (a reproduce folder, a
    finished sweep store of the same sweep), without ``force``. Raises one line otherwise.
    """
    given = str(out)
    p = Path(out).expanduser()
    check_name_lengths(p, name)
    parent = p.absolute().parent
    a = parent.resolve() / p.name if p.name not in ("", ".", "..") else p.resolve()
    up = next((q for q in [parent, *parent.parents] if q.exists() or q.is_symlink()), None)
    if up is not None and not up.is_dir():
        raise BlastscaleInputError(f"{name} = {given!r}: {str(up)!r} is a file, not a folder")
    if not parent.exists():
        raise BlastscaleInputError(f"{name} = {given!r}: the folder {str(parent)!r} does not exist (create it first)")
    if a.is_symlink() and not a.exists():
        raise BlastscaleInputError(f"{name} = {given!r} is a broken link: remove it or choose another path")
    if not kind.folder:
        if a.is_dir():
            raise BlastscaleInputError(f"{name} = {given!r} is a folder: give the path of a file")
        return a
    if a.exists() and not a.is_dir():
        raise BlastscaleInputError(f"{name} = {given!r} is a file, not a folder: give the path of a new folder")
    if a.is_dir():
        cwd = Path.cwd().resolve()
        if a.resolve() == cwd or a.resolve() in cwd.parents:
            raise BlastscaleInputError(f"{name} = {given!r} holds the current folder: refused")
        try:
            empty = not any(a.iterdir())
            own = empty or kind.is_own(a)
        except OSError as exc:
            raise fault(given, exc, "cannot be read", name) from None
        if reuse is not None and reuse(a):
            return a
        if not own:
            raise BlastscaleInputError(
                f"{name} = {given!r} exists and is not {kind.noun}: refused"
                f"{', even with --force' if force else ''} (choose another --out)"
            )
        if not force:
            raise BlastscaleInputError(f"{name} = {given!r} exists: refused (give --force to replace it)")
    return a
