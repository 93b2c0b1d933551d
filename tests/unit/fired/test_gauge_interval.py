"""The 95 % intervals of a gauge's impulse and peak are claims: the truth inside them about 95 % of the time, at the
edge of them sometimes, and the negative phase not read as a drift.

Records written here (no code shared with the reader): a Friedlander pulse (paper Eq. 1) of peak P, duration t_o
and decay d, ending at t_o (the positive phase the impulse counts), followed by Granstrom's cubic negative phase
(Rigby et al. 2014; its duration 10 t_o here, as Rigby's calibration of UFC 3-340-02 Fig. 2-16 gives at Z ~ 0.6
m/kg^(1/3)), sampled at 1 MHz with the shock at a random position between two samples, white noise of 0 or
0.5 % of the peak, and a baseline of 30 Pa. The truth: the pulse's P t_o k(d) (paper Eq. 2) and P.

What the reader left out before (measured over the records of the first test): the shock's position between two
samples. Its arrival is the midpoint of that interval, and the impulse counted the straight line across the jump
(half the pressure there); the interval held noise and baseline alone: 0 on a noiseless record. The truth was
inside the impulse's interval in 31 % of such records over Z = 0.7-10 (the error up to 2 % at 100-400 samples
over t_o, d = 6-15). Now the pulse's part before its first sample comes from the fit and the interval holds the
position's term (uniform over the interval: P dt / sqrt 12, Z95 times it): coverage 98 % over the same records.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from blastscale.fired import fit_gauge

FS = 1e6


def shot(rng, P, to, d, noise, neg_durations=10.0, record_to=30.0):
    """(t [s], p [Pa], impulse [Pa s]) of one record (module docstring)."""
    ta = 1e-3 + rng.uniform(0.0, 1.0) / FS  # the shock anywhere between two samples
    t = np.arange(-1e-3, ta + record_to * to, 1.0 / FS)
    tau = t - ta
    x = np.clip(tau, 0.0, None) / to
    p = np.where((tau >= 0) & (tau <= to), P * (1 - x) * np.exp(-d * x), 0.0)
    y = (tau - to) / (neg_durations * to)
    suction = 0.1 * P  # peak suction; Granstrom's cubic -P- (27/4) y (1 - y)^2, 0 <= y <= 1
    p = p - np.where((y >= 0) & (y <= 1), suction * 6.75 * y * (1 - y) ** 2, 0.0)
    p = p + 30.0 + noise * P * rng.standard_normal(t.size)
    return t, p, P * to * (math.exp(-d) + d - 1) / d**2


CASES = [(2e5, 60e-6, 3.0), (5e5, 100e-6, 8.0), (1e5, 300e-6, 15.0), (5e4, 800e-6, 1.5)]


def test_the_truth_lies_inside_the_intervals_about_95_percent_of_the_time():
    """Over 4 pulses (60-800 samples over t_o, d = 1.5-15) x 2 noises x 15 shock positions: the impulse's and the
    peak's 95 % intervals hold the truth in >= 90 % of the 120 records (a binomial at 95 % falls below 90 % with
    probability 0.02); before, the impulse's held it in 31 % (module docstring). And the answer "no" to an
    interval made safe by width: the largest error reaches 60 % of its interval's half-width in the impulse (the
    uniform term's edge: a shock at the end of its interval), so the intervals are not inflated beyond the
    errors they state."""
    rng = np.random.default_rng(7)
    inside_i = inside_p = n = 0
    reach = 0.0
    for P, to, d in CASES:
        for noise in (0.0, 0.005):
            for _ in range(15):
                t, p, impulse = shot(rng, P, to, d, noise)
                g = fit_gauge(t, p, "g")
                inside_i += abs(g.impulse_Pa_s - impulse) <= g.ci95_impulse_Pa_s
                inside_p += abs(g.peak_pressure_Pa - P) <= g.ci95["peak_pressure_Pa"]
                reach = max(reach, abs(g.impulse_Pa_s - impulse) / g.ci95_impulse_Pa_s)
                n += 1
    assert inside_i >= 0.90 * n and inside_p >= 0.90 * n, (inside_i, inside_p, n)
    assert reach >= 0.6


def test_a_tail_in_the_negative_phase_is_not_a_drift_and_one_past_it_checks():
    """A record of 12 positive durations whose negative phase lasts 10 (it ends at 11 t_o): its tail (the last
    tenth of the record, from ~10.3 t_o) lies inside the negative phase. Before, it was read as a drift ("the
    record's tail sits -1245 Pa off ...: the drift is not linear" and "the baseline makes the impulse
    uncertain"), the suction's offset widening the impulse's interval to 2.65 %; now a note says the tail cannot
    check the baseline, the pre-trigger's line is kept and the impulse holds its truth (-1.7 % within 2.5 %). The
    answer "no": the same record run to 30 t_o has its tail past the negative phase: it checks (the line through
    the pre-trigger and the tail), no note, and the negative phase's impulse is read (Granstrom's 9/16 P- t_o-)."""
    rng = np.random.default_rng(3)
    P, to, d = 2e5, 100e-6, 3.0
    t, p, impulse = shot(rng, P, to, d, 0.002, record_to=12.0)
    g = fit_gauge(t, p, "g")
    assert len(g.warnings) == 1 and "still below the pre-trigger's baseline" in g.warnings[0]
    assert g.tail_offset_Pa is None and "tail" not in g.baseline_from
    assert g.impulse_Pa_s == pytest.approx(impulse, abs=g.ci95_impulse_Pa_s)
    t, p, impulse = shot(rng, P, to, d, 0.002, record_to=30.0)
    g = fit_gauge(t, p, "g")
    assert g.warnings == () and g.baseline_from.startswith("pre-trigger and tail")
    assert g.negative_impulse_Pa_s == pytest.approx(-0.1 * P * 10 * to * 9 / 16, rel=0.05)


def test_a_steep_noisy_pulse_of_few_samples_is_still_read_and_its_interval_holds():
    """The window's second smoothing must not cut a steep pulse where it has sunk into the noise: d = 15 and 30 over
    40-60 samples at 1 % noise, with no negative phase, 20 shock positions each. Every record is read (a first
    version of the second smoothing refused 15 of 20: "20 samples over the pulse"), and the impulse's interval
    holds the truth in >= 17 of 20 (the binomial's 1 % tail at 95 %); the reader before held it in 3-5 of 20."""
    rng = np.random.default_rng(0)
    for to, d in ((40e-6, 15.0), (60e-6, 30.0)):
        inside = 0
        for _ in range(20):
            t, p, impulse = shot(rng, 1e5, to, d, 0.01, neg_durations=1e-9, record_to=60.0)
            g = fit_gauge(t, p, "g")
            inside += abs(g.impulse_Pa_s - impulse) <= g.ci95_impulse_Pa_s
        assert inside >= 17, (to, d, inside)
