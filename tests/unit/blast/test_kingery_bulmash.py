"""Kingery-Bulmash (Swisdak 1994) hemispherical surface burst, checked against independent data.

* UFC 3-340-02 Fig. 2-15, digitised points (tests/data/ufc_3_340_02_fig2_15.csv, source and
  reading method in its header);
* the paper's Appendix A fits (model "masi2021"), themselves fitted to Kingery-Bulmash;
* Rankine-Hugoniot for the shock-front velocity, the acoustic limit P_r -> 2 P_so;
* continuity of Swisdak's pieces, range errors, and the array/scalar contract.
"""

import csv
import math
import warnings
from pathlib import Path

import numpy as np
import pytest

from blastscale._validate import OutOfRangeError
from blastscale.blast import ExtrapolationWarning, blast_parameters, get_blast_model
from blastscale.blast.base import QUANTITIES
from blastscale.blast.kingery_bulmash import (
    SWISDAK_1994_COEFFICIENTS,
    KingeryBulmash,
    piece_boundaries,
)
from blastscale.blast.masi_fits import Masi2021

DATA = Path(__file__).resolve().parents[2] / "data"
KB = KingeryBulmash()
MASI = Masi2021()


def _ufc_rows():
    with open(DATA / "ufc_3_340_02_fig2_15.csv", newline="") as fh:
        lines = [ln for ln in fh if not ln.startswith("#")]
    return [
        pytest.param(
            r["quantity"],
            float(r["z_m_per_kg13"]),
            float(r["value_si"]),
            id=f"{r['quantity']}-Z{float(r['z_m_per_kg13']):.3g}",
        )
        for r in csv.DictReader(lines)
    ]


UFC_ROWS = _ufc_rows()


# ------------------------------------------------------------------ (a) UFC 3-340-02 Fig. 2-15
@pytest.mark.parametrize("quantity, z, ufc_value", UFC_ROWS)
def test_ufc_3_340_02_fig_2_15_hemispherical_surface_burst(quantity, z, ufc_value):
    # Tolerance 4 % (docs/design.md: ~3.5 %): Swisdak's fits follow Kingery-Bulmash and Fig. 2-15 is drawn
    # from Kingery-Bulmash, so the remainder is chart-reading error (1-2 % per coordinate on a
    # log-log chart). Measured over the 96 points: max 3.3 % (P_r at Z = 37.9, P_so at Z = 37.8).
    model = getattr(KB, quantity)(z)
    assert model == pytest.approx(ufc_value, rel=0.04)


def test_ufc_csv_covers_every_quantity_of_fig_2_15_over_0p2_to_38():
    # The CSV must test six quantities of Fig. 2-15 from Z <= 0.23 (Swisdak starts at 0.06 or 0.2)
    # to Z >= 37 (the chart ends at 40).
    by_q = {}
    for p in UFC_ROWS:
        q, z, _ = p.values
        by_q.setdefault(q, []).append(z)
    assert set(by_q) == {
        "incident_pressure",
        "reflected_pressure",
        "scaled_incident_impulse",
        "scaled_reflected_impulse",
        "scaled_arrival_time",
        "scaled_positive_duration",
    }
    for zs in by_q.values():
        assert len(zs) >= 12 and min(zs) <= 0.23 and max(zs) >= 37.0


def _imperial_pieces():
    rows = np.genfromtxt(DATA / "swisdak_1994_imperial.csv", delimiter=",", comments="#", dtype=None, encoding="utf-8")
    out: dict[str, list] = {}
    for r in rows:
        out.setdefault(str(r[0]), []).append((float(r[1]), float(r[2]), [float(c) for c in list(r)[3:]]))
    return out


IMPERIAL = _imperial_pieces()
# Exact unit factors: Z [ft/lb^(1/3)] -> [m/kg^(1/3)] and imperial Y -> SI.
_ZF = 0.3048 / 0.45359237 ** (1 / 3)
_PSI, _PER_LB13 = 6894.757293168, 1.0 / 0.45359237 ** (1 / 3)
_Y_TO_SI = {
    "incident_pressure": _PSI,
    "reflected_pressure": _PSI,
    "scaled_incident_impulse": _PSI * 1e-3 * _PER_LB13,
    "scaled_reflected_impulse": _PSI * 1e-3 * _PER_LB13,
    "scaled_positive_duration": 1e-3 * _PER_LB13,
    "shock_front_velocity": 0.3048 * 1e3,
}


