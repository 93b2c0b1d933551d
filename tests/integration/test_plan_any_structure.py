"""The plan of every structure kind through its 3D stage (tiny ensembles, short durations): a column,
the shipped running-bond wall, a block-model file and a block under clearing all plan, the top
designs carry ``odds_3d``; the ensembles run the design's own specimen."""

import json
from pathlib import Path

import numpy as np
import pytest

from blastscale.analysis.intervals import wilson_interval
from blastscale.planning import plan
from blastscale.planning.build import specimen_mass
from blastscale.planning.odds import Tolerances, specimen_members
from blastscale.scenario import Scenario, load_scenario
from blastscale.scenario.lab import LabSpec
from blastscale.similitude import scaling_factors
from blastscale.study import Study

LIB = Path(__file__).resolve().parents[2] / "src" / "blastscale" / "scenario" / "library"
TINY = dict(ensemble_3d=2, top_3d=1, materials=["same"])


def _leader(p) -> dict:
    """The screening leader (it always gets the 3D ensemble; the first ranked may be another 3D design)."""
    return next(d for d in p.designs if "screening rank 1 (lab.top_3d = 1)" in (d.get("chosen_3d_for") or []))


def _check(p, lab):
    assert p.designs and p.prototype["collapsed"] is not None
    scr = lambda d: (float(f"{d['screening_error']:.2g}"), d["safety_radius_m"])  # the screening order
    leader = min(p.designs, key=scr)  # lab.top_3d = 1, one material: the leader and the largest scale's best run
    big = min((d for d in p.designs if d["scale"] == max(x["scale"] for x in p.designs)), key=scr)
    o = leader["odds_3d"]  # the screening leader always gets its ensemble
    assert o["members"] == o["trials"] == lab.ensemble_3d and o["p_outcome_agree"] == o["agree_count"] / o["trials"]
    # the Wilson interval of agree_count of trials (tests/unit/analysis/test_intervals.py), never "+- 0"
    assert (o["p_outcome_agree_low"], o["p_outcome_agree_high"]) == wilson_interval(o["agree_count"], o["trials"])
    assert (
        leader["p_outcome_agree_low"]
        == o["p_outcome_agree_low"]
        < o["p_outcome_agree_high"]
        == leader["p_outcome_agree_high"]
    )
    assert 0 < o["top_displacement_p05_m"] <= o["top_displacement_p95_m"]
    assert leader["p_outcome_agree"] == o["p_outcome_agree"]
    if big is not leader:  # chosen for its scale: its ensemble only when the criterion passes it
        assert (big["odds_3d"] is not None) == (big["verdict"]["similar"] is True)
    assert any(d["pareto"] for d in p.designs if d["simulated_by"])  # the designs with odds have a front
    for d in p.designs:
        assert (
            d["explosive_mass_kg"] >= d["explosive_min_charge_kg"]
            and d["specimen_height_m"] <= lab.specimen_max_height_m
            and d["safety_radius_m"] <= lab.space_radius_m
        )
    run = [d["simulated_by"] == "3d" for d in p.designs]
    assert run == sorted(run, reverse=True)  # the designs simulated in 3D rank first
    assert leader["simulated_by"] == big["simulated_by"] == "3d" and sum(run) == (1 if leader is big else 2)
    assert all(d["odds_3d"] is None and d["verdict"] is None for d in p.designs if not d["simulated_by"])
    assert all(
        d["predicted_first_peak_error"] is None and d["screening_error"] >= 0
        for d in p.designs
        if not d["simulated_by"]
    )


@pytest.mark.slow
@pytest.mark.parametrize("name,duration", [("paper_column_square_250kg", 0.3), ("wall_running_bond_lambda20", 0.3)])
def test_shipped_structures_plan_with_3d_odds(name, duration):
    sc = load_scenario(LIB / f"{name}.toml").with_values({"duration_s": duration})
    lab = LabSpec(specimen_max_height_m=1.0, **TINY)
    _check(plan(sc, lab=lab), lab)


@pytest.mark.slow
def test_block_model_file_plans(tmp_path):
    box = lambda n, z0, z1: {"name": n, "vertices": [[x, y, z] for x in (0, 0.6) for y in (0, 1) for z in (z0, z1)]}
    f = tmp_path / "stack.json"
    f.write_text(json.dumps({"blocks": [box("A", 0.0, 1.2), box("B", 1.2, 2.4)]}))
    sc = Scenario.from_dict(
        {
            "structure": {"kind": "assembly", "file": str(f), "density_kg_m3": 2400.0},
            "blast": {"charge_kg": 5.0, "standoff_m": 4.0},
            "simulation": {"engine": "3d", "duration_s": 0.3},
        },
        source="test",
    )
    lab = LabSpec(**TINY)
    _check(plan(sc, lab=lab), lab)


