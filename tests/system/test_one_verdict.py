"""One design, one verdict, whichever command asks (issue #35, acceptance 1): a 3-drum square column (3 m, 250 kg TNT
at 10 m, its 1/25 specimen in the same stone, 1 s of the 3D engine) whose top agrees within 2 % but whose base
drum's first peak is 13 % off (tests/integration/test_criterion_study.py) is NOT similar, naming that quantity, in

* ``run`` (the Study: ``summary["verdict"]``),
* ``plan`` (a lab that admits this one design: the same stone, at most 13 cm tall (1/25 is 12 cm; every smaller
  specimen's TNT charge is below TNT's smallest reliable charge): the design's ``verdict``),
* ``similarity-map`` (the one-point 3D map at its lambda, gamma, charge and stand-off: ``trustworthy`` false,
  the same worst ratio),
* ``fired`` (the specimen fired as designed, its top tracked at 2000 frames/s: ``similarity_verdict``).

The four read the same criterion (blastscale.study.criterion.judge) on the same two runs, so the verdict lines are
equal as strings and the worst ratios to 1e-12 (the same arithmetic; the map stores float64)."""

from __future__ import annotations

import tomllib

import pytest
from _fired_synthetic import camera_track, write_track_csv

from blastscale.fired.refit import marker_history, simulate_specimen
from blastscale.fired.shot import as_fired
from blastscale.planning.planner import plan
from blastscale.scenario import Scenario, load_scenario
from blastscale.study import Study
from blastscale.sweeps.similarity_map import similarity_map

pytestmark = pytest.mark.slow

COLUMN = """
title = "one verdict: a 3-drum column at 1/25"
[structure]
kind = "column"
drums = 3
height_m = 3.0
top_width_m = 1.54
[blast]
charge_kg = 250.0
standoff_m = 10.0
blast_model = "kingery-bulmash"
[scale]
length = 0.04
[simulation]
engine = "3d"
duration_s = 1.0
"""


@pytest.fixture(scope="module")
def run():
    """``run``: the Study of the scenario (its design: the general law at 1/25, the same stone)."""
    return Study(Scenario.from_dict(tomllib.loads(COLUMN), source="test")).run()


def test_run_names_the_base_drum(run):
    v = run.summary()["verdict"]
    assert v["similar"] is False and (v["worst"]["quantity"], v["worst"]["where"]) == ("first peak", "P-1")
    assert v["line"].startswith("Verdict: NOT similar: first peak at P-1")
    top = {(e["quantity"], e["where"]): e for e in v["judged"]}[("first peak", "P-3")]
    assert top["ok"] and top["error"] < 0.05  # the top alone would have said "similar"


def test_plan_gives_the_design_the_same_verdict(run):
    d = run.design
    lab = (
        "\n[lab]\n"
        'materials = ["same"]\n'
        'initiator = "none"\n'
        "top_3d = 1\n"
        "ensemble_3d = 0\n"
        "specimen_max_height_m = 0.13\n"  # 1/25 (12 cm) and smaller; smaller: TNT's smallest charge refuses them
    )
    p = plan(Scenario.from_dict(tomllib.loads(COLUMN + lab), source="test"))
    simulated = [x for x in p.designs if x.get("simulated_by") == "3d"]
    assert len(simulated) == 1
    x = simulated[0]
    assert x["scale"] == pytest.approx(0.04, rel=1e-12) and x["density_ratio"] == 1.0
    assert x["tnt_equivalent_kg"] == pytest.approx(d.specimen_charge_kg, rel=1e-9)
    v = run.summary()["verdict"]
    assert x["verdict"]["line"] == v["line"] and x["verdict"]["similar"] is False
    assert x["verdict"]["worst"]["ratio"] == pytest.approx(v["worst"]["ratio"], rel=1e-12)
    assert p.recommendation["design"] is None  # never recommended: none passes, and the plan says so
    assert p.recommendation["line"].startswith("No design passes the similarity criterion")


def test_similarity_map_gives_the_design_the_same_verdict(run):
    sc = Scenario.from_dict(tomllib.loads(COLUMN), source="test")
    ds = similarity_map(sc, [0.04], [1.0], [250.0], [10.0], engine="3d")
    v = run.summary()["verdict"]
    assert bool(ds["trustworthy"].values.ravel()[0]) is False
    assert float(ds["worst_ratio"].values.ravel()[0]) == pytest.approx(v["worst"]["ratio"], rel=1e-12)


def test_fired_as_designed_gives_the_same_verdict(run, tmp_path):
    sc = Scenario.from_dict(tomllib.loads(COLUMN), source="test")
    d = run.design
    top = (0.0, 0.0, float(d.specimen_structure.describe()["height_m"]))
    h = marker_history(simulate_specimen(sc, d, d.specimen_charge_kg, d.specimen.standoff_m, "3d"), top)
    frames, u = camera_track(h, fps=2000.0, seed=0, noise_m=2e-6, start_s=-0.005)
    write_track_csv(tmp_path / "tracks.csv", frames, {"top_x": u["x"]})
    path = tmp_path / "shot.toml"
    path.write_text(
        COLUMN + f'\n[fired]\ntracks = "tracks.csv"\n[fired.marker.top]\npoint_m = [0.0, 0.0, {top[2]!r}]\n'
    )
    s = as_fired(load_scenario(path)).summary
    assert s["refit_charge_tnt_kg"] == d.specimen_charge_kg  # no gauge, no weighed charge: the design's load
    assert s["similarity_verdict"] == run.summary()["verdict"]
