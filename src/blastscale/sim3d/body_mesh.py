"""The surface of each body as stored with the motion: its solid's vertices in the body frame and outward triangles.

One geometry per structure (issue #29): each body's solid is ``structure.bodies[i].vertices``
(:class:`~blastscale.structures.base.RigidBody`: a block's box, a drum's frustum, a general block's hull), the
solid whose mass, centre of mass and inertia the engine integrates and which ``show`` and the report draw; not
the engine's contact shape (a tapered drum collides as the prism of its base section, docs/sim3d.md). The
vertices are given in the body frame the engine uses: origin at the centre of mass (``RigidBody.com``, the
MuJoCo body's position at rest), the structure's axes at rest, so a body's vertices in the world at a recorded
time are ``position + R(quaternion) @ vertex``. Stored with every 3D result
(:func:`~.record.response_from_states`) so that a result folder alone can be replayed and drawn.
"""

from __future__ import annotations

import numpy as np

from ..structures.polyhedron import hull_of

__all__ = ["hull_triangles", "structure_meshes"]


def hull_triangles(vertices, name: str = "block") -> np.ndarray:
    """The triangles of the convex hull of ``vertices`` (n, 3) [m], as indices into ``vertices`` (m, 3), each
    ordered counter-clockwise seen from outside (outward normal by the right-hand rule, that of the hull's
    facet plane). A vertex inside the hull or inside a face is kept in ``vertices`` but in no triangle."""
    hull = hull_of(vertices, name)
    tri = hull.simplices.copy()
    v = hull.points
    n = np.cross(v[tri[:, 1]] - v[tri[:, 0]], v[tri[:, 2]] - v[tri[:, 0]])
    inward = np.einsum("ij,ij->i", n, hull.equations[:, :3]) < 0.0
    tri[inward] = tri[inward][:, ::-1]
    return tri


#: The attribute a structure object carries its meshes in (issue #41: once per structure; no module memo).
_MESHES_ATTR = "_blastscale_meshes"


def structure_meshes(structure) -> tuple[np.ndarray, np.ndarray]:
    """Every body's solid, padded to the largest: vertices (nbody, nvertex, 3) [m] in the body frame
    (``RigidBody.vertices`` as they are, NaN past a body's own count) and triangles (nbody, nface, 3) of
    vertex indices (-1 past its count). Computed once per structure object and carried by it (a hull per body:
    0.2-0.7 s for a 200-block wall, on every run before issue #41); each call returns its own copies."""
    hit = getattr(structure, _MESHES_ATTR, None)
    if hit is None:
        hit = _meshes(structure)
        try:
            object.__setattr__(structure, _MESHES_ATTR, hit)
        except (AttributeError, TypeError):  # an object without a __dict__ (slots): computed on every call
            pass
    return hit[0].copy(), hit[1].copy()


def _meshes(structure) -> tuple[np.ndarray, np.ndarray]:
    verts = [np.asarray(b.vertices, dtype=float).reshape(-1, 3) for b in structure.bodies]
    tris = [hull_triangles(v, b.name) for v, b in zip(verts, structure.bodies)]
    nb, nv, nf = len(verts), max(len(v) for v in verts), max(len(t) for t in tris)
    V = np.full((nb, nv, 3), np.nan)
    F = np.full((nb, nf, 3), -1, dtype=np.int32)
    for k, (v, t) in enumerate(zip(verts, tris)):
        V[k, : len(v)] = v
        F[k, : len(t)] = t
    return V, F
