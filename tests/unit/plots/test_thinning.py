"""Histories thinned for drawing (issue #28, blastscale.plots.thinning): every bin's extremes survive,
checked against a plain loop over the bins on a signal with isolated one-sample spikes (the samples a
stride-based decimation would drop)."""

from __future__ import annotations

import numpy as np

from blastscale.plots.thinning import minmax_thin


def _signal(n):
    t = np.linspace(0.0, 8.0, n)
    y = np.sin(2.0 * np.pi * 0.7 * t) * np.exp(-0.2 * t)
    y[[17, 1234, 5001, n - 2]] += [3.0, -2.5, 4.0, -1.0]  # one-sample spikes
    return t, y


def test_every_bin_keeps_its_extremes_and_the_ends():
    n, bins = 8001, 100
    t, y = _signal(n)
    tk, yk = minmax_thin(t, y, bins)
    assert tk.size <= 2 * bins + 2 < n
    assert np.all(np.diff(tk) > 0)  # time order, no duplicates
    assert (tk[0], yk[0], tk[-1], yk[-1]) == (t[0], y[0], t[-1], y[-1])
    kept = dict(zip(tk, yk))
    assert all(kept[a] == b for a, b in zip(tk, yk)) and all(np.any(t == a) for a in tk)  # original samples
    m = -(-n // bins)
    for a in range(0, n, m):  # a plain loop over the bins: each bin's min and max are among the kept samples
        seg_t, seg_y = t[a : a + m], y[a : a + m]
        for j in (int(np.argmin(seg_y)), int(np.argmax(seg_y))):
            assert kept.get(seg_t[j]) == seg_y[j]
    assert yk.max() == y.max() and yk.min() == y.min()  # the spikes survive


def test_short_or_non_finite_series_are_drawn_whole():
    t, y = _signal(8001)
    for tt, yy in ((t[:202], y[:202]), (t, np.where(t > 4.0, np.nan, y))):
        tk, yk = minmax_thin(tt, yy, 100)
        assert tk is tt or np.array_equal(tk, tt)
        np.testing.assert_array_equal(yk, yy)
