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
