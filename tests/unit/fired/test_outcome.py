"""Markers on 3D bodies (fired/outcome.py): the marker's point moved by its body's full pose, and the fall rules
judged from markers, against rigid-body closed forms.

Closed forms: a point at lever r from the centre of mass moves by ``d + (R - I) r`` (R a yaw about z or a turn
about y); a rectangular block (half-width b, half-height h) rocking by theta about its rear toe (Housner 1963,
:func:`blastscale.fired.tracks.block_marker_displacement`) has its centre of mass at height
``b sin(theta) + h cos(theta)``. Tolerances: round-off (1e-12), the formulas being exact.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest
import xarray as xr

from blastscale.fired.outcome import (
    body_verdicts,
    marker_body,
    measured_outcome,
    pose_marker_history,
)
from blastscale.fired.tracks import block_marker_displacement

B, H = 0.2, 0.5  # half-width, half-height [m]


def one_block(rule: str):
    box = [[x, y, z] for x in (-B, B) for y in (-B, B) for z in (-H, H)]  # about the centre of mass
    body = SimpleNamespace(com=(0.0, 0.0, H), vertices=box, faces=(), toppling_angle=math.atan(B / H), base_height=-H)
    return SimpleNamespace(bodies=[body], heights=[2 * H], collapse_rule=rule)


def poses(d, axis, angle) -> xr.Dataset:
    """Two records (rest, then moved by ``d`` [m] and turned by ``angle`` [rad] about ``axis``) of one body."""
    ax = np.asarray(axis, float) / np.linalg.norm(axis)
    q = np.array([[1.0, 0, 0, 0], [math.cos(angle / 2), *(math.sin(angle / 2) * ax)]])
    pos = np.array([[0.0, 0.0, H], np.add([0.0, 0.0, H], d)])
    return xr.Dataset(
        {
            "body_position": (("time", "body", "c"), pos[:, None, :]),
            "body_quaternion": (("time", "body", "q"), q[:, None, :]),
        }
    )


def test_a_marker_follows_the_sideways_turn():
    """A yaw of 30 deg about z moves a marker 0.3 m in front of the axis along x by 0.3 (cos 30 - 1): the turn
    out of the blast's plane (the old rocking-angle-about-y rule saw none of it)."""
    st = one_block("toppling")
    phi = math.radians(30)
    ux, uz = pose_marker_history(poses((0.1, 0.2, -0.05), (0, 0, 1), phi), st, (0.3, 0.0, H + 0.4))
    assert ux[1] == pytest.approx(0.1 + 0.3 * (math.cos(phi) - 1), abs=1e-12)
    assert uz[1] == pytest.approx(-0.05, abs=1e-12)
    assert ux[0] == uz[0] == 0.0


def test_a_marker_follows_the_rocking():
    th = 0.2  # about +y: x' = x cos + z sin, z' = -x sin + z cos of the lever (0.3, 0.4)
    ux, uz = pose_marker_history(poses((0.01, 0.0, 0.0), (0, 1, 0), th), one_block("toppling"), (0.3, 0.0, H + 0.4))
    assert ux[1] == pytest.approx(0.01 + 0.3 * (math.cos(th) - 1) + 0.4 * math.sin(th), abs=1e-12)
    assert uz[1] == pytest.approx(-0.3 * math.sin(th) + 0.4 * (math.cos(th) - 1), abs=1e-12)


def rocked_markers(theta_max, points):
    th = np.linspace(0.0, theta_max, 50)
    out = {}
    for k, (x, z) in enumerate(points):
        ux, uz = block_marker_displacement(th, x, z, B)
        out[f"m{k}"] = ((x, 0.0, z), ux, uz)
    return out


def com_drop(theta):
    return H - B * math.sin(theta) - H * math.cos(theta)


@pytest.mark.parametrize(
    ("rule", "deg", "fell"),
    [("fallen", 40, False), ("fallen", 50, True), ("toppling", 20, False), ("toppling", 23, True)],
)
def test_two_markers_give_the_turn_and_the_drop(rule, deg, fell):
    """Two markers on one block: its turn (the rule's limit: 45 deg for "fallen", atan(b/h) = 21.8 deg for
    "toppling") and its centre of mass's drop, exactly."""
    th = math.radians(deg)
    v = body_verdicts(one_block(rule), rocked_markers(th, [(0.0, 2 * H), (-B, 0.3)]))[0]
    assert v["turn_rad"] == pytest.approx(th, abs=1e-12)
    assert v["drop_m"] == pytest.approx(max(com_drop(th), 0.0), abs=1e-12)
    assert v["fell"] is fell


def test_one_marker_sees_a_drop_but_no_turn():
    """One marker: no turn (50 deg of rocking unseen: stands by the drop rule), its own drop for the body's: a
    block dropped by 0.6 m (more than half its 1 m height) fell; a marker without z judges nothing."""
    st = one_block("fallen")
    v = body_verdicts(st, rocked_markers(math.radians(50), [(0.0, H)]))[0]
    assert v["turn_rad"] is None and v["fell"] is False
    t = np.linspace(0, 1, 20)
    assert measured_outcome(st, {"a": ((0.0, 0.0, H), 0 * t, -0.6 * t)}) is True
    assert measured_outcome(st, {"a": ((0.0, 0.0, H), 0 * t, -0.4 * t)}) is False
    assert measured_outcome(st, {"a": ((0.0, 0.0, H), 0 * t, None)}) is None


def test_a_marker_is_on_the_body_whose_solid_carries_it():
    """A 2 m block under a 0.5 m one (0.6 m square): a marker on the side of the lower block 0.1 m below the
    joint is nearer to the upper block's centre of mass (0.35 m against 0.9 m) but on the lower block's solid:
    the lower block carries it (issue #36 item 4: the nearest centre of mass gave it to the wrong block). On
    the joint itself (both solids), the nearer centre of mass: the upper one. Off every body, the nearest."""
    from blastscale.structures import Assembly, ConvexBlock
    from blastscale.structures.generators import box_vertices_from_bounds

    st = Assembly(
        (
            ConvexBlock("low", box_vertices_from_bounds(-0.3, 0.3, -0.3, 0.3, 0.0, 2.0), 2000.0),
            ConvexBlock("high", box_vertices_from_bounds(-0.3, 0.3, -0.3, 0.3, 2.0, 2.5), 2000.0),
        )
    )
    side = (0.0, 0.3, 1.9)  # on the side face y = +0.3, where a side camera sees it
    d = [np.linalg.norm(np.subtract(b.com, side)) for b in st.bodies]
    assert d[1] < d[0]  # the old rule's answer would be the upper block
    assert marker_body(st, side) == 0
    assert marker_body(st, (0.0, 0.3, 2.0)) == 1  # on the joint: the nearer centre (2.25 m vs 1.0 m)
    assert marker_body(st, (0.0, 0.0, 2.6)) == 1 and marker_body(st, (0.0, 0.0, -0.05)) == 0
