"""The stored motion's pieces (issue 26): the surfaces of the bodies' solids, replayed poses, animation frames."""

import numpy as np
import pytest

from blastscale.sim3d.body_mesh import hull_triangles
from blastscale.sim3d.replay import Motion, frame_count, point_positions, world_vertices
from blastscale.structures.base import centred_box_vertices


def test_box_surface_encloses_its_volume_with_outward_triangles():
    """A 2 x 1 x 4 m box (centre 0.5 m above the centre of mass): 8 corners, 12 triangles whose signed
    volumes (divergence theorem, V = sum (a . (b x c)) / 6 over outward triangles) add up to 8 m^3 exactly."""
    v = centred_box_vertices(1.0, 0.5, 2.0, centre_z=0.5)
    assert v.shape == (8, 3) and v[:, 2].min() == -1.5 and v[:, 2].max() == 2.5
    tri = hull_triangles(v)
    assert tri.shape == (12, 3)
    vol = np.einsum("ij,ij->i", v[tri[:, 0]], np.cross(v[tri[:, 1]], v[tri[:, 2]])).sum() / 6.0
    assert vol == pytest.approx(8.0, rel=1e-12)


def test_points_and_vertices_follow_a_quarter_turn_about_y():
    """A quarter turn about +y (q = (cos 45, 0, sin 45, 0)) takes body +z to world +x: a point 1 m above the
    centre of mass at (5, 0, 2) goes to (6, 0, 2)."""
    q = np.array([np.cos(np.pi / 4), 0.0, np.sin(np.pi / 4), 0.0]) * 3.0  # not unit: normalised first
    pos = np.array([[[5.0, 0.0, 2.0]]])
    p = point_positions(pos, q[None, None], [0], [[0.0, 0.0, 1.0]])
    np.testing.assert_allclose(p[0, 0], [6.0, 0.0, 2.0], atol=1e-15)
    w = world_vertices(pos, q[None, None], np.array([[[0.0, 0.0, 1.0], [np.nan] * 3]]))
    np.testing.assert_allclose(w[0, 0, 0], [6.0, 0.0, 2.0], atol=1e-15)
    assert np.isnan(w[0, 0, 1]).all()


def test_frames_are_fps_times_duration_over_speed_from_first_to_last_state():
    t = np.linspace(0.0, 2.0, 2001)
    m = Motion(
        time=t,
        labels=("prototype",),
        position=np.zeros((1, t.size, 1, 3)),
        quaternion=np.tile([1.0, 0, 0, 0], (1, t.size, 1, 1)),
        vertices=np.zeros((1, 1, 3)),
        faces=np.zeros((1, 1, 3), int),
        bodies=("B",),
    )
    assert frame_count(2.0, 20, 1.0) == 40 and frame_count(2.0, 20, 4.0) == 10 and frame_count(1e-3, 1, 1) == 2
    idx, times = m.frame_indices(20, 1.0)
    assert len(idx) == 40 and times[0] == 0.0 and times[-1] == 2.0
    np.testing.assert_allclose(np.diff(times), 2.0 / 39, atol=1e-3)  # nearest of states 1 ms apart
