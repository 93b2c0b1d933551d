"""The estimate's per-step cost of contacts (issue #40 item 6): measured to grow faster than their number, not
assumed linear (study.memory, docs/performance.md). Checked on the formula by differencing two durations of
one structure (the once-per-run terms cancel), for stand-in structures of n bodies (u = 2 n bodies and
contacts): below CONTACT_STEP_UNITS the cost per step is linear in u, above it grows as u^(1 + exponent)."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from blastscale.scenario import Scenario
from blastscale.sim3d.contact import ContactSettings
from blastscale.study import memory

CONTACT = ContactSettings()


def _per_step(n: int) -> float:
    """Seconds per step [s] of a stand-in of n bodies (no interfaces found: its contacts are its bodies)."""
    structure = SimpleNamespace(bodies=[None] * n, describe=lambda: {"height_m": 10.0})
    sc = Scenario.default().with_values({"simulation.engine": "3d", "scale.length": 0.1})

    def seconds(duration):
        return memory.estimate_seconds(sc.with_values({"simulation.duration_s": duration}), structure, CONTACT)

    steps = 1.0 / CONTACT.timestep * 2  # 1 s more of two runs (prototype and model)
    return (seconds(2.0) - seconds(1.0)) / steps * memory.step_factor_after_load(CONTACT, n)


def test_small_structures_cost_linearly_per_step():
    u = 2 * 10
    assert u <= memory.CONTACT_STEP_UNITS
    assert _per_step(10) == pytest.approx(memory.STEP_BASE_SECONDS + memory.CONTACT_STEP_SECONDS * u, rel=1e-9)
    assert (_per_step(20) - memory.STEP_BASE_SECONDS) / (_per_step(10) - memory.STEP_BASE_SECONDS) == pytest.approx(2)


def test_a_contact_costs_more_among_many():
    """1500 bodies + contacts cost (1500 / 50)^0.35 = 3.3 x a small structure's per contact under a blast; 3000 blocks
    with 5950 contacts about 18 us (measured after the load: 5.6 us at 1180, 11 us at 290, 3.75 us at 70, since side
    joints engage at the collision depth; bench_contact_cost.py)."""
    u1, u2 = 2 * 750, 2 * 3000
    a, b = (_per_step(n) - memory.STEP_BASE_SECONDS for n in (750, 3000))
    assert a / u1 == pytest.approx(memory.CONTACT_STEP_SECONDS * (u1 / memory.CONTACT_STEP_UNITS) ** 0.35, rel=1e-9)
    assert b / a == pytest.approx((u2 / u1) ** 1.35, rel=1e-9)  # superlinear: 6.5 x for 4 x the contacts
    assert 15e-6 < memory.CONTACT_STEP_SECONDS * (8950 / memory.CONTACT_STEP_UNITS) ** 0.35 < 20e-6


def test_a_step_at_rest_costs_linearly_in_the_contacts():
    """The check at rest's steps (one Newton iteration a step: no contact changes state) cost STEP_BASE_SECONDS +
    CONTACT_STEP_SECONDS u at every size: the 3000-block wall's 8950 units 27 ms a step (26 ms measured), where the
    growth factor under a blast would say 6x more."""
    assert memory.step_seconds(8950, at_rest=True) == pytest.approx(4e-6 + 3e-6 * 8950, rel=1e-12)
    assert memory.step_seconds(20, at_rest=True) == memory.step_seconds(20)  # below 50 units the two agree
    assert memory.step_seconds(8950) / memory.step_seconds(8950, at_rest=True) > 5.0
