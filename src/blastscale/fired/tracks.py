"""Marker tracks -> displacement histories, first peak, largest displacement (plain arrays, SI).

A track holds a marker's *positions* in the record axes (x along the blast, away from the charge; z up;
origin at the centre of the specimen's footprint at rest); the displacement is the position minus the
marker's rest point ``point_m``. Steps (docs/fired.md):

1. **Noise**: sigma of the samples from their second differences, ``MAD(d2 u) / 0.6745 / sqrt(6)`` (white
   noise of std sigma gives second differences of std sigma sqrt(6); the median absolute deviation is robust
   to the motion, whose second differences at video rates are far below the noise).
2. **First peak**, set in seconds of specimen time, never in frames, so that a faster camera never gives a
   worse answer: with ``t_e`` the expected time from the firing signal to the first peak (the caller's: the
   prediction's, :func:`blastscale.fired.shot.as_fired`), the displacement is smoothed by a quadratic
   Savitzky-Golay filter ``SMOOTH_FRACTION t_e`` wide (Savitzky & Golay 1964; the nearest odd number of
   frames, at least ``SMOOTH_MIN_FRAMES``), and the first peak is the first sample of the smoothed history
   that exceeds ``PEAK_NOISE_MULTIPLE`` sigma and is its largest (or, for a negative peak, its least) over
   ``+- PEAK_NEIGHBOURHOOD t_e``, with the record running that far past it or falling back from it by more
   than that threshold before it ends (a block that hits the floor 12 ms before the record's end); a rise
   still under way at the record's end is no peak. A noise wiggle during the rise is a local extremum over a
   few frames, never over a quarter of the rise: the rise gains more than the noise in that time. It is
   refined by a least-squares parabola through the raw samples whose smoothed value lies within
   ``PEAK_BAND`` of it: its vertex is the first peak and its time, and the vertex's standard error
   ``sqrt(g^T C g)`` (``C = sigma^2 (A^T A)^-1`` the coefficients' covariance for the known noise, g the
   vertex's gradient in them: the delta method, Bates & Watts 1988, ch. 1-2) is the peak's own uncertainty.
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
from scipy.ndimage import maximum_filter1d, minimum_filter1d
from scipy.signal import savgol_filter

from .._validate import BlastscaleInputError, check_positive_scalar
from ..roots import bracketed_root, root_of_bracket

__all__ = [
    "PEAK_BAND",
    "PEAK_NEIGHBOURHOOD",
    "PEAK_NOISE_MULTIPLE",
    "SMOOTH_FRACTION",
    "SMOOTH_MIN_FRAMES",
    "TrackPeak",
    "block_marker_displacement",
    "block_rotation",
    "expected_response_s",
    "history_first_peak",
    "track_first_peak",
    "track_noise",
]

#: A first peak must exceed this many noise standard deviations.
PEAK_NOISE_MULTIPLE = 10.0
#: The parabola is fitted to the samples whose smoothed value lies within this fraction of the peak.
PEAK_BAND = 0.05
#: Width of the Savitzky-Golay smoothing window, as a fraction of the expected time to the first peak.
SMOOTH_FRACTION = 0.1
#: The fewest frames smoothed (the quadratic filter's least useful width): a slow camera's window is this
#: wide when a tenth of the expected time holds fewer frames (unsmoothed, the samples kept for the parabola
#: would be chosen by their own noise, and the peak biased up).
SMOOTH_MIN_FRAMES = 5
#: The first peak is the extremum over +- this fraction of the expected time to the first peak.
PEAK_NEIGHBOURHOOD = 0.25


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
    first_peak_sigma_m : float or None
        Standard error of the first peak [m] (the parabola's vertex for the track's noise).
    smoothing_s : float
        Width of the smoothing window [s] (0: not smoothed).
    """

    first_peak_m: float | None
    first_peak_time_s: float | None
    max_displacement_m: float
    noise_m: float
    first_peak_sigma_m: float | None = None
    smoothing_s: float = 0.0


def track_noise(u) -> float:
    """Noise standard deviation [m] of a sampled history ``u`` [m] from its second differences (step 1)."""
    d2 = np.diff(np.asarray(u, dtype=float), 2)
    if d2.size < 3:
        return 0.0
    return float(np.median(np.abs(d2 - np.median(d2))) / 0.6744897501960817 / math.sqrt(6.0))


def expected_response_s(predicted_s: float | None, refit_s: float | None, record_end_s: float) -> float:
    """The expected time from the firing signal to a marker's first peak, t_e [s], that sets the first-peak
    search of its track (:func:`track_first_peak`): the prediction's (the specimen under the designed load:
    known before the shot, independent of the record's frame rate), else the re-simulation's under the load
    as fired, else (neither peaks: a predicted collapse) the record's length after the firing signal
    ``record_end_s``."""
    for v in (predicted_s, refit_s):
        if v is not None and v > 0:
            return float(v)
    return check_positive_scalar("record_end_s", record_end_s, "s")


