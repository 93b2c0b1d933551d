"""The negative phase bounded by the positive impulse (issue #24): the chart-calibrated suction
impulse exceeds Kingery-Bulmash's positive reflected impulse beyond Z ~ 8 (1.15 x at Z = 15, 1.39 x at
Z = 39); bounded, the net impulse is never negative. The second model, the Friedlander pulse
continued past its zero crossing, against its integrals done numerically."""

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import minimize_scalar

from blastscale.blast import blast_parameters, get_blast_model
from blastscale.blast.load_model import LoadModel, front_face_negative, front_face_pulse
from blastscale.blast.negative_phase import (
    RIGBY_NEGATIVE_PHASE,
    bounded_by_positive,
    friedlander_continued,
    negative_phase,
    rigby_fit,
)

CUBIC = LoadModel(negative_phase=True)
CONTINUED = LoadModel(negative_phase=True, negative_phase_model="friedlander-continued")


@pytest.mark.parametrize("z, ratio", [(15.0, 1.15), (39.0, 1.39)])
def test_the_chart_alone_would_pull_the_face_toward_the_charge(z, ratio):
    """The finding, recomputed from the cited calibration and Kingery-Bulmash (Swisdak 1994): the
    issue's ratios to their two printed digits (abs 0.005)."""
    i_neg = 1e3 * rigby_fit(RIGBY_NEGATIVE_PHASE["surface"]["impulse"], np.array([z]))[0]
    i_pos = get_blast_model("kingery-bulmash")._raw("scaled_reflected_impulse", np.array([z]))[0]
    assert i_neg / i_pos == pytest.approx(ratio, abs=0.005)


@pytest.mark.parametrize("model", [CUBIC, CONTINUED])
@pytest.mark.parametrize("z", [8.5, 15.0, 30.0, 37.6])
def test_bounded_net_impulse_is_never_negative(z, model):
    bp = blast_parameters(1.0, z, "kingery-bulmash")
    neg = front_face_negative(bp, model)
    assert neg.bounded and neg.impulse == pytest.approx(bp.reflected_impulse, rel=1e-12)
    pulse = front_face_pulse(bp, "friedlander", model)
    assert pulse.impulse >= -1e-12 * bp.reflected_impulse


def test_bound_keeps_the_duration_and_scales_the_peak():
    bp = blast_parameters(1.0, 15.0, "kingery-bulmash")
    raw = negative_phase(15.0, 1.0)
    neg = front_face_negative(bp, CUBIC)
    f = bp.reflected_impulse / raw.impulse
    assert f == pytest.approx(1 / 1.1453, rel=1e-3)
    assert neg.duration == raw.duration and neg.pressure == pytest.approx(f * raw.pressure, rel=1e-12)


def test_near_the_charge_the_bound_does_not_act():
    """The paper's block (Z = 0.46) and Z = 5: the chart's values, bit for bit."""
    for z in (0.46, 2.0, 5.0):
        bp = blast_parameters(1.0, z, "kingery-bulmash")
        neg, raw = front_face_negative(bp, CUBIC), negative_phase(z, 1.0)
        assert not neg.bounded and (neg.pressure, neg.impulse, neg.duration) == (
            raw.pressure,
            raw.impulse,
            raw.duration,
        )


def test_outside_the_charts_range_it_still_refuses_in_one_line():
    bp = blast_parameters(1.0, 39.0, "kingery-bulmash", extrapolate=True)
    with pytest.raises(Exception, match=r"\[0.07, 37.6\] m/kg\^\(1/3\)") as exc:
        front_face_negative(bp, CUBIC)
    assert "\n" not in str(exc.value)


@pytest.mark.parametrize("d", [0.5, 0.78, 1.0, 3.0, 8.0])
def test_continued_friedlander_against_its_integrals(d):
    """p(x) = P (1 - x) e^(-d x) for x > 1: impulse P t_o e^(-d) / d^2 and trough P e^(-(d+1)) / d at
    x = 1 + 1/d, checked by quadrature and a numerical minimum (rel 1e-9)."""
    P, to = 2.0e5, 3e-3
    neg = friedlander_continued(P, to, d)
    i_num = -to * quad(lambda x: P * (1 - x) * math.exp(-d * x), 1.0, math.inf, epsabs=0, epsrel=1e-12)[0]
    trough = minimize_scalar(
        lambda x: P * (1 - x) * math.exp(-d * x),
        bounds=(1.0, 1.0 + 10.0 / d),
        method="bounded",
        options={"xatol": 1e-12},
    )
    assert neg.impulse == pytest.approx(i_num, rel=1e-9)
    assert neg.pressure == pytest.approx(-trough.fun, rel=1e-9) and trough.x == pytest.approx(1 + 1 / d, rel=1e-5)
    assert neg.duration == pytest.approx(16 * math.e * to / (9 * d), rel=1e-12)  # the cubic that carries them


def test_continued_friedlander_exceeds_its_positive_impulse_below_unit_decay():
    """Net of the continued pulse: P t_o (d - 1) / d^2 (positive (d - 1 + e^-d)/d^2 minus e^-d/d^2):
    negative for d < 1, so it is bounded too."""
    P, to, d = 1.0, 1.0, 0.78
    pos = P * to * (d - 1 + math.exp(-d)) / d**2
    neg = friedlander_continued(P, to, d)
    assert pos - neg.impulse == pytest.approx(P * to * (d - 1) / d**2, rel=1e-12) and pos < neg.impulse
    b = bounded_by_positive(neg, pos)
    assert b.bounded and b.impulse == pytest.approx(pos, rel=1e-15) and b.duration == neg.duration


def test_bound_on_arrays_acts_where_needed():
    neg = friedlander_continued(np.array([1.0, 1.0]), np.array([1.0, 1.0]), np.array([0.5, 5.0]))
    b = bounded_by_positive(neg, np.array([0.1, 1.0]))
    assert b.bounded.tolist() == [True, False]
    assert b.impulse[0] == pytest.approx(0.1) and b.impulse[1] == neg.impulse[1]
