"""Deprecated names (docs/glossary.md, "Deprecated names"): the one table of old result keys, the one
function that prints them beside the new ones, and the outputs that carry only the new names."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from blastscale.io.results import LEGACY_KEYS, legacy_name, with_legacy_keys
from blastscale.scenario.specs import LEGACY_SCENARIO_KEYS

GLOSSARY = Path(__file__).resolve().parents[2] / "docs" / "glossary.md"


def _table(after: str) -> list[list[str]]:
    """The rows of the Markdown table whose header line starts with ``after`` (backticks dropped)."""
    lines = GLOSSARY.read_text().splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith(after))
    rows, seen = [], False
    for line in lines[start + 1 :]:
        if line.startswith("|"):
            seen = True
            cells = [c.strip().strip("`") for c in line.strip("|").split("|")]
            if not set(cells[0]) <= set("-"):
                rows.append(cells)
        elif seen:
            break
    return rows


def test_legacy_result_keys_are_exactly_those_of_the_glossary():
    rows = _table("| new result key")
    documented = {(None if where.startswith("any") else where, new): old for new, old, where in rows}
    assert documented == LEGACY_KEYS


def test_legacy_scenario_keys_are_exactly_those_of_the_glossary():
    rows = _table("| new scenario key")
    assert {old: new for new, old in rows} == LEGACY_SCENARIO_KEYS


def test_old_keys_are_added_beside_the_new_with_the_same_value_by_engine():
    summary = {
        "design": {"blast_model": "masi2021", "model": {"blast_model": "masi2021", "charge_kg": 1e-6}},
        "planar": {
            "prototype": {"collapsed": False, "max_rotation_rad": 0.06},
            "similarity": {"first_peak_ratio": 1.001, "collapse_time_diff_s": None},
        },
        "3d": {
            "prototype": {"collapsed": True, "max_rotation_rad": 0.05, "points": {"P-1": {"first_peak_ratio": 1.0}}}
        },
        "scenario": {
            "blast": {"blast_model": "kingery-bulmash", "pulse_shape": "friedlander"},
            "scale": {"specimen_material": None},
        },
        "scalars": {
            "planar.model.max_rotation_rad": 0.061,
            "3d.model.max_rotation_rad": 0.051,
            "planar.similarity.first_peak_ratio": 1.001,
            "3d.similarity.points.P-1.first_peak_ratio": 1.0,
        },
        "runs": [{"collapsed": True}],
    }
    out = with_legacy_keys(summary)
    assert out["design"]["model"] == summary["design"]["model"] | {"model": "masi2021"}  # the section kept
    assert out["design"]["model"]["model"] == "masi2021"  # the specimen's blast parameters: blast_model's alias
    p = out["planar"]["prototype"]
    assert p["overturned"] is False and p["max_angle_rad"] == 0.06 and "max_tilt_rad" not in p
    assert out["planar"]["similarity"]["peak_ratio"] == 1.001 and "overturn_time_diff_s" in out["planar"]["similarity"]
    q = out["3d"]["prototype"]
    assert q["max_tilt_rad"] == 0.05 and q["overturned"] is True and "max_angle_rad" not in q
    assert "peak_ratio" not in q["points"]["P-1"]  # 3D points had first_peak_ratio already
    assert out["scenario"]["blast"]["model"] == "kingery-bulmash" and out["scenario"]["blast"]["pulse"] == "friedlander"
    assert "model_material" in out["scenario"]["scale"]
    s = out["scalars"]
    assert s["planar.model.max_angle_rad"] == 0.061 and s["3d.model.max_tilt_rad"] == 0.051
    assert s["planar.similarity.peak_ratio"] == 1.001 and "3d.similarity.points.P-1.peak_ratio" not in s
    assert out["runs"][0] == {"collapsed": True}  # no engine: the outcome words are per engine
    assert with_legacy_keys(summary, "planar")["runs"][0] == {"collapsed": True, "overturned": True}
    assert list(out["planar"]["prototype"]) == ["collapsed", "overturned", "max_rotation_rad", "max_angle_rad"]
    assert with_legacy_keys(out) == out  # idempotent
    assert "overturned" not in summary["planar"]["prototype"]  # the input is not modified
    assert (
        legacy_name("planar.similarity.max_abs_rotation_diff_to_tipping_rad")
        == "planar.similarity.max_abs_angle_diff_to_tipping_rad"
    )
    assert legacy_name("charge_kg") == "charge_kg"


def test_a_sweep_store_holds_the_new_names_only(tmp_path):
    """Sweep stores are built from ``StudyResult.scalars()`` and the outcome mode: the new names,
    no deprecated one (planar and 3D engines, the outcome mode)."""
    pytest.importorskip("zarr")
    from blastscale.io.sweep_store import open_sweep
    from blastscale.scenario import Scenario
    from blastscale.sweeps import SweepSpec
    from blastscale.sweeps.run import run_sweep

    base = Scenario.default().with_values({"duration_s": 0.2, "critical_charge": False})
    names: set[str] = set()
    for i, (sc, outcomes) in enumerate(
        ((base.with_values({"engine": "both"}), False), (base.with_values({"engine": "planar"}), True))
    ):
        spec = SweepSpec.build(sc, {"charge_kg": [40.0, 120.0]}, outcomes=outcomes)
        run_sweep(spec, tmp_path / f"s{i}.zarr", workers=0)
        tree = open_sweep(tmp_path / f"s{i}.zarr")
        for node in tree.subtree:
            names |= set(node.data_vars) | set(node.attrs) | set(node.coords)
    old = {re.sub(r"_(rad|s|kg|m)$", "", o) for o in LEGACY_KEYS.values()} | set(LEGACY_KEYS.values())
    assert not names & old, sorted(names & old)
    assert {"collapsed", "max_rotation", "first_peak_ratio", "max_rotation_ratio"} <= names
