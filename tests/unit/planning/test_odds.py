"""The odds: Monte Carlo through the planar first-swing kernel against the lognormal closed form of a
charge tolerance alone near the critical charge, seeded reproducibility, the weighing precision."""

import math

import numpy as np
import pytest
from scipy.stats import norm

from blastscale.analysis.intervals import wilson_interval
from blastscale.planning.odds import Z90_ONE_SIDED, Tolerances, outcome_odds_text, planar_odds
from blastscale.rocking import RockingSystem, critical_charge
from blastscale.structures import RectangularBlock

BLOCK = RectangularBlock.from_slenderness(0.5, math.radians(15.0), 0.05, 140.0)  # the 1/20 balsa specimen
R = 0.1


@pytest.fixture(scope="module")
def wc():
    return critical_charge(RockingSystem.from_block(BLOCK), R, blast_model="masi2021").charge_kg


@pytest.mark.parametrize("ratio,beta", [(0.97, 0.05), (1.03, 0.08)])
def test_charge_alone_matches_the_lognormal_closed_form(wc, ratio, beta):
    """W eps overturns iff W eps > W_c: P(overturn) = Phi(ln(W / W_c) / beta), within 4 binomial
    standard errors (4000 draws, seed 7)."""
    n = 4000
    o = planar_odds(
        BLOCK,
        charge_kg=ratio * wc,
        standoff_m=R,
        prototype_collapsed=False,
        blast_model="masi2021",
        tolerances=Tolerances(charge=beta),
        samples=n,
        seed=7,
    )
    p = norm.cdf(math.log(ratio) / beta)
    se = math.sqrt(p * (1 - p) / n)
    assert abs(o.specimen_collapse_probability - p) < 4 * se
    assert o.p_outcome_agree == pytest.approx(1.0 - o.specimen_collapse_probability)
    assert o.p_outcome_agree == o.agree_count / o.trials and o.trials == n
    assert (o.p_outcome_agree_low, o.p_outcome_agree_high) == wilson_interval(o.agree_count, n)
    assert o.p_outcome_agree_low < o.p_outcome_agree < o.p_outcome_agree_high
    # and exactly the draws beyond the threshold (the same generator, the same order)
    eps = np.exp(beta * np.random.default_rng(7).standard_normal((4, n))[0])
    assert o.specimen_collapse_probability == pytest.approx(np.mean(ratio * wc * eps > wc), abs=2.0 / n)
    # the weighing precision that keeps the outcome with 95 %
    assert o.charge_tolerance_for_outcome == pytest.approx(abs(math.log(1 / ratio)) / Z90_ONE_SIDED, rel=1e-6)


def test_seed_reproduces_the_odds(wc):
    kw = dict(
        charge_kg=0.99 * wc,
        standoff_m=R,
        prototype_collapsed=False,
        blast_model="masi2021",
        tolerances=Tolerances(0.03, 0.001, 0.02, 0.05),
        samples=500,
    )
    a, b, c = (planar_odds(BLOCK, seed=s, **kw) for s in (3, 3, 4))
    assert a == b and a.p_outcome_agree != c.p_outcome_agree


def test_first_peak_spread_and_weighing_precision(wc):
    """Far from the threshold, with the charge alone: the first peak's relative spread is the sensitivity
    times beta (linearised, 10 %), and the precision for a 5 % target is ln(1.05) / (1.96 sensitivity)."""
    beta = 0.01
    o = planar_odds(
        BLOCK,
        charge_kg=0.5 * wc,
        standoff_m=R,
        prototype_collapsed=False,
        blast_model="masi2021",
        tolerances=Tolerances(charge=beta),
        samples=2000,
        seed=1,
        target=0.05,
    )
    assert o.p_outcome_agree == 1.0
    # 2000 of 2000 agree: P >= 0.998 at 95 % (Wilson), not P = 1 +- 0; upper bound exactly 1
    assert (o.agree_count, o.trials, o.p_outcome_agree_high) == (2000, 2000, 1.0)
    assert o.p_outcome_agree_low == pytest.approx(2000 / (2000 + 1.959963984540054**2), abs=1e-12)
    assert outcome_odds_text(o.to_dict()) == "P >= 0.998 (95 %, 2000 of 2000)"
    assert o.first_peak_spread == pytest.approx(abs(o.first_peak_sensitivity) * beta, rel=0.1)
    assert o.charge_tolerance_for_peak == pytest.approx(math.log(1.05) / (1.959963984540054 * o.first_peak_sensitivity))
