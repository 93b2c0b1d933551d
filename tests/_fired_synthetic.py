"""Synthetic records with known answers for the fired tests (issue #25), made without the fitter's code.

:func:`synthetic_trace` writes the Friedlander form itself (Baker et al. 1983; paper Eq. 1), solves the decay
for the blast model's impulse with its own root finder on the closed form ``i = P t_o (e^-d + d - 1) / d^2``
(paper Eq. 2), and adds what real records hold: white noise (a fraction of the peak), a baseline offset,
gauge ringing decaying after the front, a pre-trigger. :func:`synthetic_track` turns a planar rocking history
(the caller's simulation) into the positions of a marker on the block, by its own rigid-body kinematics,
with white noise, at a camera's frame rate. The known answers are the blast model's values of the known
charge (Kingery-Bulmash, Swisdak 1994, or the paper's fits) and the simulation's own first peak.

**A gauge at an angle of incidence** a (flush in a face whose normal makes the angle a with the direction to
the charge): the face's peak and impulse are written here from UFC 3-340-02 (2008) Fig. 2-193 (the reflection
coefficient C_r_alpha) and Fig. 2-194 (the scaled reflected impulse I), typed below (:data:`FIG_2_193`,
:data:`FIG_2_194`: the figures' digitised points, from Nyobir/ufc-blast-calculator, MIT licence; Fig. 2-194
with the held-out points of tests/data/ufc_3_340_02_fig2_194_check.csv as well), read by the generator's own
interpolation (linear in angle along a curve, linear in ln P_so between the two curves around it, no
alignment of the Mach-reflection peaks), as the reflected excess over the side-on value:
``P(a) = P_so + (P_r - P_so) (C(a) - 1)/(C(0) - 1)``, ``i(a) = i_s + (i_r - i_s) (I(a) - I(90))/(I(0) - I(90))``
(the normal and the side-on values the blast model's at the gauge; Kingery-Bulmash's side-on values beside
the paper's fits, which have none). Nothing here calls blastscale's incidence or inversion code.

**Drift**: ``drift`` (a fraction of the peak per millisecond) adds a baseline growing linearly from the
record's start, as a charge amplifier's leakage does.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from blastscale.blast import blast_parameters

#: UFC 3-340-02 Fig. 2-194: incident pressure [Pa] -> (angle [deg], i_r_alpha / W^(1/3) [Pa s/kg^(1/3)]).
FIG_2_194 = {
    68947.6: (
        (0, 133.13),
        (15.1, 130.42),
        (22.03, 127.09),
        (31.26, 120.99),
        (40.5, 112.98),
        (49.73, 104.07),
        (54.35, 99.077),
        (58.97, 94.119),
        (68.2, 83.69),
        (77.44, 73.192),
        (82.05, 68.112),
        (84.36, 65.544),
        (87.34, 62.398),
        (90, 59.893),
    ),
    137895: (
        (0, 195.63),
        (15.1, 189.77),
        (22.03, 184.53),
        (31.26, 174.28),
        (40.5, 161.23),
        (49.73, 146.4),
        (54.35, 138.56),
        (58.97, 130.42),
        (68.2, 114.44),
        (77.44, 98.894),
        (82.05, 91.55),
        (84.36, 88.045),
        (87.25, 84.129),
        (90, 79.809),
    ),
    344738: (
        (0, 319.54),
        (15.1, 309.77),
        (22.03, 298.55),
        (31.26, 278.85),
        (40.5, 254.6),
        (49.73, 227.51),
        (54.35, 213.15),
        (58.97, 199.03),
        (68.2, 171.25),
        (77.44, 145.37),
        (82.05, 133.79),
        (84.36, 128.19),
        (86.67, 123.06),
        (90, 116.75),
    ),
    689476: (
        (0, 468.25),
        (15.1, 450.88),
        (22.03, 434.41),
        (31.26, 403.14),
        (40.5, 364.03),
        (49.73, 321.41),
        (54.35, 298.83),
        (58.97, 276.8),
        (68.2, 234.39),
        (77.44, 196.23),
        (82.05, 179.55),
        (84.36, 171.88),
        (87.29, 162.93),
        (90, 155.02),
    ),
    1378950: (
        (0, 707.82),
        (15.1, 676.75),
        (22.03, 645.66),
        (31.26, 590.95),
        (40.5, 524.5),
        (49.73, 450.88),
        (54.35, 413.69),
        (58.97, 377.13),
        (68.2, 308.44),
        (77.44, 249.95),
        (82.05, 225.62),
        (84.36, 214.8),
        (87.34, 203.05),
        (90, 194.01),
    ),
}

#: UFC 3-340-02 Fig. 2-193: incident pressure [Pa] -> (angle [deg], C_r_alpha [-]), every other digitised point.
FIG_2_193 = {
    68947.6: (
        (0, 2.5068),
        (39.79, 2.4941),
        (41.38, 2.6346),
        (43.48, 2.7512),
        (45.1, 3.0175),
        (46.4, 3.2373),
        (47.77, 3.1731),
        (49.91, 2.9114),
        (52.61, 2.5911),
        (55.99, 2.2777),
        (61.13, 1.9526),
        (64.32, 1.7873),
        (70.74, 1.5349),
        (75.55, 1.3868),
        (80.55, 1.2213),
        (84.84, 1.1373),
        (90, 1),
    ),
    137895: (
        (0, 2.9997),
        (14.71, 2.9494),
        (27.91, 2.8497),
        (36.44, 2.9097),
        (40.35, 3.0846),
        (42.92, 3.3331),
        (44.03, 3.1616),
        (47.21, 2.7263),
        (49.31, 2.5296),
        (52.7, 2.1762),
        (56, 1.9413),
        (60.03, 1.777),
        (66.34, 1.5438),
        (72.85, 1.3017),
        (82.58, 1.1269),
        (90, 1),
    ),
    344738: (
        (0, 3.9962),
        (9.86, 3.8532),
        (20.11, 3.6999),
        (30.15, 3.5465),
        (36.06, 3.5023),
        (37.99, 3.6401),
        (39.24, 3.9066),
        (40.35, 4.0975),
        (41.41, 3.8518),
        (43.07, 3.388),
        (44.87, 2.9557),
        (46.12, 2.7767),
        (48.52, 2.476),
        (49.96, 2.3129),
        (52.84, 2.037),
        (56.5, 1.8594),
        (61.19, 1.628),
        (63.79, 1.4739),
        (68.08, 1.3516),
        (79.44, 1.1406),
        (90, 1),
    ),
    689476: (
        (0, 5.0079),
        (9.86, 4.8547),
        (20.03, 4.6484),
        (30.15, 4.3958),
        (36.06, 4.2521),
        (38.68, 4.4206),
        (39.79, 4.6122),
        (40.87, 4.7028),
        (42.11, 4.4752),
        (43.48, 4.2073),
        (45.65, 3.8258),
        (48.88, 3.364),
        (50.67, 3.1704),
        (54.2, 2.7455),
        (56.3, 2.4863),
        (59.22, 2.222),
        (64.32, 1.8528),
        (68.56, 1.6867),
        (74.87, 1.4111),
        (80.63, 1.2312),
        (86.7, 1.0929),
        (90, 1),
    ),
    1378950: (
        (0, 6.0021),
        (9.86, 5.8507),
        (20.26, 5.6391),
        (30.15, 5.1893),
        (36.06, 4.902),
        (38.68, 5.0178),
        (39.79, 5.1293),
        (40.94, 5.3861),
        (42.2, 5.4648),
        (43.98, 5.353),
        (45.2, 5.2093),
        (47.72, 4.9068),
        (49.18, 4.6823),
        (51.4, 4.2958),
        (53.45, 3.9449),
        (54.99, 3.6579),
        (56.8, 3.338),
        (58.62, 3.024),
        (60, 2.7888),
        (62.04, 2.4791),
        (64.53, 2.2312),
        (68.51, 1.874),
        (71.84, 1.6807),
        (77.61, 1.424),
        (83.22, 1.2378),
        (90, 1),
    ),
}


def chart(figure: dict, angle_deg: float, incident_pressure: float) -> float:
    """A UFC chart's value at the angle [deg] and the incident pressure [Pa] (the module's interpolation);
    outside the typed curves it refuses (the tests stay inside them)."""
    ps = sorted(figure)
    if not ps[0] <= incident_pressure <= ps[-1]:
        raise ValueError(f"P_so = {incident_pressure:.4g} Pa is outside the typed curves {ps[0]}-{ps[-1]} Pa")
    k = max(j for j in range(len(ps) - 1) if ps[j] <= incident_pressure)
    w = math.log(incident_pressure / ps[k]) / math.log(ps[k + 1] / ps[k])

    def along(p):
        a, v = zip(*figure[p])
        return float(np.interp(angle_deg, a, v))

    return (1.0 - w) * along(ps[k]) + w * along(ps[k + 1])


def oblique(angle_deg: float, reflected: float, side_on: float, incident_pressure: float, figure: dict) -> float:
    """The face's value at the angle [deg]: the reflected excess over the side-on value, scaled by the chart."""
    c = chart(figure, angle_deg, incident_pressure)
    c0, c90 = chart(figure, 0.0, incident_pressure), chart(figure, 90.0, incident_pressure)
    return side_on + (reflected - side_on) * (c - c90) / (c0 - c90)


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
    incidence_deg=0.0,
    drift=0.0,
    record_to=3.0,
):
    """(t [s], p [Pa], truth) of a gauge at ``distance`` [m] from ``charge`` [kg TNT]: flush in a face at the
    angle of incidence ``incidence_deg`` [deg] (module docstring), with a baseline ``drift`` [fraction of the
    peak per ms], the record running ``record_to`` positive durations past the arrival."""
    bp = blast_parameters(charge, distance, blast_model)
    P = bp.incident_pressure if side_on else bp.reflected_pressure
    i = bp.incident_impulse if side_on else bp.reflected_impulse
    ta, to = bp.arrival_time, bp.positive_duration
    if incidence_deg and not side_on:
        side = bp if bp.incident_pressure is not None else blast_parameters(charge, distance)
        pso, i_s = side.incident_pressure, side.incident_impulse
        P = oblique(incidence_deg, P, pso, pso, FIG_2_193)
        i = oblique(incidence_deg, i, i_s, pso, FIG_2_194)
    d = _decay_for(i / (P * to))
    rng = np.random.default_rng(seed)
    t = np.arange(-pre_s, ta + record_to * to, 1.0 / rate_hz)
    tau = t - ta
    x = np.clip(tau, 0.0, None) / to
    p = np.where(tau >= 0, P * (1 - x) * np.exp(-d * x), 0.0)  # with Friedlander's own negative phase
    ring = np.where(
        tau >= 0, ringing * P * np.sin(2 * np.pi * ring_hz * tau) * np.exp(-np.clip(tau, 0, None) / 10e-6), 0.0
    )
    signal = p + ring + offset * P + noise * P * rng.standard_normal(t.size) + drift * P * (t - t[0]) / 1e-3
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


