"""Replay stored motion: the bodies' surfaces and the monitoring points in the world at each recorded time,
from the poses (:data:`~.results.MOTION_VARIABLES`) a 3D result keeps.

Pure numpy on plain arrays (positions [m], unit quaternions (w, x, y, z)); a quaternion that lost its unit
length (interpolated, rounded in a file) is normalised first. Any length unit works as long as it is the same
for positions, vertices and local points (a specimen up-scaled to prototype units replays in prototype units).
"""

from __future__ import annotations

import numpy as np

from .rotations import quaternion_to_matrix

__all__ = ["rotations", "point_positions", "world_vertices", "points_of"]


def rotations(quaternion) -> np.ndarray:
    """Rotation matrices (..., 3, 3) of quaternions (..., 4) (w, x, y, z), normalised first."""
    q = np.asarray(quaternion, dtype=float)
    return quaternion_to_matrix(q / np.linalg.norm(q, axis=-1, keepdims=True))


def point_positions(position, quaternion, point_body, point_local) -> np.ndarray:
    """World positions (n, npoint, 3) [m] of points fixed on bodies.

    Parameters
    ----------
    position : array (n, nbody, 3)
        Centres of mass (body frame origins) [m].
    quaternion : array (n, nbody, 4)
        Orientations, body to world (w, x, y, z).
    point_body : array of int (npoint,)
        The body carrying each point.
    point_local : array (npoint, 3)
        Each point in its body's frame [m].
    """
    pb = np.asarray(point_body, dtype=int)
    R = rotations(np.asarray(quaternion)[:, pb])
    return np.asarray(position)[:, pb] + np.einsum("npij,pj->npi", R, np.asarray(point_local, dtype=float))


def world_vertices(position, quaternion, vertices) -> np.ndarray:
    """World positions (n, nbody, nvertex, 3) [m] of every body's vertices (NaN padding stays NaN).

    ``position`` (n, nbody, 3) [m], ``quaternion`` (n, nbody, 4), ``vertices`` (nbody, nvertex, 3) [m] in
    each body's frame."""
    R = rotations(quaternion)
    return np.asarray(position)[:, :, None, :] + np.einsum("nbij,bvj->nbvi", R, np.asarray(vertices, dtype=float))


def points_of(ds) -> np.ndarray:
    """:func:`point_positions` of a dataset holding the stored motion (one system: a
    :attr:`~.results.Response3D.dataset`, or one ``system`` of a study's ``sim3d`` group)."""
    return point_positions(ds["body_position"].values, ds["body_quaternion"].values, ds["point_body"].values,
                           ds["point_local_position"].values)
