"""Overturning capacity: the paper's critical charge (79.8 kg), critical stand-off, P-I diagram."""

from __future__ import annotations

import math

import numpy as np
import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.blast import Triangular, blast_parameters
from blastscale.rocking import RockingSystem, critical_charge, critical_standoff, overturn_margin, pi_diagram, simulate
from blastscale.structures.block import RectangularBlock

BLOCK = RectangularBlock.from_slenderness(10.0, math.radians(15.0))
SYSTEM = RockingSystem.from_block(BLOCK)

# docs/design.md: 79.84-79.87 kg depending on the pulse shape (impulsive / triangular / Friedlander);
# the paper prints 79.8 kg. Our values are 79.844, 79.864, 79.870 (see docs/rocking.md);
# +-0.005 kg brackets the independent calculation quoted in docs/design.md.
PAPER_CRITICAL = {"impulsive": 79.84, "triangular": 79.86, "friedlander": 79.87}


@pytest.mark.parametrize("shape", ["impulsive", "triangular", "friedlander"])
def test_paper_critical_charge_79_8_kg(shape):
    res = critical_charge(BLOCK, 2.0, pulse_shape=shape, blast_model="masi2021")
    assert math.floor(res.charge_kg * 10) / 10 == 79.8  # the paper truncates (docs/design.md)
    assert res.charge_kg == pytest.approx(PAPER_CRITICAL[shape], abs=0.0051)
    # the full simulation agrees on both sides of the threshold (1e-5 relative in charge
    # is ~1e4 times the search tolerance)
    bp_hi = blast_parameters(res.charge_kg * (1 + 1e-5), 2.0, blast_model="masi2021")
    bp_lo = blast_parameters(res.charge_kg * (1 - 1e-5), 2.0, blast_model="masi2021")
    assert simulate(BLOCK, bp_hi.pulse(shape), 10.0).collapsed
    assert not simulate(BLOCK, bp_lo.pulse(shape), 10.0).collapsed


def test_impulsive_critical_charge_delivers_the_critical_impulse():
    """Impulsive limit: at the critical charge the reflected impulse equals J_o w_c / (S h)."""
    res = critical_charge(BLOCK, 2.0, pulse_shape="impulsive", blast_model="masi2021")
    i = blast_parameters(res.charge_kg, 2.0, blast_model="masi2021").reflected_impulse
    wc = SYSTEM.critical_angular_velocity
    # the search stops at 1e-9 in ln W; i ~ W^0.9 here, so 1e-8 relative is safe
    assert i == pytest.approx(BLOCK.inertia_pivot * wc / (BLOCK.front_area * BLOCK.h), rel=1e-8)


def test_critical_standoff_inverts_critical_charge():
    W = critical_charge(BLOCK, 2.0, blast_model="masi2021").charge_kg
    R = critical_standoff(BLOCK, W, blast_model="masi2021").standoff_m
    assert R == pytest.approx(2.0, rel=1e-7)  # both searches at 1e-9; margin slope is finite


def test_depth_and_density_scaling_of_the_critical_charge():
    """Depth cancels (S and m both scale with it)."""
    deep = RectangularBlock(BLOCK.height, BLOCK.width, depth=3.0)
    a = critical_charge(BLOCK, 2.0, blast_model="masi2021").charge_kg
    b = critical_charge(deep, 2.0, blast_model="masi2021").charge_kg
    assert b == pytest.approx(a, rel=1e-8)


def test_overturn_margin_is_continuous_and_increasing():
    Ws = np.linspace(79.0, 80.7, 18)
    m = [overturn_margin(BLOCK, blast_parameters(W, 2.0, blast_model="masi2021").pulse()) for W in Ws]
    assert np.all(np.diff(m) > 0)
    assert m[0] < 0 < m[-1]
    assert max(abs(x) for x in m) < 0.2  # no jump across the threshold


