"""The one inversion of the blast fits (blastscale.blast.inverse): round trips through the fits, the kind
returned, the range and its errors."""

from __future__ import annotations

import numpy as np
import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.blast import blast_parameters
from blastscale.blast.inverse import (
    INVERTED_QUANTITIES,
    charge_for,
    scaled_distance_for,
    standoff_for,
)

FIELD = {
    "reflected_pressure": "reflected_pressure",
    "incident_pressure": "incident_pressure",
    "reflected_impulse": "reflected_impulse",
    "incident_impulse": "incident_impulse",
}


@pytest.mark.parametrize("quantity", sorted(INVERTED_QUANTITIES))
@pytest.mark.parametrize("blast_model", ["kingery-bulmash", "kingery-bulmash-free-air"])
def test_round_trip_through_the_fits_to_double_precision(quantity, blast_model):
    """charge_for and standoff_for undo blast_parameters over two decades of Z: 1e-12 relative (the root is
    found to double precision in ln Z; W = (R/Z)^3 triples the relative error)."""
    W = np.array([0.002, 0.5, 20.0, 300.0])
    R = np.array([0.8, 2.0, 9.0, 40.0])
    bp = blast_parameters(W, R, blast_model)
    v = getattr(bp, FIELD[quantity])
    assert charge_for(v, R, quantity, blast_model) == pytest.approx(W, rel=1e-12)
    assert standoff_for(v, W, quantity, blast_model) == pytest.approx(R, rel=1e-12)
    assert scaled_distance_for(v, quantity, blast_model, standoff=R) == pytest.approx(R / np.cbrt(W), rel=1e-12)


def test_returns_the_kind_it_was_given():
    bp = blast_parameters(2.0, 3.0)
    w = charge_for(bp.reflected_impulse, 3.0)
    assert isinstance(w, float) and w == pytest.approx(2.0, rel=1e-12)
    arr = charge_for(np.full((2, 3), float(bp.reflected_impulse)), 3.0)
    assert arr.shape == (2, 3)
    assert isinstance(standoff_for(bp.reflected_impulse, 2.0), float)


def test_a_value_out_of_reach_raises_naming_it_and_the_range():
    with pytest.raises(
        BlastscaleInputError, match=r"reflected_impulse = 1e\+09 Pa s at 2 m is out of range: .* over Z"
    ):
        charge_for(1e9, 2.0)
    assert np.isnan(charge_for(1e9, 2.0, outside="nan"))
    # "clip": the nearer end of the fit's range (Z_min: the most impulse it gives)
    assert charge_for(1e9, 2.0, outside="clip") == pytest.approx((2.0 / 0.06) ** 3, rel=1e-12)


@pytest.mark.parametrize(
    ("kw", "message"),
    [
        ({"quantity": "duration"}, "quantity = 'duration' is not known"),
        ({"outside": "wrap"}, "outside = 'wrap' is not known"),
        ({"blast_model": "masi2021", "quantity": "incident_pressure"}, "has no incident_pressure fit"),
    ],
)
def test_bad_arguments_name_parameter_value_and_valid_values(kw, message):
    with pytest.raises(BlastscaleInputError, match=message):
        scaled_distance_for(1e5, **{"quantity": "reflected_pressure", **kw})


def test_an_impulse_needs_one_of_standoff_and_charge():
    with pytest.raises(BlastscaleInputError, match="give the stand-off"):
        scaled_distance_for(100.0, "reflected_impulse")
    with pytest.raises(BlastscaleInputError, match="standoff = -1 m is out of range"):
        charge_for(100.0, -1.0)


def test_extrapolate_widens_the_range_five_times():
    """A peak beyond the fit's range at Z = 50 (valid up to 40 m/kg^(1/3)) is found only with extrapolate."""
    from blastscale.blast.parameters import get_blast_model

    p = float(get_blast_model("kingery-bulmash").reflected_pressure(50.0, extrapolate=True))
    with pytest.raises(BlastscaleInputError):
        scaled_distance_for(p, "reflected_pressure")
    assert scaled_distance_for(p, "reflected_pressure", extrapolate=True) == pytest.approx(50.0, rel=1e-12)
