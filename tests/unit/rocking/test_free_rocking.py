"""The free rocking after the pulse in closed form (rocking._free, used by simulate_batch): against
independent implementations of the elliptic functions (scipy.special), the closed forms of the
rocking block (Housner 1963) and the stepping kernel (simulate, which steps the free motion to record
its history)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.special import ellipj, ellipk, elliprf

from blastscale.blast import blast_parameters
from blastscale.blast.load_model import LoadModel, front_face_pulse
from blastscale.blast.pulses import Tabulated
from blastscale.rocking import RockingSolver, RockingSystem, simulate
from blastscale.rocking._free import carlson_rf
from blastscale.structures.block import RectangularBlock

ALPHA = math.radians(15.0)
BLOCK = RectangularBlock.from_slenderness(10.0, ALPHA)  # the paper's prototype
SYSTEM = RockingSystem.from_block(BLOCK)
ONE = RockingSolver(threads=1)


@pytest.mark.parametrize(
    "xyz", [(0.0, 0.3, 1.0), (0.0, 1e-12, 1.0), (0.2, 1.7, 1.0), (3e-5, 4e-5, 2e-5), (1.0, 1.0, 1.0)]
)
def test_carlson_rf_equals_scipy(xyz):
    """R_F by duplication against scipy's elliprf (Carlson's algorithm in C, independently coded):
    4e-16 relative, a few ulps (the series' truncation is below 1e-16)."""
    assert carlson_rf(*xyz) == pytest.approx(elliprf(*xyz), rel=4e-16)


def test_free_swing_follows_jacobi_dn():
    """From rest at theta0 the body swings back on ``sin(phi / 2) = dn(K + tau, k)`` (phi = alpha - theta,
    k = cos(phi0 / 2); the module docstring): the samples (Taylor series read off between the events)
    equal scipy's ellipj to 1e-12 rad, and the first impact comes at tau = K(k) - F(k) from the
    quadrature of the time integral (scipy ellipj's own error near m = 0.99 is ~1e-13)."""
    th0 = 0.5 * ALPHA
    p = SYSTEM.frequency_parameter
    k2 = math.cos(0.5 * (ALPHA - th0)) ** 2
    kk = ellipk(k2)
    # first impact: dn(u) = sin(alpha / 2), u in (K, 2K)
    from scipy.optimize import brentq

    u_imp = brentq(lambda u: ellipj(u, k2)[2] - math.sin(0.5 * ALPHA), kk, 2 * kk, xtol=1e-15)
    t = np.linspace(0.0, 0.98 * (u_imp - kk) / p, 57)
    res = ONE.simulate_batch(SYSTEM, None, t[-1], t, theta0=th0)
    expected = ALPHA - 2.0 * np.arcsin(ellipj(kk + p * t, k2)[2])
    np.testing.assert_allclose(res.theta[0], expected, rtol=0, atol=1e-12)
    later = ONE.simulate_batch(SYSTEM, None, 2.0 * (u_imp - kk) / p, np.array([0.0]), theta0=th0)
    assert later.first_impact_time[0] * p == pytest.approx(u_imp - kk, rel=1e-12)


def test_housner_amplitude_after_each_impact_to_round_off():
    """cos(alpha - theta_1) - cos(alpha) = e^2 [cos(alpha - theta_0) - cos(alpha)] (Housner 1963), and
    theta_2 from theta_1 alike: exact in closed form, 1e-12 relative (the stepping kernel: 1e-9)."""
    e = SYSTEM.coefficient_of_restitution
    th0 = 0.6 * ALPHA
    p = SYSTEM.frequency_parameter
    res = ONE.simulate_batch(SYSTEM, None, 12.0 / p, np.array([0.0]), theta0=th0)
    th1 = res.first_peak_angle[0]
    lhs = math.cos(ALPHA - th1) - math.cos(ALPHA)
    assert lhs == pytest.approx(e**2 * (math.cos(ALPHA - th0) - math.cos(ALPHA)), rel=1e-12)
    one = simulate(SYSTEM, None, 12.0 / p, theta0=th0)  # the stepping kernel: the same peaks to 1e-9
    assert abs(one.peak_angles[0]) == pytest.approx(th1, rel=1e-9)
    assert res.n_impacts[0] == one.n_impacts


@pytest.mark.parametrize("stop", [True, False])
def test_overturning_threshold_to_round_off(stop):
    """Overturning from upright needs theta_dot_0 > p sqrt(2 (1 - cos alpha)): 1e-9 either side decides
    (the stepping kernel needs 1e-6); the body reaches the top with theta_dot^2 = theta_dot_0^2 - wc^2
    (energy), 1e-5 relative in closed form (with ``stop_at_overturn``; the cancellation in 1e-9 of the
    energy costs 1e-7), 1e-3 where the stepping kernel follows the fall (its 1e-10 local error on an energy
    excess of 2e-9 of the barrier)."""
    wc = SYSTEM.critical_angular_velocity
    p = SYSTEM.frequency_parameter
    w0 = np.array([wc * (1 + 1e-9), wc * (1 - 1e-9)])
    res = ONE.simulate_batch(SYSTEM, None, 40.0 / p, np.array([0.0]), theta_dot0=w0, stop_at_overturn=stop)
    assert res.collapsed.tolist() == [True, False]
    assert res.angular_velocity_at_tipping[0] == pytest.approx(
        wc * math.sqrt((1 + 1e-9) ** 2 - 1), rel=1e-5 if stop else 1e-3
    )
    # the time to the top against the stepping kernel, 1e-3 above the threshold
    fast = ONE.simulate_batch(SYSTEM, None, 40.0 / p, np.array([0.0]), theta_dot0=wc * 1.001, stop_at_overturn=stop)
    one = simulate(SYSTEM, None, 40.0 / p, theta_dot0=wc * 1.001, stop_at_overturn=stop)
    assert fast.collapse_time[0] == pytest.approx(one.collapse_time, rel=1e-9)


def _cases():
    rng = np.random.default_rng(28)
    neg = LoadModel(negative_phase=True)
    bodies, pulses = [], []
    for k in range(12):
        blk = RectangularBlock.from_slenderness(
            rng.uniform(1.0, 20.0), math.radians(rng.uniform(8.0, 30.0)), density=rng.uniform(1500.0, 2700.0)
        )
        bp = blast_parameters(
            float(np.exp(rng.uniform(math.log(5.0), math.log(500.0)))), rng.uniform(2.0, 8.0), blast_model="masi2021"
        )
        shape = ("friedlander", "triangular", "impulsive", "tabulated")[k % 4]
        if shape == "tabulated":
            f = bp.pulse("friedlander")
            tt = np.linspace(0.0, f.duration, 16)
            pulse = Tabulated(tt, f.pressure(tt))
        elif k % 3 == 0:  # with the negative phase: the free motion starts after the suction
            pulse = front_face_pulse(bp, shape, neg)
        else:
            pulse = bp.pulse(shape)
        bodies.append(blk)
        pulses.append(pulse)
    return bodies, pulses


@pytest.mark.parametrize("stop", [True, False])
def test_closed_form_equals_stepping_kernel_on_mixed_cases(stop):
    """12 random blocks and loads (four pulse shapes, some with the negative phase, some overturning):
    the batch (closed-form free rocking) against the stepping kernel (rtol 1e-10): the same outcomes
    and impact counts, samples within 1e-8 rad and angular velocities within 1e-8 p (the stepping's
    global error, RockingSolver), overturning times within 1e-9 relative, NaN at the same samples."""
    bodies, pulses = _cases()
    t = np.linspace(0.0, 4.0, 81)
    batch = ONE.simulate_batch(bodies, pulses, 4.0, t, stop_at_overturn=stop)
    assert 0 < batch.collapsed.sum() < len(bodies)
    for k, (b, pl) in enumerate(zip(bodies, pulses)):
        one = simulate(b, pl, 4.0, t_eval=t, stop_at_overturn=stop)
        p = one.system.frequency_parameter
        assert batch.collapsed[k] == one.collapsed and batch.n_impacts[k] == one.n_impacts
        np.testing.assert_array_equal(np.isnan(batch.theta[k]), np.isnan(one.theta_eval))
        np.testing.assert_allclose(batch.theta[k], one.theta_eval, rtol=0, atol=1e-8)
        np.testing.assert_allclose(batch.theta_dot[k] / p, one.theta_dot_eval / p, rtol=0, atol=1e-8)
        if one.collapsed:
            assert batch.collapse_time[k] == pytest.approx(one.collapse_time, rel=1e-9)
        assert batch.max_rotation[k] == pytest.approx(one.max_rotation, abs=1e-8)


def _tight_pulse_phase(block, pulse, t):
    """The pulse phase by scipy's DOP853 at rtol 1e-13 (the dimensional equation of the plain script,
    benchmarks/bench_rocking.py; the body lifts off at t = 0): theta [rad], theta_dot [rad/s] at t."""
    from scipy.integrate import solve_ivp

    m, r, a = block.mass, block.r, block.alpha
    J, S, g = 4.0 / 3.0 * m * r * r, block.front_area, 9.81

    def rhs(tt, y):
        return [y[1], (-m * g * r * math.sin(a - y[0]) + S * float(pulse.pressure(tt)) * r * math.cos(a - y[0])) / J]

    sol = solve_ivp(rhs, (0.0, t[-1]), [0.0, 0.0], method="DOP853", rtol=1e-13, atol=1e-18, t_eval=t)
    return sol.y[0], sol.y[1]


@pytest.mark.parametrize(
    "charge, shape", [(20.0, "friedlander"), (120.0, "friedlander"), (60.0, "triangular"), (60.0, "tabulated")]
)
def test_pulse_phase_in_taylor_series(charge, shape):
    """The pulse phase of a batch (rocking._series: one Taylor expansion per piece, cut where the Friedlander
    decay d r exceeds 2; masi2021 at 2 m: d ~ 8) against scipy's DOP853 at rtol 1e-13: theta within 1e-13 rad
    and theta_dot within 1e-11 relative, in one series step per piece; the stepping kernel (DP5, rtol 1e-10,
    ~30 steps) is 30x further off (3e-10 relative on theta_dot)."""
    bp = blast_parameters(charge, 2.0, blast_model="masi2021")
    if shape == "tabulated":
        f = bp.pulse("friedlander")
        tt = np.linspace(0.0, f.duration, 16)
        pulse = Tabulated(tt, f.pressure(tt))
    else:
        pulse = bp.pulse(shape)
    t = np.linspace(0.0, pulse.duration, 9)
    fast = ONE.simulate_batch(BLOCK, pulse, pulse.duration, t)
    th, om = _tight_pulse_phase(BLOCK, pulse, t)
    np.testing.assert_allclose(fast.theta[0], th, rtol=0, atol=1e-13)
    np.testing.assert_allclose(fast.theta_dot[0], om, rtol=1e-11, atol=1e-15)
    assert fast.n_steps[0] <= (15 if shape == "tabulated" else 1) < simulate(BLOCK, pulse, pulse.duration).n_steps