@pytest.mark.parametrize(
    "quantity, tol",
    [
        # Tolerances from the measured agreement (a mistyped digit moves a fit by >= ~1 % somewhere):
        # P_so, i_s, i_r: the metric table is the imperial one in other units (measured max 0.02 %,
        # 0.07 %, 0.09 %): 0.15 %.
        ("incident_pressure", 0.0015),
        ("scaled_incident_impulse", 0.0015),
        ("scaled_reflected_impulse", 0.0015),
        # P_r, t_o, U: separate refits with other piece boundaries (measured max 1.47 %, 1.39 %, 0.43 %
        # away from the boundaries): 2 %.
        ("reflected_pressure", 0.02),
        ("scaled_positive_duration", 0.02),
        ("shock_front_velocity", 0.02),
    ],
)
def test_metric_coefficients_agree_with_swisdak_imperial_table(quantity, tol):
    # Independent provenance check of SWISDAK_1994_COEFFICIENTS: Swisdak's imperial table (another
    # transcription, tests/data/swisdak_1994_imperial.csv) converted to SI with exact unit factors.
    # Compared for Z >= 0.2 m/kg^(1/3) and away (+-5 % in Z) from every piece boundary of either table,
    # where two piecewise fits of the same data legitimately differ by their joins.
    lo, hi = KB.valid_range(quantity)
    bounds = list(piece_boundaries(quantity)) + [b * _ZF for (_, b, _) in IMPERIAL[quantity][:-1]]
    n = 0
    for a, b, coefs in IMPERIAL[quantity]:
        z = np.geomspace(a, b, 300)[1:-1] * _ZF
        z = z[(z >= max(lo, 0.2)) & (z <= hi)]
        for bb in bounds:
            z = z[np.abs(np.log(z / bb)) > 0.05]
        if z.size == 0:
            continue
        imperial = np.exp(np.polynomial.polynomial.polyval(np.log(z / _ZF), coefs)) * _Y_TO_SI[quantity]
        np.testing.assert_allclose(getattr(KB, quantity)(z), imperial, rtol=tol)
        n += z.size
    assert n > 200  # the comparison covers the range, not a handful of points


def test_reflected_impulse_cubic_coefficient_is_negative():
    # Swisdak's imperial table has D = -0.01123 and the top coefficient is invariant under the
    # unit change (a shift of ln Z). With +0.01123 the fit misses Fig. 2-15 by -36 % at
    # Z = 0.067 and +190 % at Z = 38; the UFC test above is what pins it, this is the record.
    assert SWISDAK_1994_COEFFICIENTS["scaled_reflected_impulse"][0][2][3] == -0.01123


# ------------------------------------------------------------------ (b) paper's Appendix A fits
@pytest.mark.parametrize(
    "quantity, z_lo, z_hi, measured_max",
    [
        # measured max |KB/masi2021 - 1| over 2000 log-spaced Z (kept here as the record):
        ("reflected_pressure", 0.2, 20.0, 0.0703),  # +7.0 % at Z = 0.98
        ("scaled_reflected_impulse", 0.2, 20.0, 0.0859),  # +8.6 % at Z = 6.7
        ("scaled_arrival_time", 0.2, 20.0, 0.0756),  # -7.6 % at Z = 1.18
        ("scaled_positive_duration", 0.2, 6.5, 0.0917),  # -9.2 % at Z = 0.76
    ],
)
def test_matches_paper_appendix_a_fits_within_10_percent(quantity, z_lo, z_hi, measured_max):
    # Tolerance 10 % (brief): the paper's fits are smooth single formulas fitted to the same
    # Kingery-Bulmash data; they cannot follow its kinks (t_o hump at Z ~ 1, P_r Mach knee).
    z = np.geomspace(z_lo, z_hi, 2000)
    dev = getattr(KB, quantity)(z) / getattr(MASI, quantity)(z) - 1.0
    worst = float(np.max(np.abs(dev)))
    assert worst < 0.10
    # and the measured figure above is still the figure (a change of coefficients shows here)
    assert worst == pytest.approx(measured_max, abs=0.002)