def camera_track(history: dict, *, fps: float, seed: int, noise_m: float, start_s: float = -0.01, components=("x",)):
    """A simulated marker history sampled as a camera films it: frames [s after the firing signal] from ``start_s``
    to the history's end at ``fps`` frames per second, and per component of ``components`` ("x", "z") the
    displacement ``history["u" + c]`` [m] interpolated there (0 before the history starts) plus white noise of
    ``noise_m`` [m], drawn from one generator seeded ``seed`` in the components' order."""
    frames = np.arange(start_s, history["t"][-1], 1.0 / fps)
    rng = np.random.default_rng(seed)
    return frames, {
        c: np.interp(frames, history["t"], history["u" + c], left=0.0) + noise_m * rng.standard_normal(frames.size)
        for c in components
    }


def write_gauge_csv(path, t, p, name: str = "g1") -> None:
    """A gauge record as a lab's acquisition writes it: ``time_us``, ``NAME_kPa`` (``t`` [s], ``p`` [Pa])."""
    np.savetxt(path, np.column_stack([t * 1e6, p / 1e3]), delimiter=",", header=f"time_us,{name}_kPa", comments="")


def write_track_csv(path, frames, columns: dict) -> None:
    """A track record as video-tracking software writes it: ``time_ms`` (``frames`` [s]) and one column ``NAME_mm``
    per entry of ``columns`` (``"top_x"`` -> positions [m])."""
    np.savetxt(
        path,
        np.column_stack([frames * 1e3, *(1e3 * np.asarray(v) for v in columns.values())]),
        delimiter=",",
        header=",".join(["time_ms", *(f"{n}_mm" for n in columns)]),
        comments="",
    )
