"""The rocking frame (issue 16): two free-standing monolithic columns capped by a free lintel (kind
"portal") rock in their plane as one column of the same slenderness with p_hat = p sqrt((1 + 2 gamma) /
(1 + 3 gamma)), gamma = lintel mass / columns' mass (Makris & Vassiliou 2013, EESD 42, doi:10.1002/eqe.2222;
blastscale.rocking.frame). The engine starts the frame mechanism with an angular velocity omega_0 (each
column about its own base corner, the lintel translating with the column tops) and is compared with the
closed forms: peak rotation, time back to upright (the exact equation, integrated), and the overturning
threshold. Full table: docs/assemblies.md."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from blastscale.constants import STANDARD_GRAVITY as G
from blastscale.rocking import frame_frequency_parameter, free_rocking_peak, overturning_angular_velocity
from blastscale.sim3d import simulate_structure
from blastscale.sim3d.contact import default_contact
from blastscale.structures import portal

HC, W = 4.0, 0.8  # columns 4 m x 0.8 m: alpha = atan(0.2) = 11.3 deg, R = 2.04 m


def _frame():
    P = portal(column_height_m=HC, column_width_m=W, span_m=3.0, lintel_height_m=1.0, lintel_overhang_m=0.3)
    b, h = W / 2, HC / 2
    gamma = P.bodies[2].mass / (P.bodies[0].mass + P.bodies[1].mass)
    return P, math.atan2(b, h), math.hypot(b, h), gamma


def _mechanism_velocities(P, omega):
    """Columns turning by omega about their +y base edges (tops towards +y), the lintel translating with
    the column tops it rides on (the -y top corners, 2R from the pivots)."""
    b = W / 2
    w = np.array([-omega, 0.0, 0.0])  # about -x: the top moves towards +y
    v = np.zeros((3, 6))
    for k in range(2):
        com = np.asarray(P.bodies[k].com)
        v[k, :3] = np.cross(w, com - np.array([0.0, com[1] + b, 0.0]))
        v[k, 3:] = w
    v[2, :3] = np.cross(w, np.array([0.0, -2 * b, HC]))
    return v


def _time_back_upright(p, alpha, omega):
    """theta_ddot = -p^2 sin(alpha - theta) from (0, omega) until theta = 0 again [s]."""

    def upright(t, y):
        return y[0] if t > 1e-6 else 1.0

    upright.terminal, upright.direction = True, -1
    sol = solve_ivp(
        lambda t, y: [y[1], -p * p * math.sin(alpha - y[0])],
        (0.0, 30.0),
        [0.0, omega],
        events=upright,
        rtol=1e-10,
        atol=1e-12,
        max_step=0.01,
    )
    return float(sol.t_events[0][0])


def test_frame_frequency_parameter_closed_form():
    assert frame_frequency_parameter(2.0, 0.0) == pytest.approx(math.sqrt(3 * G / 8.0), rel=1e-15)
    # gamma -> infinity: p sqrt(2/3) (the beam's mass dominates)
    assert frame_frequency_parameter(2.0, 1e12) == pytest.approx(math.sqrt(3 * G / 8.0) * math.sqrt(2 / 3), rel=1e-9)
    assert free_rocking_peak(overturning_angular_velocity(0.2, 1.5) * 1.0001, 0.2, 1.5) == math.inf


def test_rocking_frame_rocks_as_one_column_with_p_hat():
    P, alpha, R, gamma = _frame()
    assert gamma == pytest.approx(4.16 / 5.12, rel=1e-12)  # 0.8125
    p, ph = math.sqrt(3 * G / (4 * R)), frame_frequency_parameter(R, gamma)
    om = 0.8 * overturning_angular_velocity(alpha, ph)
    r = simulate_structure(
        P,
        None,
        2.0,
        contact=default_contact(P, friction=0.9),
        record_every=4,
        initial_body_velocities=_mechanism_velocities(P, om),
    )
    t, tilt = r.dataset["time"].values, r.dataset["tilt"].values
    k = int(np.argmax(tilt[:, 0]))
    back = t[np.flatnonzero((np.arange(t.size) > k) & (tilt[:, 0] < 2e-4))[0]]
    # measured: peak 0.07901 vs 0.07908 rad (-0.09 %), back upright 1.3258 vs 1.3276 s (-0.14 %); tolerance 1 %
    assert tilt[:, 0].max() == pytest.approx(free_rocking_peak(om, alpha, ph), rel=0.01)
    assert back == pytest.approx(_time_back_upright(ph, alpha, om), rel=0.01)
    # the two columns move together and the lintel translates (tilt < 1e-5 rad)
    assert np.abs(tilt[:, 0] - tilt[:, 1]).max() < 1e-4 and tilt[:, 2].max() < 1e-5
    # a single column (p, not p_hat) would be far off: peak 0.0564 rad (-29 %), back at 0.91 s (-31 %)
    assert free_rocking_peak(om, alpha, p) < 0.75 * tilt[:, 0].max()
    assert not r.summary()["collapsed"]


def test_rocking_frame_overturns_above_p_hat_threshold_a_single_column_would_survive():
    P, alpha, R, gamma = _frame()
    p, ph = math.sqrt(3 * G / (4 * R)), frame_frequency_parameter(R, gamma)
    om = 1.05 * overturning_angular_velocity(alpha, ph)
    assert om < 0.95 * overturning_angular_velocity(alpha, p)  # the single column's threshold is 14 % higher
    r = simulate_structure(
        P,
        None,
        3.0,
        contact=default_contact(P, friction=0.9),
        record_every=8,
        initial_body_velocities=_mechanism_velocities(P, om),
    )
    assert r.summary()["collapsed"]
