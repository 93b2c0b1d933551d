"""Issue #34, Deliver 3, counted: one blast inversion, one bracketed root finder, the engine does not compare
prototype and model, and every rocking-engine run outside the Study goes through ``analysis``."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[2] / "src" / "blastscale"

#: The rocking engine's runs (integrations and searches): only rocking/, study/ and analysis/ call them.
ENGINE_RUNS = {
    "DEFAULT_SOLVER",
    "simulate",
    "first_swing",
    "first_swing_blast",
    "first_swing_checked",
    "overturns",
    "critical_charge",
    "critical_standoff",
    "critical_arrays",
    "capacity_curve",
    "pi_diagram",
    "negative_phase_uncertainty",
    "simulate_reference",
    "critical_charge_by_bisection",
}


def _from_imports(path: Path):
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom):
            yield node.level, node.module or "", {a.name for a in node.names}


def _package(path: Path) -> str:
    return path.relative_to(SRC).parts[0]


def test_engine_runs_outside_study_and_analysis_are_zero():
    """No module outside rocking/, study/ and analysis/ imports a run of the rocking engine (before: 6)."""
    found = []
    for path in SRC.rglob("*.py"):
        if _package(path) in ("rocking", "study", "analysis"):
            continue
        for level, module, names in _from_imports(path):
            if "rocking" in module.split(".") and names & ENGINE_RUNS:
                found.append(f"{path.relative_to(SRC)}: {sorted(names & ENGINE_RUNS)}")
    assert found == []


def test_the_engine_does_not_import_similitude():
    """rocking/ builds no specimen: the prototype-model comparison (the model's capacity) is analysis'."""
    found = [
        str(p.relative_to(SRC))
        for p in (SRC / "rocking").rglob("*.py")
        for _, module, _ in _from_imports(p)
        if "similitude" in module.split(".")
    ]
    assert found == []


@pytest.mark.parametrize("word", ["brentq", "def _solve_z", "def _invert_impulse", "def vector_root"])
def test_one_inversion_and_one_root_finder(word):
    """scipy's brentq is used nowhere, the old copies of the inversion are gone, and the bracketed root finder is
    defined once (blastscale/roots.py)."""
    where = [str(p.relative_to(SRC)) for p in SRC.rglob("*.py") if word in p.read_text(encoding="utf-8")]
    assert where == ([] if word != "def vector_root" else ["roots.py"])
