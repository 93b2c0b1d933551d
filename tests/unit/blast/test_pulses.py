"""Pulse shapes: each integral equals its impulse; the Friedlander decay root; bad input."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from blastscale._validate import BlastscaleInputError
from blastscale.blast import Friedlander, Impulsive, Tabulated, Triangular, blast_parameters, friedlander_decay
from blastscale.blast.friedlander import NegativeDecayWarning, friedlander_impulse_ratio
from blastscale.similitude import scaling_factors


@pytest.mark.parametrize("d", [-0.9, -0.3, 1e-9, 0.5, 3.377, 20.0, 300.0])
def test_friedlander_integral_equals_eq2_impulse(d):
    # Paper Eq. (2) vs adaptive quadrature of Eq. (1): quad's own error estimate is < 1e-10 relative.
    p = Friedlander(3.0e7, 1.2e-3, d)
    num, err = quad(p.pressure, 0.0, p.duration, epsabs=0, epsrel=1e-12, limit=200)
    assert num == pytest.approx(p.impulse, rel=1e-9)
    assert p.cumulative_impulse(p.duration) == pytest.approx(p.impulse, rel=1e-12)
    t = np.linspace(0, p.duration, 7)[1:-1]
    for ti in t:  # running integral vs quadrature
        assert p.cumulative_impulse(ti) == pytest.approx(quad(p.pressure, 0, ti, epsrel=1e-12)[0], rel=1e-9)


def test_friedlander_decay_inverts_eq2():
    # Round trip k(d) -> d from d = -0.99 to 1e12 (an almost-impulsive pulse, k ~ 1/d): relative error
    # < 1e-8 (bisection + Newton polish). A fixed upper bracket (once 1e9) would miss the last two.
    d = np.array([-0.99, -0.5, -1e-5, 1e-7, 1e-3, 0.1, 1.0, 10.0, 1e3, 1e5, 1e9, 1e12])
    k = friedlander_impulse_ratio(d)
    with pytest.warns(NegativeDecayWarning):
        back = friedlander_decay(1.0, 1.0, k)
    np.testing.assert_allclose(back, d, rtol=1e-8, atol=1e-10)


def test_friedlander_no_positive_decay():
    # k >= 1/2: no positive decay; the default gives the negative root with a warning, strict mode refuses,
    # and k >= e - 2 has no monotone Friedlander fit at all.
    with pytest.warns(NegativeDecayWarning):
        d = friedlander_decay(1.0, 1.0, 0.6)
    assert -1.0 < d < 0.0
    with pytest.raises(BlastscaleInputError, match="0.5"):
        friedlander_decay(1.0, 1.0, 0.6, allow_negative=False)
    with pytest.raises(BlastscaleInputError, match="impulse ratio"):
        friedlander_decay(1.0, 1.0, 0.75)


def test_triangular_is_cut_at_two_i_over_p():
    # Paper Eq. (3) prints the cut at t_o; it must be at t_bar_o = 2 i / P for the area to be i.
    b = blast_parameters(50.0, 2.0, "masi2021")
    tri = b.pulse("triangular")
    assert tri.duration == pytest.approx(2 * b.reflected_impulse / b.reflected_pressure, rel=1e-15)
    assert tri.duration != pytest.approx(b.positive_duration, rel=0.05)  # the slip matters here (~ -17 %)
    num = quad(tri.pressure, 0.0, tri.duration, epsrel=1e-12)[0]
    assert num == pytest.approx(b.reflected_impulse, rel=1e-10)


def test_tabulated_integral_and_scaling():
    t = np.array([0.0, 1e-4, 5e-4, 2e-3])
    p = np.array([1e6, 8e5, 2e5, 0.0])
    pulse = Tabulated(t, p)
    trap = float(np.sum(0.5 * (p[1:] + p[:-1]) * np.diff(t)))
    assert pulse.impulse == pytest.approx(trap, rel=1e-14)
    assert quad(pulse.pressure, 0, 2e-3, points=t[1:-1])[0] == pytest.approx(trap, rel=1e-10)
    f = scaling_factors(
        0.1, 0.001, 1000.0
    )  # pressure factor gamma varsigma lambda = 0.1, time sqrt(lambda/varsigma) = 0.01
    assert (f.pressure, f.time) == pytest.approx((0.1, 0.01), rel=1e-14)
    s = pulse.scaled(f)
    assert s.impulse == pytest.approx(pulse.impulse * 1e-3, rel=1e-12)


def test_impulsive_pulse():
    p = Impulsive(123.0)
    assert p.impulse == 123.0 and p.duration == 0.0 and math.isinf(p.peak)
    assert p.cumulative_impulse(1e-9) == 123.0


@pytest.mark.parametrize(
    "make, match",
    [
        (lambda: Tabulated([0.0, 2e-3, 1e-3], [1.0, 0.5, 0.0]), "negative duration"),
        (lambda: Tabulated([0.0, 1e-3], [1.0, -1.0]), "pulse pressure"),
        (lambda: Friedlander(1e6, -1e-3, 1.0), "positive duration"),
        (lambda: Friedlander(1e6, 1e-3, -2.0), "decay"),
        (lambda: Triangular(float("nan"), 1.0), "peak pressure"),
        (lambda: Impulsive(0.0), "impulse"),
    ],
)
def test_bad_pulses_raise_named_errors(make, match):
    with pytest.raises(BlastscaleInputError, match=match):
        make()


def test_friedlander_cumulative_vectorised_against_quadrature():
    # J(x, d) = int_0^x (1 - s) e^{-d s} ds, by composite Simpson on 2001 points (relative error
    # ~ h^4 d^4 / 180 ~ 1e-9 at d = 40, far smaller below), over decays on both sides of the series
    # switch (|d| < 1e-4) and negative ones
    import numpy as np

    from blastscale.blast.friedlander import friedlander_cumulative, friedlander_impulse_ratio

    d = np.array([-0.9, -1e-5, 0.0, 3e-5, 0.3, 5.0, 40.0])
    x = np.linspace(0.0, 1.0, 2001)
    f = (1.0 - x)[None, :] * np.exp(-d[:, None] * x[None, :])
    h = x[1] - x[0]
    simpson = h / 3.0 * (f[:, 0] + f[:, -1] + 4.0 * f[:, 1:-1:2].sum(axis=1) + 2.0 * f[:, 2:-1:2].sum(axis=1))
    np.testing.assert_allclose(friedlander_cumulative(1.0, d), simpson, rtol=1e-8)
    np.testing.assert_allclose(friedlander_cumulative(1.0, d), friedlander_impulse_ratio(d), rtol=1e-10)


def test_decay_newton_from_a_nearby_guess_equals_the_bisection():
    import numpy as np

    from blastscale.blast.friedlander import friedlander_decay, friedlander_decay_newton

    k = np.linspace(0.02, 0.7, 60)
    with pytest.warns(Warning):  # k >= 1/2: negative decays (documented warning)
        cold = friedlander_decay(np.ones_like(k), np.ones_like(k), k)
    warm = friedlander_decay_newton(k, cold * 1.05 + 0.01)
    np.testing.assert_allclose(warm, cold, rtol=1e-10, atol=1e-12)


def test_one_pulse_shape_vocabulary_for_every_entry_point():
    # blast.pulses is the one home of the pulse names: the blast parameters, the faces' pulses and
    # a scenario accept exactly PULSE_SHAPES, and refuse anything else with the same message.
    from blastscale.blast import PULSE_SHAPES, check_pulse_shape, face_loads
    from blastscale.scenario import BlastSpec

    assert PULSE_SHAPES == ("friedlander", "triangular", "impulsive")
    msg = "pulse = 'tabulated' is not known: valid values are friedlander, triangular, impulsive"
    for shape in PULSE_SHAPES:
        assert check_pulse_shape(shape) == shape
    bp = blast_parameters(10.0, 5.0)
    fl = face_loads(10.0, (0.0, 0.0, 0.0), (5.0, 0.0, 0.5), (-1.0, 0.0, 0.0))
    for check in (check_pulse_shape, bp.pulse, fl.pulses):
        with pytest.raises(BlastscaleInputError) as err:
            check("tabulated")
        assert str(err.value) == msg
    assert [bp.pulse(s).kind for s in PULSE_SHAPES] == [fl.pulses(s).kind for s in PULSE_SHAPES] == list(PULSE_SHAPES)
    assert BlastSpec.model_json_schema()["properties"]["pulse_shape"]["enum"] == list(PULSE_SHAPES)


def test_blast_package_exports_every_public_name():
    # the names blastscale.blast exported before the pulses/faces split (#14), and the new ones
    import blastscale.blast as blast

    before = {
        "BlastModel",
        "KingeryBulmash",
        "Masi2021",
        "FaceLoads",
        "FacePulses",
        "INCIDENCE_MODELS",
        "DEFAULT_INCIDENCE",
        "face_loads",
        "oblique_combination",
        "ExtrapolationWarning",
        "BLAST_MODELS",
        "BlastParameters",
        "blast_parameters",
        "get_blast_model",
        "scaled_distance",
        "valid_scaled_distance_range",
        "Pulse",
        "Friedlander",
        "Triangular",
        "Impulsive",
        "Tabulated",
        "friedlander_decay",
    }
    assert before | {"PULSE_SHAPES", "check_pulse_shape", "face_loads_unchecked"} <= set(blast.__all__)
    for name in blast.__all__:
        assert getattr(blast, name) is not None, name
