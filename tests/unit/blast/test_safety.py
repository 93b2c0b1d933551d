"""Safety distances: the overpressure thresholds of a surface burst (Kingery-Bulmash inverted, Kinney-Graham
beyond its range), the DoD quantity-distance K-factors."""

import math

import numpy as np
import pytest

from blastscale.blast.kingery_bulmash import SWISDAK_1994_COEFFICIENTS
from blastscale.blast.safety import (
    FT_LB13,
    PSI,
    SAFETY_THRESHOLDS,
    far_field_joint,
    kinney_graham_overpressure,
    overpressure_distance,
    quantity_distance,
    safety_distances,
    surface_burst_overpressure,
)


def _kb_incident_kpa(z: float) -> float:
    """Swisdak's (1994) incident-pressure pieces evaluated here on their own (Horner's rule), an
    independent path to the fit."""
    for lo, hi, c in SWISDAK_1994_COEFFICIENTS["incident_pressure"]:
        if z <= hi:
            L, acc = math.log(z), 0.0
            for a in reversed(c):
                acc = acc * L + a
            return math.exp(acc)
    raise ValueError(z)


def _bisect(thr_kpa: float) -> float:
    lo, hi = 0.2, 198.5
    for _ in range(200):
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if _kb_incident_kpa(mid) > thr_kpa else (lo, mid)
    return math.sqrt(lo * hi)


@pytest.mark.parametrize("key", ["6.9 kPa", "34.5 kPa"])
def test_one_kg_distances_invert_kingery_bulmash(key):
    """1 kg TNT surface burst: the distance where P_so falls to the threshold, against Kingery-Bulmash
    inverted by bisection on its own (1e-3)."""
    thr = next(t for t in SAFETY_THRESHOLDS if t.key == key).pressure_Pa
    assert overpressure_distance(1.0, thr) == pytest.approx(_bisect(thr / 1e3), rel=1e-3)
    assert overpressure_distance(8.0, thr) == pytest.approx(2.0 * _bisect(thr / 1e3), rel=1e-3)  # cube-root scaling


def test_thresholds_are_their_stated_values():
    assert [t.pressure_Pa for t in SAFETY_THRESHOLDS] == pytest.approx([5 * PSI, PSI, 0.15 * PSI, 200.0])
    assert 20e-6 * 10 ** (140 / 20) == pytest.approx(200.0)  # 140 dB peak
    assert PSI == pytest.approx(6894.757, rel=1e-7)


def test_k_factor_distances_against_their_definition():
    """D = K W^(1/3), D in ft and W in lb: 1 lb gives K ft, 1000 lb 10 K ft."""
    lb = 0.45359237
    for k in (24.0, 40.0, 50.0):
        assert quantity_distance(lb, k) == pytest.approx(k * 0.3048, rel=1e-14)
        assert quantity_distance(1000 * lb, k) == pytest.approx(10 * k * 0.3048, rel=1e-14)
    d = safety_distances(1.0)
    assert d["K40"] == pytest.approx(40 * FT_LB13, rel=1e-14)


@pytest.mark.parametrize("k,psi", [(24, 2.3), (40, 1.2), (50, 0.9), (328, 0.0655)])
def test_k_factors_match_the_dod_expected_overpressures(k, psi):
    """DoD 6055.09-M's overpressures at K24, K40, K50, K328 follow Kingery-Bulmash (within 3 %)."""
    assert surface_burst_overpressure(k * FT_LB13) / PSI == pytest.approx(psi, rel=0.03)


def test_far_field_law_joins_kingery_bulmash_continuously():
    j = far_field_joint()
    z = j["scaled_distance_m_per_kg13"]
    below, above = surface_burst_overpressure(z * (1 - 1e-12)), surface_burst_overpressure(z * (1 + 1e-12))
    assert above == pytest.approx(below, rel=1e-9)  # the curve used: no jump
    assert j["raw_jump"] == pytest.approx(2.061, abs=1e-3)  # Kinney-Graham unanchored: stated, 2.06 x
    zz = np.geomspace(z, 1e4, 200)
    p = surface_burst_overpressure(zz)
    assert np.all(np.diff(p) < 0)  # decays monotonically beyond the joint
    ratio = kinney_graham_overpressure(zz / 1.8 ** (1 / 3)) / p  # Kinney-Graham's decay, anchored
    assert np.allclose(ratio, j["raw_jump"], rtol=1e-12)


def test_distances_grow_as_thresholds_fall_and_hearing_lies_in_the_far_field():
    d = safety_distances(1.0)
    keys = [t.key for t in SAFETY_THRESHOLDS]
    assert all(d[a] < d[b] for a, b in zip(keys, keys[1:]))
    assert d["200 Pa"] / 1.0 > far_field_joint()["scaled_distance_m_per_kg13"]


def test_bad_inputs_are_one_line():
    from blastscale._validate import BlastscaleInputError

    with pytest.raises(BlastscaleInputError, match="threshold"):
        overpressure_distance(1.0, 1e9)
    with pytest.raises(BlastscaleInputError, match="charge"):
        overpressure_distance(-1.0, 1e3)