def test_pi_diagram_asymptotes():
    pi = pi_diagram(BLOCK, n=8)
    # impulsive asymptote: J_o p sqrt(2(1-cos a)) / (S h)
    assert pi.impulse_asymptote == pytest.approx(
        BLOCK.inertia_pivot * SYSTEM.critical_angular_velocity / (BLOCK.front_area * BLOCK.h), rel=1e-14
    )
    # quasi-static asymptote: uplift P S h = m g b
    assert pi.pressure_asymptote * BLOCK.front_area * BLOCK.h == pytest.approx(BLOCK.mass * 9.81 * BLOCK.b, rel=1e-12)
    assert np.all(np.diff(pi.critical_impulse) < 0)  # monotone: more pressure, less impulse needed
    assert np.all(pi.critical_impulse > pi.impulse_asymptote)
    # at 1e4 x the uplift pressure the pulse lasts ~1e-4/p: impulsive within 0.1 %
    assert pi.critical_impulse[-1] == pytest.approx(pi.impulse_asymptote, rel=1e-3)
    assert pi.critical_impulse[0] > 10 * pi.impulse_asymptote  # near uplift it diverges
    # each point is on the boundary: 0.1 % more impulse overturns, 0.1 % less does not
    P, i = pi.peak_pressure[3], pi.critical_impulse[3]
    assert simulate(BLOCK, Triangular(P, i * 1.001), 30.0).collapsed
    assert not simulate(BLOCK, Triangular(P, i * 0.999), 30.0).collapsed


def test_capacity_bad_input():
    with pytest.raises(BlastscaleInputError, match="standoff"):
        critical_charge(BLOCK, -2.0, blast_model="masi2021")
    with pytest.raises(BlastscaleInputError, match="pulse"):
        critical_charge(BLOCK, 2.0, pulse_shape="square", blast_model="masi2021")
    with pytest.raises(BlastscaleInputError, match="uplift"):
        pi_diagram(BLOCK, peak_pressures=[1.0])
    # a slender 5 cm rod 1 m away overturns at every Z of the fits' range (0.2-40 m/kg^(1/3))
    with pytest.raises(BlastscaleInputError, match="no critical charge"):
        critical_charge(RectangularBlock(0.05, 0.003), 1.0)
    # odd counts, empty tables, non-pulses, a tolerance of 0: named errors, not numpy/scipy ones
    with pytest.raises(BlastscaleInputError, match="n = 0"):
        pi_diagram(BLOCK, n=0)
    with pytest.raises(BlastscaleInputError, match="peak_pressures"):
        pi_diagram(BLOCK, peak_pressures=[])
    with pytest.raises(BlastscaleInputError, match="pulse"):
        overturn_margin(BLOCK, None)
    with pytest.raises(BlastscaleInputError, match="xtol_rel"):
        critical_charge(BLOCK, 2.0, blast_model="masi2021", xtol_rel=0.0)


def test_scaled_rocking_system_is_the_scaled_blocks_system():
    """``RockingSystem.scaled`` (the specimen of a capacity curve) against an independent route: scale the
    block's geometry and density (``RectangularBlock.scaled``) and rebuild its system from its mass
    properties (m = rho V, J_o = 4/3 m r^2, S = 2h x depth, l = h) with gravity varsigma g. lambda = 1/50,
    gamma = 0.4, varsigma = 3; every field agrees to round-off (1e-14), alpha and e are unchanged."""
    from blastscale.similitude import scaling_factors

    f = scaling_factors(1 / 50, 0.4, 3.0)
    got = SYSTEM.scaled(f)
    want = RockingSystem.from_block(BLOCK.scaled(f), 9.81 * 3.0)
    for name in ("mass", "inertia_pivot", "radius", "alpha", "loaded_area", "lever_arm", "gravity"):
        assert getattr(got, name) == pytest.approx(getattr(want, name), rel=1e-14), name
    assert got.coefficient_of_restitution == SYSTEM.coefficient_of_restitution
    # the specimen's frequency parameter p x sqrt(varsigma / lambda), its critical impulse x the impulse factor
    assert got.frequency_parameter == pytest.approx(SYSTEM.frequency_parameter * f.angular_velocity, rel=1e-14)
    assert got.critical_impulse == pytest.approx(SYSTEM.critical_impulse * f.impulse, rel=1e-14)
