"""The reach of the blocks (planar closed form, 3D bound) behind the debris zone."""

import math

import numpy as np
import pytest
import xarray as xr

from blastscale.planning.debris import body_extent, planar_reach, reach_3d
from blastscale.structures import MultiDrumColumn, RectangularBlock, arch


def test_planar_reach():
    assert planar_reach(2.0, 10.0, 0.0, False) == pytest.approx(1.0)
    assert planar_reach(2.0, 10.0, 0.1, False) == pytest.approx(1.0 + 10.0 * math.sin(0.1))
    assert planar_reach(2.0, 10.0, 0.1, True) == pytest.approx(11.0)  # on its side


def test_3d_reach_bounds_every_point():
    block = RectangularBlock(height=4.0, width=1.0, depth=0.5)
    t = 3

    def ds(dx, tilt):
        com = np.zeros((t, 1, 3))
        com[-1, 0, 0] = dx
        return xr.Dataset(
            {
                "com_displacement": (("time", "body", "component"), com),
                "tilt": (("time", "body"), np.array([[0.0], [tilt / 2], [tilt]])),
            }
        )

    rest = math.hypot(0.5, 0.25)
    assert reach_3d(ds(0.0, 0.0), block) == pytest.approx(rest)
    assert reach_3d(ds(0.3, 0.0), block) == pytest.approx(0.3 + rest)
    assert reach_3d(ds(0.0, math.pi / 2), block) == pytest.approx(rest + 2.0)
    # against the corners of the block tilted about its base edge by theta: the bound holds
    for th in np.linspace(0.0, math.pi / 2, 7):
        corners = np.array([[x, y, z] for x in (-0.5, 0.5) for y in (-0.25, 0.25) for z in (0.0, 4.0)])
        piv = np.array([0.5, 0.0, 0.0])
        rot = np.array([[math.cos(th), 0, math.sin(th)], [0, 1, 0], [-math.sin(th), 0, math.cos(th)]])
        moved = (corners - piv) @ rot.T + piv
        com = (np.array([0.0, 0.0, 2.0]) - piv) @ rot.T + piv
        exact = np.max(np.hypot(moved[:, 0], moved[:, 1]))
        assert exact <= reach_3d(ds(com[0], th), block) + 1e-12


@pytest.mark.parametrize(
    "structure",
    [
        MultiDrumColumn(drums=3, height=3.0, top_width=1.54),
        MultiDrumColumn(section="circular", drums=2, height=2.0, sides=12),
        arch(voussoirs=5),
    ],
    ids=["square column", "circular column", "arch"],
)
def test_body_extent_bounds_every_vertex_of_the_solid_tilted_any_way(structure):
    """Any body (tapered drums: their centre of mass below mid-height; arch voussoirs: general convex
    blocks, their centre of mass off the middle) turned by a tilt phi about any horizontal axis and any
    spin: no vertex of its solid moves further than rho + c sin(phi) horizontally from its centre of mass."""
    rng = np.random.default_rng(29)
    for body in structure.bodies:
        rho, c = body_extent(body)
        v = np.asarray(body.vertices)
        assert rho == pytest.approx(np.hypot(v[:, 0], v[:, 1]).max(), rel=1e-12) and c >= -v[:, 2].min()
        for phi, axis, spin in zip(
            rng.uniform(0, math.pi / 2, 20), rng.uniform(0, 2 * math.pi, 20), rng.uniform(0, 2 * math.pi, 20)
        ):
            k = np.array([math.cos(axis), math.sin(axis), 0.0])  # tilt axis, horizontal
            K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
            tilt = np.eye(3) + math.sin(phi) * K + (1 - math.cos(phi)) * K @ K
            z = np.array([[math.cos(spin), -math.sin(spin), 0], [math.sin(spin), math.cos(spin), 0], [0, 0, 1]])
            moved = v @ (tilt @ z).T
            assert np.hypot(moved[:, 0], moved[:, 1]).max() <= rho + c * math.sin(phi) + 1e-12
