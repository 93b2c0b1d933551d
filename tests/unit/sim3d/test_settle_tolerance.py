"""The settling tolerance of assemblies (issue #28, deliverable 4; docs/performance.md, "Walls under a blast"): the
rule resolves by the number of bodies, one setting per default, and the settling of before stays one key away."""

from __future__ import annotations

import math
from dataclasses import replace

import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.scenario import Scenario
from blastscale.sim3d.contact import (
    ASSEMBLY_SETTLE_TOLERANCE,
    LOOSE_SETTLE_ABOVE_BODIES,
    ContactSettings,
    default_contact,
    length_time_factors,
    reference_contact,
)
from blastscale.structures import MultiDrumColumn, wall
from blastscale.structures.block import RectangularBlock
from blastscale.study.engines import contact_settings


def _wall(courses: int, units: int):
    return wall(
        length_m=0.5 * units, height_m=0.25 * courses, thickness_m=0.25, courses=courses, units_per_course=units
    )


def test_assemblies_above_ten_bodies_settle_at_mujocos_default_tolerance():
    """Above 10 bodies the default settles at 1e-8 and runs at 1e-10; the columns (10 drums), a 10-block wall and a
    single block keep the settling of before (None: the run's tolerance), so their results and goldens do not move."""
    assert LOOSE_SETTLE_ABOVE_BODIES == 10 and ASSEMBLY_SETTLE_TOLERANCE == 1e-8
    stack = wall(length_m=2.5, height_m=1.0, thickness_m=0.25, courses=2, units_per_course=5, bond="stack")
    keep = (
        MultiDrumColumn("square"),
        MultiDrumColumn("circular"),
        stack,
        RectangularBlock.from_slenderness(10.0, 0.26),
    )
    for s in keep:
        assert len(s.bodies) <= 10
        assert default_contact(s).settle_tolerance is None and reference_contact(s).settle_tolerance is None
    for s in (_wall(6, 2), _wall(20, 10), wall(courses=2, units_per_course=5)):  # 12, 200, 11 (running bond) bodies
        assert len(s.bodies) > 10
        c = default_contact(s)
        assert c.settle_tolerance == ASSEMBLY_SETTLE_TOLERANCE and c.tolerance == 1e-10  # the run's is unchanged
    assert ContactSettings().settle_tolerance is None  # explicit settings: the settling of before
    c = default_contact(_wall(6, 2))
    assert c.scaled(length_time_factors(0.1, math.sqrt(0.1))).settle_tolerance == ASSEMBLY_SETTLE_TOLERANCE  # [-]
    assert c.to_dict()["settle_tolerance"] == ASSEMBLY_SETTLE_TOLERANCE


@pytest.mark.parametrize("value", [0.0, -1e-8, 1.5, math.nan])
def test_a_settling_tolerance_out_of_range_is_refused(value):
    """(0, 1], as the run's tolerance (sim3d.contact_ranges.SETTING_RANGES)."""
    with pytest.raises(BlastscaleInputError, match="settle_tolerance"):
        ContactSettings(settle_tolerance=value)


def test_the_scenario_key_gives_the_settling_of_before():
    """``simulation.contact.settle_tolerance`` reaches the engine; set to the run's tolerance it gives the old
    settling (bitwise: tests/integration/test_walls_settling.py); left out, the structure's default."""
    base = Scenario.default()
    s = _wall(6, 2)
    assert contact_settings(base, s).settle_tolerance == ASSEMBLY_SETTLE_TOLERANCE
    old = contact_settings(base.with_values({"simulation.contact.settle_tolerance": 1e-10}), s)
    assert old.settle_tolerance == old.tolerance == 1e-10
    assert old == replace(contact_settings(base, s), settle_tolerance=1e-10)
