"""Which interfaces engage at the collision depth (blastscale.sim3d.collision.side_joints, rule 1): the head joints
of walls on level beds, and not a joint that carries weight at rest."""

from __future__ import annotations

import re

from blastscale.sim3d.collision import engagement_depth, side_joints
from blastscale.sim3d.contact import default_contact
from blastscale.sim3d.model import structure_scene
from blastscale.structures import MultiDrumColumn, arch, portal, wall


def _vertical(structure) -> set:
    return {itf.pair for itf in structure.interface_details if abs(itf.normal[2]) < 1e-9}


def test_a_running_bond_walls_head_joints_are_side_joints_and_its_beds_are_not():
    """Every head joint of a running-bond wall (blocks on level beds; 5 courses of 4 units, half units at the ends of
    every other course) is a side joint, and none of its beds or ground joints."""
    w = wall(length_m=2.0, height_m=1.5, thickness_m=0.3, courses=5, units_per_course=4, bond="running")
    side = side_joints(w.interface_details)
    assert side == _vertical(w) and len(side) > 10
    assert all(itf.pair not in side for itf in w.interface_details if abs(itf.normal[2]) > 0.5)


def test_an_arch_crown_joint_carries_its_thrust_and_is_not_a_side_joint():
    """The answer "no" where a joint is vertical: the crown joint of an arch of 20 voussoirs lies in a vertical plane
    but its voussoirs rest on inclined joints (the thrust presses it at rest), so it engages at contact."""
    a = arch(radius_m=5.0, thickness_m=0.8, voussoirs=20)
    assert len(_vertical(a)) == 1
    assert side_joints(a.interface_details) == frozenset()


def test_side_joints_engage_at_the_depth_in_the_model_and_beds_at_contact():
    """The MJCF: a side joint's pairs carry margin -g tau^2, every other interface margin 0; a column (no details)
    and a portal (a lintel on posts: no vertical joint) have none."""
    w = wall(length_m=1.0, height_m=1.0, thickness_m=0.3, courses=2, units_per_course=2, bond="stack")
    c = default_contact(w)
    scene = structure_scene(w, c, compile=False)
    margins = dict(
        ((a, b), float(m))
        for a, b, m in re.findall(r'<pair geom1="(\w+)" geom2="(\w+)"[^>]*margin="([^"]+)"', scene.xml)
    )
    names = [b.name for b in w.bodies]
    side = side_joints(w.interface_details)
    assert len(side) == 2
    for itf in w.interface_details:
        if itf.first < 0:
            continue
        key = (f"{names[itf.first]}_geom", f"{names[itf.second]}_geom")
        want = -engagement_depth(c.time_constant, 9.81) if itf.pair in side else 0.0
        assert margins[key] == float(f"{want:.15g}")
    assert side_joints(getattr(MultiDrumColumn("square"), "interface_details", ())) == frozenset()
    assert side_joints(portal().interface_details) == frozenset()
