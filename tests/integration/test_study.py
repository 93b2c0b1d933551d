"""Study: the orchestrator designs once, passes every choice through, and its result files carry units.

Physics tolerances are those of the engines it calls (their own tests); here the study is checked
against the independent direct calls it must reproduce exactly.
"""

import math

import numpy as np
import pytest
import xarray as xr

from blastscale._validate import BlastscaleInputError
from blastscale.analysis.rocking_similarity import compare_rocking
from blastscale.io.histories import write_netcdf
from blastscale.rocking import RockingSystem, simulate
from blastscale.scenario import Scenario, library_names, load_scenario
from blastscale.similitude import design_model
from blastscale.structures import RectangularBlock
from blastscale.study import Study, StudyWarning, contact_settings, estimate_memory

EXAMPLES = [n for n in library_names() if n.startswith("paper_")]  # the paper's cases (package data)
SHORT = {"duration_s": 0.15, "critical_charge": False}


def test_planar_results_equal_the_direct_comparison_with_every_choice_passed_through():
    # non-default choices everywhere: if one were dropped, the numbers would differ from the direct call
    sc = Scenario.default().with_values(
        {
            "blast.model": "kingery-bulmash",
            "pulse": "triangular",
            "restitution": 0.8,
            "gravity_m_s2": 9.5,
            "density_ratio": 0.5,
            "gravity_ratio": 2.0,
            "duration_s": 1.5,
            "samples": 301,
            "engine": "planar",
            "critical_charge": False,
        }
    )
    r = Study(sc).run()
    # the same experiment composed by hand from the library's parts, every choice written out
    block = RectangularBlock.from_slenderness(10.0, math.radians(15.0), depth=1.0, density=2000.0)
    d = design_model(50.0, 2.0, 1 / 200, 0.5, 2.0, blast_model="kingery-bulmash", geometry=block, gravity=9.5)
    t = np.linspace(0.0, 1.5, 301)
    sys_p = RockingSystem.from_block(block, 9.5, 0.8)
    res_p = simulate(sys_p, d.prototype.pulse("triangular"), 1.5, t_eval=t)
    res_m = simulate(
        RockingSystem.from_block(d.specimen_block, 9.5 * 2.0, 0.8),
        d.specimen.pulse("triangular"),
        1.5 * d.factors.time,
        t_eval=np.minimum(t * d.factors.time, 1.5 * d.factors.time),
    )
    direct = compare_rocking(res_p, res_m, d, sys_p.frequency_parameter)
    # same inputs, same deterministic solver: equal to round-off
    np.testing.assert_allclose(r.planar.theta_model, direct.theta_model, rtol=0, atol=1e-15)
    assert r.planar.to_dict() == direct.to_dict()
    assert r.design.specimen_charge_kg == direct.design.specimen_charge_kg
    assert r.response3d is None and r.critical is None


def test_the_design_runs_once(monkeypatch):
    import blastscale.similitude as sim

    calls = []
    real = sim.design_model

    def counting(*a, **k):
        calls.append(1)
        return real(*a, **k)

    monkeypatch.setattr(sim, "design_model", counting)
    Study(Scenario.default().with_values({"duration_s": 0.1})).run()
    assert len(calls) == 1


def test_progress_reports_every_stage_in_order():
    seen = []
    Study(Scenario.default().with_values({"duration_s": 0.1})).run(progress=lambda s, d, t: seen.append((s, d, t)))
    assert [d for _, d, _ in seen] == [1, 2, 3, 4] and all(t == 4 for _, _, t in seen)
    assert seen[-1][0] == "done"


@pytest.mark.parametrize("path", EXAMPLES)
def test_each_paper_scenario_runs_end_to_end(path, tmp_path):
    sc = load_scenario(path)
    sc = sc.with_values({**SHORT, "ensemble_members": min(sc.simulation.ensemble_members, 2)})
    r = Study(sc).run()
    assert (r.planar is not None) == (sc.structure.kind == "block" and sc.simulation.engine in ("planar", "both"))
    assert r.response3d is not None
    assert (r.ensemble is not None) == (sc.simulation.ensemble_members >= 2)  # the circular columns
    s = r.scalars()
    assert all(isinstance(v, (bool, int, float)) for v in s.values())
    assert s["design.model_charge_kg"] == pytest.approx(r.design.specimen_charge_kg)
    nc = tmp_path / "h.nc"
    write_netcdf(r.to_datatree(), nc)
    tree = xr.open_datatree(nc)
    for node in tree.subtree:
        for v in node.ds.variables:
            assert "units" in node.ds[v].attrs, (node.path, v)
    ds = tree["sim3d"].ds
    assert all(v.isidentifier() for v in ds.variables)
    assert list(ds["system"].values) == ["prototype", "model"]
    assert ds["time"].attrs["units"] == "s" and ds["time"].size > 2
    assert all("long_name" in ds[v].attrs for v in ds.data_vars)


