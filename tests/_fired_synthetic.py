"""Synthetic records with known answers for the fired tests (issue #25), made without the fitter's code.

:func:`synthetic_trace` writes the Friedlander form itself (Baker et al. 1983; paper Eq. 1), solves the decay
for the blast model's impulse with its own root finder on the closed form ``i = P t_o (e^-d + d - 1) / d^2``
(paper Eq. 2), and adds what real records hold: white noise (a fraction of the peak), a baseline offset,
gauge ringing decaying after the front, a pre-trigger. :func:`synthetic_track` turns a planar rocking history
(the caller's simulation) into the positions of a marker on the block, by its own rigid-body kinematics,
with white noise, at a camera's frame rate. The known answers are the blast model's values of the known
charge (Kingery-Bulmash, Swisdak 1994, or the paper's fits) and the simulation's own first peak.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from blastscale.blast import blast_parameters


def _decay_for(ratio: float) -> float:
    """d with (e^-d + d - 1)/d^2 = ratio (the generator's own root)."""
    return brentq(lambda d: (math.exp(-d) + d - 1.0) / d**2 - ratio, 1e-6, 60.0)


def synthetic_trace(
    seed: int,
    charge,
    distance,
    *,
    rate_hz=2.0e6,
    noise=0.02,
    offset=0.05,
    ringing=0.10,
    ring_hz=300e3,
    pre_s=2e-4,
    side_on=False,
    blast_model="kingery-bulmash",
):
    """(t [s], p [Pa], truth) of a gauge at ``distance`` [m] from ``charge`` [kg TNT]."""
    bp = blast_parameters(charge, distance, blast_model)
    P = bp.incident_pressure if side_on else bp.reflected_pressure
    i = bp.incident_impulse if side_on else bp.reflected_impulse
    ta, to = bp.arrival_time, bp.positive_duration
    d = _decay_for(i / (P * to))
    rng = np.random.default_rng(seed)
    t = np.arange(-pre_s, ta + 3.0 * to, 1.0 / rate_hz)
    tau = t - ta
    x = np.clip(tau, 0.0, None) / to
    p = np.where(tau >= 0, P * (1 - x) * np.exp(-d * x), 0.0)  # with Friedlander's own negative phase
    ring = np.where(
        tau >= 0, ringing * P * np.sin(2 * np.pi * ring_hz * tau) * np.exp(-np.clip(tau, 0, None) / 10e-6), 0.0
    )
    signal = p + ring + offset * P + noise * P * rng.standard_normal(t.size)
    return t, signal, {"peak": P, "impulse": i, "arrival": ta, "duration": to, "decay": d}


def synthetic_track(seed: int, frames_s, theta, point_x, point_z, half_width, noise_m=5e-5):
    """(x [m], z [m]) of a marker at rest at (point_x, point_z) on a block of half-width ``half_width`` rocking
    by ``theta`` [rad] at the frames (> 0: about the rear toe (b, 0), the top moving away from the charge)."""
    th = np.asarray(theta, dtype=float)
    px = np.where(th >= 0, half_width, -half_width)
    c, s = np.cos(th), np.sin(th)
    x = px + (point_x - px) * c + point_z * s
    z = -(point_x - px) * s + point_z * c
    rng = np.random.default_rng(seed)
    return x + noise_m * rng.standard_normal(th.size), z + noise_m * rng.standard_normal(th.size)


def rocking_block_track(
    seed: int,
    fps: float,
    *,
    half_width=0.02,
    half_height=0.1,
    omega0=0.96,
    arrival_s=0.5e-3,
    duration_s=0.4,
    noise_m=5e-5,
    g=9.81,
):
    """(t [s], ux [m], truth) of a marker at the top front corner of a rectangular block (half-width b,
    half-height h) thrown into rocking about its rear toe with angular velocity ``omega0`` [rad/s] at
    ``arrival_s``, sampled at ``fps`` frames per second from 5 ms before the firing signal, with white noise.

    Housner's (1963) linearised rocking about the toe, written out here: theta'' = p^2 (theta - alpha),
    p^2 = 3 g / (4 R) (a solid block, R = sqrt(b^2 + h^2), alpha = atan(b/h)), theta(0) = 0,
    theta'(0) = omega0: ``theta = alpha (1 - cosh p tau) + (omega0 / p) sinh p tau``; its first peak at
    ``tanh(p tau*) = omega0 / (alpha p)`` is ``alpha (1 - sqrt(1 - r^2))``, r = omega0 / (alpha p). The
    marker's horizontal displacement by rigid rotation about the rear toe (x = +b): the front top corner
    (-b, 2h) moves by ``2b (cos theta - 1) + 2h sin theta`` (increasing in theta below the tipping angle).
    The truth is that closed form at tau*."""
    b, h = half_width, half_height
    R = math.hypot(b, h)
    alpha = math.atan2(b, h)
    p = math.sqrt(3.0 * g / (4.0 * R))
    r = omega0 / (alpha * p)
    assert r < 1.0, "the block would overturn"
    t = np.arange(-5e-3, duration_s, 1.0 / fps)
    tau = np.clip(t - arrival_s, 0.0, None)
    theta = np.where(t > arrival_s, alpha * (1 - np.cosh(p * tau)) + omega0 / p * np.sinh(p * tau), 0.0)
    tau_star = math.atanh(r) / p
    theta_star = alpha * (1.0 - math.sqrt(1.0 - r * r))
    theta = np.where(tau > tau_star, np.clip(theta, 0.0, None), theta)  # no impact: it rests again after

    def ux(th):
        return 2 * b * (np.cos(th) - 1.0) + 2 * h * np.sin(th)

    rng = np.random.default_rng(seed)
    truth = {"first_peak_m": float(ux(theta_star)), "first_peak_time_s": arrival_s + tau_star}
    return t, ux(theta) + noise_m * rng.standard_normal(t.size), truth
