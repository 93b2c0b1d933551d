"""The surface of each body as the engine builds it: vertices in the body frame and outward triangles.

Read from the same engine shapes that :func:`~.model.structure_scene` compiles
(:func:`~.model.engine_shape` of each ``structure.bodies`` entry): a box (its eight corners, its centre
``centre_z`` above the centre of mass), a prism or a general convex block (its hull's vertices). The body
frame has its origin at the centre of mass and the structure's axes at rest, so a body's vertices in the
world at a recorded time are ``position + R(quaternion) @ vertex``. Stored with every 3D result
(:func:`~.record.response_from_states`) so that a result folder alone can be replayed and drawn.
"""

from __future__ import annotations

import numpy as np

from .model import BoxShape, engine_shape

__all__ = ["shape_vertices", "hull_triangles", "structure_meshes"]


def shape_vertices(shape) -> np.ndarray:
    """The vertices of an engine shape in its body frame, shape (n, 3) [m]."""
    if isinstance(shape, BoxShape):
        b, w, h, c = shape.half_width, shape.half_depth, shape.half_height, shape.centre_z
        return np.array([[sx * b, sy * w, c + sz * h] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
    return np.asarray(shape.vertex_array(), dtype=float).reshape(-1, 3)


def hull_triangles(vertices) -> np.ndarray:
    """The triangles of the convex hull of ``vertices`` (n, 3) [m], as vertex indices (m, 3), each
    ordered counter-clockwise seen from outside (outward normal by the right-hand rule)."""
    from scipy.spatial import ConvexHull

    v = np.asarray(vertices, dtype=float)
    hull = ConvexHull(v)
    tri = hull.simplices.copy()
    centre = v[hull.vertices].mean(axis=0)
    n = np.cross(v[tri[:, 1]] - v[tri[:, 0]], v[tri[:, 2]] - v[tri[:, 0]])
    inward = np.einsum("ij,ij->i", n, v[tri[:, 0]] - centre) < 0.0
    tri[inward] = tri[inward][:, ::-1]
    return tri


def structure_meshes(structure) -> tuple[np.ndarray, np.ndarray]:
    """Every body's surface, padded to the largest: vertices (nbody, nvertex, 3) [m] in the body frame
    (NaN past a body's own count) and triangles (nbody, nface, 3) of vertex indices (-1 past its count)."""
    density = float(structure.describe()["density_kg_m3"])
    verts = [shape_vertices(engine_shape(b.shape, density)) for b in structure.bodies]
    tris = [hull_triangles(v) for v in verts]
    nb, nv, nf = len(verts), max(len(v) for v in verts), max(len(t) for t in tris)
    V = np.full((nb, nv, 3), np.nan)
    F = np.full((nb, nf, 3), -1, dtype=np.int32)
    for k, (v, t) in enumerate(zip(verts, tris)):
        V[k, : len(v)] = v
        F[k, : len(t)] = t
    return V, F
