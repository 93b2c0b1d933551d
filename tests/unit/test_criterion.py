"""The one similarity criterion (blastscale.study.criterion.judge, docs/verdict.md) on synthetic summaries: the
whole structure is judged (a column whose top agrees but whose base drum's damage does not is NOT similar, naming
it), the edge of a tolerance, the floor rule, the ensemble band rule, the outcomes, the at-rest check; the
[verdict] table's keys and ranges."""

from __future__ import annotations

import copy
import math

import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.scenario import Scenario, VerdictSpec
from blastscale.study.criterion import QUANTITIES, judge

TOL = VerdictSpec()
H = 3.0  # the synthetic column's height [m]: a body "moved" beyond 1e-3 H = 3 mm


def column(res_p=(0.0338, 0.0300, 0.0280), res_m=(0.0338, 0.0300, 0.0280), peak_p=(0.020, 0.035, 0.050), peak_m=None):
    """A 3-drum column's summary (prototype and up-scaled model, SI), every quantity equal unless given (the
    largest displacements are 1.2 x the prototype's first peaks in both systems)."""
    peak_m = peak_p if peak_m is None else peak_m
    names = [f"D-{i + 1}" for i in range(3)]
    points = [f"P-{i + 1}" for i in range(3)]

    def system(res, peaks):
        return {
            "collapsed": False,
            "points": {p: {"max_displacement_m": 1.2 * v} for p, v in zip(points, peak_p)},
            "bodies": {
                n: {"residual_displacement_m": r, "residual_rotation_rad": 0.01 * (i + 1), "fallen": False}
                for i, (n, r) in enumerate(zip(names, res))
            },
        }

    return {
        "scenario": {"structure": {"kind": "column", "height_m": H}, "blast": {"charge_kg": 250.0}},
        "design": {"impulsive": {"impulsive": True}},
        "planar": None,
        "3d": {
            "prototype": system(res_p, peak_p),
            "model": system(res_m, peak_m),
            "similarity": {
                "outcomes_agree": True,
                "points": {
                    p: {"first_peak_prototype_m": a, "first_peak_model_m": b} for p, a, b in zip(points, peak_p, peak_m)
                },
            },
        },
        "ensemble": None,
    }


def entry(v: dict, quantity: str, where: str) -> dict:
    (e,) = [e for e in v["judged"] if e["quantity"] == quantity and e["where"] == where]
    return e


def test_a_column_whose_top_agrees_but_whose_base_drum_does_not_is_not_similar():
    """The issue's column: the top's first peak within 1 % (0.05 m vs 0.0496 m: 0.8 %), the base drum's residual
    displacement 14.1 mm against 33.8 mm (58.3 % off, tolerance 20 %): NOT similar, naming the quantity, the body
    and both values in mm; the worst entry is that one, its ratio 0.583 / 0.2."""
    s = column(res_m=(0.0141, 0.0300, 0.0280), peak_m=(0.020, 0.035, 0.0496))
    v = judge(s, TOL, structure_kind="column")
    assert entry(v, "first peak", "P-3")["ok"] and entry(v, "first peak", "P-3")["error"] == pytest.approx(0.008)
    assert v["similar"] is False
    assert v["line"].startswith(
        "Verdict: NOT similar: residual displacement of D-1, 14.1 mm (up-scaled model) vs 33.8 mm (prototype), "
        "58.3 % off (tolerance 20 %)"
    )
    w = v["worst"]
    assert (w["quantity"], w["where"], w["unit"], w["basis"]) == ("residual displacement", "D-1", "m", "single")
    assert w["error"] == pytest.approx((0.0338 - 0.0141) / 0.0338, rel=1e-12)
    assert w["ratio"] == pytest.approx(w["error"] / 0.20, rel=1e-12) and "ok" not in w
    # every quantity of the whole structure is judged: 1 + 3 outcomes, 3 x 2 point quantities, 3 x 2 residuals
    assert len(v["judged"]) == 16 and {e["quantity"] for e in v["judged"]} <= set(QUANTITIES)
    assert [e["where"] for e in v["judged"] if not e["ok"]] == ["D-1"]
    # the same column with its damage alike is similar, and says which quantity came closest
    ok = judge(column(peak_m=(0.020, 0.035, 0.0496)), TOL, structure_kind="column")
    assert ok["similar"] is True and ok["line"].startswith("Verdict: similar: prototype and up-scaled model both stand")
    assert ok["worst"]["where"] == "P-3" and ok["worst"]["ratio"] == pytest.approx(0.008 / 0.05)


