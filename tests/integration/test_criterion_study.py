"""The one criterion on a real engine run (issue #35): a 3-drum square column (3 m, 250 kg TNT at 10 m, 1/100,
1 s of the 3D engine, ~2 s of CPU) through the Study; its verdict agrees with its own summary's numbers, the worst
ratio recomputed here from the summary by the criterion's definition (docs/verdict.md) without the criterion's code,
and the flat scalars, the report's summary.json and the run's printed line carry that verdict."""

from __future__ import annotations

import math

import pytest

from blastscale.scenario import Scenario
from blastscale.study import Study

COLUMN = {
    "kind": "column",
    "drums": 3,
    "height_m": 3.0,
    "top_width_m": 1.54,
    "charge_kg": 250.0,
    "standoff_m": 10.0,
    "scale.length": 0.01,
    "model": "kingery-bulmash",
    "engine": "3d",
    "duration_s": 1.0,
}


@pytest.fixture(scope="module")
def column():
    return Study(Scenario.default().with_values(COLUMN)).run()


def _ratios(s: dict, tol) -> dict:
    """(quantity, where) -> error / tolerance, from the summary's numbers by the docs' definition."""
    p3, m3, sim = s["3d"]["prototype"], s["3d"]["model"], s["3d"]["similarity"]
    H = s["scenario"]["structure"]["height_m"]
    out = {}

    def judge(quantity, pairs, tolerance, scale0=0.0):
        top = max(abs(p) for p, _ in pairs.values())
        for where, (p, m) in pairs.items():
            den = max(abs(p), tol.floor * top, scale0)
            out[(quantity, where)] = (abs(m - p) / den if m != p else 0.0) / tolerance

    judge(
        "first peak",
        {n: (v["first_peak_prototype_m"], v["first_peak_model_m"]) for n, v in sim["points"].items()},
        tol.peak,
    )
    judge(
        "largest displacement",
        {n: (p3["points"][n]["max_displacement_m"], m3["points"][n]["max_displacement_m"]) for n in p3["points"]},
        tol.displacement,
    )
    judge(
        "residual displacement",
        {
            n: (b["residual_displacement_m"], m3["bodies"][n]["residual_displacement_m"])
            for n, b in p3["bodies"].items()
        },
        tol.residual,
        tol.moved_rel_height * H,
    )
    judge(
        "residual rotation",
        {n: (b["residual_rotation_rad"], m3["bodies"][n]["residual_rotation_rad"]) for n, b in p3["bodies"].items()},
        tol.residual,
        tol.moved_rel_height,
    )

    def state(b):
        return (
            "fell"
            if b["fallen"]
            else ("moved" if b["residual_displacement_m"] > tol.moved_rel_height * H else "stands")
        )

    for n, b in p3["bodies"].items():
        out[("outcome", n)] = 0.0 if state(b) == state(m3["bodies"][n]) else math.inf
    out[("outcome", "structure")] = 0.0 if p3["collapsed"] == m3["collapsed"] else math.inf
    return out


def test_the_verdict_of_a_column_is_its_own_summarys(column, tmp_path):
    s = column.summary()
    v = s["verdict"]
    tol = column.scenario.verdict
    ratios = _ratios(s, tol)
    assert not (s["3d"]["prototype"]["collapsed"] or s["3d"]["model"]["collapsed"])  # this case stands
    # every quantity of the whole structure judged, each with the ratio recomputed here (1e-12: the same
    # arithmetic in another order)
    judged = {(e["quantity"], e["where"]): e for e in v["judged"]}
    assert set(judged) == set(ratios)
    for key, r in ratios.items():
        assert judged[key]["ratio"] == pytest.approx(r, rel=1e-12, abs=1e-15), key
        assert judged[key]["ok"] is (r <= 1.0)
    worst = max(ratios, key=ratios.get)
    assert (v["worst"]["quantity"], v["worst"]["where"]) == worst
    assert v["worst"]["ratio"] == pytest.approx(ratios[worst], rel=1e-12)
    rest_ok = v["rest"] is None or v["rest"]["ok"]
    assert v["similar"] is (ratios[worst] <= 1.0 and rest_ok)
    # this column: the base drum's first peak is 13 % off (the top's 2 %), so it is NOT similar, naming P-1
    assert v["similar"] is False and worst == ("first peak", "P-1")
    assert v["line"].startswith("Verdict: NOT similar: first peak at P-1, 24.7 mm (up-scaled model) vs 21.8 mm")
    sc = column.scalars()
    assert sc["verdict.similar"] is False and sc["verdict.worst_ratio"] == v["worst"]["ratio"]
    from blastscale.report import summary_dict

    assert summary_dict(column, meta={})["verdict"] == v


def test_loosened_tolerances_make_the_same_column_similar(column):
    """The same runs judged with every tolerance x 3 (a [verdict] table): similar, worst ratio a third."""
    s = column.summary()
    tol = column.scenario.verdict
    loose = tol.model_copy(update={k: 3 * getattr(tol, k) for k in ("peak", "displacement", "residual")})
    from blastscale.study.criterion import judge

    v = judge(s, loose, structure_kind="column")
    assert v["similar"] is True and v["line"].startswith("Verdict: similar: prototype and up-scaled model both stand")
    assert v["worst"]["ratio"] == pytest.approx(s["verdict"]["worst"]["ratio"] / 3, rel=1e-12)
