"""The odds of the best design by a small 3D ensemble (lab.ensemble_3d), run as a sweep of Studies."""

import pytest

from blastscale.planning import plan
from blastscale.scenario import Scenario
from blastscale.scenario.lab import LabSpec


@pytest.mark.slow
def test_best_design_gets_a_3d_ensemble():
    base = Scenario.default().with_values({"engine": "planar", "duration_s": 1.0})
    p = plan(base, lab=LabSpec(specimen_max_height_m=0.5, samples=100, ensemble_3d=3, materials=["same"]))
    o = p.designs[0]["odds_3d"]
    assert o["members"] == 3
    assert o["p_outcome_agree"] == 1.0 and o["specimen_collapse_probability"] == 0.0  # the planar answer too
    assert 0.0 < o["first_peak_spread"] < 0.5  # the top displacement varies with the drawn tolerances
    assert p.notes and "odds_3d" in p.notes[0]
