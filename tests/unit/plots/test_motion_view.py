"""Motion you can see (issue 39) and a small 3D view (issue 41): the displacement magnification of the 3D
drawings (``blastscale.plots.motion``) and the view's data (``blastscale.report.motion.view_data``), on a motion
written by hand: a 1 x 1 x 4 m block that rocks about its front bottom edge, a closed form."""

import base64

import numpy as np
import pytest

from blastscale.plots.motion import (
    VISIBLE_FRACTION,
    auto_magnification,
    magnification_for,
    magnified_world,
    peak_motion,
    record_height,
)
from blastscale.sim3d.replay import Motion

B, H = 1.0, 4.0  # the block's width and height [m]


def _box():
    v = np.array([[x, y, z] for x in (-B / 2, B / 2) for y in (-B / 2, B / 2) for z in (-H / 2, H / 2)])
    faces = np.array(
        [[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4], [2, 6, 3], [3, 6, 7], [0, 4, 2],
         [2, 4, 6], [1, 3, 5], [3, 7, 5]]
    )  # fmt: skip
    return v, faces


def rocking(thetas, nsys: int = 2) -> Motion:
    """The block turned by each angle of ``thetas`` [rad] about its edge x = B/2, z = 0 (the blast from -x
    pushes it to +x), its pose exactly that rotation; every system the same motion."""
    v, faces = _box()
    th = np.asarray(thetas, dtype=float)
    c0 = np.array([0.0, 0.0, H / 2])
    pivot = np.array([B / 2, 0.0, 0.0])
    # rotation about +y by -theta (the top moves to +x): R = [[cos, 0, sin], [0, 1, 0], [-sin, 0, cos]]
    R = np.zeros((len(th), 3, 3))
    R[:, 0, 0] = R[:, 2, 2] = np.cos(th)
    R[:, 0, 2], R[:, 2, 0], R[:, 1, 1] = np.sin(th), -np.sin(th), 1.0
    c = pivot + np.einsum("nij,j->ni", R, c0 - pivot)
    q = np.stack([np.cos(th / 2), 0 * th, np.sin(th / 2), 0 * th], -1)  # about +y by theta: the R above
    pos = np.broadcast_to(c[None, :, None, :], (nsys, len(th), 1, 3)).copy()
    quat = np.broadcast_to(q[None, :, None, :], (nsys, len(th), 1, 4)).copy()
    return Motion(
        np.linspace(0.0, 1.0, len(th)), ("prototype", "model")[:nsys], pos, quat, v[None], faces[None], ("b",)
    )


def test_the_hand_written_motion_is_the_rotation_about_the_edge():
    """The check of the check: the replayed pivot edge stays put and the top's far corner moves by the chord."""
    th = 0.01
    w = rocking([0.0, th]).world(0, [0, 1])
    edge = (w[0][..., 0] == B / 2) & (w[0][..., 2] == 0.0)
    assert edge.sum() == 2
    np.testing.assert_allclose(w[1][edge], w[0][edge], atol=1e-15)
    top = np.argmax(w[0][0, :, 2] - w[0][0, :, 0])  # the back top corner (x = -B/2, z = H)
    r = np.hypot(B, H)
    assert np.linalg.norm(w[1][0, top] - w[0][0, top]) == pytest.approx(2 * r * np.sin(th / 2), rel=1e-12)


