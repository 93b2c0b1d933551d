"""The negative phase: Rigby's calibrations of UFC 3-340-02 Fig. 2-16 as published, Granström's cubic
(impulse, peak, implied duration against the chart's own t_o-), and the pulse that carries it."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from blastscale._validate import OutOfRangeError
from blastscale.blast import Friedlander, Impulsive, blast_parameters
from blastscale.blast.load_model import LoadModel, PhasedPulse, front_face_pulse
from blastscale.blast.negative_phase import (
    RIGBY_NEGATIVE_DURATION,
    RIGBY_NEGATIVE_PHASE,
    cubic_cumulative,
    cubic_pressure,
    negative_phase,
    rigby_fit,
)


# The cited source's formulas, written out as published (DYNAblast Class_Blast.m, "Rigby calibration"):
# pmin = 1e6 (A Z^B + C Z + D) [Pa], im = W^(1/3) 1e3 (A Z^B + C Z + D) [Pa s].
@pytest.mark.parametrize(
    "z, burst, p_source, i_source",
    [
        (0.46, "surface", 1e6 * 100e-3, 1e3 * (-724.37e-3 * 0.46**2 + 445.34e-3 * 0.46 + 553e-3)),
        (1.0, "surface", 1e6 * (-32.91e-3 * 1.0 + 13e-3 * 1.0 + 106e-3), 1e3 * (11.356e-3 - 314.76e-3 + 752e-3)),
        (2.0, "surface", 1e6 * 93e-3 * 2.0**-1.215, 1e3 * 461.8e-3 * 2.0**-0.88),
        (10.0, "surface", 1e6 * 72.99e-3 * 10.0**-0.978, 1e3 * 433.6e-3 * 10.0**-0.842),
        (0.25, "free-air", 1e6 * 100e-3, 1e3 * 496e-3),
        (
            1.2,
            "free-air",
            1e6 * (-29.078e-3 * 1.44 + 0.0352e-3 * 1.2 + 114e-3),
            1e3 * (36.919e-3 * 1.44 - 298.72e-3 * 1.2 + 583e-3),
        ),
        (5.0, "free-air", 1e6 * 59.559e-3 * 5.0**-0.945, 1e3 * 316.36e-3 * 5.0**-0.879),
    ],
)
def test_calibration_is_the_cited_source(z, burst, p_source, i_source):
    W = 8.0  # W^(1/3) = 2
    n = negative_phase(z, W, burst)
    assert n.pressure == pytest.approx(p_source, rel=1e-12)
    assert n.impulse == pytest.approx(2.0 * i_source, rel=1e-12)


@pytest.mark.parametrize("burst", ["surface", "free-air"])
def test_pieces_join_within_one_percent(burst):
    for q, pieces in RIGBY_NEGATIVE_PHASE[burst].items():
        for upper, _ in pieces[:-1]:
            a, b = rigby_fit(pieces, np.array([upper * (1 - 1e-12), upper * (1 + 1e-12)]))
            assert abs(b / a - 1) < 0.01, (q, upper)


def test_cubic_carries_the_impulse_and_peaks_at_the_suction():
    n = negative_phase(0.46, 80.0)
    area, _ = quad(lambda t: cubic_pressure(t / n.duration, n.pressure), 0.0, n.duration, epsabs=0, epsrel=1e-12)
    assert -area == pytest.approx(n.impulse, rel=1e-9)
    assert cubic_cumulative(1.0, n.pressure, n.duration) == pytest.approx(-n.impulse, rel=1e-14)
    assert float(cubic_pressure(1.0 / 3.0, n.pressure)) == pytest.approx(-n.pressure, rel=1e-14)
    assert n.duration == pytest.approx(16.0 / 9.0 * n.impulse / n.pressure, rel=1e-14)


@pytest.mark.parametrize("burst, worst", [("surface", 0.26), ("free-air", 0.35)])
def test_implied_duration_against_the_charts_own(burst, worst):
    """t_o- = 16 i_r- / (9 P_r-) of the cubic against Rigby's calibration of Fig. 2-16's t_o-: within
    25 % (surface) and 34 % (free-air) over Z = 0.2-30, 2.6 % at the paper's block (Z = 0.46)."""
    z = np.geomspace(0.2, 30.0, 300)
    r = negative_phase(z, 1.0, burst).duration / (1e-3 * rigby_fit(RIGBY_NEGATIVE_DURATION[burst], z)) - 1.0
    assert np.max(np.abs(r)) < worst
    if burst == "surface":
        z0 = np.array([0.46])
        r0 = negative_phase(z0, 1.0).duration / (1e-3 * rigby_fit(RIGBY_NEGATIVE_DURATION["surface"], z0)) - 1.0
        assert abs(r0[0]) < 0.03


def test_range_and_extrapolation():
    with pytest.raises(OutOfRangeError, match="Fig. 2-16"):
        negative_phase(50.0, 1.0)
    with pytest.warns(UserWarning, match="extrapolating"):
        negative_phase(50.0, 1.0, extrapolate=True)


def test_phased_pulse_net_impulse_and_scaling():
    pos = Friedlander.from_impulse(1e6, 1e-3, 300.0)
    p = PhasedPulse(pos, 5e4, 2e-2)
    assert p.negative_impulse == pytest.approx(9 / 16 * 5e4 * 2e-2, rel=1e-14)
    assert p.impulse == pytest.approx(pos.impulse - p.negative_impulse, rel=1e-14)
    assert p.cumulative_impulse(p.duration + 1.0) == pytest.approx(p.impulse, rel=1e-12)
    assert p.pressure(1e-3 + 2e-2 / 3) == pytest.approx(-5e4, rel=1e-12)
    s = p._rescaled(0.5, 0.1)
    assert s.impulse == pytest.approx(0.05 * p.impulse, rel=1e-12) and s.duration == pytest.approx(0.1 * p.duration)
    # an impulsive positive phase: the suction starts after the blast's positive duration
    q = PhasedPulse(Impulsive(300.0), 5e4, 2e-2, negative_start=1e-3)
    assert q.cumulative_impulse(0.5e-3) == pytest.approx(300.0) and q.duration == pytest.approx(2.1e-2)


def test_front_face_pulse_without_effects_is_the_papers_pulse_exactly():
    bp = blast_parameters(80.0, 2.0)
    for shape in ("friedlander", "triangular", "impulsive"):
        assert front_face_pulse(bp, shape) == bp.pulse(shape)
        assert front_face_pulse(bp, shape, LoadModel()) == bp.pulse(shape)
    ph = front_face_pulse(bp, "friedlander", LoadModel(negative_phase=True))
    assert isinstance(ph, PhasedPulse) and ph.positive == bp.pulse("friedlander")
    assert ph.negative_impulse == pytest.approx(negative_phase(bp.scaled_distance, 80.0).impulse, rel=1e-12)
    assert math.isclose(ph.negative_start, bp.positive_duration)