# ------------------------------------------------------------------ physics consistency
def test_shock_velocity_agrees_with_rankine_hugoniot_of_incident_pressure():
    # U = c0 sqrt(1 + 6 P_so / (7 p0)) (ideal gas, gamma = 1.4; c0 = 340.3 m/s, p0 = 101325 Pa).
    # Two separate fits (U and P_so) linked by a perfect-gas jump condition: agreement within
    # 5 % (measured 4.1 % at Z = 0.2, where the hot air departs from gamma = 1.4; 0.15 % at Z = 40).
    z = np.geomspace(0.2, 40.0, 500)
    rh = 340.3 * np.sqrt(1.0 + 6.0 * KB.incident_pressure(z) / (7.0 * 101325.0))
    np.testing.assert_allclose(KB.shock_front_velocity(z), rh, rtol=0.05)
    # far field: the shock becomes a sound wave, U -> c0. At Z = 40 the shock still carries
    # P_so = 2.4 kPa, for which Rankine-Hugoniot puts U 1.0 % above c0: tolerance 1.5 %.
    assert KB.shock_front_velocity(40.0) == pytest.approx(340.3, rel=0.015)


def test_reflection_factor_tends_to_acoustic_limit_two():
    # Normal reflection of a weak shock doubles the overpressure (acoustic limit): P_r/P_so -> 2
    # at Z = 40 (within 2 %), and it grows with shock strength (> 8 close in, UFC Fig. 2-193).
    ratio = KB.reflected_pressure(np.array([0.2, 1.0, 40.0])) / KB.incident_pressure(np.array([0.2, 1.0, 40.0]))
    assert ratio[2] == pytest.approx(2.0, rel=0.02)
    assert ratio[0] > 8.0 and ratio[0] > ratio[1] > ratio[2]


@pytest.mark.parametrize(
    "quantity, sign",
    [
        ("reflected_pressure", -1),
        ("incident_pressure", -1),
        ("scaled_reflected_impulse", -1),
        ("scaled_arrival_time", +1),
        # (not U: its fit has a 0.1 % dip to 343.8 m/s at Z = 36 before 344.2 m/s at Z = 40)
    ],
)
def test_monotone_within_each_piece_where_physics_says_so(quantity, sign):
    # Peak pressures, reflected impulse and shock speed fall, arrival time grows with distance.
    # Checked inside each of Swisdak's pieces: across a boundary the small jumps (next test) may
    # go the other way (P_so steps up by 0.70 % at Z = 23.8).
    for lo, hi, _ in SWISDAK_1994_COEFFICIENTS[quantity]:
        lo, hi = max(lo, 0.06), min(hi, 40.0)
        z = np.geomspace(lo, hi, 1000)[1:]  # the lower end belongs to the piece below
        assert np.all(sign * np.diff(getattr(KB, quantity)(z)) > 0), (lo, hi)


def test_reflected_impulse_exceeds_incident_impulse():
    z = np.geomspace(0.2, 40.0, 3000)
    assert np.all(KB.scaled_reflected_impulse(z) > KB.scaled_incident_impulse(z))


def _jumps():
    out = []
    for q in SWISDAK_1994_COEFFICIENTS:
        for b in piece_boundaries(q):
            lo = KB._evaluate(q, b, False)  # a boundary point belongs to the lower piece
            hi = KB._evaluate(q, math.nextafter(b, math.inf), False)
            out.append(pytest.param(q, b, hi / lo - 1.0, id=f"{q}-Z{b:g}"))
    return out


@pytest.mark.parametrize("quantity, boundary, jump", _jumps())
def test_piece_boundaries_join_within_published_accuracy(quantity, boundary, jump):
    # A mistyped digit shows as a jump. Measured: largest 2.40 % (i_s at Z = 2.38), then
    # t_o -1.19 % (1.02), -0.90 % (2.8), P_so +0.70 % (23.8), all others < 0.25 %.
    # Tolerance 2.5 %: below the 4 % UFC agreement; a wrong digit gives far more.
    assert abs(jump) < 0.025


# ------------------------------------------------------------------ (c) ranges
@pytest.mark.parametrize("quantity", QUANTITIES)
def test_every_quantity_has_its_own_range(quantity):
    lo, hi = KB.valid_range(quantity)
    pieces = SWISDAK_1994_COEFFICIENTS[quantity]
    assert (lo, hi) == (pieces[0][0], pieces[-1][1])
    # pieces tile the range without gaps
    for (a, b, _), (c, _, _) in zip(pieces[:-1], pieces[1:]):
        assert b == c and a < b


