"""The engine's body numbering and engagement depth (blastscale.sim3d.collision), on plain graphs."""

from __future__ import annotations

import numpy as np
import pytest

from blastscale.sim3d.collision import _graph, body_order, engagement_depth, profile
from blastscale.structures import MultiDrumColumn, wall


def test_a_chain_keeps_its_order():
    """A column's drums form a path graph: its natural order already has the least profile (n - 1)."""
    col = MultiDrumColumn("square")
    n = len(col.bodies)
    np.testing.assert_array_equal(body_order(col.interfaces, n), np.arange(n))
    assert profile(np.arange(n), _graph(col.interfaces, n)) == n - 1


def test_a_stack_bonded_wall_is_renumbered_with_a_smaller_profile():
    """Listed course by course, a 20 x 10 stack-bonded wall has profile 1909; reverse Cuthill-McKee 1705."""
    st = wall(length_m=5.0, height_m=2.5, thickness_m=0.5, courses=20, units_per_course=10, bond="stack")
    n = len(st.bodies)
    order = body_order(st.interfaces, n)
    adj = _graph(st.interfaces, n)
    assert sorted(order) == list(range(n)) and not np.array_equal(order, np.arange(n))
    assert profile(order, adj) == 1705 < profile(np.arange(n), adj) == 1909


def test_a_running_bond_wall_keeps_its_order():
    """Reverse Cuthill-McKee does not lower the profile of a 20 x 10 running-bond wall (2199 either way;
    measured 1.2x slower in its order), so the wall keeps its own."""
    st = wall(length_m=5.0, height_m=2.5, thickness_m=0.5, courses=20, units_per_course=10, bond="running")
    np.testing.assert_array_equal(body_order(st.interfaces, len(st.bodies)), np.arange(len(st.bodies)))


def test_profile_counts_the_envelope():
    adj = _graph([(0, 2), (1, 2), (-1, 0)], 3)  # the ground is not a body
    assert profile([0, 1, 2], adj) == 2  # row 2 reaches back to 0
    assert profile([2, 0, 1], adj) == 1 + 2  # 0 -> 2 (1), 1 -> 2 (2)


def test_engagement_depth_is_the_static_penetration_scale():
    assert engagement_depth(1e-3, 9.81) == pytest.approx(9.81e-6, rel=1e-15)
    assert engagement_depth(2e-3, 9.81) == pytest.approx(4 * 9.81e-6, rel=1e-15)
