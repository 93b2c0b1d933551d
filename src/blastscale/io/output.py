"""The one way blastscale writes an output: a result folder, a sweep store, a reproduce folder, a file.

Every writer goes through :func:`claim` (and, for what appears at once, :meth:`Claim.staged`):

1. **Checked before any work** (:func:`check_target`, in :mod:`.targets` and re-exported here): the
   parent folder must exist and be a folder, the target must not be a file (for a folder) nor hold the
   current folder; an existing target is refused without ``force``, and with ``force`` replaced only
   when it is empty or of the writer's own :class:`Kind` (a result folder's marker file, a sweep
   store's fingerprint): a user's folder is never deleted.
2. **Locked**: an exclusive lock (``filelock``: ``flock`` on POSIX, ``msvcrt.locking`` on Windows) on
   ``.NAME.lock`` beside the target (it holds the writer's pid and host); a second writer of the same
   target gets one line (:class:`~blastscale._validate.BlastscaleInputError`, exit 2). The lock file is
   removed, while held, when the writer ends.
3. **Stale work cleaned**: holding the lock, every partial folder of this target (``.NAME.partial-*``)
   belongs to a writer that is gone (killed with ``kill -9``, a power cut) and is removed; so are the
   partial folders of other targets in the same folder whose writer (pid in the name) is dead on this
   host. An old result set aside by a replacement that was killed half-way is put back.
4. **Staged**: a folder is written into ``.NAME.partial-PID-HOST-XXXXXXXX`` and renamed into place at
   the end, with SIGINT, SIGTERM and SIGHUP held back for the few calls that must not be split; any
   exception (Ctrl-C and the CLI's SIGTERM/SIGHUP included) removes the partial folder. A file is
   written to a unique temporary sibling and renamed (:func:`write_file`).

Every ``OSError`` (missing folder, read-only folder, ``/proc``, a full disk) becomes one line naming
the target and the cause, with nothing left behind.
"""

from __future__ import annotations

import contextlib
import os
import re
import shutil
import signal
import socket
import tempfile
from pathlib import Path
from typing import Callable, Iterator, Optional

from filelock import FileLock, Timeout

from .._hooks import pause_point
from .._validate import BlastscaleInputError
from .targets import Kind, check_name_lengths, check_target, fault

__all__ = ["Claim", "claim", "write_file", "signals_held", "HELD_SIGNALS", "tree_size"]

#: Signals held back while a rename must not be split (delivered right after).
HELD_SIGNALS = tuple(getattr(signal, s) for s in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, s))


def _host() -> str:
    return re.sub(r"[^A-Za-z0-9_.]", "_", socket.gethostname())[:40] or "host"


@contextlib.contextmanager
def signals_held() -> Iterator[None]:
    """SIGINT, SIGTERM and SIGHUP held back (delivered afterwards) around calls that must not be split."""
    can = hasattr(signal, "pthread_sigmask")
    old = signal.pthread_sigmask(signal.SIG_BLOCK, set(HELD_SIGNALS)) if can else None
    try:
        yield
    finally:
        if can:
            signal.pthread_sigmask(signal.SIG_SETMASK, old)


_PARTIAL = re.compile(r"^\.(?P<name>.+)\.partial-(?P<pid>\d+)-(?P<host>[A-Za-z0-9_.]+)-[a-z0-9_]{8}$")


def _pid_dead(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    except OSError:  # alive, another user's
        return False
    return False


def _remove(path: Path) -> None:
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path, ignore_errors=True)
    else:
        with contextlib.suppress(OSError):
            path.unlink()


def clean_stale(target: Path) -> list[Path]:
    """Remove what dead writers left (module docstring, step 3); called holding ``target``'s lock.
    Returns what was removed."""
    parent, name, host = target.parent, target.name, _host()
    removed = []
    try:
        entries = list(parent.iterdir())
    except OSError:
        return removed
    olds = sorted(e for e in entries if e.name.startswith(f".{name}.old-"))
    if olds and not target.exists():  # killed between setting the old result aside and renaming the new one
        with contextlib.suppress(OSError):
            os.rename(olds.pop(), target)
    for e in entries:
        m = _PARTIAL.match(e.name)
        mine = e.name.startswith(f".{name}.partial-") or e in olds
        theirs = m is not None and m["name"] != name and m["host"] == host and _pid_dead(int(m["pid"]))
        if (mine or theirs) and e.exists():
            _remove(e)
            removed.append(e)
    return removed


class Claim:
    """A locked output target (:func:`claim`): ``path`` (absolute), ``given`` (as the user wrote it)."""

    def __init__(self, path: Path, given: str, kind: Kind, force: bool, name: str = "out"):
        self.path, self.given, self.kind, self.force, self.name = path, given, kind, force, name

    def fault(self, exc: OSError) -> BlastscaleInputError:
        return fault(self.given, exc, name=self.name)

    @contextlib.contextmanager
    def staged(self, before_commit=None, after_commit=None) -> Iterator[Path]:
        """A partial folder to write into, renamed to the target at the end (replacing a folder of the
        target's own kind, checked again now). ``before_commit()`` (may raise to abandon the folder) and
        ``after_commit()`` run with the signals held, just before and just after the rename."""
        dest = self.path
        try:
            tmp = Path(tempfile.mkdtemp(prefix=f".{dest.name}.partial-{os.getpid()}-{_host()}-", dir=dest.parent))
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(tmp, 0o777 & ~umask)  # mkdtemp makes it 0700; a result folder is an ordinary folder
        except OSError as exc:
            raise self.fault(exc) from None
        try:
            yield tmp
            with signals_held():
                if before_commit is not None:
                    before_commit()
                trash = None
                if dest.exists() or dest.is_symlink():
                    if dest.is_dir() and any(dest.iterdir()) and not self.kind.is_own(dest):
                        raise BlastscaleInputError(
                            f"{self.name} = {self.given!r} was filled by something else while "
                            f"it ran and is not {self.kind.noun}: nothing replaced"
                        )
                    trash = dest.with_name(f".{dest.name}.old-{os.getpid()}")
                    os.rename(dest, trash)
                    pause_point("output:between-renames")  # only kill -9 can stop it here (signals held)
                os.rename(tmp, dest)
                if trash is not None:
                    _remove(trash)
                if after_commit is not None:
                    after_commit()
        except OSError as exc:  # disk full, permissions changed underneath: one line, nothing left
            with signals_held():
                _remove(tmp)
            raise self.fault(exc) from None
        except BaseException:
            with signals_held():
                _remove(tmp)
            raise


