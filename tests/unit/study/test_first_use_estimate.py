"""The size line says when a run compiles first (issue #39, deliverable 4): a cold kernel cache adds
:data:`~blastscale.study.memory.COMPILE_SECONDS` (its cold share) and the words "compiling kernels, first use
only"; a warm one adds nothing; a 3D-only run compiles nothing. No clocks and no compiling: the cache is a
temporary ``NUMBA_CACHE_DIR`` (numba's ``config.CACHE_DIR``), empty, then filled with index files named as
:mod:`blastscale._jit` names them. The estimate against measured times is ``benchmarks/bench_first_use.py``."""

from __future__ import annotations

from pathlib import Path

import pytest
from numba.core import config

import blastscale
from blastscale import _jit
from blastscale.scenario import Scenario, load_scenario
from blastscale.study import Study
from blastscale.study.memory import COMPILE_SECONDS, KERNEL_MODULES, compile_seconds, estimate_run

ROCKING = Path(blastscale.__file__).resolve().parent / "rocking"


@pytest.fixture
def cache(tmp_path, monkeypatch):
    monkeypatch.setattr(config, "CACHE_DIR", str(tmp_path))
    return tmp_path


def _warm(cache: Path, modules) -> None:
    """An index file in each module's key folder, where numba would write it under ``cache``."""
    for m in modules:
        f = ROCKING / f"{m}.py"
        base = cache / _jit.SourceKeyedLocator.get_suitable_cache_subpath(str(f.resolve()))
        folder = base / "numba" / f"{m}-{_jit.source_key(str(f.resolve()))[:16]}"
        folder.mkdir(parents=True)
        (folder / f"{m}.fn-1.py311.nbi").write_bytes(b"")


def test_cold_cache_is_said_and_counted(cache):
    sc = Scenario.default()  # planar and 3D: the planar engine runs the compiled kernels
    plan = Study(sc).check()
    assert compile_seconds(sc, plan.structure) == COMPILE_SECONDS
    size = estimate_run(sc, plan.structure, plan.contact)
    assert size.compile_s == COMPILE_SECONDS and size.seconds > COMPILE_SECONDS
    assert f"(compiling kernels, first use only, ~{COMPILE_SECONDS:.0f} s)" in size.line()


def test_warm_cache_adds_nothing_and_a_partly_warm_one_its_share(cache):
    sc = Scenario.default()
    _warm(cache, KERNEL_MODULES[:3])
    assert compile_seconds(sc) == pytest.approx(COMPILE_SECONDS * (len(KERNEL_MODULES) - 3) / len(KERNEL_MODULES))
    _warm(cache, KERNEL_MODULES[3:])
    assert compile_seconds(sc) == 0.0
    assert "compiling" not in estimate_run(sc).line()


def test_a_3d_only_run_compiles_nothing(cache):
    sc = load_scenario("paper_column_square_250kg")  # engine 3d: MuJoCo, no numba kernel
    assert compile_seconds(sc) == 0.0
    both = sc.with_values({"simulation.engine": "both"})  # planar rocking is skipped for a column
    assert compile_seconds(both, Study(both).structure()) == 0.0


def test_a_run_without_the_search_counts_only_the_kernels_it_loads(cache):
    """A planar run without the critical-charge search never loads SEARCH_KERNEL_MODULES (measured: a cold cache
    after such a run holds every module but ``_batch``): a fresh tree says 6/7 of COMPILE_SECONDS, not 7/7, and a
    cache warm but for ``_batch`` says nothing; with the search, ``_batch`` counts."""
    from blastscale.study.memory import SEARCH_KERNEL_MODULES

    search = Scenario.default().with_values({"simulation.engine": "planar"})
    plain = search.with_values({"simulation.critical_charge": False})
    assert search.simulation.critical_charge  # the default searches
    n, k = len(KERNEL_MODULES), len(SEARCH_KERNEL_MODULES)
    assert compile_seconds(plain) == pytest.approx(COMPILE_SECONDS * (n - k) / n)
    assert compile_seconds(search) == COMPILE_SECONDS
    _warm(cache, [m for m in KERNEL_MODULES if m not in SEARCH_KERNEL_MODULES])
    assert compile_seconds(plain) == 0.0
    assert compile_seconds(search) == pytest.approx(COMPILE_SECONDS * k / n)
