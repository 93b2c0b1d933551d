"""The 3D capacity's stochastic bisection (blastscale.sweeps.capacity3d) on synthetic outcomes, without the engine:
a sharp threshold (the interval is the bracket and contains it), a bracket searched by steps of x2, a chaotic
transition (the lognormal fit's interval), and a structure that never falls (a "no")."""

import math

import pytest
from scipy.stats import norm

from blastscale.sweeps.capacity3d import _Search, planned_probes


def drive(search: _Search, outcome, members: int):
    """Run the search with ``outcome(W) -> fell count`` of ``members`` (the engine's place)."""
    for _ in range(200):
        ws = search.pending()
        if not ws:
            break
        search.tell({w: (outcome(w), members) for w in ws})
    return search.result()


def test_a_sharp_threshold_lies_inside_the_final_bracket():
    w_star = 123.4
    s = _Search(5.0, (1e-3, 1e6), 10.0, 0.02, given=(10.0, 1000.0))
    res = drive(s, lambda w: 2 * (w >= w_star), 2)
    lo, hi = res.interval_kg
    assert lo < w_star <= hi and hi / lo <= 1.02 + 1e-12
    assert res.interval_basis == "bisection bracket" and res.beta is None
    assert res.critical_charge_kg == pytest.approx(math.sqrt(lo * hi), rel=1e-15)
    assert len(res.probes) == planned_probes((10.0, 1000.0), 0.02)  # 2 + ceil(log2(ln 100 / ln 1.02))
    assert res.initial_bracket_kg == (10.0, 1000.0)


def test_without_a_bracket_it_steps_by_two_from_the_start():
    s = _Search(5.0, (1e-3, 1e6), 1.0, 0.02)
    res = drive(s, lambda w: 3 * (w >= 123.4), 3)
    assert res.initial_bracket_kg == (64.0, 128.0)  # 1, 2, 4, ..., 64 stand, 128 falls
    assert res.interval_kg[0] < 123.4 <= res.interval_kg[1]


def test_a_chaotic_transition_gives_the_lognormal_fits_interval():
    """Fall counts of 40 members following P = Phi(ln(W / 100) / 0.3): the fit's median is the crossing, within
    its own 95 % interval, which contains 100 kg (the counts are the expected ones, rounded)."""
    n = 40
    s = _Search(5.0, (1e-3, 1e6), 10.0, 0.01, given=(20.0, 500.0))
    res = drive(s, lambda w: int(round(n * norm.cdf(math.log(w / 100.0) / 0.3))), n)
    assert res.interval_basis == "lognormal fit, 95 %"
    lo, hi = res.interval_kg
    assert lo < res.critical_charge_kg < hi and lo < 100.0 < hi
    assert res.critical_charge_kg == pytest.approx(100.0, rel=0.05)
    assert res.beta == pytest.approx(0.3, rel=0.5)


def test_a_structure_that_never_falls_has_no_critical_charge():
    s = _Search(5.0, (1e-3, 1e3), 1.0, 0.02)
    res = drive(s, lambda w: 0, 2)
    assert res.critical_charge_kg is None and res.interval_kg is None
    assert "stands" in res.note and "1000" in res.note
    assert res.probes[-1].charge_kg == 1e3  # the range's end was probed
