"""Test-suite configuration.

Hypothesis: under CI (``CI`` set in the environment) the property tests run derandomised, with a
fixed example sequence and no example database, so that a submission's CI verdict is
reproducible; locally they explore new random examples on every run (and keep failures in
``.hypothesis/``), which is where new edge cases get found and then pinned with ``@example``.
"""

import os

from hypothesis import settings

settings.register_profile("ci", derandomize=True, database=None, print_blob=True)
settings.register_profile("dev", print_blob=True)
settings.load_profile("ci" if os.environ.get("CI") else "dev")

# -- tiers ------------------------------------------------------------------------------------------
# tests/unit: one package at a time, fast (make test-fast, under a minute); tests/integration: engines,
# the Study, sweeps and their files; tests/system: the command line end to end, result folders, the
# report in a browser, an installed wheel. Each test is marked with its tier from its folder.
import pathlib

import pytest

_TIERS = ("unit", "integration", "system")


# -- the order of the files: the longest first ----------------------------------------------------------
# `make test` runs the files on 2 workers (pytest-xdist, --dist loadfile, --no-loadscope-reorder) in this
# order, each worker taking the next file when it has fewer than 2 waiting. A long file taken last keeps one
# worker busy while the other has nothing left (xdist's own order, by number of tests per file, put the wheel's
# 2 tests, 190 s, at the very end: one worker idle for minutes). Longest first, short ones last, the two
# workers end within about the shortest files' time of each other. The files below, longest first (seconds of
# one worker, 2-core machine, load average 3-4 with the whole suite, fresh kernel caches: CHANGELOG.md, "The suite's wall time");
# then every file with a test marked slow (most slow tests first), then the rest (most tests first). Only the
# order changes: a test within its file keeps its place, and a file still runs whole on one worker.
LONGEST_FIRST = (
    "tests/system/test_wheel.py",  # 193 s: builds and installs the wheel, runs the main job and reproduce --quick
    "tests/system/test_readme.py",  # 112 s: the README's cheap commands, one process each
    "tests/system/test_output_faults.py",  # ~100 s: two-worker sweeps interrupted
    "tests/integration/test_calibration_identifiable.py",  # ~85 s: friction profiles of 3D columns
    "tests/integration/test_stale_kernel_cache.py",  # 84 s: compiles the rocking kernel of a changed copy
    "tests/system/test_examples.py",  # ~80 s: the example scripts
)


def _file_order(items) -> dict:
    """{file: rank}: :data:`LONGEST_FIRST` in its order, then the files with the most tests marked slow, then
    the files with the most tests (ties: collection order)."""
    tests, slow = {}, {}
    for item in items:
        f = item.nodeid.split("::")[0]
        tests[f] = tests.get(f, 0) + 1
        slow[f] = slow.get(f, 0) + (item.get_closest_marker("slow") is not None)
    listed = {f: i for i, f in enumerate(LONGEST_FIRST)}
    files = sorted(tests, key=lambda f: (listed.get(f, len(listed)), -slow[f], -tests[f]))
    return {f: rank for rank, f in enumerate(files)}


def pytest_collection_modifyitems(config, items):
    for item in items:
        parts = pathlib.Path(str(item.fspath)).parts
        for tier in _TIERS:
            if tier in parts:
                item.add_marker(getattr(pytest.mark, tier))
    rank = _file_order(items)
    items.sort(key=lambda item: rank[item.nodeid.split("::")[0]])  # stable: a file's tests keep their order


# -- patching a function where it is used ---------------------------------------------------------------
@pytest.fixture
def patch_everywhere(monkeypatch):
    """``patch(module, name, new)``: ``monkeypatch.setattr(module, name, new)``, and the same in every loaded
    blastscale module that holds the original under that name (``from .x import name`` at a module's top binds
    it when that module is imported, so patching ``x`` alone would not reach it). Undone after the test."""
    import sys

    def patch(module, name, new):
        original = getattr(module, name)
        monkeypatch.setattr(module, name, new)
        for mod_name, mod in list(sys.modules.items()):
            if mod_name.startswith("blastscale") and mod is not module and getattr(mod, name, None) is original:
                monkeypatch.setattr(mod, name, new)

    return patch
