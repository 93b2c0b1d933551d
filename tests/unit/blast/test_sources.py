"""A calibrated blast source (blastscale.blast.sources): its power law, uncertainty, limits and file tables against
closed forms written here."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.stats import f as f_dist

from blastscale._validate import BlastscaleInputError
from blastscale.blast.sources import CalibratedSource, PowerLaw, source_from_dict, source_to_dict

#: A law of known parameters: W = 1e-7 kg (x / 1000 J)^1.2, var(ln W_ref) = 4e-4, var(k) = 9e-4, cov 1e-4.
LAW = PowerLaw(1000.0, 1e-7, 1.2, ((4e-4, 1e-4), (1e-4, 9e-4)), 8, 0.03)


def _source(**kw) -> CalibratedSource:
    base = dict(
        name="bank",
        kind="exploding-wire",
        control="stored_energy",
        control_unit="J",
        control_min=200.0,
        control_max=5000.0,
        impulse=LAW,
        pressure=PowerLaw(1000.0, 8e-8, 1.3, ((4e-4, 0.0), (0.0, 9e-4)), 8, 0.04),
        blast_model="masi2021",
        burst="surface",
        calibrated_control=(500.0, 4000.0),
        calibrated_scaled_distance=(2.0, 15.0),
        shots=10,
        synthetic=True,
        details={"wire_material": "aluminium", "wire_length_m": 0.04},
    )
    return CalibratedSource(**{**base, **kw})


def test_the_law_and_its_inverse_are_the_closed_form():
    x = np.array([250.0, 1000.0, 3700.0])
    w = LAW.tnt_kg(x)
    np.testing.assert_allclose(w, 1e-7 * (x / 1000.0) ** 1.2, rtol=1e-14)
    np.testing.assert_allclose(LAW.control_for(w), x, rtol=1e-13)


def test_the_interval_is_the_working_hotelling_band():
    # sigma^2 = C00 + 2 C01 u + C11 u^2 at u = ln 2; half-width sqrt(2 F_0.95(2, 8)) sigma in ln W (F_0.95(2, 8) =
    # 4.459, the tabulated 95 % point of F with 2 and 8 degrees of freedom)
    u = math.log(2.0)
    sigma = math.sqrt(4e-4 + 2e-4 * u + 9e-4 * u * u)
    assert float(LAW.sigma_fit(2000.0)) == pytest.approx(sigma, rel=1e-12)
    lo, hi = LAW.interval(2000.0)
    h = math.sqrt(2.0 * f_dist.ppf(0.95, 2, 8)) * sigma
    assert f_dist.ppf(0.95, 2, 8) == pytest.approx(4.459, abs=5e-4)
    w = 1e-7 * 2.0**1.2
    assert (float(lo), float(hi)) == pytest.approx((w * math.exp(-h), w * math.exp(h)), rel=1e-12)
    # at the reference the fit's sigma is the intercept's alone; one shot adds the repeatability in quadrature
    assert float(LAW.sigma_fit(1000.0)) == pytest.approx(0.02, rel=1e-12)
    assert float(LAW.sigma_shot(1000.0)) == pytest.approx(math.hypot(0.02, 0.03), rel=1e-12)


def test_a_shot_inside_the_limits_and_one_outside():
    s = _source()
    shot = s.shot(float(LAW.tnt_kg(1850.0)), "masi2021", 5.0)
    assert shot.control_value == pytest.approx(1850.0, rel=1e-12)
    assert shot.setting == "charge the bank to 1.85 kJ"
    assert shot.violations == ()
    assert shot.tnt_equivalent_pressure_kg == pytest.approx(8e-8 * 1.85**1.3, rel=1e-12)
    assert shot.sigma_ln_impulse == pytest.approx(float(np.hypot(0.03, LAW.sigma_fit(1850.0))), rel=1e-12)
    # the edge: exactly control_max is allowed; just above it is refused with the key, value and limit
    assert s.shot(float(LAW.tnt_kg(5000.0))).violations == ()
    over = s.shot(float(LAW.tnt_kg(5200.0)))
    (key, value, limit, text), *_ = over.violations
    assert (key, limit) == ("source control_max", 5000.0) and value == pytest.approx(5200.0)
    assert "5200 J > the source's control_max = 5000 J" in text
    assert s.shot(float(LAW.tnt_kg(150.0))).violations[0][0] == "source control_min"


def test_a_shot_warns_of_another_blast_model_and_of_an_extrapolation():
    s = _source(synthetic=False)
    assert s.shot(float(LAW.tnt_kg(1000.0)), "masi2021", 5.0).warnings == ()
    notes = " ".join(s.shot(float(LAW.tnt_kg(4500.0)), "kingery-bulmash", 30.0).warnings)
    assert "not the source's ('masi2021'" in notes
    assert "outside the calibrated 500-4000 J" in notes
    assert "self-similarity is extrapolated" in notes


def test_the_file_tables_round_trip_and_a_bad_key_is_named():
    s = _source()
    assert source_from_dict(source_to_dict(s)) == s
    d = source_to_dict(s)
    d["equivalence"]["impulse"]["exponent"] = -1.0
    with pytest.raises(BlastscaleInputError, match=r"equivalence.impulse.exponent = -1.0 is out of range: valid range"):
        source_from_dict(d, "s.toml")
    d = source_to_dict(s)
    del d["source"]["control_max"]
    with pytest.raises(BlastscaleInputError, match=r"source.control_max is missing"):
        source_from_dict(d, "s.toml")
    d = source_to_dict(s)
    d["equivalence"]["pressure"]["covariance"] = [[1.0, 0.0]]
    with pytest.raises(BlastscaleInputError, match=r"covariance = .* is not a covariance"):
        source_from_dict(d, "s.toml")
