"""The paper's Appendix A fits: units, guards and documented defects (docs/design.md)."""

import math

import numpy as np
import pytest

from blastscale._validate import BlastscaleInputError, OutOfRangeError
from blastscale.blast import ExtrapolationWarning, get_blast_model

M = get_blast_model("masi2021")


def test_units_are_converted_to_si():
    # Hand evaluation of the printed formulas at Z = 1 (ln Z = 0): P = (1 + e^-10/2) e^2.0304 MPa,
    # i_rw = e^-0.110157 MPa ms/kg^1/3, t_Aw = e^-0.6847 ms/kg^1/3. Exact up to round-off.
    assert M.reflected_pressure(1.0) == pytest.approx((1 + 0.5 * math.exp(-10)) * math.exp(2.0304) * 1e6, rel=1e-14)
    assert M.scaled_reflected_impulse(1.0) == pytest.approx(math.exp(-0.110157) * 1e3, rel=1e-14)
    assert M.scaled_arrival_time(1.0) == pytest.approx(math.exp(-0.6847) * 1e-3, rel=1e-14)
    td = 0.592 + 0.537 * math.cos(1.032 * (0 - 0.859)) ** 7 * math.sinh(1.088 * (0 - 2.023))
    assert M.scaled_positive_duration(1.0) == pytest.approx(math.exp(td) * 1e-3, rel=1e-14)


def test_duration_fit_guarded_above_6p5():
    # docs/design.md: the printed t_ow is trustworthy only for Z <= ~6.5 (diverges above ~12).
    M.scaled_positive_duration(6.5)
    with pytest.raises(OutOfRangeError, match=r"scaled_positive_duration.*Z = 7.*\[0.2, 6.5\]"):
        M.scaled_positive_duration(7.0)
    with pytest.warns(ExtrapolationWarning):
        assert np.isfinite(M.scaled_positive_duration(7.0, extrapolate=True))


def test_duration_constant_below_018_does_not_join_the_formula():
    # docs/design.md: the constant 0.251703 ms/kg^1/3 used below Z = 0.18 jumps 6.7 % from the formula at 0.18.
    with pytest.warns(ExtrapolationWarning):
        below = M.scaled_positive_duration(0.18 * (1 - 1e-12), extrapolate=True)
        at = M.scaled_positive_duration(0.18, extrapolate=True)
    assert abs(at / below - 1) == pytest.approx(0.067, abs=0.002)


def test_vectorised_shape_and_scalar_type():
    z = np.array([[0.5, 1.0], [2.0, 5.0]])
    assert M.reflected_pressure(z).shape == (2, 2)
    assert isinstance(M.reflected_pressure(0.5), float)
    # monotone decrease of pressure and scaled impulse with Z over the range (physical requirement)
    zz = np.geomspace(0.2, 20, 400)
    assert np.all(np.diff(M.reflected_pressure(zz)) < 0)
    assert np.all(np.diff(M.scaled_reflected_impulse(zz)) < 0)


@pytest.mark.parametrize(
    "z, words",
    [
        (0.0, ["Z = 0", "must be > 0"]),
        (-1.0, ["Z = -1", "must be > 0"]),
        (0.1, ["reflected_pressure (masi2021)", "Z = 0.1 m/kg^(1/3)", "[0.2, 20]"]),
        (25.0, ["reflected_pressure (masi2021)", "Z = 25 m/kg^(1/3)", "[0.2, 20]"]),
        (float("nan"), ["Z = nan", "not a finite number"]),
    ],
)
def test_out_of_range_z_names_quantity_value_and_range(z, words):
    # A named one-line error (never a NaN): the quantity where it applies, the Z value and the valid range.
    with pytest.raises(BlastscaleInputError) as e:
        M.reflected_pressure(z)
    msg = str(e.value)
    assert "\n" not in msg and all(w in msg for w in words), msg