@pytest.mark.parametrize(
    "model, tolerance, ok",
    [
        (1.25, 0.25, True),  # binary-exact: the error is exactly the tolerance
        (1.25 + 1e-9, 0.25, False),  # 1e-9 over it
        (1.05, 0.05, True),  # decimal: |1.05 - 1| = 0.05 + 4e-17 in binary, still exactly 5 %
        (1.05 + 1e-9, 0.05, False),
        (1.0 - 0.05, 0.05, True),
        (1.0 - 0.05 - 1e-9, 0.05, False),
    ],
)
def test_an_error_exactly_at_the_tolerance_passes_and_1e9_over_fails(model, tolerance, ok):
    s = column(peak_p=(1.0, 1.0, 1.0), peak_m=(1.0, 1.0, model))
    v = judge(s, VerdictSpec(peak=tolerance), structure_kind="column")
    e = entry(v, "first peak", "P-3")
    assert e["ok"] is ok and v["similar"] is ok
    assert (e["ratio"] <= 1.0 + 1e-12) is ok


def test_the_floor_judges_small_values_on_the_structures_scale():
    """P-1's first peak is 1 mm beside P-3's 100 mm: with floor 0.1 its error is |m - p| / 10 mm, not / 1 mm. 1.4 mm
    vs 1 mm is 4 % (passes, 40 % without the floor), 1.6 mm is 6 % (fails at 5 %); and a value above the floor is
    judged on itself (P-3, 104 mm vs 100 mm: 4 %)."""
    p = (0.001, 0.050, 0.100)
    v = judge(column(peak_p=p, peak_m=(0.0014, 0.050, 0.104)), TOL, structure_kind="column")
    assert entry(v, "first peak", "P-1")["error"] == pytest.approx(0.0004 / 0.010, rel=1e-12)
    assert entry(v, "first peak", "P-3")["error"] == pytest.approx(0.004 / 0.100, rel=1e-12)
    assert v["similar"] is True
    assert judge(column(peak_p=p, peak_m=(0.0016, 0.050, 0.100)), TOL, structure_kind="column")["similar"] is False
    bare = judge(column(peak_p=p, peak_m=(0.0014, 0.050, 0.100)), VerdictSpec(floor=0.0), structure_kind="column")
    assert bare["similar"] is False and entry(bare, "first peak", "P-1")["error"] == pytest.approx(0.4, rel=1e-12)


def test_residuals_below_the_moved_height_are_judged_on_it():
    """Residual displacements of 0.1 mm and 0.2 mm (100 % apart) in a 3 m column that barely moved: judged on
    the 'moved' scale 1e-3 H = 3 mm (3.3 %), not as a 100 % difference of noise."""
    v = judge(column(res_p=(1e-4, 1e-4, 1e-4), res_m=(2e-4, 2e-4, 2e-4)), TOL, structure_kind="column")
    assert entry(v, "residual displacement", "D-1")["error"] == pytest.approx(1e-4 / 3e-3, rel=1e-12)
    assert v["similar"] is True