def history_first_peak(t, u, *, noise: float) -> TrackPeak:
    """First peak of a clean simulated history ``u`` [m] at times ``t`` [s]: its first local extremum whose size
    exceeds ``PEAK_NOISE_MULTIPLE`` x ``noise`` [m], refined by the parabola of step 2 (no smoothing: the
    engine's samples carry no noise; :func:`blastscale.analysis.compare.first_peak` is the same rule)."""
    t = np.asarray(t, dtype=float)
    u = np.asarray(u, dtype=float)
    if t.size < 5:
        raise BlastscaleInputError(f"a history of {t.size} samples: at least 5 are needed for a first peak")
    big = max(PEAK_NOISE_MULTIPLE * float(noise), 1e-12)
    du = np.diff(u)
    turn = np.flatnonzero((np.sign(du[:-1]) != np.sign(du[1:])) & (np.sign(du[:-1]) != 0)) + 1
    turn = turn[np.abs(u[turn]) > big]
    largest = float(np.max(np.abs(u)))
    if turn.size == 0:
        return TrackPeak(None, None, largest, float(noise))
    peak, when, _ = _vertex(t, u, u, int(turn[0]), float(noise))
    return TrackPeak(peak, when, largest, float(noise))


def track_first_peak(t, u, response_s: float, *, noise: float | None = None) -> TrackPeak:
    """First peak of a measured marker track's displacement ``u`` [m] at times ``t`` [s] (steps 2 and 3 of the
    module docstring: smoothed and searched over spans set in seconds, above the noise, refined by a
    parabola).

    Parameters
    ----------
    t, u : array_like
        Frame times [s] after the firing signal and displacements [m].
    response_s : float
        The expected time from the firing signal to the first peak, t_e [s] (> 0): the smoothing is
        ``SMOOTH_FRACTION t_e`` wide, a peak the extremum over ``+- PEAK_NEIGHBOURHOOD t_e``.
    noise : float, optional
        The noise standard deviation [m] (default :func:`track_noise`).

    Returns
    -------
    TrackPeak
        ``first_peak_m`` None when no sample qualifies (the track never leaves the noise, or still rises at
        the record's end).
    """
    t = np.asarray(t, dtype=float)
    u = np.asarray(u, dtype=float)
    response_s = check_positive_scalar("response_s", response_s, "s")
    if t.size < 5:
        raise BlastscaleInputError(f"a track of {t.size} frames: at least 5 are needed for a first peak")
    sigma = track_noise(u) if noise is None else float(noise)
    dt = float(np.median(np.diff(t)))
    w = 2 * int(round((SMOOTH_FRACTION * response_s / dt - 1.0) / 2.0)) + 1  # the nearest odd number of frames
    w = min(max(w, SMOOTH_MIN_FRAMES), (t.size - 1) // 2 * 2 + 1)
    smoothed = sigma > 0 and w >= SMOOTH_MIN_FRAMES
    us = savgol_filter(u, w, 2) if smoothed else u
    largest = float(np.max(np.abs(us)))
    half = max(int(round(PEAK_NEIGHBOURHOOD * response_s / dt)), 1)
    big = max(PEAK_NOISE_MULTIPLE * sigma, 1e-12)
    size = 2 * half + 1
    top = (us >= maximum_filter1d(us, size, mode="nearest")) & (us > big)
    bottom = (us <= minimum_filter1d(us, size, mode="nearest")) & (us < -big)
    cand = np.flatnonzero(top | bottom)
    # the record runs the neighbourhood past the peak, or falls back from it by more than the threshold
    back = np.array([abs(us[k] - (us[k:].min() if us[k] > 0 else us[k:].max())) for k in cand])
    cand = cand[(cand + half < t.size) | (back > big)]
    if cand.size == 0:
        return TrackPeak(None, None, largest, sigma, None, w * dt if smoothed else 0.0)
    peak, when, se = _vertex(t, u, us, int(cand[0]), sigma)
    return TrackPeak(peak, when, largest, sigma, se, w * dt if smoothed else 0.0)


def _vertex(t: np.ndarray, u: np.ndarray, us: np.ndarray, k: int, sigma: float) -> tuple[float, float, float]:
    """(peak [m], time [s], standard error [m]) at the smoothed history's extremum ``k``: the vertex of the
    least-squares parabola through the raw samples ``u`` whose smoothed value ``us`` lies within
    ``PEAK_BAND`` of ``us[k]`` (contiguous around k); the sample itself when the parabola does not apply
    (fewer than 5 samples, the wrong curvature, a vertex outside them), with the noise ``sigma`` as error."""
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
        a = np.column_stack([tc**2, tc, np.ones_like(tc)])
        (c2, c1, c0), *_ = np.linalg.lstsq(a, u[lo : hi + 1], rcond=None)
        if c2 != 0 and np.sign(c2) == -np.sign(peak):
            tv = -c1 / (2 * c2)
            if tc[0] <= tv <= tc[-1]:
                g = np.array([c1 * c1 / (4 * c2 * c2), -c1 / (2 * c2), 1.0])
                cov = sigma**2 * np.linalg.inv(a.T @ a)
                return float(c0 - c1 * c1 / (4 * c2)), float(t[k] + tv), float(math.sqrt(g @ cov @ g))
    return float(peak), float(t[k]), float(sigma)


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
