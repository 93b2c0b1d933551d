"""analysis.planar: the one place outside the Study that builds a rocking system and runs the engine gives the
engine's own numbers, bit for bit."""

from __future__ import annotations

import math

import numpy as np
import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.analysis.planar import critical_of, first_swing_of, first_swing_under, planar_system
from blastscale.blast import blast_parameters
from blastscale.rocking import RockingSystem, critical_charge, first_swing, first_swing_blast
from blastscale.structures import RectangularBlock

BLOCK = RectangularBlock.from_slenderness(2.0, math.radians(12.0))


def test_runs_equal_the_engine_bit_for_bit():
    system = RockingSystem.from_block(BLOCK)
    assert planar_system(BLOCK) == system
    W, R = np.array([0.5, 2.0, 8.0]), 1.5
    a, b = first_swing_of(BLOCK, W, R), first_swing(system, W, R)
    assert np.array_equal(a.max_rotation, b.max_rotation) and np.array_equal(a.collapsed, b.collapsed)
    assert critical_of(BLOCK, standoff=R).charge_kg == critical_charge(system, R).charge_kg
    bp = blast_parameters(W, np.full(3, R))
    rho = np.array([0.9, 1.0, 1.2])
    got = first_swing_under(system, bp, density_ratio=rho)
    want = first_swing_blast(
        system.alpha,
        system.coefficient_of_restitution,
        system.frequency_parameter,
        system.load_ratio_per_pascal / rho,
        bp,
    )
    assert np.array_equal(got.max_rotation, want.max_rotation)


@pytest.mark.parametrize("kw", [{}, {"standoff": 1.0, "charge": 2.0}])
def test_critical_of_needs_exactly_one_of_standoff_and_charge(kw):
    with pytest.raises(BlastscaleInputError, match="give exactly one"):
        critical_of(BLOCK, **kw)