def test_a_body_that_moved_in_one_system_only_is_an_outcome_disagreement():
    """D-3 stays within 3 mm (1e-3 H: stands) in the prototype and moves 4 mm in the model: the outcomes disagree
    (ratio inf) though the residual's own error (1 mm / 3.4 mm) is within 20 %... and fell beats moved."""
    s = column(res_p=(0.0338, 0.0300, 0.0029), res_m=(0.0338, 0.0300, 0.0031))
    v = judge(s, TOL, structure_kind="column")
    e = entry(v, "outcome", "D-3")
    assert (e["prototype"], e["model"], e["ok"], e["ratio"]) == (0.0, 1.0, False, math.inf)
    assert v["line"].startswith(
        "Verdict: NOT similar: the outcomes disagree at D-3: the prototype's stands, the model's moved"
    )
    s["3d"]["model"]["bodies"]["D-3"]["fallen"] = True
    v = judge(s, TOL, structure_kind="column")
    assert "the prototype's stands, the model's fell" in v["line"]
    assert [e for e in v["judged"] if e["where"] == "D-3" and e["quantity"] != "outcome"] == []  # fell: not judged


def _ensemble(p_med, p_band, m_med, m_band):
    return {
        "n_members": 8,
        "collapse_probability_prototype": 0.0,
        "collapse_probability_model": 0.0,
        "collapse_probability_prototype_low": 0.0,
        "collapse_probability_prototype_high": 0.324,
        "collapse_probability_model_low": 0.0,
        "collapse_probability_model_high": 0.324,
        "points": {
            "P-3": {
                "first_peak_prototype_median_m": p_med,
                "first_peak_prototype_p05_m": p_band[0],
                "first_peak_prototype_p95_m": p_band[1],
                "first_peak_model_median_m": m_med,
                "first_peak_model_p05_m": m_band[0],
                "first_peak_model_p95_m": m_band[1],
            }
        },
    }


def test_ensembles_are_judged_by_medians_outside_the_other_band():
    """P-3's first peak between ensembles (prototype median 10 mm, 5-95 % 8-12 mm): a model median 12.5 mm in a
    band 9.5-14 mm lies 0.5 mm outside the prototype's band (5 % of 10 mm: at the tolerance, passes) while the
    prototype's median lies inside the model's; with the model band 11-14 mm the prototype median lies 1 mm
    outside it: 10 %, NOT similar, on the ensemble basis (the single runs, 30 % apart, are not judged there)."""
    s = column(peak_p=(0.020, 0.035, 0.050), peak_m=(0.020, 0.035, 0.065))
    s["ensemble"] = _ensemble(0.010, (0.008, 0.012), 0.0125, (0.0095, 0.014))
    v = judge(s, TOL, structure_kind="column", circular=True)
    e = entry(v, "first peak", "P-3")
    assert e["basis"] == "ensemble" and e["error"] == pytest.approx(0.05, rel=1e-12) and e["ok"]
    assert (e["prototype"], e["model"]) == (0.010, 0.0125)
    assert v["similar"] is True and "circular drums wobble chaotically" in v["line"]
    s["ensemble"] = _ensemble(0.010, (0.008, 0.012), 0.0125, (0.011, 0.014))
    v = judge(s, TOL, structure_kind="column", circular=True)
    e = entry(v, "first peak", "P-3")
    assert e["error"] == pytest.approx(0.10, rel=1e-12) and not e["ok"] and v["similar"] is False
    assert "first peak at P-3, median 12.5 mm (up-scaled model, 5-95 % 11 mm to 14 mm) vs 10 mm" in v["line"]
    # the ensembles' quantiles absent (a summary without them): the single runs are judged, 30 % apart
    del s["ensemble"]["points"]["P-3"]["first_peak_model_p05_m"]
    e = entry(judge(s, TOL, structure_kind="column", circular=True), "first peak", "P-3")
    assert e["basis"] == "single" and e["error"] == pytest.approx(0.3, rel=1e-12)


