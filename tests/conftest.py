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


def pytest_collection_modifyitems(config, items):
    for item in items:
        parts = pathlib.Path(str(item.fspath)).parts
        for tier in _TIERS:
            if tier in parts:
                item.add_marker(getattr(pytest.mark, tier))


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
