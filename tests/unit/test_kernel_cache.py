"""The compiled kernels' caches are keyed on every source they are compiled from (issue #30,
:mod:`blastscale._jit`). These checks compile nothing; the end-to-end check (edit a helper of a copy
of the package, run, restore, run) is tests/integration/test_stale_kernel_cache.py."""

from __future__ import annotations

import ast
import importlib.util
import os
import re
import shutil
from pathlib import Path

import pytest
from numba.core.caching import CacheImpl

import blastscale
from blastscale import _jit
from blastscale.rocking import _load as L, kernel as K

SRC = Path(blastscale.__file__).resolve().parent


def _ast_imports(path: Path) -> set:
    """The blastscale files ``path`` imports, from a full parse (the reference for the text scan)."""
    mod = _jit._module_name(path)
    pkg = mod if path.name == "__init__.py" else mod.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_bytes())):
        if isinstance(node, ast.ImportFrom):
            parts = pkg.split(".")
            module = [node.module] if node.module else []
            base = ".".join(parts[: len(parts) - node.level + 1] + module) if node.level else node.module
            names = [base] + [f"{base}.{a.name}" for a in node.names]
        elif isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        else:
            continue
        found.update(f for f in map(_jit._module_file, names) if f is not None)
    return found


def test_every_compiled_function_goes_through_the_keyed_cache():
    """No module takes numba's ``njit``/``jit`` directly: its cache would be keyed on its own file only."""
    direct = re.compile(
        r"from numba import[^\n]*\b(n?jit|vectorize|guvectorize|cfunc)\b|numba\.(n?jit|vectorize|cfunc)\b"
    )
    bad = [str(p.relative_to(SRC)) for p in SRC.rglob("*.py") if p.name != "_jit.py" and direct.search(p.read_text())]
    assert bad == []
    users = sorted(p.name for p in SRC.rglob("*.py") if "from .._jit import njit" in p.read_text())
    assert users == ["_batch.py", "_dopri.py", "_events.py", "_free.py", "_load.py", "_series.py", "kernel.py"]


def test_the_text_scan_finds_every_import_a_parse_finds():
    """The key's import scan (a regular expression, for start-up speed) misses nothing that Python's own
    parser sees, over every blastscale module (it may find more: a key over too many files is only
    invalidated more often)."""
    missing = {str(p.relative_to(SRC)): _ast_imports(p) - _jit._imported(p) for p in SRC.rglob("*.py")}
    assert {k: v for k, v in missing.items() if v} == {}


def test_the_kernel_is_keyed_on_the_helpers_it_inlines():
    names = [f.relative_to(SRC).as_posix() for f in _jit.kernel_sources(K.__file__)]
    assert names == [
        "__init__.py",
        "_jit.py",
        "rocking/_dopri.py",
        "rocking/_events.py",
        "rocking/_free.py",
        "rocking/_load.py",
        "rocking/_series.py",
        "rocking/kernel.py",
        "rocking/layout.py",
    ]
    assert [f.name for f in _jit.kernel_sources(L.__file__)] == ["__init__.py", "_jit.py", "_load.py", "layout.py"]


def test_a_changed_helper_changes_the_callers_key_and_restoring_it_restores_the_key(tmp_path, monkeypatch):
    """On a copy of the package: doubling the load in ``_load`` changes the key of every kernel module
    (each reaches ``_load`` through its imports); back to the original bytes, back to the original
    keys; a comment added to ``_events`` changes the keys of ``_events`` and ``kernel`` (its importer)
    only."""
    copy = tmp_path / "blastscale"
    shutil.copytree(SRC, copy, ignore=shutil.ignore_patterns("__pycache__"))
    monkeypatch.setattr(_jit, "_ROOT", Path(os.path.realpath(copy)))
    files = {n: str(copy / "rocking" / f"{n}.py") for n in ("kernel", "_load", "_dopri", "_events")}

    def keys():
        _jit.source_key.cache_clear()
        return {n: _jit.source_key(f) for n, f in files.items()}

    try:
        before = keys()
        load = Path(files["_load"])
        text = load.read_text()
        load.write_text(text.replace("f = base_ratio(", "f = 2.0 * base_ratio(", 1))
        changed = keys()
        assert all(changed[n] != before[n] for n in files)  # every kernel module reaches _load
        load.write_text(text)
        assert keys() == before
        Path(files["_events"]).write_text(Path(files["_events"]).read_text() + "\n# a comment\n")
        after_events = keys()
        assert after_events["_load"] == before["_load"] and after_events["_dopri"] == before["_dopri"]
        assert after_events["kernel"] != before["kernel"] and after_events["_events"] != before["_events"]
    finally:
        _jit.source_key.cache_clear()


def test_the_locator_is_first_and_keeps_to_blastscale(tmp_path):
    assert CacheImpl._locator_classes[0] is _jit.SourceKeyedLocator
    other = tmp_path / "theirs.py"
    other.write_text("def f():\n    return 1\n")
    spec = importlib.util.spec_from_file_location("theirs", other)
    theirs = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(theirs)
    assert _jit.SourceKeyedLocator.from_function(theirs.f, str(other)) is None  # numba's own locators take it


@pytest.mark.skipif(bool(os.environ.get("NUMBA_CACHE_LOCATOR_CLASSES")), reason="the user chose numba's locators")
def test_the_kernels_cache_folder_is_named_after_its_key():
    path = Path(K.solve_case.stats.cache_path)
    assert path.name == f"kernel-{_jit.source_key(os.path.realpath(K.__file__))[:16]}"
    assert path.parent.name == "numba"


def test_stale_key_folders_beyond_the_most_recent_are_removed(tmp_path):
    folder, legacy = tmp_path / "numba", tmp_path
    for i in range(_jit.KEEP + 3):
        d = folder / f"_load-{i:016x}"
        d.mkdir(parents=True)
        os.utime(d, (1e9 + i, 1e9 + i))
    (folder / "_dopri-0000000000000000").mkdir()
    (legacy / "_load.load_ratio-55.py311.nbi").write_bytes(b"")
    (legacy / "_load.load_ratio-55.py311.1.nbc").write_bytes(b"")
    (legacy / "_dopri.rhs-63.py311.nbi").write_bytes(b"")
    _jit._prune(folder, "_load", legacy)
    left = sorted(p.name for p in folder.iterdir())
    newest = [f"_load-{i:016x}" for i in range(3, _jit.KEEP + 3)]
    assert left == ["_dopri-0000000000000000"] + newest  # another module's folders are not touched
    assert sorted(p.name for p in legacy.glob("*.nb?")) == ["_dopri.rhs-63.py311.nbi"]