#: Tries to take a lock whose file vanished under us (its holder finished and removed it) before saying "busy".
_LOCK_TRIES = 5


def _holder(path: Path) -> Optional[list]:
    """The words of a lock file (its holder's pid and host); None when it is not there to read (gone, or
    unreadable: Windows locks the file's first byte against every other handle)."""
    try:
        return path.read_bytes()[:200].decode("utf-8", "replace").split()
    except OSError:
        return None


def _size(path: Path) -> int:
    try:
        return path.stat().st_size
    except OSError:
        return -1


def _lock(target: Path, given: str, name: str = "out") -> FileLock:
    """Take the exclusive lock of ``target`` (``.NAME.lock`` beside it, through ``filelock``: ``flock`` on
    POSIX, ``msvcrt.locking`` on Windows), or raise one line naming the writer holding it."""
    path = target.with_name(f".{target.name}.lock")
    for _ in range(_LOCK_TRIES):
        # filelock (>= 3.32) opens the file before locking it and, once locked, drops a file that its holder
        # removed meanwhile (st_nlink 0) as contention: a lock taken is the one the path names
        lock = FileLock(str(path), timeout=0, thread_local=False)
        try:
            lock.acquire()
        except Timeout:
            holder = _holder(path)
            if holder is None:  # gone: its holder just finished; or it cannot be created (the cause said)
                try:
                    os.close(os.open(path, os.O_RDWR | os.O_CREAT, 0o644))
                except OSError as exc:
                    raise fault(given, exc, name=name) from None
                continue
            who = f" (pid {holder[0]} on {holder[1]})" if len(holder) >= 2 else ""
            raise BlastscaleInputError(
                f"{name} = {given!r} is being written by another blastscale process{who}: "
                "wait for it to finish or choose another --out"
            ) from None
        except OSError as exc:
            raise fault(given, exc, name=name) from None
        # the holder for a second writer's message, in the file filelock left empty (Windows: not readable by
        # others; a soft lock, where the system has no file locks, writes its own)
        if os.name != "nt" and _size(path) == 0:
            try:
                fd = os.open(path, os.O_WRONLY)
                try:
                    os.write(fd, f"{os.getpid()} {_host()}\n".encode())
                finally:
                    os.close(fd)
            except OSError as exc:  # a full disk: the lock file (ours, held) goes, nothing is left
                _unlock(target, lock)
                raise fault(given, exc, name=name) from None
        return lock
    raise BlastscaleInputError(
        f"{name} = {given!r} is being written by another blastscale process: "
        "wait for it to finish or choose another --out"
    )


def _unlock(target: Path, lock: FileLock) -> None:
    with contextlib.suppress(OSError):
        os.unlink(target.with_name(f".{target.name}.lock"))  # while held: a waiting writer sees a new file
    lock.release()


@contextlib.contextmanager
def claim(
    out, kind: Kind, force: bool = False, reuse: Optional[Callable[[Path], bool]] = None, name: str = "out"
) -> Iterator[Claim]:
    """Check ``out`` (:func:`check_target`), lock it, clean dead writers' partial work; yields a
    :class:`Claim`. Any ``OSError`` inside becomes one line naming ``name = 'out'``."""
    target = check_target(out, kind, force, reuse, name)
    lock = _lock(target, str(out), name)
    try:
        clean_stale(target)
        check_target(out, kind, force, reuse, name)  # again, under the lock: a writer may have finished meanwhile
        yield Claim(target, str(out), kind, force, name)
    except OSError as exc:
        raise fault(str(out), exc, name=name) from None
    finally:
        with signals_held():
            _unlock(target, lock)


def write_file(path, data: "str | bytes", what: str = "out", raw: bool = False) -> Path:
    """Write a file atomically: a unique temporary sibling (removed on any failure) renamed into place;
    an ``OSError`` becomes one line naming ``what = path`` (``raw``: the ``OSError`` itself, for a file
    inside a claimed output, whose :func:`claim` names the output as the user gave it)."""
    path = Path(path)
    check_name_lengths(path, what)
    payload = data.encode("utf-8") if isinstance(data, str) else data
    tmp = None
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.partial-{os.getpid()}-{_host()}-", dir=path.parent)
        with os.fdopen(fd, "wb") as fh:
            fh.write(payload)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, path)
        tmp = None
    except OSError as exc:
        if raw:
            raise
        raise fault(str(path), exc, name=what) from None
    finally:
        if tmp is not None:
            with signals_held(), contextlib.suppress(OSError):
                os.unlink(tmp)
    return path


def tree_size(path) -> int:
    """Bytes of a file or of every file under a folder."""
    p = Path(path)
    if p.is_file():
        return p.stat().st_size
    return sum(f.stat().st_size for f in p.rglob("*") if f.is_file())