@pytest.mark.parametrize("quantity", QUANTITIES)
def test_out_of_range_raises_naming_quantity_z_and_range(quantity):
    lo, hi = KB.valid_range(quantity)
    z_bad = hi * 1.5
    with pytest.raises(OutOfRangeError) as exc:
        getattr(KB, quantity)(z_bad)
    msg = str(exc.value)
    assert quantity in msg and f"{z_bad:.6g}" in msg and f"[{lo:g}, {hi:g}]" in msg
    with pytest.raises(OutOfRangeError):
        getattr(KB, quantity)(np.array([lo, lo * 0.5]))


@pytest.mark.parametrize("quantity", QUANTITIES)
def test_extrapolate_warns_and_returns_finite(quantity):
    lo, hi = KB.valid_range(quantity)
    for z in (lo * 0.8, hi * 1.2):
        with pytest.warns(ExtrapolationWarning, match=quantity):
            v = getattr(KB, quantity)(z, extrapolate=True)
        assert isinstance(v, float) and math.isfinite(v) and v > 0


def test_nonpositive_z_rejected():
    with pytest.raises(OutOfRangeError, match="must be > 0"):
        KB.reflected_pressure(0.0, extrapolate=True)


# ------------------------------------------------------------------ (d) shapes
@pytest.mark.parametrize("quantity", QUANTITIES)
def test_array_in_array_out_scalar_in_float_out(quantity):
    z = np.array([[0.3, 0.5, 1.0], [2.0, 5.0, 10.0]])
    out = getattr(KB, quantity)(z)
    assert isinstance(out, np.ndarray) and out.shape == z.shape
    single = getattr(KB, quantity)(1.0)
    assert isinstance(single, float)
    # the array path is the scalar path element by element (piece selection per element)
    np.testing.assert_allclose(out, [[getattr(KB, quantity)(float(v)) for v in row] for row in z], rtol=1e-14)


# ------------------------------------------------------------------ registry
def test_default_model_is_kingery_bulmash_with_incident_quantities():
    assert isinstance(get_blast_model(), KingeryBulmash)
    bp = blast_parameters(100.0, 10.0)  # Z = 2.154 m/kg^(1/3)
    assert bp.blast_model == "kingery-bulmash"
    w13 = 100.0 ** (1.0 / 3.0)
    z = 10.0 / w13
    assert bp.reflected_pressure == pytest.approx(KB.reflected_pressure(z), rel=1e-12)
    assert bp.reflected_impulse == pytest.approx(KB.scaled_reflected_impulse(z) * w13, rel=1e-12)
    assert bp.incident_impulse == pytest.approx(KB.scaled_incident_impulse(z) * w13, rel=1e-12)
    assert bp.arrival_time == pytest.approx(KB.scaled_arrival_time(z) * w13, rel=1e-12)
    assert bp.incident_pressure is not None and bp.shock_front_velocity is not None
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a valid point must not warn
        KB.reflected_pressure(z)


@pytest.mark.parametrize("model", ["kingery-bulmash", "masi2021"])
def test_blast_parameters_vectorised_equals_scalar_path(model):
    # Arrays broadcast (charges x stand-offs); each element equals the scalar call (1e-12: same arithmetic,
    # the Friedlander root solved per element to ~1e-14).
    W = np.array([[10.0], [50.0], [200.0]])
    R = np.array([2.0, 3.0, 5.0])
    b = blast_parameters(W, R, model)
    assert b.reflected_pressure.shape == (3, 3)
    for (j, k), _ in np.ndenumerate(b.reflected_pressure):
        s = blast_parameters(float(W[j, 0]), float(R[k]), model)
        for f in ("reflected_pressure", "reflected_impulse", "arrival_time", "positive_duration", "friedlander_decay"):
            assert getattr(b, f)[j, k] == pytest.approx(getattr(s, f), rel=1e-12), f
    assert isinstance(b.to_dict()["reflected_pressure_Pa"], list)


def test_blast_parameters_bad_shapes_and_values():
    from blastscale._validate import BlastscaleInputError

    with pytest.raises(BlastscaleInputError, match=r"shapes \(3,\) and \(2,\)"):
        blast_parameters([1.0, 2.0, 3.0], [1.0, 2.0])
    with pytest.raises(BlastscaleInputError, match=r"standoff = -1 m .*> 0"):
        blast_parameters([1.0, 2.0], [1.0, -1.0])
    with pytest.raises(BlastscaleInputError, match="a pulse needs one charge"):
        blast_parameters([10.0, 20.0], 5.0).pulse()