@pytest.mark.slow
def test_a_block_under_clearing_with_a_stand_plans_in_3d():
    """Clearing and a free-air specimen charge are planned (were refused): the 3D path, each design says
    its burst and the stand's height."""
    sc = Scenario.default().with_values(
        {"duration_s": 0.3, "blast.clearing": True, "blast.blast_model": "kingery-bulmash"}
    )
    lab = LabSpec(specimen_max_height_m=1.0, bursts=["surface", "free-air"], **TINY)
    p = plan(sc, lab=lab)
    _check(p, lab)
    air = [d for d in p.designs if d["burst"] == "free-air"]
    assert air and all(d["charge_height_m"] > 0 for d in air)
    assert all(d["charge_height_m"] == 0 for d in p.designs if d["burst"] == "surface")


@pytest.mark.parametrize("name", ["paper_column_square_250kg", "wall_running_bond_lambda20"])
def test_the_ensembles_specimen_is_the_designs(name):
    """An ensemble member runs the design's specimen itself (no scenario written back: its density x the member's
    draw by ``structure.scaled``): under a factor of 1 the same mass and centres of mass as the design's."""
    sc = load_scenario(LIB / f"{name}.toml")
    d = Study(sc).design()
    (m,) = specimen_members(sc, d, Tolerances(), 1)
    assert m.density_factor == pytest.approx(1.0, abs=1e-11) and m.standoff_m == pytest.approx(d.specimen_standoff_m)
    spec = d.specimen_structure.scaled(scaling_factors(1.0, density_ratio=1.0))
    assert spec.mass == pytest.approx(d.specimen_structure.mass, rel=1e-12)
    assert specimen_mass(d) == pytest.approx(d.specimen_structure.mass, rel=1e-12)  # lambda^3 gamma x the prototype's
    got = np.array([b.com for b in spec.bodies])
    assert got == pytest.approx(np.array([b.com for b in d.specimen_structure.bodies]), rel=1e-12, abs=1e-15)


@pytest.mark.slow
def test_threads_and_dask_give_the_same_odds(tmp_path):
    """The members on native threads in this process and on a local Dask worker: the same draws (the
    sweeps' samples, one seed), the same runs, so the same odds to the last bit."""
    box = lambda n, z0, z1: {"name": n, "vertices": [[x, y, z] for x in (0, 0.6) for y in (0, 1) for z in (z0, z1)]}
    f = tmp_path / "stack.json"
    f.write_text(json.dumps({"blocks": [box("A", 0.0, 1.2), box("B", 1.2, 2.4)]}))
    sc = Scenario.from_dict(
        {
            "structure": {"kind": "assembly", "file": str(f), "density_kg_m3": 2400.0},
            "blast": {"charge_kg": 5.0, "standoff_m": 4.0},
            "simulation": {"engine": "3d", "duration_s": 0.2},
        },
        source="test",
    )
    lab = LabSpec(**TINY)
    a, b = _leader(plan(sc, lab=lab))["odds_3d"], _leader(plan(sc, lab=lab, workers=1))["odds_3d"]
    assert a is not None and a == b


def test_a_block_model_with_supports_gets_its_ensemble():
    """A COMPAS arch on two is_support abutments: its specimen runs as the design carries it (supports included;
    before, the specimen had to be written as a block-model file, which cannot carry supports, and the design
    ranked on its comparison alone), so its best design has the 3D comparison and its ensemble."""
    data = Path(__file__).resolve().parents[1] / "data" / "compas_dem_arch_rotated.json"
    sc = Scenario.from_dict(
        {
            "structure": {"kind": "assembly", "file": str(data)},
            "blast": {"charge_kg": 2.0, "standoff_m": 4.0},
            "simulation": {"engine": "3d", "duration_s": 0.2},
        },
        source="test",
    )
    p = plan(sc, lab=LabSpec(**TINY))
    d = _leader(p)
    assert d["odds_3d"]["members"] == TINY["ensemble_3d"] and 0 <= d["similarity_error"] <= 1
