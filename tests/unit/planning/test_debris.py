"""The reach of the blocks (planar closed form, 3D bound) behind the debris zone."""

import math

import numpy as np
import pytest
import xarray as xr

from blastscale.planning.debris import planar_reach, reach_3d
from blastscale.structures import RectangularBlock


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
        return xr.Dataset({"com_displacement": (("time", "body", "component"), com),
                           "tilt": (("time", "body"), np.array([[0.0], [tilt / 2], [tilt]]))})

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
