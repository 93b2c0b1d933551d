"""Issue #23: "the top" of a structure is its highest monitoring point at rest, for every kind: the crown of
an arch (the last point, a springer, was taken before), the lintel of a portal, the top drum of a column, the
top course of a wall; a structure and its scaled copy name the same point."""

from __future__ import annotations

import math

import pytest

from blastscale.similitude import scaling_factors
from blastscale.structures import MultiDrumColumn, RectangularBlock, arch, portal, top_monitoring_point, wall
from blastscale.structures.base import MonitoringPoint


def _z(structure, point) -> float:
    return structure.bodies[point.body].com[2] + point.position[2]


def test_the_top_of_a_semicircular_arch_is_its_crown_voussoirs_front_centre():
    # 15 voussoirs of 12 deg: the crown voussoir V8 spans 84-96 deg; its front face is a symmetric trapezoid
    # between the intrados and extrados chords at z_i = ri cos 6 deg, z_o = ro cos 6 deg, of lengths
    # a = 2 ri sin 6 deg and b = 2 ro sin 6 deg: its centroid lies h (a + 2b) / (3 (a + b)) above the intrados
    # chord (h = z_o - z_i), the closed form the generator's polygon centroid must meet to round-off.
    R, t = 2.5, 0.5
    a_ = arch(radius_m=R, thickness_m=t, voussoirs=15)
    top = top_monitoring_point(a_)
    ri, ro, half = R - t / 2, R + t / 2, math.radians(6.0)
    zi, zo, a, b = ri * math.cos(half), ro * math.cos(half), 2 * ri * math.sin(half), 2 * ro * math.sin(half)
    assert top.name == "V8"
    assert _z(a_, top) == pytest.approx(zi + (zo - zi) * (a + 2 * b) / (3 * (a + b)), rel=1e-12)
    last = a_.monitoring_points[-1]  # what "the top" was: the +y springer, near the ground
    assert last.name == "V15" and _z(a_, last) < 0.11 * _z(a_, top)


@pytest.mark.parametrize(
    "kw, crown", [({"voussoirs": 16}, "V9"), ({"voussoirs": 9, "embrace_deg": 120.0, "pier_height_m": 1.0}, "V5")]
)
def test_an_even_arch_names_the_last_crown_voussoir_and_piers_are_not_the_top(kw, crown):
    a_ = arch(**kw)
    for s in (a_, a_.scaled(scaling_factors(1 / 200))):  # the same point at any scale
        assert top_monitoring_point(s).name == crown
    if kw["voussoirs"] == 16:  # V8 and V9 stand level: the tie goes to the last of them
        z = {p.name: _z(a_, p) for p in a_.monitoring_points}
        assert z["V8"] == pytest.approx(z["V9"], rel=1e-12)


def test_the_top_of_the_other_kinds():
    p = portal(drums=3)
    assert top_monitoring_point(p).name == "lintel"
    col = MultiDrumColumn()
    assert top_monitoring_point(col).name == f"P-{col.drums}"
    w = wall(length_m=3.0, height_m=2.0, thickness_m=0.4, courses=4, units_per_course=3)
    top = top_monitoring_point(w)
    assert _z(w, top) == pytest.approx(2.0 - 0.25, rel=1e-12)  # the centre of the top course (0.5 m high)
    assert top_monitoring_point(RectangularBlock(10.0, 2.68)).name == "P-1"
    # a user's point above the top drum's front centre is the top
    capped = MultiDrumColumn(
        drums=3, height=3.0, top_width=1.54, extra_points=(MonitoringPoint("cap", 2, (0.0, 0.0, 0.5)),)
    )
    assert top_monitoring_point(capped).name == "cap"