def test_model_experiment_is_the_scaled_prototype():
    r = Study(Scenario.default().with_values({"duration_s": 0.1, "model_material": "balsa"})).run()
    e = r.experiment()
    lam = 1 / 200
    assert e["model"]["height_m"] == pytest.approx(10.0 * lam, rel=1e-12)
    assert e["model"]["mass_kg"] == pytest.approx(e["prototype"]["mass_kg"] * lam**3 * 0.07, rel=1e-12)
    assert e["model"]["material"] == "balsa" and e["density_ratio"] == pytest.approx(0.07, rel=1e-12)


def test_scalars_keep_their_keys_when_an_outcome_changes():
    rocks = Study(Scenario.default().with_values({"duration_s": 2.0, "engine": "planar"})).run().scalars()
    falls = (
        Study(Scenario.default().with_values({"duration_s": 2.0, "engine": "planar", "charge_kg": 100.0}))
        .run()
        .scalars()
    )
    assert rocks.keys() == falls.keys()
    assert math.isnan(rocks["planar.prototype.collapse_time_s"]) and falls["planar.prototype.collapse_time_s"] > 0
    assert rocks["critical.critical_charge_kg"] == pytest.approx(79.87, abs=0.01)  # paper: 79.8 kg


def test_contact_settings_pass_through():
    sc = Scenario.default().with_values({"timestep_s": 1e-3, "simulation.contact.impratio": 5.0, "friction": 0.4})
    block = Study(sc).structure()
    c = contact_settings(sc, block)
    assert (c.timestep, c.impratio, c.friction) == (1e-3, 5.0, 0.4)
    assert c.time_constant == pytest.approx(4e-3)  # kept >= 4 steps when only the step is given


def test_memory_check_refuses_a_huge_duration_before_running():
    sc = Scenario.default().with_values({"duration_s": 1e5})
    assert estimate_memory(sc) > 50 * 2**30  # ~260 GiB of histories at dt 0.2 ms
    with pytest.raises(BlastscaleInputError, match=r"simulation\.duration_s = 100000 s is out of range: .* GiB"):
        Study(sc).check()


def test_engine_that_does_not_fit_the_structure_is_one_line():
    sc = load_scenario("paper_column_square_500kg").with_values({"engine": "planar"})
    with pytest.raises(BlastscaleInputError, match=r"simulation\.engine = 'planar' is not available for a column"):
        Study(sc).run()


def test_study_rejects_a_non_scenario():
    with pytest.raises(BlastscaleInputError, match="scenario must be a Scenario"):
        Study({"blast": {}})


def test_both_engines_on_a_column_runs_3d_and_says_why_planar_is_skipped():
    sc = load_scenario("paper_column_square_500kg").with_values({"engine": "both", "duration_s": 0.1})
    with pytest.warns(StudyWarning, match="planar engine skipped"):  # said to the caller as well
        r = Study(sc).run()
    assert r.planar is None and r.response3d is not None
    assert any(
        w.startswith("planar engine skipped: planar rocking applies to a single rectangular block") for w in r.warnings
    )


def test_ensemble_settings_are_checked_before_running():
    with pytest.raises(
        BlastscaleInputError,
        match=r"simulation\.ensemble_members = 1 is out of range: valid values "
        r"are 0 \(no ensemble\) or 2 to 64",
    ):
        Scenario.default().with_values({"ensemble_members": 1})
    sc = Scenario.default().with_values({"ensemble_members": 2, "engine": "planar"})
    with pytest.raises(BlastscaleInputError, match=r"simulation\.ensemble_members = 2 needs the 3D engine"):
        Study(sc).check()


def test_blast_extrapolate_reaches_the_3d_loads_and_the_ensemble():
    # Method C on the paper's 1/200 block puts the model's rear faces beyond the masi2021 duration
    # fit (Z > 6.5): refused with one line unless blast.extrapolate, which must reach the loads of
    # the 3D comparison and of every ensemble member (both would fail otherwise).
    sc = Scenario.default().with_values({"load": "C", "engine": "3d", "duration_s": 0.05, "critical_charge": False})
    with pytest.raises(BlastscaleInputError, match=r"outside the fit's valid range"):
        Study(sc).run()
    r = Study(sc.with_values({"extrapolate": True, "ensemble_members": 2})).run()
    assert r.response3d is not None and r.ensemble is not None
