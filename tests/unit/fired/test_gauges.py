"""Gauge processing against synthetic records with known answers (issue #25 acceptance).

The generator (tests/_fired_synthetic.py) shares no code with the fitter: it writes the Friedlander form and
solves its decay itself, with 2 % white noise (of the peak), a 5 % baseline offset, 10 % ringing at 300 kHz
decaying after the front and a 0.2 ms pre-trigger. The known answers are the Kingery-Bulmash (Swisdak 1994)
values of the known charge at the gauge.

Tolerances (the issue's): impulse 3 %, peak 10 %, arrival 2 %, effective charge 5 %, over 24 seeds. The
impulse's own noise is ~0.3 % (2 % noise integrated over ~1000 samples) and the arrival is quantised to half
a sample (0.25 us of 1.5 ms); the peak has 10 % because the ringing sits on the front, where the fit is
least constrained (Rigby et al. 2014). The effective charge from the impulse goes as ~1.5 x the impulse's
error at fixed R (i ~ W^(2/3) near Z = 6).
"""

from __future__ import annotations

import math

import pytest
from _fired_synthetic import synthetic_trace as _trace

from blastscale.fired import effective_charge, fit_gauge

CHARGE_KG = 0.002  # 2 g TNT, a lab charge
DISTANCE_M = 0.8  # reflected gauge flush in the plate facing it
SEEDS = range(24)


def synthetic_trace(seed, charge=CHARGE_KG, **kw):
    return _trace(seed, charge, DISTANCE_M, **kw)


@pytest.mark.parametrize("seed", SEEDS)
def test_fit_recovers_a_known_charge(seed):
    t, y, truth = synthetic_trace(seed)
    g = fit_gauge(t, y, "g1")
    assert g.impulse_Pa_s == pytest.approx(truth["impulse"], rel=0.03)
    assert g.peak_pressure_Pa == pytest.approx(truth["peak"], rel=0.10)
    assert g.arrival_time_s == pytest.approx(truth["arrival"], rel=0.02)
    assert g.positive_duration_s == pytest.approx(truth["duration"], rel=0.10)
    w = effective_charge(g.impulse_Pa_s, DISTANCE_M)
    assert w == pytest.approx(CHARGE_KG, rel=0.05)
    # the interval is a real one: finite, positive, and not absurdly wide
    assert 0 < g.ci95["peak_pressure_Pa"] < 0.2 * truth["peak"]
    # the negative phase is in the record (3 t_o long) and negative
    assert g.negative_impulse_Pa_s is not None and g.negative_impulse_Pa_s < 0


def test_effective_charge_from_pressure_and_a_stronger_charge():
    """A charge 15 % above the nominal one is seen as such by both bases (peak: within 10 % -> W ~ 15 %)."""
    t, y, _truth = synthetic_trace(3, charge=1.15 * CHARGE_KG)
    g = fit_gauge(t, y, "g1")
    assert effective_charge(g.impulse_Pa_s, DISTANCE_M) == pytest.approx(1.15 * CHARGE_KG, rel=0.05)
    assert effective_charge(g.peak_pressure_Pa, DISTANCE_M, basis="pressure") == pytest.approx(
        1.15 * CHARGE_KG, rel=0.20
    )


def test_side_on_gauge_reads_the_incident_fits():
    t, y, truth = synthetic_trace(5, side_on=True)
    g = fit_gauge(t, y, "s1")
    assert g.impulse_Pa_s == pytest.approx(truth["impulse"], rel=0.03)
    assert effective_charge(g.impulse_Pa_s, DISTANCE_M, kind="side-on") == pytest.approx(CHARGE_KG, rel=0.05)


def test_baseline_and_noise_are_the_pretrigger():
    t, y, truth = synthetic_trace(0)
    g = fit_gauge(t, y)
    assert g.baseline_Pa == pytest.approx(0.05 * truth["peak"], abs=0.02 * truth["peak"] / math.sqrt(200) * 4)
    assert g.noise_Pa == pytest.approx(0.02 * truth["peak"], rel=0.15)