def test_collapse_probabilities_agree_when_their_intervals_overlap():
    """0 of 8 vs 3 of 8 collapse (Wilson 95 %: 0-0.324 vs 0.137-0.694): overlapping, the outcome agrees; 0 of 8 vs
    8 of 8 (0-0.324 vs 0.676-1): disjoint, NOT similar."""
    s = column()
    s["ensemble"] = _ensemble(0.05, (0.04, 0.06), 0.05, (0.04, 0.06))
    s["ensemble"].update(
        collapse_probability_model=0.375, collapse_probability_model_low=0.137, collapse_probability_model_high=0.694
    )
    v = judge(s, TOL, structure_kind="column", circular=True)
    assert entry(v, "collapse probability", "structure")["ok"] and v["similar"] is True
    s["ensemble"].update(
        collapse_probability_model=1.0, collapse_probability_model_low=0.676, collapse_probability_model_high=1.0
    )
    v = judge(s, TOL, structure_kind="column", circular=True)
    assert v["similar"] is False and v["worst"]["quantity"] == "collapse probability"
    assert v["line"].startswith(
        "Verdict: NOT similar: the ensembles disagree on collapse: probability 0 (prototype) vs 1 (model) "
        "(0-0.32 vs 0.68-1)"
    )


def test_not_at_rest_before_the_blast_is_a_reason():
    s = column()
    rest = {"creep_m": 3e-4, "creep_rel_height": 1e-4, "final_speed_rel_sqrt_gh": 0.0, "equilibrium": True}
    s["3d"]["prototype"]["rest"] = {**rest, "duration_s": 2.0}
    s["3d"]["model"]["rest"] = {**rest, "duration_s": 0.2}
    v = judge(s, TOL, structure_kind="column")
    assert v["similar"] is True and v["rest"]["ok"] is True  # creep exactly at the tolerance: at rest
    s["3d"]["prototype"]["rest"].update(creep_m=1.5e-3, creep_rel_height=5e-4)
    v = judge(s, TOL, structure_kind="column")
    assert v["similar"] is False and not v["rest"]["ok"] and v["rest"]["prototype"]["at_rest"] is False
    assert "the prototype is not at rest before the blast: it creeps 1.5 mm under gravity alone over 2 s" in v["line"]
    s["3d"]["model"]["rest"]["equilibrium"] = False
    v = judge(s, TOL, structure_kind="column")
    assert "the specimen is not at rest before the blast: not in equilibrium" in v["line"]


def test_planar_and_impulsive_and_nothing_compared():
    planar = {
        "prototype": {"collapsed": False, "max_rotation_rad": 0.10},
        "model": {"collapsed": False, "max_rotation_rad": 0.105},
        "similarity": {"first_peak_ratio": 0.9, "outcomes_agree": True},
    }
    s = {"design": {"impulsive": {"impulsive": True}}, "planar": planar, "3d": None, "ensemble": None}
    v = judge(s, TOL)
    assert v["similar"] is False and v["worst"]["quantity"] == "first peak" and v["worst"]["where"] == "planar"
    assert entry(v, "largest rotation", "planar")["error"] == pytest.approx(0.05, rel=1e-12)
    assert v["line"].startswith("Verdict: NOT similar: first peak (planar), ratio 0.9 (up-scaled model / prototype)")
    s["planar"]["similarity"]["first_peak_ratio"] = 1.01
    s["design"]["impulsive"]["impulsive"] = False
    v = judge(s, TOL)
    assert v["similar"] is False and v["reasons"] == [
        "the load is not impulsive, so the general law does not guarantee similarity"
    ]
    none = judge({"design": {}, "planar": None, "3d": None}, TOL)
    assert none["similar"] is None and none["worst"] is None and none["judged"] == []
    assert none["line"] == "Verdict: not established: no engine compared the prototype and the model."
    proto = judge({"design": None, "scenario": {"blast": {"charge_kg": 5.0}}, "planar": copy.deepcopy(planar)}, TOL)
    assert proto["similar"] is None and proto["line"].startswith("Verdict: prototype only")


def test_the_verdict_table_is_a_scenario_table():
    sc = Scenario.default()
    assert sc.verdict == VerdictSpec() and (sc.verdict.peak, sc.verdict.residual) == (0.05, 0.20)
    assert sc.with_values({"verdict.residual": 0.3}).verdict.residual == 0.3
    with pytest.raises(BlastscaleInputError, match=r"verdict\.peak"):
        sc.with_values({"verdict.peak": -0.1})
    with pytest.raises(BlastscaleInputError, match=r"verdict\.floor"):
        sc.with_values({"verdict.floor": 1.5})
