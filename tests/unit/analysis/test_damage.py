"""Damage states (analysis.damage): the limits of the [damage] table at their edges, collapse from a fall,
the Study summary's damage section for a planar block, and ensemble members."""

from __future__ import annotations

import math
from types import SimpleNamespace

import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.analysis.damage import LEVELS, damage_state, damage_summary
from blastscale.scenario import DamageSpec, Scenario
from blastscale.study import Study

LIM = DamageSpec()  # intact 1e-3 (drift) and 1e-3 rad, moderate from 6e-3, severe from 1e-2
H = 10.0


def body(u=0.0, phi=0.0, fell=False):
    return {"residual_displacement_m": u, "residual_rotation_rad": phi, "fallen": fell}


@pytest.mark.parametrize(
    "u, phi, name",
    [
        (0.0, 0.0, "intact"),
        (0.01, 1e-3, "intact"),  # both exactly at the intact limits (<=): intact
        (0.0101, 0.0, "slight"),  # just past the drift limit
        (0.0, 1.01e-3, "slight"),  # past the rotation limit alone: damaged, the mildest band
        (0.0599, 0.0, "slight"),
        (0.06, 0.0, "moderate"),  # at the moderate limit (>=)
        (0.0999, 0.5, "moderate"),  # a large rotation does not raise the band: bands are by drift
        (0.1, 0.0, "severe"),
        (3.0, 0.0, "severe"),
    ],
)
def test_states_at_the_edges_of_the_limits(u, phi, name):
    """Drift = largest residual displacement / H = u / 10 m; the state's name and level follow the table."""
    s = damage_state({"D-1": body(0.0), "D-2": body(u, phi)}, H, LIM)
    assert s.name == name and s.level == LEVELS.index(name)
    assert s.state == ("intact" if name == "intact" else "damaged")
    assert s.residual_drift == pytest.approx(u / H, rel=1e-15)


def test_a_fall_or_a_collapse_is_collapse_whatever_the_offsets():
    s = damage_state({"D-1": body(0.0), "D-2": body(0.0, 0.0, True)}, H, LIM)
    assert (s.state, s.band, s.level, s.fallen) == ("collapse", None, 4, ("D-2",))
    assert damage_state({"D-1": body(0.0)}, H, LIM, collapsed=True).name == "collapse"
    # planar rocking: no bodies; intact unless it overturned, no residual quantities
    p = damage_state(None, H, LIM)
    assert p.name == "intact" and math.isnan(p.residual_drift) and math.isnan(p.residual_rotation_rad)


def test_a_height_that_is_no_height_is_refused():
    with pytest.raises(BlastscaleInputError, match="height_m = 0.0 is out of range"):
        damage_state({"D-1": body(0.01)}, 0.0, LIM)


def test_the_limits_must_increase():
    with pytest.raises(BlastscaleInputError, match="must increase"):
        Scenario.default().with_values({"damage.moderate_drift": 0.02})  # above severe_drift = 0.01


def test_study_summary_damage_planar_block_prototype_and_model():
    """The paper's block, planar: 50 kg at 2 m rocks and comes back (intact); 130 kg overturns (collapse, at
    the first-swing median of about 80 kg, tests/integration/test_fragility.py). The model is up-scaled: the
    same state."""
    for charge, name in ((50.0, "intact"), (130.0, "collapse")):
        r = Study(
            Scenario.default().with_values({"engine": "planar", "charge_kg": charge, "critical_charge": False})
        ).run()
        d = r.summary()["damage"]
        assert d["engine"] == "planar" and d["prototype"]["name"] == name and d["model"]["name"] == name
        assert r.scalars()["damage.prototype.level"] == LEVELS.index(name)


def test_ensemble_members_each_get_a_state():
    """Three members of a 2-body structure (H = 10 m): one intact, one moderate (6 cm), one whose top fell."""
    members = [
        {"A": body(0.0), "B": body(0.005)},
        {"A": body(0.0), "B": body(0.07)},
        {"A": body(0.0), "B": body(0.2, 0.3, True)},
    ]
    ens = SimpleNamespace(
        prototype={"member_bodies": members, "member_collapsed": [False, False, True]},
        model={"member_bodies": members[:1], "member_collapsed": [False]},
    )
    summary = {"3d": {"prototype": {"bodies": members[1], "collapsed": False}, "model": None}}
    d = damage_summary(summary, LIM, H, ens)
    assert d["prototype"]["name"] == "moderate" and d["model"] is None
    assert d["ensemble"]["prototype"]["members"] == ["intact", "moderate", "collapse"]
    assert d["ensemble"]["prototype"]["counts"] == {"intact": 1, "slight": 0, "moderate": 1, "severe": 0, "collapse": 1}
    assert d["ensemble"]["model"]["members"] == ["intact"]
