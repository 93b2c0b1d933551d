"""Marker tracks -> displacement histories, first peak, largest displacement (plain arrays, SI).

A track holds a marker's *positions* in the record axes (x along the blast, away from the charge; z up;
origin at the centre of the specimen's footprint at rest); the displacement is the position minus the
marker's rest point ``point_m``. Steps (docs/fired.md):

1. **Noise**: sigma of the samples from their second differences, ``MAD(d2 u) / 0.6745 / sqrt(6)`` (white
   noise of std sigma gives second differences of std sigma sqrt(6); the median absolute deviation is robust
   to the motion, whose second differences at video rates are far below the noise).
2. **First peak**: the first local extremum of the displacement smoothed by a Savitzky-Golay filter
   (quadratic, ``SMOOTH_FRAMES`` frames wide, at most a tenth of the record) whose size exceeds
   ``PEAK_NOISE_MULTIPLE`` sigma; refined by a least-squares parabola through the raw samples within
   ``PEAK_BAND`` of it (Savitzky & Golay 1964; the parabola's vertex is the peak and its time).
3. **Largest displacement**: the largest |smoothed displacement| over the record.

For a rectangular block rocking in the plane (:func:`block_marker_displacement`): a point at (x0, z0) turns
about the rear toe (x = +b, z = 0) for theta > 0 (away from the charge), about the front toe for theta < 0
(Housner 1963); ``block_rotation`` inverts it for a measured track, and the outcome is the planar solver's
rule (:mod:`blastscale.rocking.solver`): collapsed once |theta| passed alpha, the tipping angle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.signal import savgol_filter

from .._validate import BlastscaleInputError
from ..roots import bracketed_root, root_of_bracket

__all__ = [
    "PEAK_BAND",
    "PEAK_NOISE_MULTIPLE",
    "TrackPeak",
    "block_marker_displacement",
    "block_rotation",
    "track_first_peak",
    "track_noise",
]

#: A first peak must exceed this many noise standard deviations.
PEAK_NOISE_MULTIPLE = 10.0
#: The parabola is fitted to the samples whose smoothed value lies within this fraction of the peak.
PEAK_BAND = 0.05
#: Frames of the Savitzky-Golay smoothing window (odd), at most 1/10 of the record.
SMOOTH_FRAMES = 15


@dataclass(frozen=True)
class TrackPeak:
    """A displacement history's first peak and largest value (SI).

    Attributes
    ----------
    first_peak_m : float or None
        Signed first peak [m]; None when the history never leaves the noise.
    first_peak_time_s : float or None
        Its time [s] after the firing signal.
    max_displacement_m : float
        Largest |displacement| [m] (smoothed).
    noise_m : float
        Noise standard deviation [m].
    """

    first_peak_m: float | None
    first_peak_time_s: float | None
    max_displacement_m: float
    noise_m: float


def track_noise(u) -> float:
    """Noise standard deviation [m] of a sampled history ``u`` [m] from its second differences (step 1)."""
    d2 = np.diff(np.asarray(u, dtype=float), 2)
    if d2.size < 3:
        return 0.0
    return float(np.median(np.abs(d2 - np.median(d2))) / 0.6744897501960817 / math.sqrt(6.0))


def track_first_peak(t, u, *, noise: float | None = None, smooth: bool = True) -> TrackPeak:
    """First peak of a measured marker track's displacement ``u`` [m] at times ``t`` [s] (steps 2 and 3 of the
    module docstring: above the noise, smoothed, refined by a parabola; a clean sampled history's first peak
    is :func:`blastscale.analysis.compare.first_peak`).

    ``noise`` [m]: the noise standard deviation (default :func:`track_noise`); ``smooth=False`` for a clean
    simulated history (no filter; ``noise`` then only sets the smallest peak)."""
    t = np.asarray(t, dtype=float)
    u = np.asarray(u, dtype=float)
    if t.size < 5:
        raise BlastscaleInputError(f"a track of {t.size} frames: at least 5 are needed for a first peak")
    sigma = track_noise(u) if noise is None else float(noise)
    w = min(SMOOTH_FRAMES, (t.size // 10) | 1)
    us = savgol_filter(u, w, 2) if smooth and sigma > 0 and w >= 5 else u
    big = max(PEAK_NOISE_MULTIPLE * sigma, 1e-12)
    du = np.diff(us)
    turn = np.flatnonzero((np.sign(du[:-1]) != np.sign(du[1:])) & (np.sign(du[:-1]) != 0)) + 1
    turn = turn[np.abs(us[turn]) > big]
    largest = float(np.max(np.abs(us)))
    if turn.size == 0:
        return TrackPeak(None, None, largest, sigma)
    k = int(turn[0])
    peak = us[k]
    near = np.abs(us - peak) <= PEAK_BAND * abs(peak)
    lo = k
    while lo > 0 and near[lo - 1]:
        lo -= 1
    hi = k
    while hi < t.size - 1 and near[hi + 1]:
        hi += 1
    if hi - lo >= 4:
        tc = t[lo : hi + 1] - t[k]
        c2, c1, c0 = np.polyfit(tc, u[lo : hi + 1], 2)
        if c2 != 0 and np.sign(c2) == -np.sign(peak):
            tv = -c1 / (2 * c2)
            if tc[0] <= tv <= tc[-1]:
                return TrackPeak(float(c0 - c1 * c1 / (4 * c2)), float(t[k] + tv), largest, sigma)
    return TrackPeak(float(peak), float(t[k]), largest, sigma)


def block_marker_displacement(theta, point_x, point_z, half_width):
    """Horizontal and vertical displacement [m] of a point at rest at (``point_x``, ``point_z``) [m] of a
    rectangular block of half-width b = ``half_width`` [m] rocking by ``theta`` [rad] (> 0 away from the
    charge, about the rear toe (b, 0); < 0 about the front toe (-b, 0)). Rigid rotation:
    ``x' = x_p + (x - x_p) cos(theta) + z sin(theta)``, ``z' = -(x - x_p) sin(theta) + z cos(theta)``."""
    th = np.asarray(theta, dtype=float)
    xp = np.where(th >= 0, half_width, -half_width)
    rx = point_x - xp
    x = xp + rx * np.cos(th) + point_z * np.sin(th)
    z = -rx * np.sin(th) + point_z * np.cos(th)
    return x - point_x, z - point_z


def block_rotation(ux, uz, point_x, point_z, half_width):
    """Rocking angle [rad] of a rectangular block from a marker's displacement (inverse of
    :func:`block_marker_displacement`): the turn of the toe-to-marker vector about the toe on the side of
    the motion. With no vertical record (``uz`` None) the horizontal one alone, solved for theta by
    the package's root finder (:func:`blastscale.roots.bracketed_root`) on the monotone branch."""
    ux = np.asarray(ux, dtype=float)
    side = np.where(ux >= 0, 1.0, -1.0)
    xp = side * half_width
    rx, rz = point_x - xp, point_z
    if uz is not None:
        nx, nz = rx + ux, rz + np.asarray(uz, dtype=float)
        return np.arctan2(rx * nz - rz * nx, rx * nx + rz * nz) * -1.0
    ux, side = np.broadcast_arrays(ux, side)
    lo = np.where(side > 0, 0.0, -0.5 * math.pi).ravel()
    hi = np.where(side > 0, 0.5 * math.pi, 0.0).ravel()
    uxf, px, pz = ux.ravel(), np.broadcast_to(point_x, ux.shape).ravel(), np.broadcast_to(point_z, ux.shape).ravel()
    hw = np.broadcast_to(half_width, ux.shape).ravel()

    def f(idx, th):  # the marker's horizontal displacement, increasing in theta on the branch
        return block_marker_displacement(th, px[idx], pz[idx], hw[idx])[0] - uxf[idx]

    every = np.arange(lo.size)
    flo, fhi = f(every, lo), f(every, hi)
    th = np.where(flo > 0.0, lo, hi)  # beyond the branch: its nearer end
    ok = np.flatnonzero((flo <= 0.0) & (fhi >= 0.0))
    if ok.size:

        def g(j, t):
            return f(ok[j], t)

        th[ok] = root_of_bracket(*bracketed_root(g, lo[ok], hi[ok], flo[ok], fhi[ok])[:4])
    return th.reshape(ux.shape)