@pytest.mark.parametrize("m", [1.0, 10.0, 20.0])
def test_magnified_motion_is_m_times_the_motion_and_keeps_the_pivot(m):
    """Every vertex moves M times its true displacement to first order in the angle: |u_M - M u| <= (M^2 + M)
    theta^2 r / 2 (the second-order terms of a rotation by M theta against M times one by theta, r the largest
    distance to the pivot); so the pivot edge stays within that of its place, the block keeps its shape
    (every edge length to round-off) and M = 1 is the motion itself."""
    th, r = 2e-3, np.hypot(B, H)
    mo = rocking([0.0, th])
    w0, w1 = mo.world(0, [0, 1])
    u = w1 - w0
    wm = magnified_world(mo, 0, [0, 1], m)
    assert np.array_equal(wm[0], w0)  # the first record is the rest state: not moved
    um = wm[1] - w0
    bound = (m * m + m) * th * th * r / 2
    assert np.abs(um - m * u).max() <= bound
    assert np.abs(um).max() > 0.9 * m * np.abs(u).max()  # not trivially small: the top moves ~M times
    edge = (w0[..., 0] == B / 2) & (w0[..., 2] == 0.0)
    assert np.abs(um[edge]).max() <= bound
    d0 = np.linalg.norm(w0[0, :, None] - w0[0, None], axis=-1)
    dm = np.linalg.norm(wm[1][0, :, None] - wm[1][0, None], axis=-1)
    np.testing.assert_allclose(dm, d0, atol=1e-12)
    if m == 1.0:
        np.testing.assert_array_equal(wm, mo.world(0, [0, 1]))


def test_magnification_is_the_largest_1_2_5_step_that_keeps_the_motion_a_tenth_of_the_height():
    """The column of issue 39 (8 cm at the top of 10.4 m): 0.1 x 10.4 / 0.08 = 13 -> x 10; edges: exactly at
    the target it is that step; a motion of 10 % of the height or more (a collapse) is drawn as it is (the
    answer "no magnification"); no motion, no magnification."""
    assert VISIBLE_FRACTION == 0.1
    assert magnification_for(0.08, 10.4) == 10.0
    assert magnification_for(0.02, 10.0) == 50.0  # target exactly 50
    assert magnification_for(0.021, 10.0) == 20.0  # target 47.6
    assert magnification_for(0.5e-3, 10.0) == 2000.0
    assert magnification_for(1.0, 10.0) == 1.0 and magnification_for(5.0, 10.0) == 1.0
    assert magnification_for(0.0, 10.0) == 1.0
    th = 0.004  # the top's far corner moves 2 r sin(th / 2) = 0.0165 m: 0.4 / 0.0165 = 24.3 -> x 20
    mo = rocking(np.linspace(0.0, th, 5))
    assert record_height(mo) == pytest.approx(H, rel=1e-12)
    assert peak_motion(mo) == pytest.approx(2 * np.hypot(B, H) * np.sin(th / 2), rel=1e-9)
    assert auto_magnification(mo) == 20.0


def test_record_height_is_the_one_name_for_a_records_height():
    """A motion record's vertical extent is ``record_height``; ``structure_height`` is the run summary's
    (``blastscale.study.criterion``) alone: no second public name with other logic, no alias."""
    import blastscale.plots.motion as pm
    import blastscale.study.criterion as crit

    assert not hasattr(pm, "structure_height") and "structure_height" not in pm.__all__
    assert "record_height" in pm.__all__ and crit.structure_height is not pm.record_height


def test_view_data_carries_the_surfaces_once_and_only_poses_per_frame():
    """Issue 41: the page's data is the surface once (8 vertices, 12 triangles) and 7 float32 per body, system
    and frame; doubling the frames doubles only the poses. The magnification stated is the automatic one
    unless one is asked; the colour scale's top is the largest displacement of a centre of mass."""
    from blastscale.report.motion import view_data

    th = 0.004
    mo = rocking(np.linspace(0.0, th, 41))

    def nbytes(s):
        return len(base64.b64decode(s))

    d10, d20 = view_data(mo, np.arange(0, 40, 4)), view_data(mo, np.arange(0, 40, 2))
    for d, n in ((d10, 10), (d20, 20)):
        assert nbytes(d["vertices"]) == 8 * 3 * 4 and nbytes(d["triangles"]) == 12 * 3 * 4
        assert nbytes(d["position"]) == 2 * n * 1 * 3 * 4 and nbytes(d["quaternion"]) == 2 * n * 1 * 4 * 4
        assert len(d["times"]) == n and d["counts"] == [8]
    assert d10["magnification"] == d10["auto_magnification"] == 20.0
    assert view_data(mo, [0, 40], magnification=3.0)["magnification"] == 3.0
    c = mo.position[0, :, 0]
    assert d20["colour_max_m"] == pytest.approx(np.linalg.norm(c[38] - c[0]), rel=1e-6)  # float32
