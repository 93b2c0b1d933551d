"""numba's ``njit`` for blastscale's kernels, with on-disk caches that cannot outlive their source.

numba's own cache (``cache=True``) keys a compiled function on the source file *of that function
only* (a SHA-256 of its bytes in numba 0.68, its mtime and size before): a kernel that calls and
inlines helpers from other files keeps its old machine code after those helpers change (numba's
"Notes on Caching": "Cache invalidation fails to recognize changes in symbols defined in a different
file"; globals are frozen as constants at compile time). Issue #30: doubling the load in
``rocking/_load.py`` left ``rock`` of the paper's block at 0.0687 rad (stands) instead of 1.5708 rad
(falls) until ``__pycache__`` was deleted.

Here every function decorated through :func:`njit` in a blastscale module is cached by
:class:`SourceKeyedLocator`, a numba cache locator (a subclass of numba's documented
``_CacheLocator``, put first in ``CacheImpl._locator_classes``; it declines every file outside
blastscale, so other libraries' caches are untouched). Its key is the SHA-256 of the blastscale
version, the numba version and the bytes of the function's own module *and of every blastscale module
that module imports, transitively* (found by reading the import statements), so any change to a
helper, a constant or this file gives a new key. Each key has its own folder::

    <module dir>/__pycache__/numba/<module>-<first 16 hex digits of the key>/

(``$NUMBA_CACHE_DIR/<dir>_<sha1 of the dir path>/numba/...`` when ``NUMBA_CACHE_DIR`` is set; numba's
user-wide cache folder when the source folder is read-only.) The key is also the index's source stamp,
so an index of another key is never read. A stale folder is never looked at; when a new key's folder
is made, the folders of that module beyond the :data:`KEEP` most recently used are removed, with
numba's own files of the module left in ``__pycache__`` by versions before this one. Going back to an
earlier source (``git checkout``, an undone edit) finds its folder again while it is among those kept.
Setting ``NUMBA_CACHE_LOCATOR_CLASSES`` overrides every locator, this one included (then numba's
own keying applies).
"""

from __future__ import annotations

import functools
import hashlib
import os
import re
import shutil
from pathlib import Path

import numba
from numba import njit
from numba.core import config
from numba.core.caching import CacheImpl, _CacheLocator
from numba.misc.appdirs import AppDirs

from . import __version__

__all__ = ["KEEP", "SourceKeyedLocator", "is_cached", "kernel_sources", "njit", "source_key"]

