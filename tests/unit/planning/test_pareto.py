"""Pareto-optimal designs: checked against the definition by brute force, and on hand-made cases."""

import itertools

import numpy as np
import pytest

from blastscale.planning.pareto import mark_pareto, pareto_mask


def _brute(c):
    """Row i is dominated if some row j is <= in every column and < in one (the definition, loops)."""
    n = len(c)
    return [
        not any(
            all(c[j][k] <= c[i][k] for k in range(len(c[i]))) and any(c[j][k] < c[i][k] for k in range(len(c[i])))
            for j in range(n)
            if j != i
        )
        for i in range(n)
    ]


@pytest.mark.parametrize("seed", range(5))
def test_mask_is_the_definition(seed):
    rng = np.random.default_rng(seed)
    c = rng.integers(0, 4, size=(40, 4)).astype(float)  # small integers: many ties and dominated rows
    assert pareto_mask(c).tolist() == _brute(c.tolist())


def test_hand_made_front():
    # (p_outcome_agree, error, safety radius, charge): A best odds, B smallest charge, C dominated by A, D equals A
    d = [
        dict(p_outcome_agree=1.0, predicted_first_peak_error=0.01, safety_radius_m=2.0, tnt_equivalent_kg=1e-3),
        dict(p_outcome_agree=0.9, predicted_first_peak_error=0.02, safety_radius_m=1.0, tnt_equivalent_kg=1e-4),
        dict(p_outcome_agree=0.95, predicted_first_peak_error=0.01, safety_radius_m=2.0, tnt_equivalent_kg=1e-3),
        dict(p_outcome_agree=1.0, predicted_first_peak_error=0.01, safety_radius_m=2.0, tnt_equivalent_kg=1e-3),
        dict(p_outcome_agree=None, predicted_first_peak_error=0.0, safety_radius_m=0.1, tnt_equivalent_kg=1e-6),
    ]
    mark_pareto(d)
    assert [x["pareto"] for x in d] == [True, True, False, True, None]  # no odds: not compared


def test_every_point_of_a_front_on_a_line_is_optimal():
    c = np.array([[x, 1.0 - x, 0.0, 0.0] for x in np.linspace(0, 1, 7)])
    assert pareto_mask(c).all()
    assert not any(pareto_mask(np.vstack([c, [-1.0, -1.0, -1.0, -1.0]]))[:-1])  # one point dominating all
    assert list(itertools.compress(range(8), pareto_mask(np.vstack([c, [-1.0, -1.0, -1.0, -1.0]])))) == [7]
