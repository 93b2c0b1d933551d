"""The first peak of a marker track found in time, not frames (issue #36 item 3): one motion sampled at 500,
1000, 2000 and 5000 frames per second gives the same first peak.

The tracks are made by ``tests/_fired_synthetic.py:rocking_block_track``, which shares no code with the reader:
Housner's (1963) linearised rocking of a block thrown about its toe, written out in closed form there, whose
first peak is known exactly (``alpha (1 - sqrt(1 - r^2))``), with white noise (0.05 and 0.1 mm on a 7.1 mm
peak at 0.077 s; the issue's shot had 8.45 mm at ~0.077 s). Before (15-frame smoothing): 0.1 mm of noise at
2000 frames per second gave 6.56 mm at 0.0545 s, at 5000 frames per second 3.15 mm at 0.019 s (seed 0).

Tolerances: the issue's 2 % on each first peak and between the frame rates; the measured errors are under
1 % (the largest at 500 frames per second with 0.1 mm of noise, 0.9 %: some 15 frames over the peak's top).
The 5-95 % band (``peak +- 1.645 first_peak_sigma_m``) is a 90 % band: it holds the truth in 90 % of the
records, not in every one, so its coverage is checked over 50 seeds x 4 frame rates (binomial standard
deviation 2.1 %: the coverage within [0.84, 0.96], three of them), and every record's error within 3.3 of its
standard errors (a 99.9 % band).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from _fired_synthetic import rocking_block_track  # noqa: E402

from blastscale._validate import BlastscaleInputError  # noqa: E402
from blastscale.fired.tracks import (  # noqa: E402
    PEAK_NOISE_MULTIPLE,
    expected_response_s,
    history_first_peak,
    track_first_peak,
)

FPS = (500, 1000, 2000, 5000)
Q95 = 1.6448536269514722


@pytest.mark.parametrize("noise", [5e-5, 1e-4])
@pytest.mark.parametrize("seed", range(5))
def test_one_track_at_four_frame_rates(seed, noise):
    """The first peaks within 2 % of the truth and of each other, whatever the frame rate; the search set by
    the expected time to the first peak, here the truth's (the prediction's in `fired`)."""
    peaks = []
    for fps in FPS:
        t, u, truth = rocking_block_track(seed, fps, noise_m=noise)
        pk = track_first_peak(t, u, truth["first_peak_time_s"])
        assert pk.first_peak_m == pytest.approx(truth["first_peak_m"], rel=0.02), fps
        assert pk.first_peak_time_s == pytest.approx(truth["first_peak_time_s"], rel=0.05), fps
        assert abs(pk.first_peak_m - truth["first_peak_m"]) < 3.3 * pk.first_peak_sigma_m, fps
        peaks.append(pk.first_peak_m)
    assert (max(peaks) - min(peaks)) / truth["first_peak_m"] < 0.02


@pytest.mark.parametrize("factor", [0.5, 2.0])
def test_an_expected_time_off_by_two_still_finds_the_peak(factor):
    """The prediction's first-peak time half or twice the truth's (a shot fired far off its design): still
    within 2 % at every frame rate."""
    for fps in FPS:
        t, u, truth = rocking_block_track(0, fps, noise_m=1e-4)
        pk = track_first_peak(t, u, factor * truth["first_peak_time_s"])
        assert pk.first_peak_m == pytest.approx(truth["first_peak_m"], rel=0.02), fps


def test_the_band_covers_the_truth_nine_times_in_ten():
    """The vertex's standard error is the peak's: the 5-95 % band holds the truth in 84-96 % of 200 records."""
    held = []
    for fps in FPS:
        for seed in range(50):
            t, u, truth = rocking_block_track(100 + seed, fps, noise_m=1e-4)
            pk = track_first_peak(t, u, truth["first_peak_time_s"])
            held.append(abs(pk.first_peak_m - truth["first_peak_m"]) <= Q95 * pk.first_peak_sigma_m)
    assert 0.84 <= np.mean(held) <= 0.96, np.mean(held)


def test_the_smoothing_is_set_in_seconds():
    """The window is a tenth of the expected time at every frame rate (to within a frame)."""
    for fps in FPS:
        t, u, truth = rocking_block_track(0, fps)
        pk = track_first_peak(t, u, 0.08)
        assert abs(pk.smoothing_s - 0.008) <= 1.0 / fps + 1e-12


def test_no_peak_in_the_noise_nor_in_a_rise_cut_by_the_record():
    """No: a still marker (noise only) has no first peak; a rise that the record ends before it turns (a
    collapse, or a record cut at the peak) has none either, however high it went."""
    rng = np.random.default_rng(3)
    t = np.arange(0.0, 0.4, 1.0 / 2000)
    assert track_first_peak(t, 1e-4 * rng.standard_normal(t.size), 0.08).first_peak_m is None
    t, u, truth = rocking_block_track(0, 2000, duration_s=0.3)
    cut = t <= truth["first_peak_time_s"] + 0.01  # the record ends 10 ms after the peak, < 0.25 x 0.077 s
    assert track_first_peak(t[cut], u[cut], truth["first_peak_time_s"]).first_peak_m is None
    cut = t <= truth["first_peak_time_s"] + 0.03  # 30 ms after: the neighbourhood is in the record
    assert track_first_peak(t[cut], u[cut], truth["first_peak_time_s"]).first_peak_m == pytest.approx(
        truth["first_peak_m"], rel=0.02
    )


@pytest.mark.parametrize(("drop", "found"), [(2e-3, True), (3e-4, False)])
def test_a_peak_the_record_cuts_short_counts_when_it_falls_back(drop, found):
    """A rise to 0.1 s, then a fall (a block landing) of 2 mm or 0.3 mm by the record's end 6 ms after the
    peak (short of its +-25 ms neighbourhood): a peak when the fall exceeds 10 sigma (0.5 mm), else none.
    Tolerance: 1 % on the peak (the top is lopsided: the parabola's vertex is biased by the fall's curvature,
    0.3 % here), 6 ms on its time (the record holds 6 ms after it)."""
    t = np.arange(0.0, 0.106, 5e-4)
    u = np.where(t <= 0.1, 0.05 * np.sin(0.5 * np.pi * t / 0.1), 0.05 - drop * ((t - 0.1) / 0.006) ** 2)
    pk = track_first_peak(t, u, 0.1, noise=5e-5)
    if found:
        assert pk.first_peak_m == pytest.approx(0.05, rel=0.01) and pk.first_peak_time_s == pytest.approx(0.1, abs=6e-3)
    else:
        assert pk.first_peak_m is None


def test_the_edge_of_the_noise():
    """A clean half-sine bump of 1.05 x and 0.95 x the threshold (PEAK_NOISE_MULTIPLE x the given noise): the
    first is a peak (exactly its height: a clean parabola-like top), the second is not."""
    t = np.arange(0.0, 0.4, 1e-3)
    bump = np.where(t < 0.2, np.sin(np.pi * t / 0.2), 0.0)
    sigma = 1e-4
    hi = track_first_peak(t, 1.05 * PEAK_NOISE_MULTIPLE * sigma * bump, 0.1, noise=sigma)
    assert hi.first_peak_m == pytest.approx(1.05 * PEAK_NOISE_MULTIPLE * sigma, rel=1e-3)
    assert hi.first_peak_time_s == pytest.approx(0.1, abs=1e-3)
    assert track_first_peak(t, 0.95 * PEAK_NOISE_MULTIPLE * sigma * bump, 0.1, noise=sigma).first_peak_m is None


def test_a_simulated_history_peaks_at_its_first_turn():
    """A clean history (no noise, no smoothing): its first local maximum, not its largest."""
    t = np.linspace(0.0, 1.0, 1001)
    u = np.sin(2 * np.pi * t) * (1 + t)  # first peak near t = 0.25, the second (larger) near 1.25: outside
    pk = history_first_peak(t, u, noise=1e-6)
    assert pk.first_peak_time_s == pytest.approx(0.25, abs=0.02)


def test_the_expected_time_and_its_faults():
    assert expected_response_s(0.08, 0.1, 0.4) == 0.08
    assert expected_response_s(None, 0.1, 0.4) == 0.1
    assert expected_response_s(None, None, 0.4) == 0.4
    t = np.arange(0.0, 0.1, 1e-3)
    with pytest.raises(BlastscaleInputError, match="response_s = 0 s is out of range: must be > 0 s"):
        track_first_peak(t, t, 0.0)