#: Key folders kept per module (the most recently used); older ones are removed when a new one is made.
KEEP = 4
_ROOT = Path(os.path.realpath(Path(__file__).parent))  # the blastscale package folder
_FOLDER = "numba"


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(_ROOT.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _module_file(name: str) -> Path | None:
    """The source file of the blastscale module ``name`` (None: not a blastscale module)."""
    parts = name.split(".")
    if parts[0] != _ROOT.name:
        return None
    base = _ROOT.joinpath(*parts[1:])
    for cand in (base.with_suffix(".py"), base / "__init__.py"):
        if cand.is_file():
            return cand
    return None


#: An import statement, anywhere (module level, in a function, in a docstring: a match too many only
#: adds a file to the key): ``from <dots><module> import <names>`` or ``import <modules>``.
_IMPORT = re.compile(
    r"^[ \t]*(?:from[ \t]+(\.*)([\w.]*)[ \t]+import[ \t]+(\([^)]*\)|[^\n#]*)|import[ \t]+([^\n#]*))", re.MULTILINE
)


def _imported(path: Path) -> set:
    """The blastscale source files ``path`` imports (relative imports resolved; a name imported
    from a package counts when it is a submodule). A scan of the text, not a parse: ~50x faster."""
    mod = _module_name(path)
    pkg = mod.split(".") if path.name == "__init__.py" else mod.split(".")[:-1]
    found = set()
    for dots, module, names, plain in _IMPORT.findall(path.read_text(encoding="utf-8")):
        if plain:
            targets = [n.split(" as ")[0].strip() for n in plain.split(",")]
        else:
            base = ".".join(pkg[: len(pkg) - len(dots) + 1] + ([module] if module else [])) if dots else module
            targets = [base] + [f"{base}.{n.split(' as ')[0].strip()}" for n in names.strip("()").split(",")]
        found.update(f for f in map(_module_file, targets) if f is not None)
    return found


def kernel_sources(py_file) -> tuple:
    """The source files whose bytes key the cache of a function defined in ``py_file``: the file and
    every blastscale module it imports, transitively (sorted)."""
    todo, seen = [Path(os.path.realpath(py_file))], set()
    while todo:
        f = todo.pop()
        if f not in seen:
            seen.add(f)
            todo.extend(_imported(f) - seen)
    return tuple(sorted(seen))


@functools.cache
def source_key(py_file: str) -> str:
    """SHA-256 (hex) of the blastscale and numba versions and of the bytes of
    :func:`kernel_sources` ``(py_file)`` with their paths inside the package (memoised per process)."""
    h = hashlib.sha256(f"blastscale {__version__}\0numba {numba.__version__}\0".encode())
    for f in kernel_sources(py_file):
        h.update(f.relative_to(_ROOT).as_posix().encode() + b"\0")
        h.update(hashlib.sha256(f.read_bytes()).digest())
    return h.hexdigest()


def _prune(folder: Path, stem: str, legacy: Path | None) -> None:
    """Remove ``stem``'s key folders beyond the :data:`KEEP` most recently used, and numba's own cache
    files of ``stem`` in ``legacy`` (``__pycache__``: written before this locator existed)."""
    try:
        olds = sorted(folder.glob(f"{stem}-*"), key=lambda p: p.stat().st_mtime, reverse=True)[KEEP:]
        olds += list(legacy.glob(f"{stem}.*.nb[ic]")) if legacy is not None else []
    except OSError:
        return
    for p in olds:
        if p.is_dir():
            shutil.rmtree(p, ignore_errors=True)
        else:
            p.unlink(missing_ok=True)


class SourceKeyedLocator(_CacheLocator):
    """numba cache locator of blastscale's kernels: a folder and an index stamp per
    :func:`source_key` (module docstring)."""

    def __init__(self, py_func, py_file, base: Path, legacy: Path | None):
        self._lineno = py_func.__code__.co_firstlineno
        self._key = source_key(os.path.realpath(py_file))
        self._stem = Path(py_file).stem
        self._folder = base / _FOLDER
        self._legacy = legacy
        self._cache_path = str(self._folder / f"{self._stem}-{self._key[:16]}")

    def ensure_cache_path(self):
        new = not os.path.isdir(self._cache_path)
        super().ensure_cache_path()
        if new:
            _prune(self._folder, self._stem, self._legacy)

    def get_cache_path(self):
        return self._cache_path

    def get_source_stamp(self):
        return self._key

    def get_disambiguator(self):
        return str(self._lineno)

    @classmethod
    def _places(cls, real: Path):
        """(base folder, folder of numba's own old files) in the order tried: ``NUMBA_CACHE_DIR`` when
        set, beside the source, numba's user-wide cache folder."""
        if config.CACHE_DIR:
            yield Path(config.CACHE_DIR) / cls.get_suitable_cache_subpath(str(real)), None
        yield real.parent / "__pycache__", real.parent / "__pycache__"
        user = Path(AppDirs(appname="numba", appauthor=False).user_cache_dir)
        yield user / cls.get_suitable_cache_subpath(str(real)), None

    @classmethod
    def from_function(cls, py_func, py_file):
        real = Path(os.path.realpath(py_file))
        if not real.is_file() or _ROOT not in real.parents:
            return None  # not blastscale's: numba's next locator
        for base, legacy in cls._places(real):
            self = cls(py_func, py_file, base, legacy)
            try:
                self.ensure_cache_path()
            except OSError:
                continue  # not writable: the next place
            return self
        return None


if SourceKeyedLocator not in CacheImpl._locator_classes:
    CacheImpl._locator_classes.insert(0, SourceKeyedLocator)


def is_cached(py_file) -> bool:
    """Whether the kernels of the blastscale module ``py_file`` have compiled machine code on disk for its
    current :func:`source_key` (an index file in its key folder, at any of the places numba would look:
    ``NUMBA_CACHE_DIR``, beside the source, the user-wide folder). Compiles nothing and creates no folder;
    ``False`` means the first call compiles (minutes for the rocking kernels on a shared 2-core machine:
    :func:`blastscale.study.memory.compile_seconds`). A signature not yet compiled in a warm folder still
    compiles: this says the folder is warm, not that every signature is."""
    real = Path(os.path.realpath(py_file))
    stem, key = real.stem, source_key(str(real))[:16]
    for base, _ in SourceKeyedLocator._places(real):
        folder = base / _FOLDER / f"{stem}-{key}"
        try:
            if any(folder.glob("*.nbi")):
                return True
        except OSError:
            pass
        if _writable(folder):  # the place numba would use (SourceKeyedLocator.from_function): cold there
            return False
    return False


def _writable(folder: Path) -> bool:
    """Whether ``folder`` exists writable or could be made (its nearest existing parent is writable)."""
    p = folder
    while not p.exists() and p != p.parent:
        p = p.parent
    return os.access(p, os.W_OK)
